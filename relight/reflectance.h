// Reflectance from the photo, per polygon, by inverse radiosity: the photo shows radiance
// L = rho H / pi on a Lambertian surface of irradiance H, so
//     rho_p = pi sum(L) / sum(H)      over the photo samples that see polygon p,
// with H from the radiosity solution of the lights of the photo. H itself depends on the
// reflectances (indirect light), so solve and estimate alternate. The plain fixed point
// rho <- pi L / H(rho) oscillates: where a surface gets a share s of its light indirectly,
// the error changes sign each round and shrinks only by s, and a ceiling lit only by
// bounced light (s ~ 1) never settles. Each round therefore moves half-way to the new
// estimate, rho <- (rho + pi L / H(rho)) / 2, which damps the error by (1 - s) / 2 per
// round for s in [0, 1]. Rounds stop when no reflectance moves by more than `tolerance`.
//
// This is the per-polygon version of Loscos et al. 1999, §4 (radiosity-based reflectance
// from a single image). Per-element estimation on textured surfaces comes with the photo
// pipeline. Polygons the photo does not see keep the object's `reflectance` from
// scene.json, or else take the area-weighted mean of the estimated ones. Estimates are
// clamped to [0, 0.98]: a reflectance of 1 or more would make the radiosity system
// singular (B = E / (1 - rho)).
#pragma once

#include <functional>
#include <string>

#include "radiosity/solver.h"
#include "relight/image.h"
#include "relight/item_buffer.h"
#include "relight/lighting_buffer.h"
#include "relight/scene_file.h"

namespace relight {

struct ReflectanceReport {
    int rounds = 0;
    int polygonsSeen = 0;       ///< polygons with enough photo samples
    int polygonsDefaulted = 0;  ///< reflecting polygons the photo does not see
    double lastChange = 0;      ///< largest reflectance change in the last round
};

/// `rounds` estimate/solve rounds from a solved `solver`. H per sample is the direct light
/// of `lighting` (relight/lighting_buffer.h) plus indirect light gathered from the solver
/// at up to 256 of each polygon's gather points per round. Only pixels whose samples all
/// see one reflecting polygon, with no emitting face within one pixel and finite values,
/// are used. A polygon needs `minSamples` photo samples to be estimated.
ReflectanceReport estimatePolygonReflectance(radiosity::HierarchicalSolver& solver,
                                             const SceneFile& sceneFile, const ItemBuffer& items,
                                             const LightingBuffer& lighting, const Image& photo,
                                             int rounds = 12, int minSamples = 16,
                                             double tolerance = 1e-3);

}  // namespace relight
