#include "relight/pipeline/pixel_light.h"

#include <algorithm>
#include <numbers>
#include <stdexcept>
#include <string>

#include "radiosity/parallel.h"
#include "relight/pipeline/lighting_buffer.h"

namespace relight {

using radiosity::Rgb;

std::vector<float> measurePixelDirect(const ItemBuffer& items,
                                      const radiosity::HierarchicalSolver& solver,
                                      radiosity::DirectLightOptions options) {
    // G per sample, every pixel (stride 1), the shadow rays seeded by the sample.
    const LightingBuffer buf = computeLightingBuffer(items, solver, options, 1);
    const size_t L = static_cast<size_t>(buf.lights);
    const size_t pixels = static_cast<size_t>(items.width) * static_cast<size_t>(items.height);
    std::vector<float> out(pixels * L, 0.0f);
    const auto& polygons = solver.scene().polygons;
    radiosity::parallelFor(pixels, 64, [&](size_t px) {
        const int x = static_cast<int>(px % static_cast<size_t>(items.width));
        const int y = static_cast<int>(px / static_cast<size_t>(items.width));
        std::vector<double> sum(L, 0.0);
        int n = 0;
        for (int s = 0; s < items.spp; ++s) {
            const int idx = items.sampleIndex(x, y, s);
            const int p = items.polygon[static_cast<size_t>(idx)];
            if (p < 0 || polygons[static_cast<size_t>(p)].light >= 0) continue;
            const float* G = buf.direct(idx);
            for (size_t l = 0; l < L; ++l) sum[l] += static_cast<double>(G[l]);
            ++n;
        }
        if (n == 0) return;
        for (size_t l = 0; l < L; ++l)
            out[px * L + l] = static_cast<float>(std::numbers::pi * sum[l] / n);
    });
    return out;
}

std::vector<Rgb> vertexIndirect(const VertexLighting& lighting, const VertexDirect& direct) {
    if (lighting.lights != direct.lights || lighting.response.size() != direct.visible.size())
        throw std::invalid_argument("vertexIndirect: lighting and direct light differ in size");
    std::vector<Rgb> ind(lighting.response.size());
    for (size_t i = 0; i < ind.size(); ++i)
        ind[i] = lighting.response[i] - Rgb::gray(direct.visible[i]);
    return ind;
}

void renderPixelLight(const DisplayMap& map, const Image& photo, std::span<const float> pixelDirect,
                      std::span<const Rgb> indirect, std::span<const Rgb> radianceNow,
                      std::span<const Rgb> radianceInPhoto, Image& out) {
    const size_t L = radianceInPhoto.size();
    const size_t pixels = static_cast<size_t>(map.width) * static_cast<size_t>(map.height);
    if (radianceNow.size() != L || pixelDirect.size() != pixels * L ||
        (L > 0 && indirect.size() % L != 0) || out.width != map.width || out.height != map.height)
        throw std::invalid_argument("renderPixelLight: sizes do not match (" +
                                    std::to_string(pixelDirect.size()) + " direct values for " +
                                    std::to_string(pixels) + " pixels x " + std::to_string(L) +
                                    " lights)");
    // Per-light irradiance of every surface pixel under the photo's light, for the guard
    // delta (kRatioFloor times its mean, per channel, as the ratio display's).
    const auto pixelH = [&](size_t px, std::span<const Rgb> radiance) {
        double wsum = 0;
        for (int k = map.start[px]; k < map.start[px + 1]; ++k)
            wsum += static_cast<double>(map.weight[static_cast<size_t>(k)]);
        Rgb H;
        for (size_t l = 0; l < L; ++l) {
            Rgb ind;
            for (int k = map.start[px]; k < map.start[px + 1]; ++k)
                ind += indirect[static_cast<size_t>(map.vertex[static_cast<size_t>(k)]) * L + l] *
                       (static_cast<double>(map.weight[static_cast<size_t>(k)]) / wsum);
            H += radiance[l] * (Rgb::gray(static_cast<double>(pixelDirect[px * L + l])) + ind);
        }
        return H;
    };
    const auto surface = [&](size_t px) {
        return map.emitterStart[px] == map.emitterStart[px + 1] && map.unshaded[px] == 0 &&
               map.start[px] < map.start[px + 1];
    };
    Rgb meanPhoto;
    size_t count = 0;
    for (size_t px = 0; px < pixels; ++px)
        if (surface(px)) {
            meanPhoto += pixelH(px, radianceInPhoto);
            ++count;
        }
    const Rgb delta = meanPhoto * (kRatioFloor / static_cast<double>(std::max<size_t>(count, 1)));
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        if (!surface(px)) return;  // the ratio display's value stays
        const Rgb now = pixelH(px, radianceNow), before = pixelH(px, radianceInPhoto);
        const float* t = photo.rgb.data() + px * 3;
        float* o = out.rgb.data() + px * 3;
        for (int c = 0; c < 3; ++c) {
            const double d = std::max(delta[c], 1e-300);  // a photo with no light at all
            const double r = (std::max(now[c], 0.0) + d) / (std::max(before[c], 0.0) + d);
            o[c] = std::max(static_cast<float>(static_cast<double>(t[c]) * r), 0.0f);
        }
    });
}

}  // namespace relight
