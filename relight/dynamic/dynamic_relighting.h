// DynamicRelighting: virtual lights and virtual objects in the relit photo, and objects
// moved interactively (Loscos, Drettakis & Robert 2000, §5.1-5.2; Loscos et al. 1999,
// §5.2), over a prepared Relighting.
//
// The solver inserts each virtual part (radiosity/solver.h, insertObject: a cluster under
// the root, the links whose shafts it cuts get their visibility again, its own links by the
// refinement oracle, links from a virtual light forced down to leaf elements). The display
// is then the prepared ratio display with the vertex irradiance changed where the edit
// changes it:
//   H(v) = sum_l L_l h_l(v)                          the photo's lights at the edit's radiances
//        + sum_l L_l C_link(v) pi (G'_l(v) - G_l(v))  direct light the objects now block, at
//                                                     the corners of the leaves whose light
//                                                     links an object's shaft cut
//        + sum_k L_k pi G_k(v)                       direct light of the virtual lights
//        + H_ind(leaf, now) - H_ind(leaf, before)     indirect light as the solver's leaves
//                                                     gather it, Gouraud at the vertices
// and pixel = T * k H/D (Eq. (3)) as for a light edit: new shadows fall on real surfaces
// through B/D. In the projected bounding boxes of the virtual parts only, the camera's
// samples are cast again (the item buffer's update): a sample that now sees a virtual
// object shows rho H / pi of the object's leaf vertices (its own radiosity), one that sees a
// virtual light's face shows its radiance; the pixel's other samples keep the ratio display.
// The per-pixel display (DisplayMode::pixel, relight/pipeline/pixel_light.h) takes the
// direct light per pixel instead (Loscos et al. 1999, §5.2): each virtual light's at every
// sample, every light's again at the pixels with a sample on a leaf whose light links an
// object's shaft cut (pixelDirect()), and the indirect change interpolated at each pixel
// (a light's change gathered at the vertices by rays, as the preparation gathered the
// photo's: radiosity::rayGatherIndirect, Relighting::gatherSide). An insertion splits the
// scene's leaves under its new shadows (radiosity::SolverOptions::newShadowSplits, down to
// the display's pieces; Loscos et al. 2000, Fig. 24(a)); a split leaf is displayed as one,
// with the mean of what its leaves gather.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "radiosity/leaf_mesh.h"
#include "radiosity/solver.h"
#include "radiosity/visibility.h"
#include "relight/dynamic/object_removal.h"
#include "relight/dynamic/specular.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/pipeline/pixel_light.h"
#include "relight/relighting.h"

