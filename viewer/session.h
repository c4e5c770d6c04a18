// A viewer session: the edit a user builds by hand, and what the display needs of it.
//
// The session owns the prepared relighting (relight/relighting.h) and the lights' and
// virtual parts' controls. Without virtual parts a light change is the superposition path
// (relight/prepared.h: B(v) = sum_l L_l h_l(v), a weighted sum per vertex). With virtual
// parts the solver holds them (relight/dynamic/dynamic_relighting.h): the part added last is
// moved or removed incrementally (a drag is moveLastObject); any other change (a radiance,
// a part that is not the last) inserts the parts again from the prepared solver, in the
// order `relight render` inserts an edit's parts (virtual lights, then objects, each in
// list order), so that a saved edit renders to the image on the screen.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/io/obj_reader.h"
#include "relight/relighting.h"

namespace relight::viewer {

using radiosity::Rgb;
using radiosity::Vec3;

/// One light of the panel: a real light of the scene or a virtual one. A real sun, point
/// lamp or sky is one control per component (a sky: 9, one per scene light), sharing one
/// emitter.
struct LightControl {
    std::string name;
    bool isVirtual = false;
    bool on = true;
    Rgb colour{1, 1, 1};   ///< a quad's radiance's colour, brightest channel 1
    double intensity = 0;  ///< a quad's radiance's brightest channel when on
    VirtualLight face;     ///< virtual quad lights: the emitting face (its radiance unused)
    /// A sun, point lamp or sky (radiosity/emitter.h) as the session has it, edited in
    /// place (Session::editLight) and shared by a real light's components; null for a quad.
    /// Its strengths are the light's (colour and intensity are unused).
    std::shared_ptr<radiosity::Emitter> emitter{};
    int component = 0;  ///< the emitter's component this control stands for
    /// The strength of this control's component (a quad's radiance), zero when off.
    Rgb radiance() const;
    /// Sets colour and intensity from a radiance (black: white at intensity 0).
    void setRadiance(const Rgb& radiance);
};

/// One virtual object.
struct ObjectControl {
    VirtualObject object;    ///< file, reflectance, transform and placed polygons
    ObjFile geometry;        ///< its OBJ before the transform (to place it again)
    bool viewerBox = false;  ///< made in the viewer: saved with a unit box OBJ beside the edit
};

/// A real lamp placed on the photo: a lamp that is in the room (seen in the photo) but not
/// in scene.json yet. It is drawn as an outline and saved into scene.json as a real light
/// (relight/io/scene_lights.h); the scene relights with it once it is prepared again (a
/// real lamp is part of the photo's lighting, which the preparation solves).
struct PlacedLamp {
    std::string name;
    Vec3 centre{0, 0, 0};  ///< on the surface clicked
    Vec3 normal{0, 0, 1};  ///< the surface's, turned towards the camera: the side it lights
    double width = 0.3, height = 0.3;  ///< metres
    bool estimate = true;              ///< "radiance": "estimate" (from the photo), else `radiance`
    Rgb radiance{10, 10, 10};
    bool onInPhoto = true;  ///< lit in the photo (its first photo's lights_on)
    /// The emitting quad, a few millimetres off the surface so that it does not sit in it.
    std::vector<Vec3> corners() const;
};

/// What the camera ray through a pixel hits.
struct Pick {
    bool hit = false;
    Vec3 point{0, 0, 0};
    Vec3 normal{0, 0, 1};    ///< of the face hit, turned towards the camera
    int object = -1;         ///< the virtual object hit, or -1
    std::string realObject;  ///< the scene's object hit when scene.json marks it removable
};

class Session {
  public:
    /// `r` from prepareRelighting(), which must outlive the session (the session inserts
    /// its virtual parts into r's solver and takes them out again when it ends); `edit`
    /// loaded against r.scene. The edit's removals and parts are made at once.
    Session(Relighting& r, const EditFile& edit);
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    const Relighting& relighting() const { return *r_; }
    const PreparedImage& prepared() const { return r_->prepared; }

