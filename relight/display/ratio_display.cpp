#include "relight/display/ratio_display.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "radiosity/parallel.h"

namespace relight {

using radiosity::parallelFor;
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

namespace {

/// Rows of the display map built in parallel: each band into its own arrays (offsets from
/// the band's start), then joined in order, so that the map does not depend on the number
/// of threads.
constexpr int kBandRows = 8;
struct DisplayBand {
    std::vector<int> start, vertex, emitterStart, emitterLight;
    std::vector<float> weight, emitterFraction;
};

/// What one pixel's samples see, each sample weighing 1/spp: the leaf vertices that
/// interpolate at its points (with their weights), the lights whose faces it sees (with the
/// fraction of samples), and the fraction on nothing to shade (background, no leaf).
struct PixelCover {
    std::vector<std::pair<int, double>> verts, emitters;  // small: searched linearly
    double unshaded = 0;
};

void coverPixel(const ItemBuffer& items, const radiosity::LeafMesh& mesh,
                const radiosity::Scene& scene, int x, int y, PixelCover& cover) {
    const double perSample = 1.0 / items.spp;
    cover.verts.clear();
    cover.emitters.clear();
    cover.unshaded = 0;
    auto add = [](std::vector<std::pair<int, double>>& list, int key, double w) {
        auto it =
            std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == key; });
        if (it == list.end())
            list.push_back({key, w});
        else
            it->second += w;
    };
    for (int s = 0; s < items.spp; ++s) {
        const int idx = items.sampleIndex(x, y, s);
        const SampleHit hit = locateSample(items, mesh.hierarchy(), scene, idx);
        if (hit.light >= 0) {
            add(cover.emitters, hit.light, perSample);
            continue;
        }
        if (!hit.surface()) {
            cover.unshaded += perSample;
            continue;
        }
        const auto st = mesh.stencil(hit.leaf, items.point[idx]);
        for (int i = 0; i < st.count; ++i)
            if (st.weight[i] > 0) add(cover.verts, st.vertex[i], st.weight[i] * perSample);
    }
}

/// Band `b` of the map: its pixels' entries, and their unshaded fractions into `unshaded`.
void buildBand(const ItemBuffer& items, const radiosity::LeafMesh& mesh,
               const radiosity::Scene& scene, int b, DisplayBand& band,
               std::vector<float>& unshaded) {
    const int y0 = b * kBandRows, y1 = std::min(items.height, y0 + kBandRows);
    const size_t bandPixels = static_cast<size_t>(y1 - y0) * items.width;
    band.start.reserve(bandPixels);
    band.emitterStart.reserve(bandPixels);
    band.vertex.reserve(bandPixels * 4);  // a pixel inside a quad leaf: its 4 corners
    band.weight.reserve(bandPixels * 4);
    PixelCover cover;
    for (int y = y0; y < y1; ++y) {
        for (int x = 0; x < items.width; ++x) {
            coverPixel(items, mesh, scene, x, y, cover);
            band.start.push_back(static_cast<int>(band.vertex.size()));
            for (const auto& [v, w] : cover.verts) {
                band.vertex.push_back(v);
                band.weight.push_back(static_cast<float>(w));
            }
            band.emitterStart.push_back(static_cast<int>(band.emitterLight.size()));
            for (const auto& [l, f] : cover.emitters) {
                band.emitterLight.push_back(l);
                band.emitterFraction.push_back(static_cast<float>(f));
            }
            unshaded[static_cast<size_t>(y) * items.width + x] = static_cast<float>(cover.unshaded);
        }
    }
}

/// The bands joined: each band's entries go after those of the bands above it.
void joinBands(std::vector<DisplayBand>& bands, DisplayMap& m) {
    const int pixels = m.width * m.height;
    std::vector<size_t> vFirst(bands.size() + 1, 0), eFirst(bands.size() + 1, 0);
    for (size_t b = 0; b < bands.size(); ++b) {
        vFirst[b + 1] = vFirst[b] + bands[b].vertex.size();
        eFirst[b + 1] = eFirst[b] + bands[b].emitterLight.size();
    }
    if (vFirst.back() > static_cast<size_t>(std::numeric_limits<int>::max()))
        throw std::length_error("buildDisplayMap: more than 2^31 (pixel, vertex) pairs");
    m.start.resize(static_cast<size_t>(pixels) + 1);
    m.emitterStart.resize(static_cast<size_t>(pixels) + 1);
    m.vertex.resize(vFirst.back());
    m.weight.resize(vFirst.back());
    m.emitterLight.resize(eFirst.back());
    m.emitterFraction.resize(eFirst.back());
    radiosity::parallelFor(bands.size(), 1, [&](size_t b) {
        DisplayBand& band = bands[b];
        const size_t p0 = static_cast<size_t>(b) * kBandRows * m.width;
        for (size_t i = 0; i < band.start.size(); ++i) {
            m.start[p0 + i] = band.start[i] + static_cast<int>(vFirst[b]);
            m.emitterStart[p0 + i] = band.emitterStart[i] + static_cast<int>(eFirst[b]);
        }
        std::copy(band.vertex.begin(), band.vertex.end(), m.vertex.begin() + vFirst[b]);
        std::copy(band.weight.begin(), band.weight.end(), m.weight.begin() + vFirst[b]);
        std::copy(band.emitterLight.begin(), band.emitterLight.end(),
                  m.emitterLight.begin() + eFirst[b]);
        std::copy(band.emitterFraction.begin(), band.emitterFraction.end(),
                  m.emitterFraction.begin() + eFirst[b]);
        band = DisplayBand();  // freed as we go: the map is the peak of memory
    });
    m.start[pixels] = static_cast<int>(vFirst.back());
    m.emitterStart[pixels] = static_cast<int>(eFirst.back());
}

}  // namespace