namespace relight {

/// Where the time of the last update and frame went (seconds).
struct FrameTimes {
    double shafts = 0;      ///< walking the link tree's shafts
    double visibility = 0;  ///< visibility rays of the cut links
    double links = 0;       ///< the object's links (and the removal at the old place)
    double radiosity = 0;   ///< gather/push-pull
    double vertices = 0;    ///< direct light at the changed vertices, indirect change
    double display = 0;     ///< item buffer in the boxes, ratio display, virtual surfaces
    double fill = 0;        ///< a removed object's pixels: rays, texture synthesis, direct light
    double total() const {
        return shafts + visibility + links + radiosity + vertices + display + fill;
    }
};

/// What the virtual parts show in their projected bounding box, per pixel of the box: the
/// share of the pixel's samples that still see the photo's surfaces (they keep the ratio
/// display) and the radiance the other samples add (virtual objects' rho H / pi, virtual
/// light faces), already divided by the samples per pixel:
///   pixel = realShare * ratio display + added.
/// Pixels outside the box are the ratio display's alone.
struct VirtualOverlay {
    int x0 = 0, y0 = 0, width = 0, height = 0;  ///< the box in pixels (empty: nothing)
    std::vector<float> rgba;                    ///< per box pixel: added r, g, b; realShare
    bool empty() const { return width <= 0 || height <= 0; }
};

/// Applies an overlay to a ratio-display image (same size as the photo).
void applyOverlay(Image& img, const VirtualOverlay& overlay);

/// What successive DynamicRelighting instances over one Relighting share (a viewer session:
/// a radiance change with virtual parts inserts them again, in a new instance, so that the
/// image equals `relight render`'s of the edit; viewer/session.h): the values that depend on
/// the scene's geometry only, never on a radiance. A shadow ray's stream is seeded by the
/// point and the lamp's face, not by the solver's links (radiosity/direct_light.cpp), so the
/// direct light's geometry term G of a point is the same in every solver state with the same
/// geometry: taken from here it is what the instance would measure again. Each entry is
/// kept for the geometry `key` it was measured in (the virtual parts' faces, the objects
/// taken out, the emitters' shapes) and dropped when the geometry changes.
struct GeometryCache {
    /// Per item-buffer sample: its leaf of the prepared scene (-1: none); the prepared
    /// hierarchy's, the same for every edit.
    std::vector<int> sampleLeaf;
    std::vector<double> key;  ///< the geometry the entries below hold for (empty: none)
    size_t lights = 0;        ///< lights of that geometry (the stride of the entries)
    /// Per pixel and light: the per-pixel display's pi Gbar (pixelDirect()); per pixel the
    /// first light measured, plus one (0: not measured).
    std::vector<float> pixelDirect;
    std::vector<int> pixelFrom;
    /// Per leaf vertex of the scene and light: G at its inside point (the vertices' direct
    /// light); per vertex the first light measured, plus one (0: not measured).
    std::vector<double> vertexG;
    std::vector<int> vertexFrom;
    uint64_t pixelHits = 0, vertexHits = 0;  ///< entries taken from here (for tests, benches)
    /// The prepared photo's pooled reflectance per radius (pipeline/pixel_light.h,
    /// pooledByRadius), which no edit changes (kept whatever the geometry): made by the
    /// first movedLightFrame(), 30 ms at 320 x 240, and read by the others.
    std::shared_ptr<const std::vector<float>> pooledByRadius;
};

/// The per-pixel display of a DynamicRelighting as a function of one sun's, point lamp's or
/// one-faced quad lamp's direct light alone (DynamicRelighting::movedLightFrame): for a
/// display that measures that light itself at every frame while the light moves (the
/// viewer's GPU frames, viewer/gpu_moved_light.h). With g the light's unit irradiance at
/// each pixel's receiver (`receivers`: relight/dynamic/quick_light.h, quickReceivers), per
/// pixel and channel
///   image = scale * out(g) + offset     (out: pipeline/pixel_light.h, evalPixelLightTerms)
/// `scale` is 0 where the per-pixel display does not draw (`offset` then holds the ratio
/// display's value), the overlay's realShare in the virtual parts' box (`offset` its added
/// radiance), else 1 (and `offset` 0).
struct MovedLightFrame {
    PixelLightTerms terms;
    std::vector<float> receivers;      ///< 6 per pixel: point, normal (0: no receiver)
    std::vector<float> scale, offset;  ///< 3 per pixel
    radiosity::ShadowSource source;    ///< the light as it stands (shownSource)
    /// The photo's camera and the overlay's samples per side of a pixel. A lamp's face
    /// (ShadowSource::Kind::face) is not in `offset`: the display draws it over the share of
    /// each pixel it covers in front of what the pixel's centre shows (`surface`), its
    /// radiance L_m on its front, black on its back (relight/dynamic/quick_light.h,
    /// faceCoverage).
    Camera camera;
    int samplesPerSide = 1;
    /// A face: per pixel, 3 floats, the first point the camera's ray through the pixel's
    /// centre meets in the solver's scene, the virtual parts in and the face where it was
    /// passed (metres; 1e6 m out where it meets nothing). Empty for a point or direction.
    std::vector<float> surface;
    /// What casts its shadows: the solver's polygons that its visibility holds (the virtual
    /// parts in, the objects taken out not), as triangles, 9 floats each (metres).
    std::vector<float> blockers;
};

class DynamicRelighting {
  public:
    /// `r` must come from prepareRelighting() and outlive this object, which changes its
    /// solver (virtual parts are inserted into it) until it is destroyed: the destructor
    /// removes them and restores the solver's radiances, so sessions can follow each other.
    /// `radiance`: the real lights' radiance for the edit (editRadiance()), one per scene light.
    /// `cache` (optional, outliving this object): the geometry terms measured by earlier
    /// instances over `r`, taken where the geometry is the same and filled with what this
    /// one measures.
    DynamicRelighting(Relighting& r, std::span<const Rgb> radiance, GeometryCache* cache = nullptr);
    ~DynamicRelighting();

