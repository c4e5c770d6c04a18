#include "relight/pipeline/lighting_buffer.h"

#include <algorithm>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include "radiosity/parallel.h"
#include "radiosity/shared_gather.h"

namespace relight {

using radiosity::Rgb;
using radiosity::Vec3;

LightingBuffer computeLightingBuffer(const ItemBuffer& items,
                                     const radiosity::HierarchicalSolver& solver,
                                     radiosity::DirectLightOptions options, int stride) {
    const radiosity::DirectLight dl(solver, options);
    const radiosity::Scene& scene = solver.scene();
    LightingBuffer buf;
    buf.lights = dl.lightCount();
    buf.stride = std::max(stride, 1);
    buf.width = items.width;
    buf.spp = items.spp;
    buf.gridWidth = (items.width + buf.stride - 1) / buf.stride;
    const int gridHeight = (items.height + buf.stride - 1) / buf.stride;
    const int gridPixels = buf.gridWidth * gridHeight;
    const int n = gridPixels * items.spp;  // slots
    // Item-buffer sample of slot i.
    auto sampleOf = [&](int i) {
        const int gp = i / items.spp;
        return items.sampleIndex((gp % buf.gridWidth) * buf.stride,
                                 (gp / buf.gridWidth) * buf.stride, i % items.spp);
    };
    buf.G.assign(static_cast<size_t>(n) * buf.lights, 0.0f);
    if (buf.lights > 0) {
        radiosity::parallelForChunks(static_cast<size_t>(n), 256, [&](size_t first, size_t last) {
            std::vector<double> G(static_cast<size_t>(buf.lights));
            for (int i = static_cast<int>(first); i != static_cast<int>(last); ++i) {
                const int idx = sampleOf(i);
                const int p = items.polygon[idx];
                if (p < 0 || scene.polygons[p].light >= 0) continue;
                // The ray seed is the item-buffer sample, so that a sample's direct
                // light does not depend on the stride.
                dl.geometry(p, items.point[idx], static_cast<uint64_t>(idx), G.data());
                for (int l = 0; l < buf.lights; ++l)
                    buf.G[static_cast<size_t>(i) * buf.lights + l] = static_cast<float>(G[l]);
            }
        });
    }
    buf.rays = dl.raysCast();

    // Gather points: per pixel, one per reflecting polygon its samples see, at their mean
    // (inside the polygon: it is convex).
    buf.gatherPoint.assign(static_cast<size_t>(n), -1);
    std::vector<int> count;  // samples per gather point of the current pixel
    for (int gp = 0; gp < gridPixels; ++gp) {
        const int first = static_cast<int>(buf.gatherPolygon.size());
        count.clear();
        for (int s = 0; s < items.spp; ++s) {
            const int slot = gp * items.spp + s;
            const int idx = sampleOf(slot);
            const int p = items.polygon[idx];
            if (p < 0 || scene.polygons[p].light >= 0) continue;
            int g = first;
            while (g < static_cast<int>(buf.gatherPolygon.size()) && buf.gatherPolygon[g] != p) ++g;
            if (g == static_cast<int>(buf.gatherPolygon.size())) {
                buf.gatherPolygon.push_back(p);
                buf.gatherPosition.push_back(Vec3{0, 0, 0});
                count.push_back(0);
            }
            buf.gatherPosition[g] += items.point[idx];
            ++count[g - first];
            buf.gatherPoint[slot] = g;
        }
        for (size_t k = 0; k < count.size(); ++k)
            buf.gatherPosition[first + k] /= static_cast<double>(count[k]);
    }
    return buf;
}

void updateIndirect(LightingBuffer& buf, const radiosity::HierarchicalSolver& solver,
                    const radiosity::ProgressFn& progress, radiosity::Clock::time_point raysUntil) {
    // The far links shared per receiving element (radiosity/shared_gather.h): a per-point
    // gather walked every link above each of a stair hall's 141 k gather points, 16-18 s.
    // The shared gather keeps each point's terms, thousands where a large element holds
    // links from many small sources (5 GB there at once): the points go in chunks, by
    // polygon so that a chunk shares its elements' corners, each chunk's terms summed with
    // the radiosities now and dropped.
    const size_t m = buf.gatherPolygon.size();
    std::vector<size_t> order(m);
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return buf.gatherPolygon[a] < buf.gatherPolygon[b];
    });
    buf.indirect.assign(m, Rgb{});
    radiosity::ProgressMeter meter(progress, "final gather", m);
    std::vector<radiosity::GatherPoint> points;
    std::vector<Rgb> H;
    for (size_t first = 0; first < m; first += kIndirectChunk) {
        const size_t last = std::min(m, first + kIndirectChunk);
        points.clear();
        for (size_t k = first; k < last; ++k) {
            const size_t g = order[k];
            points.push_back(
                {buf.gatherPolygon[g], buf.gatherPosition[g], static_cast<uint64_t>(g)});
        }
        const radiosity::SharedGather gather =
            radiosity::sharedFinalGather(solver, points, 4, {}, raysUntil);
        H.assign(points.size(), Rgb{});
        gather.addIndirect(solver, H.data());
        for (size_t k = first; k < last; ++k) buf.indirect[order[k]] = H[k - first];
        meter.add(last - first);
    }
}

Rgb sampleIrradiance(const LightingBuffer& buf, const radiosity::Scene& scene, int idx) {
    const int g = buf.gatherPointOf(idx);
    if (g < 0) return {};
    Rgb H = static_cast<size_t>(g) < buf.indirect.size() ? buf.indirect[g] : Rgb{};
    const float* G = buf.direct(idx);
    for (int l = 0; l < buf.lights; ++l)
        H += scene.lights[l].emittance() * static_cast<double>(G[l]);
    return H;
}

Image renderRadiosity(const ItemBuffer& items, const LightingBuffer& buf,
                      const radiosity::Scene& scene) {
    if (buf.stride != 1)
        throw std::invalid_argument("renderRadiosity: the lighting buffer has pixel stride " +
                                    std::to_string(buf.stride) + "; it needs every pixel");
    Image img(items.width, items.height);
    radiosity::parallelForChunks(
        static_cast<size_t>(items.height), 1, [&](size_t first, size_t last) {
            for (int y = static_cast<int>(first); y != static_cast<int>(last); ++y) {
                for (int x = 0; x < items.width; ++x) {
                    Rgb sum;
                    for (int s = 0; s < items.spp; ++s) {
                        const int idx = items.sampleIndex(x, y, s);
                        const int p = items.polygon[idx];
                        if (p < 0) continue;
                        // The radiosity equation at a point, B = E + rho H (HSA91).
                        sum += scene.emittance(p) +
                               scene.polygons[p].rho * sampleIrradiance(buf, scene, idx);
                    }
                    float* px = img.at(x, y);
                    for (int c = 0; c < 3; ++c)
                        px[c] = static_cast<float>(sum[c] / (std::numbers::pi * items.spp));
                }
            }
        });
    return img;
}

int finestStrideWithin(double probeSeconds, int probeStride, int finest, double secondsLeft) {
    if (!(secondsLeft > 0) || finest < 1 || finest >= probeStride) return probeStride;
    const double probe = std::max(probeSeconds, 0.0);
    for (int s = finest; s < probeStride; s *= 2) {
        const double r = static_cast<double>(probeStride) / s;
        if (probe * r * r <= secondsLeft) return s;
    }
    return probeStride;
}

}  // namespace relight
