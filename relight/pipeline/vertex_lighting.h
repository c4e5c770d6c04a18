// VertexLighting: the irradiance at every leaf vertex, split by light.
//
// The vertices are radiosity::LeafMesh's: the corners of the leaf elements, and of the
// display pieces of the leaves that cover several photo pixels (a finer display than the
// solution: the light is measured at each of these points, not interpolated from the leaf).
//
// Loscos et al. 2000 display B and D at the vertices of the leaf elements (§4.4.1: "we
// modulate the original texture by a correction factor computed at the vertices of the leaf
// radiosity patches"; §5.3: glColor per vertex). Here each vertex holds, for every light l,
// its irradiance per unit radiance of l:
//   h_l(v) = pi G_l(v) + H_l,indirect(v)
// - direct: G_l(v) per point (radiosity/direct_light.h: exact form factor, shadow rays
//   where the solution's shafts are not empty), times E = pi L for L = 1;
// - indirect: final gather of the per-light responses (radiosity/light_response.h).
// Because the solution is linear in the lights' radiances L_l, the irradiance of any
// light setting is the weighted sum  H(v) = sum_l L_l * h_l(v)  (channel by channel): a
// change of colour or strength costs lights x vertices multiply-adds, no ray, no gather.
#pragma once

#include <span>
#include <vector>

#include "radiosity/direct_light.h"
#include "radiosity/final_gather.h"
#include "radiosity/leaf_mesh.h"
#include "radiosity/light_response.h"
#include "radiosity/shared_gather.h"
#include "radiosity/solver.h"

namespace relight {

struct VertexLighting {
    int lights = 0;
    std::vector<radiosity::Rgb> response;  ///< [vertex * lights + l], per unit radiance
    uint64_t rays = 0;                     ///< shadow and gather rays cast

    size_t vertexCount() const { return lights > 0 ? response.size() / lights : 0; }
    /// H(v) = sum_l radiance[l] * h_l(v) (radiosity units).
    radiosity::Rgb irradiance(int v, std::span<const radiosity::Rgb> radiance) const;
};

/// Direct light alone at every vertex, per unit radiance of each light ([v * lights + l]):
/// with the blockers (pi G_l(v)) and without them (pi G0_l(v)). Their difference per light
/// is the blocked irradiance of Loscos et al. 2000, Eq. (8), at the vertex.
struct VertexDirect {
    int lights = 0;
    std::vector<double> visible, unoccluded;
    /// The final gather's terms at every vertex, far links shared per element
    /// (radiosity/shared_gather.h): while the links stay, a later lighting of the same mesh
    /// only weighs new responses by them (no ray, no form factor). Only needed while
    /// preparing: clear them after.
    radiosity::SharedGather gather;
};

/// The first lighting of `mesh`'s vertices (built on `solver`'s hierarchy): h_l measured
/// afresh, the direct light by per-point form factors and shadow rays, the indirect light by
/// a final gather of `responses`. `direct` receives the direct light alone, with and
/// without blockers, and the gather's terms, so that the lightings that follow on the same
/// mesh and links (regatherVertexLighting) cast no ray. In parallel, deterministically
/// (each vertex draws its rays from its own index) unless `gatherRaysUntil` passes during
/// the gather: the vertices gathered after it keep their PARTIAL links' V
/// (radiosity::sharedFinalGather), a coarser indirect light within a time budget.
VertexLighting measureVertexLighting(
    const radiosity::HierarchicalSolver& solver, const radiosity::LeafMesh& mesh,
    const radiosity::LightResponses& responses, radiosity::DirectLightOptions options,
    VertexDirect& direct, const radiosity::ProgressFn& progress = {},
    radiosity::Clock::time_point gatherRaysUntil = radiosity::Clock::time_point::max());

/// The lighting again after the radiosities changed but not the geometry (new reflectances,
/// scaled light links): the direct light is `direct`'s, as measureVertexLighting measured
/// it, scaled per vertex and channel by `directScale` when it is not empty (the link
/// correction C_link of shadow removal, one per vertex); only the indirect part is gathered
/// again, by `direct`'s terms when it still has them (the links must be those they were
/// made with), else afresh.
VertexLighting regatherVertexLighting(const radiosity::HierarchicalSolver& solver,
                                      const radiosity::LeafMesh& mesh,
                                      const radiosity::LightResponses& responses,
                                      const VertexDirect& direct,
                                      std::span<const radiosity::Rgb> directScale = {});

}  // namespace relight
