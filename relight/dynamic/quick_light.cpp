#include "relight/dynamic/quick_light.h"

#include "radiosity/detail/rng.h"
#include "radiosity/parallel.h"

namespace relight {

namespace {
// The stream of a pixel's quick ray: apart from the exact light's (seeded by the sample).
constexpr uint64_t kQuickSeed = 0x9b1c4a11ull << 20;
}  // namespace

std::vector<float> quickPixelLight(const ItemBuffer& items, const radiosity::Scene& scene,
                                   const radiosity::Visibility& vis,
                                   const radiosity::Emitter& light) {
    const size_t n = static_cast<size_t>(light.components());
    const size_t pixels = static_cast<size_t>(items.width) * static_cast<size_t>(items.height);
    std::vector<float> out(pixels * n, 0.0f);
    const int spp = items.spp;
    radiosity::parallelForChunks(pixels, 256, [&](size_t first, size_t last) {
        double unit[radiosity::kMaxEmitterComponents] = {};
        for (size_t px = first; px != last; ++px) {
            const int x = static_cast<int>(px % static_cast<size_t>(items.width));
            const int y = static_cast<int>(px / static_cast<size_t>(items.width));
            // The middle sample (nearest the pixel's centre of its strata), else the first
            // that sees a reflecting surface, as the exact mean counts them.
            int idx = -1;
            for (int k = 0; k <= spp && idx < 0; ++k) {
                const int s = k == 0 ? spp / 2 : k - 1;
                if (k > 0 && s == spp / 2) continue;
                const int i = items.sampleIndex(x, y, s);
                const int p = items.polygon[static_cast<size_t>(i)];
                if (p >= 0 && scene.polygons[static_cast<size_t>(p)].light < 0) idx = i;
            }
            if (idx < 0) continue;
            const int p = items.polygon[static_cast<size_t>(idx)];
            const radiosity::ReceiverPoint at{items.point[static_cast<size_t>(idx)],
                                              scene.polygons[static_cast<size_t>(p)].normal, p};
            radiosity::Rng rng(kQuickSeed ^ static_cast<uint64_t>(idx));
            light.unitIrradiance(vis, at, 1, rng, unit);
            for (size_t c = 0; c < n; ++c) out[px * n + c] = static_cast<float>(unit[c]);
        }
    });
    return out;
}

}  // namespace relight