DisplayMap buildDisplayMap(const ItemBuffer& items, const radiosity::LeafMesh& mesh,
                           const radiosity::Scene& scene) {
    DisplayMap m;
    m.width = items.width;
    m.height = items.height;
    m.unshaded.assign(static_cast<size_t>(items.width) * items.height, 0.0f);
    std::vector<DisplayBand> bands(static_cast<size_t>((items.height + kBandRows - 1) / kBandRows));
    radiosity::parallelFor(bands.size(), 1, [&](size_t b) {
        buildBand(items, mesh, scene, static_cast<int>(b), bands[b], m.unshaded);
    });
    joinBands(bands, m);
    packDisplayMap(m);
    return m;
}

void packDisplayMap(DisplayMap& m) {
    using Run = DisplayMap::Run;
    const size_t pixels = static_cast<size_t>(m.width) * m.height;
    m.runWeight.assign(pixels * 3, 0.0f);
    std::vector<std::vector<Run>> rows(static_cast<size_t>(m.height));
    radiosity::parallelFor(static_cast<size_t>(m.height), 1, [&](size_t row) {
        const int y = static_cast<int>(row);
        std::vector<Run>& runs = rows[row];
        for (int x = 0; x < m.width; ++x) {
            const size_t px = static_cast<size_t>(y) * m.width + x;
            const int k0 = m.start[px], count = m.start[px + 1] - k0;
            Run here;
            here.x0 = x;
            here.length = 1;
            if (m.emitterStart[px] == m.emitterStart[px + 1] && m.unshaded[px] == 0 && count >= 1 &&
                count <= 4) {
                for (int i = 0; i < 4; ++i) here.vertex[i] = m.vertex[k0 + (i < count ? i : 0)];
                for (int i = 1; i < count; ++i) m.runWeight[px * 3 + (i - 1)] = m.weight[k0 + i];
            }
            if (!runs.empty() && runs.back().vertex == here.vertex)
                ++runs.back().length;
            else
                runs.push_back(here);
        }
    });
    m.rowRuns.assign(static_cast<size_t>(m.height) + 1, 0);
    for (int y = 0; y < m.height; ++y)
        m.rowRuns[y + 1] = m.rowRuns[y] + static_cast<int>(rows[y].size());
    m.runs.resize(static_cast<size_t>(m.rowRuns.back()));
    for (int y = 0; y < m.height; ++y)
        std::copy(rows[y].begin(), rows[y].end(), m.runs.begin() + m.rowRuns[y]);
}

void weighByPhotoRadiance(DisplayMap& m, std::span<const double> photoRadiance) {
    const size_t pixels = static_cast<size_t>(m.width) * static_cast<size_t>(m.height);
    for (const int v : m.vertex)
        if (v < 0 || static_cast<size_t>(v) >= photoRadiance.size())
            throw std::invalid_argument("weighByPhotoRadiance: vertex " + std::to_string(v) +
                                        " of the map, " + std::to_string(photoRadiance.size()) +
                                        " values given");
    parallelFor(pixels, 1024, [&](size_t px) {
        const int k0 = m.start[px], k1 = m.start[px + 1];
        double total = 0, weighed = 0;
        for (int k = k0; k < k1; ++k) {
            const double y = photoRadiance[static_cast<size_t>(m.vertex[k])];
            total += static_cast<double>(m.weight[k]);
            weighed +=
                static_cast<double>(m.weight[k]) * (std::isfinite(y) ? std::max(y, 0.0) : 0.0);
        }
        // Nothing shown in the photo at any of the pixel's vertices: no basis to weigh by.
        if (!(weighed > 0) || !std::isfinite(weighed)) return;
        const double scale = total / weighed;
        for (int k = k0; k < k1; ++k) {
            const double y = photoRadiance[static_cast<size_t>(m.vertex[k])];
            m.weight[k] = static_cast<float>(static_cast<double>(m.weight[k]) *
                                             (std::isfinite(y) ? std::max(y, 0.0) : 0.0) * scale);
        }
    });
    packDisplayMap(m);
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
        for (int c = 0; c < 3; ++c) r[v][c] = guardedRatio(B[v][c], D[v][c], delta[c]);
    return r;
}