    /// Real lights (scene order), then virtual lights. After changing one, call update().
    std::vector<LightControl>& lights() { return lights_; }
    const std::vector<ObjectControl>& objects() const { return objects_; }
    int realLights() const { return realLights_; }

    /// Brings the solution up to date with the lights' controls (a no-op when nothing
    /// changed). Changes the generation when the display values change. A radiance that
    /// would make the display not finite (typed into a slider: 1e38) is undone, and an
    /// InputError names the light.
    /// With virtual objects, a change of the real lights' radiances alone (a colour or
    /// strength slider) is quick: DynamicRelighting::setRealRadiances, the parts' links as
    /// they are, no shadow ray; the image is then near `relight render`'s of the edit, not
    /// equal to it (exactPending()), until settle() inserts the parts again.
    void update();
    /// update() where it is quick (nothing to solve, the superposition path, the quick image
    /// of a slider or of a moved sun or lamp) and returns true; returns false, changing
    /// nothing, where the change needs the parts inserted again (seconds on a large scene):
    /// the window then runs update() on its worker thread (viewer/app.cpp), so that a
    /// slider keeps its quick frames and nothing slow runs inside a frame.
    bool updateQuickly();
    /// Whether the image is a quick one (update()) that settle() makes exact.
    bool exactPending() const { return exactPending_; }
    /// Whether a sun turned or a point lamp moved (editLight's "direction" or "position",
    /// the strengths kept) is shown quickly while it moves: the light's direct light per
    /// pixel at its new place from one shadow ray per pixel, the rest (its indirect light,
    /// the other lights, the virtual parts) as last solved
    /// (DynamicRelighting::previewEmitter); exactPending() until settle(). For the per-pixel
    /// displays only (relitPerPixel), which the viewer says (viewer/app.cpp); off, each move
    /// is solved as `relight render` solves the saved edit (a second a turn on the courtyard).
    void setQuickMoves(bool on) { quickMoves_ = on; }
    bool quickMoves() const { return quickMoves_; }
    /// Inserts the virtual parts again at the radiances as they stand, as `relight render`
    /// inserts the saved edit, when the image is a quick one (the viewer calls it when the
    /// slider rests; a screenshot before it is taken); the shadow rays come from the
    /// GeometryCache. Returns whether it did anything (not during a drag).
    bool settle();
    /// Whether settle() would do anything now (the window runs it in the background only
    /// then: viewer/background_work.h).
    bool canSettle() const {
        return exactPending_ && (dragging_ < 0 || (dyn_ && dyn_->previewingObject()));
    }
    /// Sets object i's reflectance (inserted again).
    void setReflectance(int i, const Rgb& reflectance);
    /// Sets object i's specular term (none: Lambertian; relight/dynamic/specular.h). It
    /// changes the overlay only: nothing is inserted again unless another object shares
    /// its name. Throws std::invalid_argument for ks < 0 or a shininess that is not > 0.
    void setSpecular(int i, const std::optional<Specular>& specular);

    /// What the camera ray through pixel (u, v) hits (OpenCV pixel coordinates). `through`:
    /// a light whose face (a lamp of one face, as the solver holds it) the ray passes, so
    /// that a lamp being dragged is not put onto itself.
    Pick pick(double u, double v, const std::string& through = {}) const;
    /// A virtual quad light on the face picked, facing out of it: the size of the scene's
    /// lights (their mean area), their mean radiance, a few millimetres off the face.
    void addLightAt(const Pick& p);
    /// A virtual box standing on the face picked (its base on the face, its up the face's
    /// normal), 6 % of the scene's diagonal on a side, reflectance 0.7, 0.2, 0.2.
    void addBoxAt(const Pick& p);
    /// A real lamp on the face picked, facing out of it, named L1, L2, ... (a name no light
    /// has), `width` x `height` metres (0: the size of the scene's lights, their mean area,
    /// else 5 % of the scene's diagonal). Returns its index in placedLamps().
    int placeLampAt(const Pick& p, double width = 0, double height = 0);
    /// Moves placed lamp i onto the face picked, facing out of it.
    void moveLampTo(int i, const Pick& p);
    std::vector<PlacedLamp>& placedLamps() { return placed_; }
    /// Adds the placed lamps to <sceneDir>/scene.json as real quad lights
    /// (relight/io/scene_lights.h) and forgets them. Throws InputError (a name taken, an
    /// empty one) with scene.json as it was.
    void saveLamps(const std::filesystem::path& sceneDir);

