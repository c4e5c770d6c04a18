// Edit loading: "relight-edit/1" as specified in docs/scene-format.md ("Edit").
//
// An edit is read and validated against the scene it applies to (light names must exist).
// Every problem is an InputError naming the edit file and the JSON key path, e.g.
//   edits/x.json: key "lights.Q": unknown light "Q" (the scene has A, B, C, D)
// Every part is read and checked here: real-light changes, virtual lights (their emitting
// face checked like a scene light's), virtual objects (OBJ, PLY or glTF read relative to the edit
// file, faces checked and repaired like the scene's, placed by the transform) and removals
// (removable objects of the scene).
#pragma once

#include <array>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "radiosity/emitter.h"
#include "relight/io/obj_reader.h"
#include "relight/io/scene_file.h"

namespace relight {

/// A change to one real light. A quad: exactly one of scale and radiance is set. A sun,
/// point lamp or sky (radiosity/emitter.h): `emitter` holds the edit's fields (scale,
/// irradiance, intensity, sh9, direction, position, rotate), checked against the light;
/// `scale` repeats its scale.
struct LightEdit {
    std::optional<double> scale;  ///< multiplies the nominal radiance (0 = off), >= 0
    std::optional<Rgb> radiance;  ///< sets the radiance, every channel >= 0
    std::optional<radiosity::EmitterEdit> emitter{};
    /// The scene's light that `emitter` edits (as scene.json has it): it names the edit's
    /// fields when the edit is written (Emitter::strengthKey, edit_writer.h).
    std::shared_ptr<const radiosity::Emitter> light{};
    /// Whether it moves its light (a sun's direction, a point lamp's position): what the
    /// light gives then changes in shape, not only in strength.
    bool moves() const { return emitter && (emitter->direction || emitter->position); }
};

/// A virtual light ("add_lights": the fields of a scene light; the radiance must be given).
struct VirtualLight {
    std::string name;
    std::vector<radiosity::Vec3> corners;  ///< quad: a planar convex polygon of non-zero area
    Rgb radiance;                          ///< quad: photo units, >= 0
    /// A sun, point lamp or sky (no corners), with its strengths; null for a quad.
    std::shared_ptr<const radiosity::Emitter> emitter{};
};

/// A Blinn-Phong specular term on a virtual object (an engine extension of the edit format:
/// "specular": {"ks": [r, g, b], "shininess": s}; relight/dynamic/specular.h draws it).
struct Specular {
    Rgb ks;                 ///< every channel >= 0: the lobe's share of the light at its peak
    double shininess = 32;  ///< the exponent s > 0
};

/// A virtual object ("add_objects"), its faces in world space.
struct VirtualObject {
    std::string name;
    std::filesystem::path file;  ///< its geometry file, resolved against the edit's folder
    Rgb reflectance;             ///< every channel in [0, 1)
    std::array<std::array<double, 4>, 4> transform{};  ///< row-major, as in the file
    /// Checked, repaired faces after the transform (object index 0, reflectance set).
    std::vector<radiosity::Polygon> polygons;
    /// Its specular term added on top of the relit image ("specular"), or none (Lambertian).
    std::optional<Specular> specular{};
};

struct EditFile {
    std::filesystem::path file;               ///< as given to loadEdit(), for messages
    std::map<std::string, LightEdit> lights;  ///< by real light name (all exist in the scene)
    std::vector<VirtualLight> addLights;
    std::vector<VirtualObject> addObjects;
    std::vector<std::string> removeObjects;  ///< removable objects of the scene
    std::vector<std::string> warnings;       ///< repairs of the virtual objects' faces
};

/// Reads and validates an edit against the scene. Throws InputError naming the file and
/// key path (missing file, invalid JSON, duplicate key, wrong "format", unknown keys,
/// unknown light, a light entry with both or neither of scale/radiance, negative or
/// non-finite values; a virtual light with a duplicate name, a degenerate or zero-area
/// face or no radiance; a virtual object whose file is missing or has no faces, whose
/// reflectance is not below 1, whose transform is not affine or is singular; a removal
/// naming an object the scene lacks or does not mark removable; a scale that overflows the
/// light's scene.json radiance, as editedRadiance() does).
EditFile loadEdit(const std::filesystem::path& file, const SceneFile& sf);

/// loadEdit() with the edit's text read from `editJson` rather than from `file`, which
/// still names it in messages and is where virtual objects' files are resolved from. Lets
/// the JSON reading be driven from memory (fuzz/).
EditFile parseEdit(std::istream& editJson, const std::filesystem::path& file, const SceneFile& sf);

/// Radiance of every real light after the edit (same index as sf.scene.lights), given the
/// lights' nominal radiance (scene.json's, or the estimated one where scene.json says
/// "estimate"). A light the edit does not name keeps its state in the first photo: nominal
/// when it is in photos[0].lightsOn or when there is no photo, zero otherwise. A named
/// light gets scale * nominal, or the given radiance. Throws InputError naming the edit's
/// file and key ("lights.A.scale") when scale * nominal is not finite (the relit image would
/// not be), and std::invalid_argument when `nominal` has the wrong size or the edit names a
/// light the scene lacks (an edit loaded against another scene). A sun, point lamp or sky
/// (radiosity/emitter.h) named by the edit gets the strengths of its emitter edited
/// (scale, irradiance, intensity, sh9, rotate), or 0 when the edit moves it (movedLights()).
std::vector<Rgb> editedRadiance(const SceneFile& sf, const EditFile& edit,
                                const std::vector<Rgb>& nominal);

/// The lights that `edit` moves (a sun's direction, a point lamp's position: LightEdit::moves)
/// at their new places, with their edited strengths (from scene.json's), as virtual lights:
/// a moved light is drawn as the light switched off where it was (editedRadiance gives its
/// components 0) and a virtual light where it went, so that its new shadows and bounces are
/// measured as a virtual light's (relight/dynamic/dynamic_relighting.h).
std::vector<VirtualLight> movedLights(const SceneFile& sf, const EditFile& edit);

/// Places an object's geometry as loadEdit does: v.transform applied to `obj`'s positions
/// (faces turned back under a mirroring transform), faces checked and repaired with
/// v.name and v.reflectance, into v.polygons (empty when no usable face remains). The
/// repairs' messages go to `warnings`. The viewer places its boxes with it, so that a
/// saved edit loads to the same polygons.
void placeObject(VirtualObject& v, ObjFile obj, std::vector<std::string>& warnings);

}  // namespace relight
