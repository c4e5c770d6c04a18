// Confidence in the photo's reflectance at each leaf vertex (Loscos et al. 1999, §4.1-4.3),
// and the model's reflectance to lean on where it is low.
//
// The ratio display reads the reflectance off the photo: pixel = T k B/D is the photo's
// reflectance pi T k / D times the new radiosity B / pi (Loscos et al. 1999, Eq. (2) and
// (4)). That reading is only as good as D, the model of the photo's light. Where the photo's
// lamps shine straight on a point the model is good (exact form factors, shadow rays); where
// they do not (their light blocked, the point lit by indirect light alone) the model's D is
// coarse, and light that the edit brings there (a virtual lamp, a lamp that was off) is
// multiplied by whatever error D has. The 1999 paper sets its confidence from the same
// observation, "initially, confidence K_i is set equal to V_i, since we have less confidence
// in regions in shadow", V_i the visibility of the photo's light source.
//
// Here, per vertex:
//   V = sum_l |L_l| G_l(visible) / sum_l |L_l| G_l(unoccluded)   over the photo's lamps
//       (brightest channel of their radiance; 0 where no lamp of the photo faces the point)
//   K = clamp((V - vLow) / (vFull - vLow), 0, 1)
// K is 1 in full light, 0 in umbra, and falls across penumbrae, where the visibility of a
// point depends most on the model's exact geometry (the paper's reason to widen low
// confidence near shadow boundaries). K is dimensionless.
#pragma once

#include <span>
#include <vector>

#include "radiosity/leaf_mesh.h"
#include "radiosity/rgb.h"
#include "radiosity/scene.h"
#include "relight/pipeline/vertex_lighting.h"

namespace relight {

struct ConfidenceOptions {
    /// V at or below which K = 0, and at or above which K = 1 (dimensionless). Chosen by
    /// accuracy on the bundled scenes' edits with virtual lights or lamps off in the photo
    /// (bench/RESULTS.md, 2026-11-25: of 0-0.3, 0.2-0.7, 0.6-0.99 and 0.9-0.999, the only
    /// ramp better than the ratio display or within 0.0012 of it on each): a point that sees
    /// less than a fifth of the photo's lamps is left to the model, one that sees more than
    /// 70 % to the photo.
    double vLow = 0.2, vFull = 0.7;
};

/// K per vertex from the direct light that measureVertexLighting() recorded (visible and
/// unoccluded G per vertex and light) and the photo's light radiances.
std::vector<float> vertexConfidence(const VertexDirect& direct,
                                    std::span<const radiosity::Rgb> photoRadiance,
                                    const ConfidenceOptions& options = {});

/// The model's reflectance per vertex: the mean of the leaf reflectances (from their
/// texture) over the vertex's surface (the polygons joined within 25 degrees, surfaceOf:
/// a wall a reconstruction cut into triangles is one), each leaf weighted by its area and
/// its confidence. The merge is the 1999 paper's, Eq. (3), R = sum K_i R_i / sum K_i, taken
/// over the surface's well-lit parts instead of over several photos: a dim leaf's own
/// estimate, which divides by the model's light where the model is least sure, does not
/// count. A surface with no trusted leaf keeps its polygon's estimate.
/// `surface`: surfaceOf(scene), one per polygon.
std::vector<radiosity::Rgb> vertexModelReflectance(const radiosity::LeafMesh& mesh,
                                                   const radiosity::Scene& scene,
                                                   std::span<const int> surface,
                                                   std::span<const float> confidence);

}  // namespace relight
