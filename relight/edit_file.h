// Edit loading: "relight-edit/1" as specified in ../shared/spec/scene-format.md ("Edit").
//
// An edit is read and validated against the scene it applies to (light names must exist).
// Every problem is an InputError naming the edit file and the JSON key path, e.g.
//   edits/x.json: key "lights.Q": unknown light "Q" (the scene has A, B, C, D)
// This version applies changes to real lights only; add_lights, add_objects and
// remove_objects are type-checked here (arrays), recorded as present, and refused by
// requireLightsOnly() until a later version renders them.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "relight/scene_file.h"

namespace relight {

/// A change to one real light; exactly one of the two is set.
struct LightEdit {
    std::optional<double> scale;  ///< multiplies the nominal radiance (0 = off), >= 0
    std::optional<Rgb> radiance;  ///< sets the radiance, every channel >= 0
};

struct EditFile {
    std::filesystem::path file;               ///< as given to loadEdit(), for messages
    std::map<std::string, LightEdit> lights;  ///< by real light name (all exist in the scene)
    bool hasAddLights = false;                ///< "add_lights" present and non-empty
    bool hasAddObjects = false;               ///< "add_objects" present and non-empty
    bool hasRemoveObjects = false;            ///< "remove_objects" present and non-empty
};

/// Reads and validates an edit against the scene. Throws InputError naming the file and
/// key path (missing file, invalid JSON, duplicate key, wrong "format", unknown keys,
/// unknown light, a light entry with both or neither of scale/radiance, negative or
/// non-finite values, add_* / remove_objects that are not arrays).
EditFile loadEdit(const std::filesystem::path& file, const SceneFile& sf);

/// Radiance of every real light after the edit (same index as sf.scene.lights), given the
/// lights' nominal radiance (scene.json's, or the estimated one where scene.json says
/// "estimate"). A light the edit does not name keeps its state in the first photo: nominal
/// when it is in photos[0].lightsOn or when there is no photo, zero otherwise. A named
/// light gets scale * nominal, or the given radiance. Throws std::invalid_argument when
/// `nominal` has the wrong size or the edit names a light the scene lacks (an edit loaded
/// against another scene).
std::vector<Rgb> editedRadiance(const SceneFile& sf, const EditFile& edit,
                                const std::vector<Rgb>& nominal);

/// Throws InputError("<file>: \"add_lights\" is not supported yet ...") naming every part
/// of the edit that this version cannot render (non-empty add_lights, add_objects,
/// remove_objects); returns when the edit changes real lights only.
void requireLightsOnly(const EditFile& edit);

}  // namespace relight
