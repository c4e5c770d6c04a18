#include "relight/ratio_display.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace relight {

using radiosity::Rgb;

SampleHit locateSample(const ItemBuffer& items, const radiosity::Hierarchy& h,
                       const radiosity::Scene& scene, int index) {
    SampleHit hit;
    const int p = items.polygon[index];
    if (p < 0) return hit;
    if (const int light = scene.polygons[p].light; light >= 0)
        hit.light = light;
    else
        hit.leaf = h.locateLeaf(p, items.point[index]);
    return hit;
}

DisplayMap buildDisplayMap(const ItemBuffer& items, const radiosity::LeafMesh& mesh,
                           const radiosity::Scene& scene) {
    DisplayMap m;
    m.width = items.width;
    m.height = items.height;
    const int pixels = items.width * items.height;
    m.start.reserve(pixels + 1);
    m.emitterStart.reserve(pixels + 1);
    m.unshaded.assign(pixels, 0.0f);
    const double perSample = 1.0 / items.spp;
    // Per-pixel accumulators: small, searched linearly (a pixel touches few vertices).
    std::vector<std::pair<int, double>> verts, emitters;
    for (int y = 0; y < items.height; ++y) {
        for (int x = 0; x < items.width; ++x) {
            verts.clear();
            emitters.clear();
            double unshaded = 0;
            for (int s = 0; s < items.spp; ++s) {
                const int idx = items.sampleIndex(x, y, s);
                const SampleHit hit = locateSample(items, mesh.hierarchy(), scene, idx);
                if (hit.light >= 0) {
                    auto it = std::find_if(emitters.begin(), emitters.end(),
                                           [&](const auto& e) { return e.first == hit.light; });
                    if (it == emitters.end())
                        emitters.push_back({hit.light, perSample});
                    else
                        it->second += perSample;
                    continue;
                }
                if (!hit.surface()) {
                    unshaded += perSample;
                    continue;
                }
                const int leaf = hit.leaf;
                const auto w = mesh.weights(leaf, items.point[idx]);
                const auto& c = mesh.corners(leaf);
                for (int i = 0; i < mesh.hierarchy().nodes[leaf].vertexCount; ++i) {
                    if (!(w[i] > 0)) continue;
                    auto it = std::find_if(verts.begin(), verts.end(),
                                           [&](const auto& e) { return e.first == c[i]; });
                    if (it == verts.end())
                        verts.push_back({c[i], w[i] * perSample});
                    else
                        it->second += w[i] * perSample;
                }
            }
            m.start.push_back(static_cast<int>(m.vertex.size()));
            for (const auto& [v, w] : verts) {
                m.vertex.push_back(v);
                m.weight.push_back(static_cast<float>(w));
            }
            m.emitterStart.push_back(static_cast<int>(m.emitterLight.size()));
            for (const auto& [l, f] : emitters) {
                m.emitterLight.push_back(l);
                m.emitterFraction.push_back(static_cast<float>(f));
            }
            m.unshaded[y * items.width + x] = static_cast<float>(unshaded);
        }
    }
    m.start.push_back(static_cast<int>(m.vertex.size()));
    m.emitterStart.push_back(static_cast<int>(m.emitterLight.size()));
    return m;
}

int trustPhotoAtEmitters(DisplayMap& m, const Image& photo, std::span<const Rgb> radianceInPhoto) {
    int changed = 0;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            const int px = y * m.width + x;
            Rgb expected;
            for (int k = m.emitterStart[px]; k < m.emitterStart[px + 1]; ++k)
                expected += radianceInPhoto[m.emitterLight[k]] * m.emitterFraction[k];
            const float* t = photo.at(x, y);
            const double shown = std::max({t[0], t[1], t[2]});
            if (!(expected.maxComponent() > 0) || shown >= 0.5 * expected.maxComponent()) continue;
            for (int k = m.emitterStart[px]; k < m.emitterStart[px + 1]; ++k) {
                if (!(radianceInPhoto[m.emitterLight[k]].maxComponent() > 0)) continue;
                m.unshaded[px] += m.emitterFraction[k];
                m.emitterFraction[k] = 0;
            }
            ++changed;
        }
    return changed;
}

Rgb ratioFloor(std::span<const Rgb> D) {
    Rgb mean;
    for (const Rgb& d : D) mean += d;
    if (!D.empty()) mean = mean * (1.0 / static_cast<double>(D.size()));
    Rgb delta = mean * kRatioFloor;
    // A scene with no light at all in the photo: every D is 0; delta must stay positive.
    for (int c = 0; c < 3; ++c)
        if (!(delta[c] > 0)) delta[c] = 1e-30;
    return delta;
}

std::vector<Rgb> displayRatio(std::span<const Rgb> B, std::span<const Rgb> D) {
    const Rgb delta = ratioFloor(D);
    std::vector<Rgb> r(D.size());
    for (size_t v = 0; v < D.size(); ++v)
        for (int c = 0; c < 3; ++c)
            r[v][c] = (std::max(B[v][c], 0.0) + delta[c]) / (std::max(D[v][c], 0.0) + delta[c]);
    return r;
}

Image renderRatio(const DisplayMap& map, const Image& photo, std::span<const Rgb> ratio,
                  std::span<const Rgb> radianceNow, std::span<const Rgb> radianceInPhoto) {
    Image out(map.width, map.height);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, map.height), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y) {
                for (int x = 0; x < map.width; ++x) {
                    const int px = y * map.width + x;
                    const float* t = photo.at(x, y);
                    Rgb T{t[0], t[1], t[2]};
                    Rgb emitNow;
                    double emitFraction = 0;
                    for (int k = map.emitterStart[px]; k < map.emitterStart[px + 1]; ++k) {
                        const double f = map.emitterFraction[k];
                        T -= radianceInPhoto[map.emitterLight[k]] * f;
                        emitNow += radianceNow[map.emitterLight[k]] * f;
                        emitFraction += f;
                    }
                    Rgb sum = Rgb::gray(map.unshaded[px]);
                    for (int k = map.start[px]; k < map.start[px + 1]; ++k)
                        sum += ratio[map.vertex[k]] * static_cast<double>(map.weight[k]);
                    const double rest = 1.0 - emitFraction;
                    Rgb value = emitNow;
                    // T_rest is left signed: where the photo shows less of a face than the item
                    // buffer says (its edge), T_rest < 0 and the unedited display still gives
                    // back T exactly; only the result is clamped.
                    if (rest > 1e-6)
                        for (int c = 0; c < 3; ++c) value[c] += T[c] * sum[c] / rest;
                    float* o = out.at(x, y);
                    for (int c = 0; c < 3; ++c) o[c] = static_cast<float>(std::max(value[c], 0.0));
                }
            }
        });
    return out;
}

}  // namespace relight
