#include "relight/pipeline/reflectance.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numbers>
#include <vector>

#include "radiosity/deadline.h"
#include "radiosity/final_gather.h"
#include "radiosity/leaf_mesh.h"
#include "radiosity/parallel.h"
#include "radiosity/shared_gather.h"
#include "radiosity/stopwatch.h"
#include "relight/pipeline/leaf_texture.h"

namespace relight {

using radiosity::Rgb;

std::vector<int> surfaceOf(const radiosity::Scene& scene) {
    const int np = static_cast<int>(scene.polygons.size());
    std::vector<int> parent(np);
    for (int p = 0; p < np; ++p) parent[p] = p;
    const auto find = [&](int p) {
        while (parent[p] != p) p = parent[p] = parent[parent[p]];
        return p;
    };
    std::map<std::array<double, 3>, std::vector<int>> atCorner;
    for (int p = 0; p < np; ++p) {
        const radiosity::Polygon& P = scene.polygons[p];
        if (P.light >= 0) continue;
        for (int i = 0; i < P.vertexCount; ++i)
            atCorner[{P.v[i].x + 0.0, P.v[i].y + 0.0, P.v[i].z + 0.0}].push_back(p);
    }
    for (const auto& [corner, polys] : atCorner)
        for (size_t i = 1; i < polys.size(); ++i)
            for (size_t j = 0; j < i; ++j) {
                const auto& a = scene.polygons[polys[i]];
                const auto& b = scene.polygons[polys[j]];
                if (glm::dot(a.normal, b.normal) >= radiosity::LeafMesh::kSmoothCos)
                    parent[find(polys[i])] = find(polys[j]);
            }
    for (int p = 0; p < np; ++p) parent[p] = find(p);
    return parent;
}

ObjectMeans objectMeans(const radiosity::Scene& scene, std::span<const Rgb> rho,
                        const std::function<bool(int)>& use) {
    ObjectMeans m;
    m.rho.assign(scene.objects.size(), Rgb{});
    m.area.assign(scene.objects.size(), 0.0);
    for (size_t p = 0; p < scene.polygons.size(); ++p) {
        if (!use(static_cast<int>(p))) continue;
        const radiosity::Polygon& poly = scene.polygons[p];
        m.rho[static_cast<size_t>(poly.object)] += rho[p] * poly.area;
        m.area[static_cast<size_t>(poly.object)] += poly.area;
    }
    for (size_t o = 0; o < m.rho.size(); ++o)
        if (m.area[o] > 0) m.rho[o] = m.rho[o] * (1.0 / m.area[o]);
    return m;
}

namespace {

/// Per polygon, what does not change between rounds: sums over its usable photo samples
/// (the photo's values, the direct light, which depends on the lights only), and the gather
/// points that stand for them, each with the number of samples it stands for.
struct PhotoSums {
    std::vector<Rgb> L, direct;
    std::vector<int> count;
    std::vector<std::vector<std::pair<int, int>>> points;  // (gather point, samples)
};

PhotoSums sumPhotoSamples(const radiosity::Scene& scene, const ItemBuffer& items,
                          const LightingBuffer& lighting, const Image& photo) {
    const int np = static_cast<int>(scene.polygons.size());
    // The lighting buffer's sub-grid (its stride) decides which pixels the sums take.
    const std::vector<uint8_t> usable = usablePixels(items, scene, photo, lighting.stride);
    PhotoSums sums;
    sums.L.resize(np);
    sums.direct.resize(np);
    sums.count.assign(np, 0);
    sums.points.resize(np);
    for (int y = 0; y < items.height; ++y) {
        for (int x = 0; x < items.width; ++x) {
            if (!usable[static_cast<size_t>(y) * items.width + x]) continue;
            const float* px = photo.at(x, y);
            const int idx0 = items.sampleIndex(x, y, 0);
            const int p = items.polygon[idx0];
            for (int s = 0; s < items.spp; ++s) {
                const int idx = items.sampleIndex(x, y, s);
                sums.L[p] += Rgb{px[0], px[1], px[2]};
                const float* G = lighting.direct(idx);
                for (int l = 0; l < lighting.lights; ++l)
                    sums.direct[p] += scene.lights[l].emittance() * static_cast<double>(G[l]);
                ++sums.count[p];
            }
            // A pure pixel: one gather point for all its samples.
            sums.points[p].push_back({lighting.gatherPointOf(idx0), items.spp});
        }
    }
    return sums;
}

/// Indirect light varies slowly: its mean over a polygon's usable samples is taken from at
/// most kIndirectPoints of their gather points, evenly spread in scan order; and at most
/// kGatherBudget points in all per round (a mesh of 22 k small triangles would otherwise
/// gather at every usable pixel, 12 times: 30 s), each polygon keeping its share, at least
/// one point.
void thinGatherPoints(std::vector<std::vector<std::pair<int, int>>>& points) {
    constexpr int kIndirectPoints = 256;
    constexpr double kGatherBudget = 16384;
    double total = 0;
    for (const auto& list : points) total += std::min<double>(list.size(), kIndirectPoints);
    const double share = total > kGatherBudget ? kGatherBudget / total : 1.0;
    for (auto& list : points) {
        const int cap =
            std::max(1, static_cast<int>(std::min<double>(list.size(), kIndirectPoints) * share));
        if (static_cast<int>(list.size()) <= cap) continue;
        std::vector<std::pair<int, int>> kept;
        const double step = static_cast<double>(list.size()) / cap;
        for (int i = 0; i < cap; ++i) kept.push_back(list[static_cast<size_t>(i * step)]);
        list.swap(kept);
    }
}

/// The gather points' final gathers, far links shared per element
/// (radiosity/shared_gather.h): polygon p's points are first[p] .. first[p + 1] - 1, in the
/// order of PhotoSums::points.
struct GatherTerms {
    radiosity::SharedGather gather;
    std::vector<size_t> first;
};

GatherTerms gatherTerms(const radiosity::HierarchicalSolver& solver, const PhotoSums& sums,
                        const LightingBuffer& lighting) {
    GatherTerms t;
    const size_t np = sums.points.size();
    t.first.assign(np + 1, 0);
    for (size_t p = 0; p < np; ++p) t.first[p + 1] = t.first[p] + sums.points[p].size();
    std::vector<radiosity::GatherPoint> points;
    points.reserve(t.first[np]);
    for (size_t p = 0; p < np; ++p)
        for (auto [g, n] : sums.points[p])
            points.push_back(
                {static_cast<int>(p), lighting.gatherPosition[g], static_cast<uint64_t>(g)});
    t.gather = radiosity::sharedFinalGather(solver, points, 4);
    return t;
}

/// Per polygon, the irradiance summed over its usable samples with the solver's radiosities
/// now: the direct light's sum, plus the indirect light's mean over the gather points (each
/// weighted by the samples it stands for) times the samples.
std::vector<Rgb> sumIrradiance(const radiosity::HierarchicalSolver& solver, const PhotoSums& sums,
                               const GatherTerms& terms) {
    const int np = static_cast<int>(sums.L.size());
    std::vector<Rgb> H(terms.gather.points());
    terms.gather.addIndirect(solver, H.data());
    std::vector<Rgb> sumH(np);
    radiosity::parallelFor(static_cast<size_t>(np), 1, [&](size_t p) {
        Rgb sumI;
        double weight = 0;
        for (size_t i = 0; i < sums.points[p].size(); ++i) {
            const int n = sums.points[p][i].second;
            sumI += H[terms.first[p] + i] * static_cast<double>(n);
            weight += n;
        }
        sumH[p] = sums.direct[p] + (weight > 0 ? sumI * (sums.count[p] / weight) : Rgb{});
    });
    return sumH;
}

/// One round's estimates, rho = pi sum(L) / sum(H) per polygon seen (on its own samples, or
/// pooled over its surface when it has too few), clamped; and their area-weighted means,
/// over every polygon seen and over each object's.
struct RoundEstimates {
    std::vector<Rgb> rho;
    std::vector<bool> seen;
    Rgb meanRho;
    double meanArea = 0;
    ObjectMeans objects;  ///< per object, over its polygons seen
    int seenCount = 0;
};

RoundEstimates estimateFromSums(const radiosity::Scene& scene, const std::vector<int>& surface,
                                const PhotoSums& sums, const std::vector<Rgb>& sumH,
                                int minSamples) {
    const int np = static_cast<int>(scene.polygons.size());
    // A polygon with too few samples of its own (a small triangle of a reconstructed wall)
    // takes its surface's: the sums pooled over the surface's polygons.
    std::vector<Rgb> poolL(np), poolH(np);
    std::vector<int> poolCount(np, 0);
    for (int p = 0; p < np; ++p) {
        poolL[surface[p]] += sums.L[p];
        poolH[surface[p]] += sumH[p];
        poolCount[surface[p]] += sums.count[p];
    }
    RoundEstimates e;
    e.rho.resize(np);
    e.seen.assign(np, false);
    for (int p = 0; p < np; ++p) {
        if (scene.polygons[p].light >= 0) continue;
        const bool own = sums.count[p] >= minSamples;
        if (!own && poolCount[surface[p]] < minSamples) continue;
        const Rgb& L = own ? sums.L[p] : poolL[surface[p]];
        const Rgb& H = own ? sumH[p] : poolH[surface[p]];
        for (int c = 0; c < 3; ++c)  // guard: a polygon in darkness (H = 0) says nothing
            e.rho[p][c] = H[c] > 0 ? std::numbers::pi * L[c] / H[c] : scene.polygons[p].rho[c];
        e.rho[p] = clampReflectance(e.rho[p]);
        e.seen[p] = true;
        ++e.seenCount;
        e.meanRho += e.rho[p] * scene.polygons[p].area;
        e.meanArea += scene.polygons[p].area;
    }
    if (e.meanArea > 0) e.meanRho = e.meanRho * (1.0 / e.meanArea);
    e.objects = objectMeans(scene, e.rho, [&](int p) { return static_cast<bool>(e.seen[p]); });
    return e;
}

/// Sets every reflecting polygon's reflectance one damped step (see the header) towards the
/// round's estimate: a full step from the first guess, half steps after. Polygons the photo
/// does not see take the object's scene.json reflectance; else the mean of the estimates on
/// the same object's faces that the photo sees (a block's hidden back is most likely the
/// material of its front: taking the mean of the whole room instead, walls of every colour,
/// lit the Cornell box's ceiling through the blocks' unseen faces 4-9 % too little, bluest
/// where the colours differ most); else the mean of all the estimates.
void stepReflectances(radiosity::HierarchicalSolver& solver, const SceneFile& sceneFile,
                      RoundEstimates& e, int round, ReflectanceReport& report) {
    const radiosity::Scene& scene = solver.scene();
    report.polygonsSeen = e.seenCount;
    report.polygonsDefaulted = 0;
    report.lastChange = 0;
    for (int p = 0; p < static_cast<int>(scene.polygons.size()); ++p) {
        const radiosity::Polygon& poly = scene.polygons[p];
        if (poly.light >= 0) continue;
        if (!e.seen[p]) {
            ++report.polygonsDefaulted;
            const std::string& name = scene.objects[poly.object];
            auto it = sceneFile.objectSettings.find(name);
            if (it != sceneFile.objectSettings.end() && it->second.reflectance)
                e.rho[p] = *it->second.reflectance;
            else if (e.objects.area[poly.object] > 0)
                e.rho[p] = e.objects.rho[poly.object];
            else
                e.rho[p] = e.meanArea > 0 ? e.meanRho : poly.rho;
        }
        const Rgb previous = poly.rho;
        const double alpha = round == 0 ? 1.0 : 0.5;
        const Rgb next = previous * (1.0 - alpha) + e.rho[p] * alpha;
        for (int c = 0; c < 3; ++c)
            report.lastChange = std::max(report.lastChange, std::abs(next[c] - previous[c]));
        solver.setReflectance(p, next);
    }
}

/// The estimate/solve rounds of estimatePolygonReflectance, within `o.seconds` (counted
/// from `start`: at least one round) and `o.until` (none owed; see ReflectanceOptions).
void runRounds(radiosity::HierarchicalSolver& solver, const SceneFile& sceneFile,
               const PhotoSums& sums, const GatherTerms& terms, const ReflectanceOptions& o,
               radiosity::Clock::time_point start, ReflectanceReport& report) {
    const radiosity::Scene& scene = solver.scene();
    double spentBefore = radiosity::secondsSince(start);  // at the start of a round
    for (int round = 0; round < o.rounds; ++round) {
        // The irradiance sums are a final gather at every gather point; given up at
        // `until`, the round has changed nothing yet.
        std::vector<Rgb> sumH;
        if (!radiosity::runUntil(o.until, [&] { sumH = sumIrradiance(solver, sums, terms); })) {
            report.budgetReached = true;
            break;
        }
        RoundEstimates e = estimateFromSums(scene, report.surface, sums, sumH, o.minSamples);
        stepReflectances(solver, sceneFile, e, round, report);
        solver.pullReflectance();
        // Between rounds only the radiosity changes: the links stay (re-refining 700 k
        // links each round made a 22 k-triangle room's reflectance take a minute). The
        // links are refined for the final reflectances once the rounds end.
        solver.gatherPushPull();
        report.rounds = round + 1;
        const double spent = radiosity::secondsSince(start);
        const double thisRound = spent - spentBefore;
        spentBefore = spent;
        if (o.progress) {
            char msg[128];
            std::snprintf(msg, sizeof msg, "  reflectance round %d: largest change %.4f, %.1f s",
                          round + 1, report.lastChange, thisRound);
            o.progress(msg);
        }
        if (round > 0 && report.lastChange < o.tolerance) break;
        if (round + 1 == o.rounds) break;
        // The budget is checked between rounds, so the solution is always that of complete
        // rounds (consistent reflectances and radiosities), never half a round: the next
        // round is begun only when a round as long as this one fits.
        const auto roundLength = std::chrono::duration_cast<radiosity::Clock::duration>(
            std::chrono::duration<double>(thisRound));
        const bool secondsSpent = o.seconds > 0 && spent + thisRound > o.seconds;
        const bool untilPassed = o.until != radiosity::Clock::time_point::max() &&
                                 radiosity::Clock::now() + roundLength > o.until;
        if (secondsSpent || untilPassed) {
            report.budgetReached = true;
            break;
        }
    }
}

}  // namespace

ReflectanceReport estimatePolygonReflectance(radiosity::HierarchicalSolver& solver,
                                             const SceneFile& sceneFile, const ItemBuffer& items,
                                             const LightingBuffer& lighting, const Image& photo,
                                             const ReflectanceOptions& o) {
    const auto start = radiosity::Clock::now();
    ReflectanceReport report;
    const radiosity::Scene& scene = solver.scene();
    PhotoSums sums;
    GatherTerms terms;  // the gather points' terms, once: between rounds only B changes
    const bool setUp = radiosity::runUntil(o.until, [&] {
        sums = sumPhotoSamples(scene, items, lighting, photo);
        thinGatherPoints(sums.points);
        terms = gatherTerms(solver, sums, lighting);
    });
    if (!setUp) {
        report.skipped = true;
        return report;
    }
    report.surface = surfaceOf(scene);
    runRounds(solver, sceneFile, sums, terms, o, start, report);
    // The closing solve refines the links for the final reflectances; once the solver's
    // refinement time is over it would refine nothing, and the last round has gathered
    // with these reflectances already (2.6 s of energy bound and sweeps on the stair hall).
    if (!solver.refinementOver()) solver.solve();
    return report;
}

bool leafReflectanceFromTexture(const radiosity::Hierarchy& h, const radiosity::LeafMesh& mesh,
                                const LeafTexture& texture, std::span<const Rgb> H, int leaf,
                                int minSamples, Rgb* rho) {
    if (texture.samples(leaf) < minSamples) return false;
    // The ratio of the sums over the leaf's samples, each sample's H interpolated where it
    // lies (over the display piece that holds it, as the display does): a shadow edge
    // inside the leaf then weighs its lit and shadowed samples as the photo does, where the
    // mean of the leaf's corners would count the whole leaf at their average.
    (void)h;
    Rgb c, Hn;
    for (int idx : texture.sampleIndices(leaf)) {
        const radiosity::Vec3& x = texture.samplePoint(idx);
        const auto st = mesh.stencil(leaf, x);
        Rgb Hs;
        for (int i = 0; i < st.count; ++i)
            Hs += H[static_cast<size_t>(st.vertex[static_cast<size_t>(i)])] *
                  st.weight[static_cast<size_t>(i)];
        Hn += Hs;
        c += texture.sampleColour(idx);
    }
    if (!(Hn.minComponent() > 0)) return false;
    for (int ch = 0; ch < 3; ++ch) (*rho)[ch] = std::numbers::pi * c[ch] / Hn[ch];
    return true;
}

int estimateLeafReflectance(radiosity::HierarchicalSolver& solver, const radiosity::LeafMesh& mesh,
                            const LeafTexture& texture, std::span<const Rgb> H, int minSamples) {
    const radiosity::Hierarchy& h = solver.hierarchy();
    const radiosity::Scene& scene = solver.scene();
    int set = 0;
    for (int n = 0; n < static_cast<int>(h.nodes.size()); ++n) {
        const radiosity::Node& node = h.nodes[n];
        if (node.isCluster() || !node.isLeaf() || scene.polygons[node.polygon].light >= 0) continue;
        Rgb rho;
        if (!leafReflectanceFromTexture(h, mesh, texture, H, n, minSamples, &rho)) continue;
        solver.setElementReflectance(n, clampReflectance(rho));
        ++set;
    }
    solver.pullReflectance();
    return set;
}

}  // namespace relight
