// One quad light as JSON ("lights" of scene.json, "add_lights" of an edit: the same fields,
// spec "Scene" and "Edit"), read and checked with messages naming the key path. Shared by
// the scene loader and the edit loader.
#pragma once

#include <string>
#include <vector>

#include "radiosity/rgb.h"
#include "radiosity/vec.h"
#include "relight/io/json_reader.h"

namespace relight {

struct LightJson {
    std::string name;                      ///< not empty
    std::vector<radiosity::Vec3> corners;  ///< a planar convex polygon of non-zero area
    radiosity::Rgb radiance;               ///< >= 0; zero where it is "estimate"
    bool estimate = false;                 ///< "radiance": "estimate"
};

/// Reads {"name", "type", "vertices", "radiance"} at `path`. `typeRequired`: scene.json
/// needs "type" ("quad", the only type relight lights with; the format's "sun", "point" and
/// "environment" are refused, naming the light and its type); an edit may leave it out.
/// `estimateAllowed`: a scene light may say "estimate" (its photo calibrates it); a virtual light
/// may not. Throws InputError naming the key.
LightJson readLightJson(const jsonio::JsonReader& r, const nlohmann::json& lj,
                        const std::string& path, bool typeRequired, bool estimateAllowed);

}  // namespace relight