    /// Inserts a virtual light; returns its index among the solver's lights.
    int addLight(const VirtualLight& light);
    /// Inserts a virtual object (its polygons in world space, VirtualObject::polygons). Its
    /// specular term (VirtualObject::specular), if any, is added to its samples in overlay()
    /// (relight/dynamic/specular.h; ../shared/seeds/000, §6).
    void addObject(const VirtualObject& object);
    /// Sets the specular term of the virtual objects named `name` (none: Lambertian). It
    /// changes what overlay() adds on them, not the radiosity: no update. Returns how many
    /// objects it set.
    int setObjectSpecular(const std::string& name, const std::optional<Specular>& specular);
    /// Moves the object added last to new world-space polygons (same faces).
    void moveLastObject(std::vector<radiosity::Polygon> polygons);
    /// Takes the scene's object `name` out (Loscos et al. 1999, §5.3): out of the solver
    /// (radiosity::HierarchicalSolver::removeRealObject), its shadows gone through the display
    /// as any change of light, and its pixels filled (relight/dynamic/object_removal.h; the
    /// overlay replaces them). Throws std::invalid_argument when the scene has no such
    /// object or it is out already.
    void removeObject(const std::string& name);
    /// How the next removal synthesises the hidden surfaces' texture (rectified_fill.h):
    /// non-parametric sampling by default, OpenCV's inpainting for comparison (bench/).
    void setSurfaceSynthesis(SurfaceSynthesis s) { synthesis_ = s; }
    /// A quick change of the real lights' radiances (one per real light; a colour or
    /// strength slider), for the frames while it moves: the links and subdivision as they
    /// are (refined at the radiances the parts were inserted at), gather/push-pull again,
    /// the direct light recombined from its geometry terms (the GeometryCache's: no shadow
    /// ray), the indirect light's "before" by linearity (the prepared light responses,
    /// relight/relighting.h). Not `relight render`'s image of the edit: the refinement oracle
    /// weighs B, so inserting the parts at the new radiances may link and split otherwise;
    /// insert them again (a new instance) for that. Needs a cache (constructor) and only
    /// virtual objects (no virtual lamp, object taken out, sun, point lamp or sky: their
    /// light is gathered or measured again per change); returns false, changing nothing,
    /// otherwise.
    bool setRealRadiances(std::span<const Rgb> radiance);
    /// A quick look at a sun, point lamp or quad lamp moved (a drag, a slider), for the
    /// frames while it moves: light `light` (the solver's first light of a sun, point lamp or
    /// sky; or a lamp of faces, with `moved` a quad lamp, radiosity::makeQuadLamp, whose
    /// polygons are the light's own, so that they do not block it; real or virtual, as this
    /// instance holds it) shown as `moved` has it in the per-pixel displays' direct light
    /// (a lamp's face drawn where it now is, overlay()), measured at every pixel through the
    /// light model
    /// (radiosity::Emitter::unitIrradiance) with one shadow ray from one camera sample per
    /// pixel (quickPixelLight(), relight/dynamic/quick_light.h). The solver, its links, the
    /// vertices and the indirect light stay as they are (the light's indirect share is the
    /// last exact solution's), as do the pixels the per-pixel display leaves to the ratio
    /// display and the virtual parts' overlay. Not `relight render`'s image of the edit: a
    /// new instance with the light moved is (the viewer's Session::settle). `moved` must
    /// have the light's components; its strengths are not read (the light's radiance
    /// stays). A quad's soft shadow is then one ray's: 0 or 1 at each pixel of its penumbra.
    /// Throws std::invalid_argument for a lamp of faces shown as another type than a quad,
    /// or a component count that differs.
    void previewEmitter(int light, const radiosity::Emitter& moved);
    /// The image as it stands as a function of light `light`'s direct light alone
    /// (MovedLightFrame): render(DisplayMode::pixel) is scale * out(g) + offset with g the
    /// light's quick measurement (previewEmitter()'s, or the preparation's where it was not
    /// moved), to float rounding. nullopt where that form does not hold: a merged
    /// reflectance (several photos), an object dragged (previewLastObject), a light that is
    /// not one point, direction or face (Emitter::shadowSource: a lamp of several faces, a
    /// sky), no per-pixel light. The light's own faces are not among the frame's blockers.
    std::optional<MovedLightFrame> movedLightFrame(int light);
    /// Light `light` as one point, direction or face where it is shown (previewEmitter()'s
    /// place while it moves; a lamp of one face as radiosity::makeQuadLamp models it); nullopt
    /// for a light without one (Emitter::shadowSource).
    std::optional<radiosity::ShadowSource> shownSource(int light) const;
    /// Whether a light is shown by previewEmitter() (the image is a quick one).
    bool previewing() const { return !previews_.empty() || objectPreview_ != nullptr; }
    /// A quick look at the object added last moved to `polygons` (same faces, world space),
    /// for the frames of a drag (the viewer's box drag; issue 32): bounded work per frame,
    /// no link or visibility work in the solver. The first call takes the object out of the
    /// solver (removeLastObject: the scene and its light as without it, exactly, one
    /// update), keeping what its faces gathered (their mean indirect irradiance). Each call
    /// then shows, in the per-pixel displays (render(), pixelDirect()):
    ///   - its shadows: each pixel's direct light of every light times the share of it that
    ///     the object at `polygons` lets through, measured at one camera sample with
    ///     kPreviewRays shadow rays per lamp face against the object alone (its own Embree
    ///     scene; quickTransmission(), quick_light.h), at the pixels whose rays can meet
    ///     its bounding sphere only; exact where the object's shadow and the scene's own do
    ///     not overlap within a pixel, as independent shares elsewhere;
    ///   - the object itself over the image: rho (direct + indirect) / pi, its direct light
    ///     from kPreviewRays rays per lamp face against the scene (it does not shade itself:
    ///     exact for a convex object) at one point per pixel and face, its indirect light
    ///     the faces' gathered mean as last solved (before the drag);
    ///   - the indirect light of the rest as the scene has it without the object (it moves:
    ///     no light bounced off or blocked by it at either place).
    /// Not `relight render`'s image: a new instance with the object at its place is (the
    /// viewer's Session::settle). Returns false, changing nothing, where it does not apply
    /// (no object added last, a lamp's face, a real object taken out, a specular term on the
    /// object, another face count); then moveLastObject() is the exact move. While it is on,
    /// the other edits throw std::logic_error: insert the parts again (a new instance).
    bool previewLastObject(const std::vector<radiosity::Polygon>& polygons);
    bool previewingObject() const { return objectPreview_ != nullptr; }
    /// Shadow rays per lamp face of previewLastObject()'s frames.
    static constexpr int kPreviewRays = 16;
    /// Undoes the last change: removes the virtual part added last (object or light), or
    /// brings back the real object taken out last.
    void removeLast();
    /// The pixels of the objects taken out, as the overlay fills them (empty: none).
    const RemovedRegion& removedRegion() const { return removed_; }

