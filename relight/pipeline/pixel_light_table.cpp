#include "relight/pipeline/pixel_light_table.h"

#include <algorithm>
#include <array>

#include "radiosity/parallel.h"
#include "relight/pipeline/pixel_light.h"

namespace relight {

using radiosity::Rgb;

namespace {

/// Pixels per chunk of the edit: 3 channels of `now` on the stack (6 KiB) stay in L1 while
/// each light's arrays stream through once.
constexpr size_t kChunk = 512;

/// h_l(p) for every light at pixel px, in double: pi Gbar_l(p) plus the indirect part
/// interpolated with the display map's weights, as renderPixelLight() sums them.
void pixelResponses(const DisplayMap& map, size_t px, std::span<const float> pixelDirect,
                    std::span<const Rgb> indirect, size_t L, std::vector<Rgb>& h) {
    pixelIndirectParts(map, px, indirect, L, [&](size_t l, const Rgb& ind) {
        h[l] = Rgb::gray(static_cast<double>(pixelDirect[px * L + l])) + ind;
    });
}

/// The pixels the per-pixel display does not draw and the vertices they read.
void ratioPart(const DisplayMap& map, size_t pixels, PixelLightTable& t) {
    std::vector<char> used;
    for (size_t px = 0; px < pixels; ++px) {
        if (shownPerPixel(map, px)) continue;
        t.ratioPixels.push_back(static_cast<int>(px));
        for (int k = map.start[px]; k < map.start[px + 1]; ++k) {
            const size_t v = static_cast<size_t>(map.vertex[static_cast<size_t>(k)]);
            if (v >= used.size()) used.resize(v + 1, 0);
            if (!used[v]) t.ratioVertices.push_back(static_cast<int>(v));
            used[v] = 1;
        }
    }
    std::sort(t.ratioVertices.begin(), t.ratioVertices.end());
}

}  // namespace

PixelLightTable pixelLightTable(const DisplayMap& map, const Image& photo,
                                std::span<const float> pixelDirect, std::span<const Rgb> indirect,
                                std::span<const Rgb> radianceInPhoto, const Rgb& delta,
                                const PhotoPixels* pool) {
    const size_t L = radianceInPhoto.size();
    const size_t pixels = static_cast<size_t>(map.width) * static_cast<size_t>(map.height);
    PixelLightTable t;
    if (L == 0 || pixelDirect.size() != pixels * L || indirect.size() % L != 0 ||
        3 * pixels * L > kMaxPixelTransfers)
        return t;
    t.pixels = pixels;
    t.lights = L;
    t.delta = delta;
    t.h.assign(3 * pixels * L, 0.0f);
    t.rho.assign(3 * pixels, 0.0f);
    t.photoLight.assign(pixels, 0.0f);
    radiosity::parallelForChunks(pixels, 256, [&](size_t begin, size_t end) {
        std::vector<Rgb> h(L);
        for (size_t px = begin; px < end; ++px) {
            if (!shownPerPixel(map, px)) continue;
            pixelResponses(map, px, pixelDirect, indirect, L, h);
            Rgb H;
            for (size_t l = 0; l < L; ++l) {
                H += radianceInPhoto[l] * h[l];
                for (size_t c = 0; c < 3; ++c)
                    t.h[(l * 3 + c) * pixels + px] = static_cast<float>(h[l][static_cast<int>(c)]);
            }
            for (int c = 0; c < 3; ++c) {
                const size_t i = 3 * px + static_cast<size_t>(c);
                t.rho[i] = static_cast<float>(static_cast<double>(photo.rgb[i]) /
                                              (std::max(H[c], 0.0) + delta[c]));
            }
            t.photoLight[px] = static_cast<float>(H.luminance());
        }
    });
    ratioPart(map, pixels, t);
    if (pool && pool->light.size() == pixels && pool->rho.size() == 3 * pixels &&
        5 * 3 * pixels <= kMaxPixelTransfers)
        t.pooled = pooledByRadius(map, *pool);
    return t;
}

namespace {

/// now[c][j] = sum_l L_l,c h[l][c][p0 + j]: one contiguous multiply-add per light and
/// channel (vectorised), skipping the channels of lights at radiance 0.
void sumLights(const PixelLightTable& t, std::span<const Rgb> radianceNow, size_t p0, size_t n,
               float (*now)[kChunk]) {
    for (int c = 0; c < 3; ++c) std::fill(now[c], now[c] + n, 0.0f);
    for (size_t l = 0; l < t.lights; ++l)
        for (int c = 0; c < 3; ++c) {
            const float a = static_cast<float>(radianceNow[l][c]);
            if (a == 0.0f) continue;
            const float* __restrict hp =
                t.h.data() + (l * 3 + static_cast<size_t>(c)) * t.pixels + p0;
            float* __restrict np = now[c];
            for (size_t j = 0; j < n; ++j) np[j] += a * hp[j];
        }
}

/// out = max(0, rho (max(now, 0) + delta)), interleaved RGB.
void writeRatio(const float* __restrict rho, const float (*now)[kChunk], const float* d, size_t n,
                float* __restrict o) {
    const float* __restrict n0 = now[0];
    const float* __restrict n1 = now[1];
    const float* __restrict n2 = now[2];
    for (size_t j = 0; j < n; ++j) {
        o[3 * j] = std::max(rho[3 * j] * (std::max(n0[j], 0.0f) + d[0]), 0.0f);
        o[3 * j + 1] = std::max(rho[3 * j + 1] * (std::max(n1[j], 0.0f) + d[1]), 0.0f);
        o[3 * j + 2] = std::max(rho[3 * j + 2] * (std::max(n2[j], 0.0f) + d[2]), 0.0f);
    }
}

bool samePhotoLight(std::span<const Rgb> now, std::span<const Rgb> photo) {
    return now.size() == photo.size() && std::equal(now.begin(), now.end(), photo.begin());
}

}  // namespace

void renderPixelLightFast(const PixelLightTable& t, const DisplayMap& map, const Image& photo,
                          std::span<const Rgb> radianceNow, std::span<const Rgb> radianceInPhoto,
                          Image& out, const PhotoPixels* pool) {
    if (radianceNow.size() != t.lights || photo.rgb.size() != 3 * t.pixels)
        throw std::invalid_argument("renderPixelLightFast: sizes do not match the table");
    if (out.width != map.width || out.height != map.height) out = Image(map.width, map.height);
    if (samePhotoLight(radianceNow, radianceInPhoto)) {
        // The photo's own light: the ratio is exactly 1, the photo is given back bit for bit.
        const float* __restrict T = photo.rgb.data();
        float* __restrict o = out.rgb.data();
        radiosity::parallelForChunks(3 * t.pixels, 3 * kChunk, [&](size_t b, size_t e) {
            for (size_t i = b; i < e; ++i) o[i] = std::max(T[i], 0.0f);
        });
        return;
    }
    const bool pooling = pool && pool->rho.size() == 3 * t.pixels && pool->light.size() == t.pixels;
    const float d[3] = {static_cast<float>(t.delta[0]), static_cast<float>(t.delta[1]),
                        static_cast<float>(t.delta[2])};
    const size_t chunks = (t.pixels + kChunk - 1) / kChunk;
    radiosity::parallelFor(chunks, 1, [&](size_t k) {
        const size_t p0 = k * kChunk, n = std::min(kChunk, t.pixels - p0);
        alignas(64) float now[3][kChunk];
        sumLights(t, radianceNow, p0, n, now);
        float* o = out.rgb.data() + 3 * p0;
        writeRatio(t.rho.data() + 3 * p0, now, d, n, o);
        if (!pooling) return;
        // Where the edit brightens the photo's light by more than kPoolAbove: the pooled
        // reflectance (pixel_light.h). The threshold is tested in float first; pooledPixel()
        // decides in double, as the reference path does.
        const float* light = t.photoLight.data() + p0;
        const float above = static_cast<float>(kPoolAbove);
        for (size_t j = 0; j < n; ++j) {
            const float lum = 0.2126f * now[0][j] + 0.7152f * now[1][j] + 0.0722f * now[2][j];
            if (!(light[j] > 0 && lum > above * light[j] * 0.999f)) continue;
            pooledPixel(map, *pool, p0 + j, Rgb{now[0][j], now[1][j], now[2][j]},
                        static_cast<double>(light[j]), t.delta, o + 3 * j, t.pooled);
        }
    });
}

}  // namespace relight