Image renderRatio(const DisplayMap& map, const Image& photo, std::span<const Rgb> ratio,
                  std::span<const Rgb> radianceNow, std::span<const Rgb> radianceInPhoto) {
    Image out;
    renderRatio(map, photo, ratio, radianceNow, radianceInPhoto, out);
    return out;
}

namespace {

// The pixels of one leaf run: out = max(0, T r) with r = q0 + w1 d1 + w2 d2 + w3 d3 per
// channel. Written channel by channel with the run's constants in scalars and pointers
// that do not alias, so that the compiler vectorises it (interleaved RGB, groups of 3):
// at 12 MP this loop is the whole edit, and scalar code was compute-bound at about twice
// the time.
void leafRun(const float* __restrict t, const float* __restrict w, float* __restrict o, int length,
             const float* q, const float (*d)[3]) {
    const float q0 = q[0], q1 = q[1], q2 = q[2];
    const float a0 = d[0][0], a1 = d[0][1], a2 = d[0][2];
    const float b0 = d[1][0], b1 = d[1][1], b2 = d[1][2];
    const float c0 = d[2][0], c1 = d[2][1], c2 = d[2][2];
    for (int j = 0; j < length; ++j) {
        const float x = w[3 * j], y = w[3 * j + 1], z = w[3 * j + 2];
        o[3 * j] = std::max(t[3 * j] * (q0 + x * a0 + y * b0 + z * c0), 0.0f);
        o[3 * j + 1] = std::max(t[3 * j + 1] * (q1 + x * a1 + y * b1 + z * c1), 0.0f);
        o[3 * j + 2] = std::max(t[3 * j + 2] * (q2 + x * a2 + y * b2 + z * c2), 0.0f);
    }
}

// The same with an added radiance interpolated alike: out = max(0, T r + a), a = p0 + w1 e1 +
// w2 e2 + w3 e3 (the confidence display).
void leafRunAdded(const float* __restrict t, const float* __restrict w, float* __restrict o,
                  int length, const float* q, const float (*d)[3], const float* p,
                  const float (*e)[3]) {
    for (int j = 0; j < length; ++j) {
        const float x = w[3 * j], y = w[3 * j + 1], z = w[3 * j + 2];
        for (int c = 0; c < 3; ++c) {
            const float r = q[c] + x * d[0][c] + y * d[1][c] + z * d[2][c];
            const float a = p[c] + x * e[0][c] + y * e[1][c] + z * e[2][c];
            o[3 * j + c] = std::max(t[3 * j + c] * r + a, 0.0f);
        }
    }
}

/// A leaf run's vertex values read once: v0 = f(vertex[0]) and d[i] = f(vertex[i + 1]) - v0,
/// so that the interpolation sum_i w_i f_i is v0 + sum_i w_i d[i-1] (the weights sum to 1).
const float* runDeltas(const std::vector<std::array<float, 4>>& f, const DisplayMap::Run& run,
                       float (*d)[3]) {
    const float* v0 = f[static_cast<size_t>(run.vertex[0])].data();
    for (int i = 0; i < 3; ++i) {
        const float* vi = f[static_cast<size_t>(run.vertex[i + 1])].data();
        for (int c = 0; c < 3; ++c) d[i][c] = vi[c] - v0[c];
    }
    return v0;
}

/// Per vertex as floats, 16 bytes a vertex: the table stays in cache while the pixels
/// stream through.
std::vector<std::array<float, 4>> asFloats(std::span<const Rgb> values) {
    std::vector<std::array<float, 4>> f(values.size());
    for (size_t v = 0; v < values.size(); ++v)
        f[v] = {static_cast<float>(values[v][0]), static_cast<float>(values[v][1]),
                static_cast<float>(values[v][2]), 0.0f};
    return f;
}

}  // namespace