    /// The relit photo as it stands: the display of vertexDisplay(mode) with overlay(); for
    /// DisplayMode::pixel, the per-pixel display (relight/pipeline/pixel_light.h) with the
    /// direct light of pixelDirect() and the vertices' indirect change, then overlay(). The
    /// pixel mode needs a preparation with per-pixel light (std::invalid_argument otherwise).
    Image render(DisplayMode mode = DisplayMode::ratio);
    /// The per-pixel display's direct light as the edit stands, pi Gbar per pixel and light
    /// (the real lights, then the virtual ones; Loscos et al. 1999, §5.2: "the direct light
    /// is recomputed per pixel in the changed region"): the photo's, measured again at the
    /// pixels with a sample on a leaf whose light links a virtual part's shaft cut, and for
    /// each virtual light at every pixel. Updated since the last call only.
    std::span<const float> pixelDirect();
    /// Its two parts, for a display that does the per-pixel work itself (the viewer's GPU):
    /// the display ratio k H/D per leaf vertex of the scene (relight/prepared.h, vertexRatio;
    /// the ratio display) and the virtual parts' overlay (casts the camera's samples in their
    /// box again).
    std::vector<Rgb> vertexRatios() const;
    /// The display values per vertex for `mode` (relight/prepared.h): the light the virtual
    /// parts change counts as fresh light, weighed by the photo's confidence.
    VertexDisplay vertexDisplay(DisplayMode mode) const;
    /// `movedFaces`: the lamps' faces that previewEmitter() shows moved are drawn where
    /// they now are (where they were, the ray passes them); false: drawn nowhere (the
    /// viewer's GPU frames draw them, movedLightFrame).
    VirtualOverlay overlay(bool movedFaces = true);
    /// Irradiance H per leaf vertex of the scene, with every change the edit makes.
    std::vector<Rgb> vertexIrradiance() const;
    /// Radiance of the real lights (scene order), then of the virtual lights.
    std::span<const Rgb> radiance() const { return radiance_; }
    int realLights() const { return realLights_; }