    /// Starts dragging object i, grabbed at p (the object becomes the part added last).
    void beginDrag(int i, const Pick& p);
    /// Moves the dragged object so that the grabbed point follows the camera ray through
    /// (u, v) in the plane of the object's base. False when that ray misses the plane.
    /// With setQuickMoves (the per-pixel displays) a quick frame
    /// (DynamicRelighting::previewLastObject: its shadows and its own light per pixel, the
    /// solver without it; exactPending() until settle() or endDrag()); else the solver moves
    /// it (moveLastObject).
    bool dragTo(double u, double v);
    /// Ends the drag. The object's last position is inserted again from the prepared
    /// solver, as `relight render` inserts it: the incremental moves of the drag agree with
    /// a fresh insertion to about 1e-5 (bench/move_box), the resting image exactly, so that
    /// a saved edit renders to what the window shows.
    void endDrag();
    int dragging() const { return dragging_; }
    /// What the image shows, for the window to say: "exact" (`relight render`'s image of the
    /// edit), or which quick stage (a slider's quick image; a dragged object's quick frames,
    /// DynamicRelighting::previewLastObject, in the per-pixel displays with setQuickMoves).
    std::string stage() const;
    void removeLight(int i);  ///< a virtual light (index into lights())
    void removeObject(int i);
    /// Takes the scene's removable object `name` out (Loscos et al. 1999, §5.3: its pixels
    /// filled, its shadows gone; relight/dynamic/object_removal.h), or brings it back. The
    /// parts are inserted again in render's order (removals first). Throws
    /// std::invalid_argument for an object that scene.json does not mark removable.
    void removeRealObject(const std::string& name);
    void restoreRealObject(const std::string& name);
    /// The scene's objects taken out, in the order they went.
    const std::vector<std::string>& removedObjects() const { return removed_; }

    /// Edits the sun, point lamp or sky `name` (real or virtual) as an edit's fields do
    /// (radiosity::Emitter::apply): a sun turned ("direction"), a lamp moved ("position"),
    /// a sky turned ("rotate"), set ("sh9") or scaled, a strength set. A real light that
    /// moves is drawn as `relight render` draws the saved edit: off where it was, a virtual
    /// light where it went (movedLights(), edit_file.h). Throws std::invalid_argument for a
    /// quad, an unknown name or a field the light lacks (the light unchanged).
    void editLight(const std::string& name, const radiosity::EmitterEdit& e);
    /// The emitter of light `name` as it stands, or null (a quad, an unknown name).
    const radiosity::Emitter* emitter(const std::string& name) const;
    /// A virtual point lamp above the face picked, `offset` metres along its normal (0: 2 %
    /// of the scene's diagonal), named P1, P2, ...; its intensity gives the face the scene's
    /// mean irradiance at 10 % of the diagonal. Returns its name.
    std::string addPointLampAt(const Pick& p, double offset = 0);
    /// Moves point lamp `name` (real or virtual) above the face picked, as addPointLampAt.
    void movePointLampTo(const std::string& name, const Pick& p, double offset = 0);
    /// Moves light `name` onto the face picked: a point lamp as movePointLampTo; a virtual
    /// quad lamp's face, its shape kept, parallel to the surface 2 % of its size above it
    /// (as addLightAt puts one), turned by the least rotation that takes its normal to the
    /// surface's. With quick moves (setQuickMoves) the lamp is shown there quickly, its
    /// direct light per pixel through the quad lamp's model (DynamicRelighting::
    /// previewEmitter; movedLightFrame for the window's GPU), the rest as last solved,
    /// exactPending() until settle(); else it is inserted there again. Throws
    /// std::invalid_argument for a sun, a sky, a real quad lamp or an unknown name.
    void moveLightTo(const std::string& name, const Pick& p, double offset = 0);
    /// The direction towards a sun of azimuth `azimuth` (degrees from +x towards +y) and
    /// elevation `elevation` (degrees above the horizontal plane; the world's z is up, as
    /// in the bundled scenes), and back.
    static Vec3 sunDirection(double azimuth, double elevation);
    /// Turns the sun `name` as a drag of (du, dv) photo pixels on the image does: the
    /// azimuth by -180 degrees across the photo's width, the elevation by -90 degrees down
    /// its height (kept in [-10, 90]), each step through editLight (a "direction" edit).
    void dragSun(const std::string& name, double du, double dv);
    static void sunAngles(const Vec3& direction, double& azimuth, double& elevation);

