// Real-shadow removal (Loscos, Drettakis & Robert 2000, §4.3-4.5, Fig. 13), with the
// correction factors computed at the leaf vertices as the paper does (§4.4.1: "we modulate
// the original texture by a correction factor computed at the vertices of the leaf
// radiosity patches").
//
// §4.3 Shadow regions. Per leaf and light, the visibility V = F V / F of its light links
// (at the leaves after refinement). A leaf is occluded when a light that gives it at least
// `minShare` of its unoccluded direct light is not fully visible; lit when every such light
// is. The frontier is the lit leaves with an occluded edge neighbour (Fig. 14(a)). The
// blocked irradiance Ē = sum_s F (1 - V) E_s (Eq. (8)) is taken per vertex from the
// per-point form factors with and without blockers (relight/pipeline/vertex_lighting.h).
//
// §4.4.1 Step 1. Each occluded leaf i gets a reference r among the frontier leaves
// (Fig. 15): the nearest one whose colour is similar (Eq. (10): the channel ratios
// c_i / c_r = (alpha, beta, gamma) differ pairwise by less than `colourThreshold`, are all
// below 1, and the brightest channel is the same) and whose reflectance is not lower
// (Eq. (11)). Then
//     B_corr / D_orig = (rho_r / rho_i) (H + Ē) / H                 (Eq. (12)-(13))
// is the texture factor k_inter = T_inter / T_orig at the vertices. Here rho is estimated
// per leaf against the leaf's own irradiance (rho_i = pi c_i / H_i), which already carries
// the distance to the lights; Eq. (12)'s form-factor ratio sum F_is / sum F_rs would count
// that distance a second time and is left out. The reflectance of T_inter (against the
// unoccluded irradiance H + Ē) replaces the element's, and a radiosity step follows.
//
// §4.4.2 Step 2. Where a vertex still gets at least `umbraThreshold` of its unoccluded
// direct light, the link correction
//     C_link = ((T_orig / T_inter) (sum F E + E_ind) - E_ind) / sum F V E      (Eq. (15))
// scales its direct light (and, averaged per leaf, the light links in the gather), so that
// the unedited display T_inter B_link / D_inter gives back T_orig (Eq. (14)). Elsewhere
// (umbra) the umbra correction
//     C_umbra = (T_orig / T_inter) D_inter / B_link                             (Eq. (16))
// darkens the texture: T_final = C_umbra T_inter. A last radiosity step with the final
// reflectance gives B_final, and D_final = B_final + Ē (per unit reflectance, §4.4.1).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "radiosity/direct_light.h"
#include "radiosity/leaf_mesh.h"
#include "radiosity/light_response.h"
#include "radiosity/solver.h"
#include "relight/pipeline/leaf_texture.h"
#include "relight/pipeline/vertex_lighting.h"

namespace relight {

struct ShadowRemovalOptions {
    double colourThreshold = 0.1;  ///< Eq. (10): largest |alpha - beta| etc., dimensionless
    double umbraThreshold = 0.1;   ///< visible / unoccluded direct light below which C_link
                                   ///< is not used (umbra), dimensionless
    double minShare = 0.02;        ///< as in relight/pipeline/shadow_refinement.h
    int minSamples = 32;           ///< photo samples a leaf needs to have a colour
};

enum class LeafShadowClass : uint8_t { none, lit, occluded, frontier };

struct ShadowRemoval {
    // Per node (leaf elements; other nodes: none / -1 / 1).
    std::vector<LeafShadowClass> leafClass;
    std::vector<int> reference;            ///< occluded leaf: its reference leaf (or itself)
    std::vector<radiosity::Rgb> rhoRatio;  ///< rho_r / rho_i (1 where no reference)
    // Per leaf vertex.
    std::vector<radiosity::Rgb> blocked;          ///< Ē, Eq. (8) (photo units)
    std::vector<radiosity::Rgb> kInter;           ///< T_inter / T_orig, Eq. (13)
    std::vector<radiosity::Rgb> linkCorrection;   ///< C_link, Eq. (15) (1: not used)
    std::vector<radiosity::Rgb> umbraCorrection;  ///< C_umbra, Eq. (16) (1: not used)
    std::vector<radiosity::Rgb> kFinal;           ///< T_final / T_orig
    std::vector<radiosity::Rgb> D;                ///< D_final per unit reflectance: H_final + Ē
    VertexLighting lighting;                      ///< h_l(v) with C_link on the direct part
    int occluded = 0, frontier = 0, referenced = 0, partialVertices = 0, umbraVertices = 0;
};

/// Runs §4.3-4.4 on a solved, refined solver (light links at the leaves, receiver index
/// built). `photoRadiance` is each light's radiance in the photo; `lighting` and `direct`
/// the per-vertex lighting of measureVertexLighting on that solution. Changes the solver
/// (element reflectances, light links' V) and replaces `responses` by the final solution's.
ShadowRemoval removeRealShadows(radiosity::HierarchicalSolver& solver,
                                const radiosity::LeafMesh& mesh, const LeafTexture& texture,
                                std::span<const radiosity::Rgb> photoRadiance,
                                const VertexLighting& lighting, const VertexDirect& direct,
                                std::unique_ptr<radiosity::LightResponses>& responses,
                                const ShadowRemovalOptions& options = {});

}  // namespace relight
