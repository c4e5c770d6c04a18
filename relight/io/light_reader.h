// One quad light as JSON ("lights" of scene.json, "add_lights" of an edit: the same fields,
// spec "Scene" and "Edit"), read and checked with messages naming the key path. Shared by
// the scene loader and the edit loader.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "radiosity/emitter.h"
#include "radiosity/rgb.h"
#include "radiosity/vec.h"
#include "relight/io/json_reader.h"

namespace relight {

struct LightJson {
    std::string name;                      ///< not empty
    std::vector<radiosity::Vec3> corners;  ///< quad: a planar convex polygon of non-zero area
    radiosity::Rgb radiance;               ///< quad: >= 0; zero where it is "estimate"
    /// quad "radiance", sun "irradiance", environment "sh9": "estimate" (strengths 0 until
    /// estimated: relight/pipeline/emittance.h, relight/pipeline/sky_estimate.h)
    bool estimate = false;
    /// A sun, point lamp or environment (radiosity/emitter.h), with its strengths; null for
    /// a quad.
    std::shared_ptr<radiosity::Emitter> emitter;
};

/// Reads a light at `path`: {"name", "type", ...} with the fields of its type
/// (docs/scene-format.md, "lights"): quad "vertices", "radiance"; sun "direction", "angle",
/// "irradiance"; point "position", "intensity"; environment "sh9" (9 RGB rows).
/// `typeRequired`: scene.json needs "type"; an edit may leave it out (a quad).
/// `estimateAllowed`: a scene's quad, sun or sky may say "estimate" (its photo calibrates
/// it); a virtual light may not, nor a point lamp. Throws InputError naming the key.
LightJson readLightJson(const jsonio::JsonReader& r, const nlohmann::json& lj,
                        const std::string& path, bool typeRequired, bool estimateAllowed);

/// An environment's "sh9": 9 rows of RGB, each finite (a coefficient may be negative).
radiosity::Sh9Rgb readSh9(const jsonio::JsonReader& r, const nlohmann::json& j,
                          const std::string& path);

}  // namespace relight
