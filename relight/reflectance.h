// Reflectance from the photo, per polygon, by inverse radiosity: the photo shows radiance
// L = rho H / pi on a Lambertian surface of irradiance H, so
//     rho_p = pi sum(L) / sum(H)      over the photo samples that see polygon p,
// with H from the radiosity solution of the lights of the photo. H itself depends on the
// reflectances (indirect light), so solve and estimate alternate for a few rounds; the
// fixed point converges fast because the indirect share of H is small.
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
#include "relight/scene_file.h"

namespace relight {

struct ReflectanceReport {
    int rounds = 0;
    int polygonsSeen = 0;       ///< polygons with enough photo samples
    int polygonsDefaulted = 0;  ///< reflecting polygons the photo does not see
};

/// Runs solver.solve() and `rounds` estimate/solve rounds. Only pixels whose samples all
/// see one reflecting polygon, with no emitting face within one pixel and finite values,
/// are used. A polygon needs `minSamples` photo samples to be estimated.
ReflectanceReport estimatePolygonReflectance(radiosity::HierarchicalSolver& solver,
                                             const SceneFile& sceneFile, const ItemBuffer& items,
                                             const Image& photo, int rounds = 3,
                                             int minSamples = 16);

}  // namespace relight