void ratioPixel(const DisplayMap& map, const Image& photo, size_t px,
                const std::array<float, 4>* ratio, const std::array<float, 4>* added,
                std::span<const Rgb> radianceNow, std::span<const Rgb> radianceInPhoto,
                Image& out) {
    // A pixel from the general arrays: any mix of vertices, emitting faces and unshaded
    // samples.
    const float* t = photo.rgb.data() + 3 * px;
    float* o = out.rgb.data() + 3 * px;
    float sum[3], add[3] = {0, 0, 0};
    sum[0] = sum[1] = sum[2] = map.unshaded[px];
    for (int k = map.start[px]; k < map.start[px + 1]; ++k) {
        const float w = map.weight[k];
        const float* q = ratio[static_cast<size_t>(map.vertex[k])].data();
        for (int c = 0; c < 3; ++c) sum[c] += w * q[c];
        if (added) {
            const float* p = added[static_cast<size_t>(map.vertex[k])].data();
            for (int c = 0; c < 3; ++c) add[c] += w * p[c];
        }
    }
    if (map.emitterStart[px] == map.emitterStart[px + 1]) {
        // No emitting face in the pixel: T times the mean ratio (plus the added term).
        for (int c = 0; c < 3; ++c) o[c] = std::max(t[c] * sum[c] + add[c], 0.0f);
        return;
    }
    Rgb T{t[0], t[1], t[2]};
    Rgb emitNow;
    double emitFraction = 0;
    for (int k = map.emitterStart[px]; k < map.emitterStart[px + 1]; ++k) {
        const double f = map.emitterFraction[k];
        T -= radianceInPhoto[map.emitterLight[k]] * f;
        emitNow += radianceNow[map.emitterLight[k]] * f;
        emitFraction += f;
    }
    const double rest = 1.0 - emitFraction;
    Rgb value = emitNow + Rgb{add[0], add[1], add[2]};
    // T_rest is left signed: where the photo shows less of a face than the item buffer
    // says (its edge), T_rest < 0 and the unedited display still gives back T exactly;
    // only the result is clamped.
    if (rest > 1e-6)
        for (int c = 0; c < 3; ++c) value[c] += T[c] * static_cast<double>(sum[c]) / rest;
    for (int c = 0; c < 3; ++c) o[c] = static_cast<float>(std::max(value[c], 0.0));
}

void renderRatio(const DisplayMap& map, const Image& photo, std::span<const Rgb> ratio,
                 std::span<const Rgb> radianceNow, std::span<const Rgb> radianceInPhoto, Image& out,
                 std::span<const Rgb> added, bool leafRuns) {
    if (out.width != map.width || out.height != map.height) out = Image(map.width, map.height);
    if (!added.empty() && added.size() != ratio.size())
        throw std::invalid_argument("renderRatio: " + std::to_string(added.size()) +
                                    " added values for " + std::to_string(ratio.size()) +
                                    " vertices");
    // One multiply-add per (pixel, vertex) pair, Eq. (3); two with an added radiance.
    const std::vector<std::array<float, 4>> r = asFloats(ratio);
    const std::vector<std::array<float, 4>> a = asFloats(added);
    const bool adds = !a.empty();
    const bool packed = map.rowRuns.size() == static_cast<size_t>(map.height) + 1 &&
                        map.runWeight.size() == static_cast<size_t>(map.width) * map.height * 3;

    auto general = [&](int x, int y) {
        ratioPixel(map, photo,
                   static_cast<size_t>(y) * static_cast<size_t>(map.width) + static_cast<size_t>(x),
                   r.data(), adds ? a.data() : nullptr, radianceNow, radianceInPhoto, out);
    };

    // Rows in fixed blocks: each pixel is computed alone, so the image does not depend on
    // the number of threads.
    parallelFor(static_cast<size_t>(map.height), 4, [&](size_t row) {
        const int y = static_cast<int>(row);
        if (!packed) {
            for (int x = 0; x < map.width; ++x) general(x, y);
            return;
        }
        for (int k = map.rowRuns[y]; k < map.rowRuns[y + 1]; ++k) {
            const DisplayMap::Run& run = map.runs[k];
            if (run.vertex[0] < 0) {
                for (int x = run.x0; x < run.x0 + run.length; ++x) general(x, y);
                continue;
            }
            if (!leafRuns) continue;
            // r = r_0 + sum_i w_i (r_i - r_0): the run's vertex ratios read once.
            float d[3][3];
            const float* q0 = runDeltas(r, run, d);
            const size_t first = static_cast<size_t>(y) * map.width + run.x0;
            if (!adds) {
                leafRun(photo.rgb.data() + first * 3, map.runWeight.data() + first * 3,
                        out.rgb.data() + first * 3, run.length, q0, d);
                continue;
            }
            float e[3][3];
            const float* p0 = runDeltas(a, run, e);
            leafRunAdded(photo.rgb.data() + first * 3, map.runWeight.data() + first * 3,
                         out.rgb.data() + first * 3, run.length, q0, d, p0, e);
        }
    });
}

}  // namespace relight
