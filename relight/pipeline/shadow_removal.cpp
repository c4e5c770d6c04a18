#include "relight/pipeline/shadow_removal.h"

#include <algorithm>
#include <cmath>
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

}  // namespace

ShadowRemoval removeRealShadows(radiosity::HierarchicalSolver& solver,
                                const radiosity::LeafMesh& mesh, const LeafTexture& texture,
                                std::span<const Rgb> L, const VertexLighting& photoLighting,
                                const VertexDirect& direct,
                                std::unique_ptr<radiosity::LightResponses>& responses,
                                const ShadowRemovalOptions& o) {
    ShadowRemoval out;
    const radiosity::Hierarchy& h = solver.hierarchy();
    const radiosity::Scene& scene = solver.scene();
    const int nNodes = static_cast<int>(h.nodes.size());
    const int nv = static_cast<int>(mesh.vertices().size());
    auto isSurfaceLeaf = [&](int n) {
        const radiosity::Node& node = h.nodes[n];
        return !node.isCluster() && node.isLeaf() && scene.polygons[node.polygon].light < 0;
    };
    auto hasColour = [&](int n) { return texture.samples(n) >= o.minSamples; };

    // ---- per vertex: H, visible and unoccluded direct light, blocked irradiance (Eq. 8)
    std::vector<Rgb> H(nv), Dv(nv), D0(nv);
    out.blocked.resize(nv);
    for (int v = 0; v < nv; ++v) {
        H[v] = photoLighting.irradiance(v, L);
        Dv[v] = weighted(direct.visible, v, L);
        D0[v] = weighted(direct.unoccluded, v, L);
        for (int c = 0; c < 3; ++c) out.blocked[v][c] = std::max(0.0, D0[v][c] - Dv[v][c]);
    }
    const Rgb deltaH = ratioFloor(H);
    auto meanOverCorners = [&](int leaf, const std::vector<Rgb>& x) {
        Rgb m;
        const int k = h.nodes[leaf].vertexCount;
        for (int i = 0; i < k; ++i) m += x[mesh.corners(leaf)[i]];
        return m * (1.0 / k);
    };

    // ---- §4.3: classes of the leaves, and the frontier
    std::vector<double> emittance;
    for (const Rgb& l : L) emittance.push_back(l.maxComponent());
    out.leafClass.assign(nNodes, LeafShadowClass::none);
    for (int n = 0; n < nNodes; ++n) {
        if (!isSurfaceLeaf(n)) continue;
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
    std::vector<int> frontier;
    for (int n = 0; n < nNodes; ++n) {
        if (out.leafClass[n] != LeafShadowClass::lit || !hasColour(n)) continue;
        for (int m : h.edgeNeighbours(n))
            if (out.leafClass[m] == LeafShadowClass::occluded) {
                out.leafClass[n] = LeafShadowClass::frontier;
                frontier.push_back(n);
                break;
            }
    }
    out.frontier = static_cast<int>(frontier.size());

    // ---- per leaf: colour and reflectance against its own irradiance
    std::vector<Rgb> colour(nNodes), rho(nNodes);
    std::vector<bool> hasRho(nNodes, false);
    for (int n = 0; n < nNodes; ++n) {
        if (out.leafClass[n] == LeafShadowClass::none || !hasColour(n)) continue;
        colour[n] = texture.colour(n);
        hasRho[n] = leafReflectanceFromTexture(h, mesh, texture, H, n, o.minSamples, &rho[n]);
    }

    // ---- §4.4.1 Step 1: reference patches (Fig. 15, Eq. 10-11) and k_inter (Eq. 12-13)
    out.reference.assign(nNodes, -1);
    out.rhoRatio.assign(nNodes, Rgb::gray(1.0));
    auto argmax = [](const Rgb& c) {
        return c[0] >= c[1] && c[0] >= c[2] ? 0 : (c[1] >= c[2] ? 1 : 2);
    };
    for (int i = 0; i < nNodes; ++i) {
        if (out.leafClass[i] != LeafShadowClass::occluded || !hasRho[i]) continue;
        ++out.occluded;
        out.reference[i] = i;
        const Rgb ci = colour[i];
        double best = std::numeric_limits<double>::infinity();
        for (int r : frontier) {
            if (!hasRho[r]) continue;
            const Rgb cr = colour[r];
            if (!(cr.minComponent() > 0)) continue;
            const Rgb a{ci[0] / cr[0], ci[1] / cr[1], ci[2] / cr[2]};  // (alpha, beta, gamma)
            if (!(a.maxComponent() < 1)) continue;  // the reference must be brighter
            if (std::abs(a[0] - a[1]) >= o.colourThreshold ||
                std::abs(a[1] - a[2]) >= o.colourThreshold ||
                std::abs(a[0] - a[2]) >= o.colourThreshold)
                continue;
            if (argmax(ci) != argmax(cr)) continue;
            if (rho[r].maxComponent() < rho[i].maxComponent()) continue;  // Eq. (11)
            const double d = glm::length(h.nodes[r].centre - h.nodes[i].centre);
            if (d < best) {
                best = d;
                out.reference[i] = r;
            }
        }
        const int r = out.reference[i];
        if (r == i) continue;
        ++out.referenced;
        for (int c = 0; c < 3; ++c)  // never darken (Eq. (11)), channel by channel
            out.rhoRatio[i][c] = rho[i][c] > 0 ? std::max(1.0, rho[r][c] / rho[i][c]) : 1.0;
    }
    const std::vector<Rgb> q = mesh.averageOfLeaves([&](int leaf) { return out.rhoRatio[leaf]; });
    out.kInter.assign(nv, Rgb::gray(1.0));
    for (int v = 0; v < nv; ++v) {
        if (!(out.blocked[v].maxComponent() > 0)) continue;  // nothing blocked at v
        for (int c = 0; c < 3; ++c)
            out.kInter[v][c] =
                q[v][c] * (H[v][c] + out.blocked[v][c] + deltaH[c]) / (H[v][c] + deltaH[c]);
    }
    // Reflectance of T_inter against the unoccluded irradiance, then a radiosity step.
    auto setLeafReflectance = [&](const std::vector<Rgb>& factor) {
        for (int n = 0; n < nNodes; ++n) {
            if (!isSurfaceLeaf(n)) continue;
            const Rgb f = meanOverCorners(n, factor);
            if (f == Rgb::gray(1.0)) continue;
            Rgb r = h.nodes[n].rho;
            for (int c = 0; c < 3; ++c) r[c] *= f[c];
            solver.setElementReflectance(n, clampReflectance(r));
        }
        solver.pullReflectance();
        solver.gatherPushPull();
        responses = std::make_unique<radiosity::LightResponses>(solver, responses.get());
    };
    {
        std::vector<Rgb> f(nv);
        for (int v = 0; v < nv; ++v)
            for (int c = 0; c < 3; ++c)
                f[v][c] = out.kInter[v][c] * (H[v][c] + deltaH[c]) /
                          (H[v][c] + out.blocked[v][c] + deltaH[c]);
        setLeafReflectance(f);
    }
    VertexLighting lighting = regatherVertexLighting(solver, mesh, *responses, direct);
    std::vector<Rgb> Iinter(nv), Hinter(nv);
    for (int v = 0; v < nv; ++v) {
        Hinter[v] = lighting.irradiance(v, L);
        Iinter[v] = Hinter[v] - Dv[v];
    }

    // ---- §4.4.2 Step 2: link correction (Eq. 14-15) where some direct light arrives
    out.linkCorrection.assign(nv, Rgb::gray(1.0));
    std::vector<bool> umbra(nv, false);
    for (int v = 0; v < nv; ++v) {
        if (!(D0[v].maxComponent() > 0) || !(out.blocked[v].maxComponent() > 0)) continue;
        if (Dv[v].maxComponent() < o.umbraThreshold * D0[v].maxComponent()) {
            umbra[v] = true;
            ++out.umbraVertices;
            continue;
        }
        ++out.partialVertices;
        for (int c = 0; c < 3; ++c) {
            if (!(Dv[v][c] > 0)) continue;
            const double Cl =
                ((D0[v][c] + Iinter[v][c]) / out.kInter[v][c] - Iinter[v][c]) / Dv[v][c];
            // A light cannot give more than it would unoccluded, nor less than nothing.
            out.linkCorrection[v][c] = std::clamp(Cl, 0.0, D0[v][c] / Dv[v][c]);
        }
    }
    for (int n = 0; n < nNodes; ++n) {
        if (!isSurfaceLeaf(n)) continue;
        const Rgb c = meanOverCorners(n, out.linkCorrection);
        const double mean = (c[0] + c[1] + c[2]) / 3;
        if (mean != 1.0) solver.scaleLightLinks(n, mean);
    }
    solver.gatherPushPull();
    responses = std::make_unique<radiosity::LightResponses>(solver, responses.get());
    lighting = regatherVertexLighting(solver, mesh, *responses, direct, out.linkCorrection);

    // ---- umbra correction (Eq. 16) and T_final
    out.umbraCorrection.assign(nv, Rgb::gray(1.0));
    out.kFinal = out.kInter;
    for (int v = 0; v < nv; ++v) {
        if (!umbra[v]) continue;
        const Rgb Hlink = lighting.irradiance(v, L);
        for (int c = 0; c < 3; ++c) {
            out.umbraCorrection[v][c] = (Hinter[v][c] + out.blocked[v][c] + deltaH[c]) /
                                        (out.kInter[v][c] * (Hlink[c] + deltaH[c]));
            out.kFinal[v][c] = out.kInter[v][c] * out.umbraCorrection[v][c];
        }
    }
    setLeafReflectance(out.umbraCorrection);  // reflectance of T_final, radiosity step
    out.lighting = regatherVertexLighting(solver, mesh, *responses, direct, out.linkCorrection);
    out.D.resize(nv);
    std::vector<Rgb> Hfinal(nv);
    for (int v = 0; v < nv; ++v) {
        Hfinal[v] = out.lighting.irradiance(v, L);
        out.D[v] = Hfinal[v] + out.blocked[v];
    }
    // T_final: Eq. (14) and (16) ask that the unedited display T_final B/D give back
    // T_orig. Each correction above was computed from the previous step's radiosity; the
    // steps change the indirect light a little, so the factor is closed with the final
    // B and D: T_final / T_orig = D_final / B_final, exactly (guarded where B vanishes, with the
    // display's floor). What the steps changed stays in B: the link-corrected direct light and the
    // indirect light of the corrected reflectances. The floor is the display's own (displayRatio:
    // kRatioFloor x mean D), so that k B/D is 1 to rounding for the unedited lights, umbra
    // included.
    const Rgb deltaF = ratioFloor(out.D);
    for (int v = 0; v < nv; ++v)
        for (int c = 0; c < 3; ++c)
            out.kFinal[v][c] = (out.D[v][c] + deltaF[c]) / (Hfinal[v][c] + deltaF[c]);
    return out;
}

}  // namespace relight
