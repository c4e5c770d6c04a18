#include "relight/pipeline/shadow_removal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "relight/display/ratio_display.h"
#include "relight/pipeline/reflectance.h"

namespace relight {

using radiosity::Rgb;

namespace {

constexpr double kFullyVisible = 1 - 1e-3;  // V above this: the light is not blocked

/// sum_l L_l a[v * L + l] (per channel).
Rgb weighted(const std::vector<double>& a, int v, std::span<const Rgb> L) {
    Rgb out;
    const size_t n = L.size(), at = static_cast<size_t>(v) * n;
    for (size_t l = 0; l < n; ++l) out += L[l] * a[at + l];
    return out;
}

/// A leaf element of a reflecting polygon: what removal classifies and corrects (a light's
/// emitting face is shown with the light's radiance, never lit).
bool isSurfaceLeaf(const radiosity::HierarchicalSolver& solver, int n) {
    const radiosity::Node& node = solver.hierarchy().nodes[n];
    return !node.isCluster() && node.isLeaf() && solver.scene().polygons[node.polygon].light < 0;
}

/// The mean of a per-vertex quantity over a leaf's corners: what the leaf's element takes
/// of a correction computed at the vertices.
Rgb meanOverCorners(const radiosity::Hierarchy& h, const radiosity::LeafMesh& mesh, int leaf,
                    std::span<const Rgb> x) {
    Rgb m;
    const int k = h.nodes[leaf].vertexCount;
    for (int i = 0; i < k; ++i) m += x[mesh.corners(leaf)[i]];
    return m * (1.0 / k);
}

/// H(v) = sum_l L_l h_l(v) at every vertex.
std::vector<Rgb> irradianceAtVertices(const VertexLighting& lighting, std::span<const Rgb> L,
                                      size_t vertices) {
    std::vector<Rgb> H(vertices);
    for (size_t v = 0; v < vertices; ++v) H[v] = lighting.irradiance(static_cast<int>(v), L);
    return H;
}

/// A radiosity step with the reflectances a texture factor implies: every surface leaf's
/// reflectance times `factor` averaged over its corners, then gather/push-pull and the
/// per-light responses of the new solution.
void applyReflectanceFactor(radiosity::HierarchicalSolver& solver, const radiosity::LeafMesh& mesh,
                            std::span<const Rgb> factor,
                            std::unique_ptr<radiosity::LightResponses>& responses) {
    const radiosity::Hierarchy& h = solver.hierarchy();
    for (int n = 0; n < static_cast<int>(h.nodes.size()); ++n) {
        if (!isSurfaceLeaf(solver, n)) continue;
        const Rgb f = meanOverCorners(h, mesh, n, factor);
        if (f == Rgb::gray(1.0)) continue;
        Rgb r = h.nodes[n].rho;
        for (int c = 0; c < 3; ++c) r[c] *= f[c];
        solver.setElementReflectance(n, clampReflectance(r));
    }
    solver.pullReflectance();
    solver.gatherPushPull();
    responses = std::make_unique<radiosity::LightResponses>(solver, std::move(responses));
}

/// Eq. (15) in the gather: each surface leaf's light links scaled by C_link averaged over its
/// corners and channels (a link carries one visibility), then gather/push-pull and the
/// responses of the new solution.
void applyLinkCorrection(radiosity::HierarchicalSolver& solver, const radiosity::LeafMesh& mesh,
                         std::span<const Rgb> linkCorrection,
                         std::unique_ptr<radiosity::LightResponses>& responses) {
    const radiosity::Hierarchy& h = solver.hierarchy();
    for (int n = 0; n < static_cast<int>(h.nodes.size()); ++n) {
        if (!isSurfaceLeaf(solver, n)) continue;
        const Rgb c = meanOverCorners(h, mesh, n, linkCorrection);
        const double mean = (c[0] + c[1] + c[2]) / 3;
        if (mean != 1.0) solver.scaleLightLinks(n, mean);
    }
    solver.gatherPushPull();
    responses = std::make_unique<radiosity::LightResponses>(solver, std::move(responses));
}

int argmax(const Rgb& c) {
    return c[0] >= c[1] && c[0] >= c[2] ? 0 : (c[1] >= c[2] ? 1 : 2);
}

}  // namespace

VertexShadowLight vertexShadowLight(const radiosity::LeafMesh& mesh, const VertexLighting& lighting,
                                    const VertexDirect& direct, std::span<const Rgb> L) {
    const int nv = static_cast<int>(mesh.vertices().size());
    VertexShadowLight out;
    out.H.resize(nv);
    out.visible.resize(nv);
    out.unoccluded.resize(nv);
    out.blocked.resize(nv);
    for (int v = 0; v < nv; ++v) {
        out.H[v] = lighting.irradiance(v, L);
        out.visible[v] = weighted(direct.visible, v, L);
        out.unoccluded[v] = weighted(direct.unoccluded, v, L);
        for (int c = 0; c < 3; ++c)
            out.blocked[v][c] = std::max(0.0, out.unoccluded[v][c] - out.visible[v][c]);
    }
    out.floor = ratioFloor(out.H);
    return out;
}

ShadowClasses classifyShadowLeaves(const radiosity::HierarchicalSolver& solver,
                                   const LeafTexture& texture, std::span<const Rgb> L,
                                   const ShadowRemovalOptions& o) {
    const radiosity::Hierarchy& h = solver.hierarchy();
    const int nNodes = static_cast<int>(h.nodes.size());
    ShadowClasses out;
    // A light counts for a leaf when it gives at least minShare of the leaf's unoccluded
    // direct light; the leaf is occluded when such a light is not fully visible.
    std::vector<double> emittance;
    for (const Rgb& l : L) emittance.push_back(l.maxComponent());
    out.leafClass.assign(nNodes, LeafShadowClass::none);
    for (int n = 0; n < nNodes; ++n) {
        if (!isSurfaceLeaf(solver, n)) continue;
        const auto ex = solver.lightExchange(n);
        double total = 0;
        for (size_t s = 0; s < ex.size(); ++s) total += ex[s].F * emittance[s];
        if (!(total > 0)) continue;  // no direct light: neither lit nor in shadow
        bool blocked = false;
        for (size_t s = 0; s < ex.size(); ++s)
            if (ex[s].F * emittance[s] >= o.minShare * total && ex[s].FV < kFullyVisible * ex[s].F)
                blocked = true;
        out.leafClass[n] = blocked ? LeafShadowClass::occluded : LeafShadowClass::lit;
    }
    // The frontier: lit leaves with a colour (they serve as references) next to a shadow.
    for (int n = 0; n < nNodes; ++n) {
        if (out.leafClass[n] != LeafShadowClass::lit || texture.samples(n) < o.minSamples) continue;
        for (int m : h.edgeNeighbours(n))
            if (out.leafClass[m] == LeafShadowClass::occluded) {
                out.leafClass[n] = LeafShadowClass::frontier;
                out.frontier.push_back(n);
                break;
            }
    }
    return out;
}

LeafPhotoReflectance leafPhotoReflectance(const radiosity::Hierarchy& h,
                                          const radiosity::LeafMesh& mesh,
                                          const LeafTexture& texture, std::span<const Rgb> H,
                                          std::span<const LeafShadowClass> leafClass,
                                          int minSamples) {
    const size_t nNodes = h.nodes.size();
    LeafPhotoReflectance out;
    out.colour.resize(nNodes);
    out.rho.resize(nNodes);
    out.known.assign(nNodes, false);
    for (int n = 0; n < static_cast<int>(nNodes); ++n) {
        if (leafClass[n] == LeafShadowClass::none || texture.samples(n) < minSamples) continue;
        out.colour[n] = texture.colour(n);
        out.known[n] = leafReflectanceFromTexture(h, mesh, texture, H, n, minSamples, &out.rho[n]);
    }
    return out;
}

bool canBeReference(const Rgb& ci, const Rgb& cr, const Rgb& rhoI, const Rgb& rhoR,
                    double colourThreshold) {
    if (!(cr.minComponent() > 0)) return false;
    const Rgb a{ci[0] / cr[0], ci[1] / cr[1], ci[2] / cr[2]};  // (alpha, beta, gamma)
    if (!(a.maxComponent() < 1)) return false;                 // the reference must be brighter
    if (std::abs(a[0] - a[1]) >= colourThreshold || std::abs(a[1] - a[2]) >= colourThreshold ||
        std::abs(a[0] - a[2]) >= colourThreshold)
        return false;
    if (argmax(ci) != argmax(cr)) return false;
    return rhoR.maxComponent() >= rhoI.maxComponent();  // Eq. (11)
}

ShadowReferences chooseReferences(std::span<const radiosity::Node> nodes,
                                  const ShadowClasses& classes, const LeafPhotoReflectance& leaves,
                                  double colourThreshold) {
    const int nNodes = static_cast<int>(nodes.size());
    ShadowReferences out;
    out.reference.assign(nNodes, -1);
    out.rhoRatio.assign(nNodes, Rgb::gray(1.0));
    for (int i = 0; i < nNodes; ++i) {
        if (classes.leafClass[i] != LeafShadowClass::occluded || !leaves.known[i]) continue;
        ++out.occluded;
        out.reference[i] = i;
        double best = std::numeric_limits<double>::infinity();
        for (int r : classes.frontier) {
            if (!leaves.known[r] || !canBeReference(leaves.colour[i], leaves.colour[r],
                                                    leaves.rho[i], leaves.rho[r], colourThreshold))
                continue;
            const double d = glm::length(nodes[r].centre - nodes[i].centre);
            if (d < best) {
                best = d;
                out.reference[i] = r;
            }
        }
        const int r = out.reference[i];
        if (r == i) continue;
        ++out.referenced;
        const Rgb& rhoI = leaves.rho[i];
        const Rgb& rhoR = leaves.rho[r];
        for (int c = 0; c < 3; ++c)  // never darken (Eq. (11)), channel by channel
            out.rhoRatio[i][c] = rhoI[c] > 0 ? std::max(1.0, rhoR[c] / rhoI[c]) : 1.0;
    }
    return out;
}

std::vector<Rgb> interTextureFactor(std::span<const Rgb> q, const VertexShadowLight& light) {
    const std::vector<Rgb>& H = light.H;
    const std::vector<Rgb>& blocked = light.blocked;
    const Rgb& delta = light.floor;
    std::vector<Rgb> k(H.size(), Rgb::gray(1.0));
    for (size_t v = 0; v < H.size(); ++v) {
        if (!(blocked[v].maxComponent() > 0)) continue;  // nothing blocked at v
        for (int c = 0; c < 3; ++c)
            k[v][c] = q[v][c] * (H[v][c] + blocked[v][c] + delta[c]) / (H[v][c] + delta[c]);
    }
    return k;
}

std::vector<Rgb> interReflectanceFactor(std::span<const Rgb> kInter,
                                        const VertexShadowLight& light) {
    const std::vector<Rgb>& H = light.H;
    const Rgb& delta = light.floor;
    std::vector<Rgb> f(H.size());
    for (size_t v = 0; v < H.size(); ++v)
        for (int c = 0; c < 3; ++c)
            f[v][c] =
                kInter[v][c] * (H[v][c] + delta[c]) / (H[v][c] + light.blocked[v][c] + delta[c]);
    return f;
}

LinkCorrection linkCorrection(const VertexShadowLight& light, std::span<const Rgb> Hinter,
                              std::span<const Rgb> kInter, double umbraThreshold) {
    const size_t nv = light.H.size();
    LinkCorrection out;
    out.factor.assign(nv, Rgb::gray(1.0));
    out.umbra.assign(nv, false);
    for (size_t v = 0; v < nv; ++v) {
        const Rgb& D0 = light.unoccluded[v];
        const Rgb& Dv = light.visible[v];
        if (!(D0.maxComponent() > 0) || !(light.blocked[v].maxComponent() > 0)) continue;
        if (Dv.maxComponent() < umbraThreshold * D0.maxComponent()) {
            out.umbra[v] = true;
            ++out.umbraVertices;
            continue;
        }
        ++out.partialVertices;
        const Rgb I = Hinter[v] - Dv;  // indirect light after step 1
        for (int c = 0; c < 3; ++c) {
            // A channel the lights leave dark or negative (a sky whose 9 coefficients give a
            // negative irradiance there, as a fitted one may) has nothing to correct.
            if (!(Dv[c] > 0) || !(D0[c] > 0)) continue;
            const double Cl = ((D0[c] + I[c]) / kInter[v][c] - I[c]) / Dv[c];
            // A light cannot give more than it would unoccluded, nor less than nothing.
            out.factor[v][c] = std::clamp(Cl, 0.0, D0[c] / Dv[c]);
        }
    }
    return out;
}

std::vector<Rgb> umbraCorrection(const VertexShadowLight& light, std::span<const Rgb> Hinter,
                                 std::span<const Rgb> Hlink, std::span<const Rgb> kInter,
                                 const std::vector<bool>& umbra) {
    const Rgb& delta = light.floor;
    std::vector<Rgb> u(light.H.size(), Rgb::gray(1.0));
    for (size_t v = 0; v < u.size(); ++v) {
        if (!umbra[v]) continue;
        for (int c = 0; c < 3; ++c)
            u[v][c] = (Hinter[v][c] + light.blocked[v][c] + delta[c]) /
                      (kInter[v][c] * (Hlink[v][c] + delta[c]));
    }
    return u;
}

FinalDisplay closeDisplay(std::span<const Rgb> Hfinal, std::span<const Rgb> blocked) {
    FinalDisplay out;
    out.D.resize(Hfinal.size());
    for (size_t v = 0; v < Hfinal.size(); ++v) out.D[v] = Hfinal[v] + blocked[v];
    const Rgb delta = ratioFloor(out.D);
    out.kFinal.resize(Hfinal.size());
    for (size_t v = 0; v < Hfinal.size(); ++v)
        for (int c = 0; c < 3; ++c)
            out.kFinal[v][c] = (out.D[v][c] + delta[c]) / (Hfinal[v][c] + delta[c]);
    return out;
}

ShadowRemoval removeRealShadows(radiosity::HierarchicalSolver& solver,
                                std::unique_ptr<radiosity::LightResponses>& responses,
                                const ShadowRemovalInputs& in, const ShadowRemovalOptions& o) {
    ShadowRemoval out;
    const auto start = radiosity::Clock::now();
    const auto step = [&](const char* what) {
        if (!o.progress) return;
        char msg[160];
        std::snprintf(msg, sizeof msg, "  %s (%.0f s)", what, radiosity::secondsSince(start));
        o.progress(msg);
    };
    const std::span<const Rgb> L = in.photoRadiance;
    const size_t nv = in.mesh.vertices().size();
    const VertexShadowLight light = vertexShadowLight(in.mesh, in.lighting, in.direct, L);
    out.blocked = light.blocked;

    // §4.3: the leaves in shadow and their lit neighbours.
    ShadowClasses classes = classifyShadowLeaves(solver, in.texture, L, o);
    out.frontier = static_cast<int>(classes.frontier.size());

    step("step 1 of 2 (§4.4.1): reference patches and the texture factor");
    // §4.4.1 Step 1: reference patches (Fig. 15, Eq. (10)-(11)), the texture factor
    // k_inter (Eq. (12)-(13)), and a radiosity step with the reflectance of T_inter.
    const radiosity::Hierarchy& h = solver.hierarchy();
    ShadowReferences refs = chooseReferences(
        h.nodes, classes,
        leafPhotoReflectance(h, in.mesh, in.texture, light.H, classes.leafClass, o.minSamples),
        o.colourThreshold);
    out.occluded = refs.occluded;
    out.referenced = refs.referenced;
    const std::vector<Rgb> q =
        in.mesh.averageOfLeaves([&](int leaf) { return refs.rhoRatio[leaf]; });
    out.kInter = interTextureFactor(q, light);
    applyReflectanceFactor(solver, in.mesh, interReflectanceFactor(out.kInter, light), responses);
    const std::vector<Rgb> Hinter =
        irradianceAtVertices(regatherVertexLighting(solver, in.mesh, *responses, in.direct), L, nv);

    step("step 2 of 2 (§4.4.2): link and umbra corrections");
    // §4.4.2 Step 2: the link correction (Eq. (14)-(15)) where some direct light arrives,
    // the umbra correction (Eq. (16)) elsewhere, each followed by a radiosity step.
    LinkCorrection link = linkCorrection(light, Hinter, out.kInter, o.umbraThreshold);
    out.partialVertices = link.partialVertices;
    out.umbraVertices = link.umbraVertices;
    out.linkCorrection = std::move(link.factor);
    applyLinkCorrection(solver, in.mesh, out.linkCorrection, responses);
    const std::vector<Rgb> Hlink = irradianceAtVertices(
        regatherVertexLighting(solver, in.mesh, *responses, in.direct, out.linkCorrection), L, nv);
    out.umbraCorrection = umbraCorrection(light, Hinter, Hlink, out.kInter, link.umbra);
    applyReflectanceFactor(solver, in.mesh, out.umbraCorrection, responses);  // T_final's

    step("D_final and T_final");
    // D_final and T_final. Eq. (14) and (16) ask that the unedited display T_final B/D give
    // back T_orig. Each correction above was computed from the previous step's radiosity;
    // the steps change the indirect light a little, so the factor is closed with the final
    // B and D (closeDisplay). What the steps changed stays in B: the link-corrected direct
    // light and the indirect light of the corrected reflectances.
    out.lighting =
        regatherVertexLighting(solver, in.mesh, *responses, in.direct, out.linkCorrection);
    FinalDisplay closed = closeDisplay(irradianceAtVertices(out.lighting, L, nv), light.blocked);
    out.D = std::move(closed.D);
    out.kFinal = std::move(closed.kFinal);
    out.reference = std::move(refs.reference);
    out.rhoRatio = std::move(refs.rhoRatio);
    out.leafClass = std::move(classes.leafClass);
    return out;
}

}  // namespace relight