    /// Changes whenever what the display shows changes.
    int generation() const { return generation_; }
    /// The solver light being moved quickly when it alone is shown so (a sun turned, a
    /// point lamp or virtual quad lamp moved, setQuickMoves): the window may then draw its
    /// frames on the GPU (viewer/gpu_moved_light.h); -1 otherwise.
    int movingLight() const { return movingLight_; }
    /// Changes whenever anything but that light's place changes: a movedLightFrame() holds
    /// for every frame of one epoch.
    int movingEpoch() const { return movingEpoch_; }
    /// The image as a function of the moving light's direct light alone
    /// (DynamicRelighting::movedLightFrame); nullopt where there is none or it does not hold.
    std::optional<MovedLightFrame> movedLightFrame();
    /// Where the moving light is now (its ShadowSource as shown); nullopt without one.
    std::optional<radiosity::ShadowSource> movingSource() const;
    /// Makes beforehand what every movedLightFrame() of the session shares and no edit
    /// changes (the photo's pooled reflectance per radius: 30 ms at 320 x 240, 0.5 s at
    /// 1280 x 960), so that a drag's first frame does not wait for it. Returns whether there
    /// was anything to make (a preparation with per-pixel light and its pool).
    bool prepareMovedLightFrames();
    /// The display ratio k H/D per leaf vertex; the irradiance H per leaf vertex.
    std::vector<Rgb> vertexRatios() const;
    std::vector<Rgb> vertexIrradiance() const;
    std::vector<Rgb> realRadiance() const;
    /// The virtual parts' overlay box (empty without virtual parts); casts rays.
    VirtualOverlay overlay();
    /// The relit photo in a per-pixel display (relight/pipeline/pixel_light.h; `mode`
    /// pixel, ratio-map or wen: drawsPerPixel()), drawn on the CPU as `relight render
    /// --display MODE` draws it; needs a preparation with per-pixel light
    /// (std::invalid_argument otherwise, and for a mode that does not draw per pixel).
    Image relitPerPixel(DisplayMode mode = DisplayMode::pixel);

    /// The edit as it stands, to be written to `editFile`: every real light by radiance
    /// (off: scale 0), the virtual lights, the objects (the viewer's boxes refer to the unit
    /// box OBJ boxObjFile(editFile)).
    EditFile edit(const std::filesystem::path& editFile) const;
    /// Writes edit(editFile) and, when there are boxes, the unit box OBJ beside it.
    void save(const std::filesystem::path& editFile) const;
    static std::filesystem::path boxObjFile(const std::filesystem::path& editFile);

    /// Seconds of the last update (solver and vertex values) and its parts.
    double updateSeconds() const { return updateSeconds_; }
    const FrameTimes* dynamicTimes() const { return dyn_ ? &dyn_->times() : nullptr; }
    const GeometryCache& geometryCache() const { return geometry_; }
    size_t links() const { return r_->solver->links().size(); }

