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
#include "radiosity/progress.h"
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
    /// Hears each step as it begins, with the seconds spent (may be empty).
    radiosity::ProgressFn progress;
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

/// What removal reads besides the solver: the photo's texture and lighting at the leaves.
struct ShadowRemovalInputs {
    const radiosity::LeafMesh& mesh;                ///< on the solver's hierarchy
    const LeafTexture& texture;                     ///< the photo per leaf (T_orig)
    std::span<const radiosity::Rgb> photoRadiance;  ///< each light's radiance in the photo
    const VertexLighting& lighting;                 ///< h_l(v) of the solution before removal
    const VertexDirect& direct;                     ///< the direct light of measureVertexLighting
};

/// Runs §4.3-4.4 on a solved, refined solver (light links at the leaves, receiver index
/// built): the steps below, in the paper's order. Changes the solver (element reflectances,
/// light links' V) and replaces `responses` by the final solution's.
ShadowRemoval removeRealShadows(radiosity::HierarchicalSolver& solver,
                                std::unique_ptr<radiosity::LightResponses>& responses,
                                const ShadowRemovalInputs& in,
                                const ShadowRemovalOptions& options = {});

// ---- The steps of removeRealShadows, each callable on its own -------------------------

/// The photo's lighting at every vertex of `mesh`, split as §4.3-4.4 use it (radiosity
/// units): the lights' h_l and direct light weighted by their radiances in the photo.
struct VertexShadowLight {
    std::vector<radiosity::Rgb> H;           ///< irradiance, sum_l L_l h_l(v)
    std::vector<radiosity::Rgb> visible;     ///< direct light with the blockers, sum F V E
    std::vector<radiosity::Rgb> unoccluded;  ///< direct light without them, sum F E
    std::vector<radiosity::Rgb> blocked;     ///< Ē = max(0, unoccluded - visible), Eq. (8)
    radiosity::Rgb floor;  ///< ratioFloor(H): keeps the ratios of H finite where it vanishes
};
VertexShadowLight vertexShadowLight(const radiosity::LeafMesh& mesh, const VertexLighting& lighting,
                                    const VertexDirect& direct,
                                    std::span<const radiosity::Rgb> photoRadiance);

/// §4.3: every leaf's class (per node; none for other nodes, light faces and leaves no light
/// reaches), and the frontier leaves, in node order: lit, with a colour, and with an
/// occluded edge neighbour (Fig. 14(a)).
struct ShadowClasses {
    std::vector<LeafShadowClass> leafClass;
    std::vector<int> frontier;
};
ShadowClasses classifyShadowLeaves(const radiosity::HierarchicalSolver& solver,
                                   const LeafTexture& texture,
                                   std::span<const radiosity::Rgb> photoRadiance,
                                   const ShadowRemovalOptions& options);

/// Per node, for the classed leaves with a colour: the mean photo colour c_i and the
/// reflectance against the leaf's own irradiance, rho_i = pi c_i / H_i (`known` where the
/// leaf has light in every channel: leafReflectanceFromTexture).
struct LeafPhotoReflectance {
    std::vector<radiosity::Rgb> colour, rho;
    std::vector<bool> known;
};
LeafPhotoReflectance leafPhotoReflectance(
    const radiosity::Hierarchy& h, const radiosity::LeafMesh& mesh, const LeafTexture& texture,
    std::span<const radiosity::Rgb> H, std::span<const LeafShadowClass> leafClass, int minSamples);

/// Eq. (10)-(11): whether a frontier leaf of colour `cr` and reflectance `rhoR` may be the
/// reference of an occluded leaf of colour `ci` and reflectance `rhoI`: the ratios
/// c_i / c_r = (alpha, beta, gamma) differ pairwise by less than `colourThreshold` and are all
/// below 1 (the reference is brighter), the brightest channel is the same, and the
/// reference's reflectance is not lower.
bool canBeReference(const radiosity::Rgb& ci, const radiosity::Rgb& cr, const radiosity::Rgb& rhoI,
                    const radiosity::Rgb& rhoR, double colourThreshold);

/// Fig. 15: each occluded leaf with a reflectance takes the nearest frontier leaf (by the
/// distance between `nodes`' centres) that canBeReference() allows, or itself when there is
/// none, and the ratio rho_r / rho_i channel by channel, never below 1 (Eq. (11)).
struct ShadowReferences {
    std::vector<int> reference;            ///< per node; -1 where not occluded
    std::vector<radiosity::Rgb> rhoRatio;  ///< per node; 1 where no reference
    int occluded = 0, referenced = 0;
};
ShadowReferences chooseReferences(std::span<const radiosity::Node> nodes,
                                  const ShadowClasses& classes, const LeafPhotoReflectance& leaves,
                                  double colourThreshold);

/// Eq. (12)-(13): k_inter = q (H + Ē) / H at every vertex where light is blocked (1
/// elsewhere), q the ratio rho_r / rho_i averaged over the vertex's leaves; H and H + Ē
/// are floored by light.floor.
std::vector<radiosity::Rgb> interTextureFactor(std::span<const radiosity::Rgb> q,
                                               const VertexShadowLight& light);

/// The factor on the reflectance that T_inter = k_inter T_orig shows against the unoccluded
/// irradiance H + Ē rather than H: k_inter H / (H + Ē) (floored as above).
std::vector<radiosity::Rgb> interReflectanceFactor(std::span<const radiosity::Rgb> kInter,
                                                   const VertexShadowLight& light);

/// Eq. (14)-(15) at the vertices where light is blocked and at least `umbraThreshold` of
/// the unoccluded direct light still arrives:
///     C_link = ((D0 + I) / k_inter - I) / Dv,
/// with D0 and Dv the unoccluded and visible direct light and I = Hinter - Dv the indirect
/// light after step 1, clamped to [0, D0 / Dv]; then k_inter (C_link Dv + I) = D0 + I, the
/// unedited display gives back T_orig. The other blocked vertices are the umbra.
struct LinkCorrection {
    std::vector<radiosity::Rgb> factor;  ///< C_link per vertex (1: not used)
    std::vector<bool> umbra;             ///< per vertex: C_umbra is used instead
    int partialVertices = 0, umbraVertices = 0;
};
LinkCorrection linkCorrection(const VertexShadowLight& light,
                              std::span<const radiosity::Rgb> Hinter,
                              std::span<const radiosity::Rgb> kInter, double umbraThreshold);

/// Eq. (16) at the umbra vertices (1 elsewhere):
///     C_umbra = (Hinter + Ē) / (k_inter Hlink)     (floored by light.floor),
/// with Hinter the irradiance after step 1 and Hlink after the link correction: T_final =
/// C_umbra T_inter darkens the texture where C_link cannot take light away.
std::vector<radiosity::Rgb> umbraCorrection(const VertexShadowLight& light,
                                            std::span<const radiosity::Rgb> Hinter,
                                            std::span<const radiosity::Rgb> Hlink,
                                            std::span<const radiosity::Rgb> kInter,
                                            const std::vector<bool>& umbra);

/// The closing of §4.4: D_final = H_final + Ē (per unit reflectance), and the texture factor
/// T_final / T_orig = D_final / H_final, with the display's floor (displayRatio), so that the
/// unedited display T_final B / D gives back T_orig to rounding.
struct FinalDisplay {
    std::vector<radiosity::Rgb> D, kFinal;
};
FinalDisplay closeDisplay(std::span<const radiosity::Rgb> Hfinal,
                          std::span<const radiosity::Rgb> blocked);

}  // namespace relight