    const FrameTimes& times() const { return times_; }
    const radiosity::DynamicUpdate& lastUpdate() const { return last_; }

  private:
    /// pixelDirect(), the column of a light previewEmitter() shows left unmeasured (0) when
    /// it is light `unmeasured`: what movedLightFrame() reads, which skips that column.
    std::span<const float> pixelDirectExcept(int unmeasured);
    void afterUpdate(const radiosity::DynamicUpdate& u, bool allVertices);
    void refreshDirect(const std::vector<int>& vertices, bool virtualOnly);
    void refreshIndirect(bool full);  ///< and the virtual objects' surfaces
    /// What may block the preparation's gather rays (Relighting::vertexRayHits) since: the
    /// added lamps' faces (polygon indices); nullopt where an object was put in or taken out and
    /// they do not hold.
    std::optional<std::vector<int>> addedLampFaces() const;
    /// Per node: what it reflects (B - E) now less before any virtual part.
    std::vector<Rgb> reflectedChange() const;
    /// The final gather (or, byRays, the gather by rays) of `change` at every leaf vertex, or
    /// at the vertices `only` lists (the others 0).
    std::vector<Rgb> gatherChangeAtVertices(std::span<const Rgb> change, bool byRays = false,
                                            const std::vector<int>* only = nullptr) const;
    /// Finishes the final gather of the last full update (gatherDelta_) at the vertices
    /// `only` lists, or at every vertex still waiting (null). Called before the solver
    /// changes again (the gather reads its links) and before indirect_ is read.
    void completeVertexGather(const std::vector<int>* only = nullptr) const;
    /// vertexIrradiance() as indirect_ stands (a vertex still waiting for its gather lacks it).
    std::vector<Rgb> irradianceAsItStands() const;
    /// The vertices of the pixels the per-pixel display leaves to the ratio display (lamps'
    /// faces, edges; relight/pipeline/pixel_light.h, shownPerPixel), each once.
    const std::vector<int>& ratioPixelVertices();
    /// The indirect light at a removed region's box pixel and its sample i (object_removal.h).
    Rgb removedIndirect(const RemovedRegion& gone, size_t pixel, size_t i) const;
    /// indirectPixel_ where the per-pixel display has its own, indirect_ otherwise.
    const std::vector<Rgb>& pixelIndirect() const {
        return indirectPixel_.empty() ? indirect_ : indirectPixel_;
    }
    void markChangedLeaves(const std::vector<int>& leaves);
    /// unitSource_ (see there), from the prepared light responses.
    void makeUnitSources();
    /// The shared cache, emptied first when the geometry changed since it was filled (null:
    /// none). Called before each measurement of the direct light.
    GeometryCache* geometryCache();
    std::vector<double> geometryKey() const;
    std::vector<Rgb> indirectPerNode() const;