  private:
    void rebuild();  ///< inserts every virtual part again, in render's order
    /// update(); with `quickOnly`, updateQuickly().
    bool apply(bool quickOnly);
    /// Every change but the frames of one light's drag ends that drag's frames
    /// (movingLight(); apply() starts them again).
    void changed() {
        ++generation_;
        movingLight_ = -1;
        ++movingEpoch_;
    }
    bool displayFinite() const;  ///< every display ratio fits a 32-bit float
    /// Puts the lights' radiances back to `before` (one per light) and throws InputError
    /// naming the lights that changed.
    [[noreturn]] void undo(const std::vector<Rgb>& before);
    bool hasVirtualParts() const {
        return lights_.size() > static_cast<size_t>(realLights_) || !objects_.empty() ||
               !removed_.empty() || anyMoved();
    }
    /// Whether real light l's emitter is away from where scene.json puts it.
    bool moved(size_t l) const;
    bool anyMoved() const;
    /// The emitters' shapes (their fields and whether they are on), to tell a change.
    std::vector<double> emitterState() const;
    LightControl* findControl(const std::string& name);
    /// update()'s quick path for lights moved (setQuickMoves); false, showing nothing,
    /// where a change is not a move of a sun or point lamp that the solution holds.
    bool previewMoves();
    /// Shows virtual quad light i's face where it now is quickly (moveLightTo); false where
    /// it cannot (quick moves off, the parts to insert again, the light off).
    bool previewFace(size_t i);
    double offsetOrDefault(double offset) const { return offset > 0 ? offset : 0.02 * diagonal_; }

    Relighting* r_;
    /// The geometry terms the solver's sessions measured (dynamic_relighting.h): a radiance
    /// change inserts the parts again, in a new DynamicRelighting, and measures no shadow
    /// ray twice. Declared before dyn_, which points at it.
    GeometryCache geometry_;
    std::unique_ptr<DynamicRelighting> dyn_;
    std::vector<LightControl> lights_;
    std::vector<ObjectControl> objects_;
    std::vector<std::string> removed_;  ///< real objects taken out
    std::vector<PlacedLamp> placed_;    ///< real lamps placed, not yet in scene.json
    std::vector<std::pair<size_t, size_t>> objectPolygons_;  ///< per object: its polygons
    std::vector<Rgb> applied_;          ///< radiances the solution was computed for
    std::vector<double> appliedState_;  ///< emitterState() the solution was computed for
    /// Per light, a copy of its emitter as last applied (null for quads), for undo().
    std::vector<std::shared_ptr<radiosity::Emitter>> appliedEmitters_;
    bool stale_ = false;           ///< the parts changed in a way only rebuild() follows
    bool exactPending_ = false;    ///< the solution is setRealRadiances' or previewMoves' quick one
    bool faceShownMoved_ = false;  ///< a lamp's face shown moved (previewFace): insert it again
    bool quickMoves_ = false;      ///< setQuickMoves
    /// Per light control: the solver's first light that rebuild() gave its light (the scene's
    /// index for a real light in place, addLight's for a moved or virtual one); -1: none.
    std::vector<int> solverLight_;
    int realLights_ = 0;
    size_t realPolygons_ = 0;
    double diagonal_ = 1;  ///< of the scene's bounding box (metres)
    /// movingLight(), movingEpoch(); the solver light previewMoves() showed last when it
    /// showed one (-1: several).
    int movingLight_ = -1, movingEpoch_ = 0, previewed_ = -1;
    int generation_ = 0, dragging_ = -1, nextLight_ = 1, nextBox_ = 1, nextLamp_ = 1;
    int nextPoint_ = 1;
    Vec3 grab_{0, 0, 0}, dragUp_{0, 0, 1};
    double updateSeconds_ = 0;
};

}  // namespace relight::viewer