    Relighting& r_;
    radiosity::HierarchicalSolver& solver_;
    GeometryCache* cache_ = nullptr;
    int realLights_ = 0;
    size_t realPolygons_ = 0;    ///< polygons below this index are the scene's
    size_t realNodes_ = 0;       ///< nodes below this id are the scene's
    std::vector<Rgb> radiance_;  ///< real lights, then virtual lights (solver order)
    /// The solver's light and radiances before the session (restored at its end).
    radiosity::HierarchicalSolver::LightState prepared_;
    std::vector<Rgb> base_;           ///< per vertex: sum_l L_l h_l(v)
    std::vector<Rgb> realDirect_;     ///< per vertex: the real lights' direct light change
    std::vector<Rgb> virtualDirect_;  ///< per vertex: the virtual lights' direct light
    std::vector<Rgb> indirect0_;      ///< per node: H_ind before any virtual part
    /// For setRealRadiances, per scene node and real light, before any virtual part and per
    /// unit radiance of the light: what the node reflects (reflectedBy) and H_ind
    /// (indirectPerNode), so that both follow a radiance change by linearity. Made with a
    /// cache only (a viewer session); empty otherwise.
    std::vector<Rgb> unitReflected_, unitIndirect_;
    /// The scene's vertices whose direct light an object changed (refreshDirect), each once.
    std::vector<int> directVertices_;
    std::vector<char> directSeen_;
    mutable std::vector<Rgb> indirect_;  ///< per vertex: H_ind(now) - H_ind(before)
    std::vector<Rgb> reflected0_;        ///< per scene node: what it reflected (B - E) before
    // Per vertex: the final gather (radiosity/final_gather.h) of the indirect light's change
    // at the last full update (a light added or removed), and the leaf-level change at that
    // time; objects moved since add only their leaf-level change.
    // With per-pixel light the gather waits until a vertex display needs it (the per-pixel
    // display has its own by rays, gatherDeltaRays_): gatherChange_ is the change it gathers,
    // gatherWaiting_ flags the vertices not gathered yet; indirect_ holds their gather as 0.
    mutable std::vector<Rgb> gatherDelta_;
    std::vector<Rgb> leafAtFull_;
    mutable std::vector<Rgb> gatherChange_;
    mutable std::vector<char> gatherWaiting_;
    std::vector<int> ratioPixelVertices_;
    bool ratioPixelVerticesMade_ = false;
    // The same by rays (radiosity::rayGatherIndirect), for the per-pixel display when the
    // preparation gathered the photo's indirect light by rays (Relighting::gatherSide): each
    // display's change is measured as its photo light was, so that a gather's own error
    // divides out. indirectPixel_ is then the per-pixel display's indirect_.
    std::vector<Rgb> gatherDeltaRays_, indirectPixel_;
    std::unique_ptr<radiosity::LeafMesh> objectMesh_;  ///< virtual objects' leaf corners
    /// Per object of the solver's scene: the specular term of a virtual object that has one.
    std::vector<std::optional<Specular>> objectSpecular_;
    /// The specular radiance L_s of overlay sample `sample` seeing polygon `polygon` at
    /// `point` along the camera ray `dir`; 0 without a specular term.
    Rgb specularAt(const SpecularLights* lights, int polygon, const radiosity::Vec3& point,
                   const radiosity::Vec3& dir, uint64_t sample) const;
    std::vector<Rgb> objectRadiance_;  ///< per object vertex: rho H / pi
    // The per-pixel display (pixelDirect()): the scene leaf of each item-buffer sample (-1:
    // none), the leaves whose light changed since the last call and since the photo, and the
    // direct light per pixel with its number of lights.
    std::vector<int> sampleLeaf_;
    std::vector<char> leafPending_, leafEver_;
    std::vector<float> pixelDirect_;
    /// The lights previewEmitter() shows moved: the first solver light, its components and
    /// their quick direct light per pixel ([pixel * count + c]); pixelShown_ is pixelDirect_
    /// with those columns replaced (what pixelDirect() returns while there are any).
    struct Preview {
        int light = 0, count = 0;
        std::vector<float> direct;  ///< empty until pixelDirect() measures it
        std::shared_ptr<const radiosity::Emitter> emitter;  ///< the light as shown
    };
    std::vector<Preview> previews_;
    /// previewLastObject()'s object: where it is shown, its faces' reflectance and indirect
    /// irradiance (from before the drag), its own Embree scene (group 0), and per pixel and
    /// light the share of the direct light it lets through.
    struct ObjectPreview {
        std::vector<radiosity::Polygon> polygons;
        std::vector<Rgb> rho, indirect;
        std::unique_ptr<radiosity::Visibility> vis;
        int group = -1;
        std::vector<float> transmission;
    };
    std::unique_ptr<ObjectPreview> objectPreview_;
    /// The moved object over the image (previewLastObject): its pixels' share and radiance.
    VirtualOverlay previewOverlay() const;
    /// A lamp of one face that previewEmitter() shows moved: its solver polygon, where it
    /// was, and its corners now.
    struct MovedFace {
        int light = -1, polygon = -1;
        std::vector<Vec3> corners;
    };
    std::vector<MovedFace> movedFaces() const;
    /// MovedLightFrame::surface for light `light`.
    std::vector<float> faceOccluders(int light) const;
    /// Throws std::logic_error while an object is shown moved (`what`: the edit refused).
    void noPreview(const char* what) const;
    /// previewLastObject()'s first call: the checks, the faces' indirect light, the object
    /// out of the solver, its own Embree scene.
    bool startObjectPreview(const std::vector<radiosity::Polygon>& polygons);
    /// Per object vertex (objectMesh_): the indirect irradiance its leaves gather.
    std::vector<Rgb> objectIndirect_;
    std::vector<float> pixelShown_;
    size_t pixelLights_ = 0;
    /// The real objects taken out: their pixels (object_removal.h), and the mask's growth.
    RemovedRegion removed_;
    std::vector<int> regionObjects_;  ///< the objects removed_ was built for
    int maskGrowth_ = 1;
    SurfaceSynthesis synthesis_ = SurfaceSynthesis::exemplar;
    /// Per vertex and real light: the indirect part of its response (indirectAt).
    std::vector<Rgb> ownIndirectParts_;
    std::span<const Rgb> indirectParts_;
    void refreshRemoved(const radiosity::DynamicUpdate& u, bool allLights);
    /// The indirect irradiance at a point of a scene leaf, as the edit stands.
    Rgb indirectAt(int leaf, const radiosity::Vec3& x) const;
    FrameTimes times_;
    radiosity::DynamicUpdate last_;
};

}  // namespace relight
