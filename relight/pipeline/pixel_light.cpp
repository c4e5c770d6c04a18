#include "relight/pipeline/pixel_light.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "radiosity/emitter.h"
#include "radiosity/parallel.h"
#include "radiosity/sh9.h"

namespace relight {

using radiosity::Rgb;

std::vector<float> pixelDirect(const ItemBuffer& items, const radiosity::Scene& scene,
                               const LightingBuffer& buf) {
    if (buf.stride != 1)
        throw std::invalid_argument("pixelDirect: the lighting buffer has pixel stride " +
                                    std::to_string(buf.stride) + "; it needs every pixel");
    const size_t L = static_cast<size_t>(buf.lights);
    const size_t pixels = static_cast<size_t>(items.width) * static_cast<size_t>(items.height);
    std::vector<float> out(pixels * L, 0.0f);
    radiosity::parallelFor(pixels, 64, [&](size_t px) {
        const int x = static_cast<int>(px % static_cast<size_t>(items.width));
        const int y = static_cast<int>(px / static_cast<size_t>(items.width));
        std::vector<double> sum(L, 0.0);
        int n = 0;
        for (int s = 0; s < items.spp; ++s) {
            const int idx = items.sampleIndex(x, y, s);
            const int p = items.polygon[static_cast<size_t>(idx)];
            if (p < 0 || scene.polygons[static_cast<size_t>(p)].light >= 0) continue;
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

std::vector<float> pixelNormals(const ItemBuffer& items, const radiosity::Scene& scene) {
    const size_t pixels = static_cast<size_t>(items.width) * static_cast<size_t>(items.height);
    std::vector<float> out(3 * pixels, 0.0f);
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        const int x = static_cast<int>(px % static_cast<size_t>(items.width));
        const int y = static_cast<int>(px / static_cast<size_t>(items.width));
        radiosity::Vec3 sum{0, 0, 0};
        for (int s = 0; s < items.spp; ++s) {
            const int p = items.polygon[static_cast<size_t>(items.sampleIndex(x, y, s))];
            if (p < 0 || scene.polygons[static_cast<size_t>(p)].light >= 0) continue;
            sum += scene.polygons[static_cast<size_t>(p)].normal;
        }
        // Samples on faces turned apart (an edge seen edge-on) may cancel: no normal then.
        const double len = glm::length(sum);
        if (!(len > 1e-9)) return;
        for (int c = 0; c < 3; ++c)
            out[3 * px + static_cast<size_t>(c)] = static_cast<float>(sum[c] / len);
    });
    return out;
}

std::vector<int> skyCoefficients(const radiosity::Scene& scene) {
    std::vector<int> k(scene.lights.size(), -1);
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const auto& e = scene.lights[l].emitter;
        // A sky is the emitter of 9 components, its coefficients (radiosity/emitter.h).
        if (e && e->components() == radiosity::kSh9Count) k[l] = scene.lights[l].component;
    }
    return k;
}

std::vector<float> measurePixelDirect(const ItemBuffer& items,
                                      const radiosity::HierarchicalSolver& solver,
                                      radiosity::DirectLightOptions options) {
    return pixelDirect(items, solver.scene(), computeLightingBuffer(items, solver, options, 1));
}

std::vector<Rgb> vertexIndirect(const VertexLighting& lighting, const VertexDirect& direct) {
    if (lighting.lights != direct.lights || lighting.response.size() != direct.visible.size())
        throw std::invalid_argument("vertexIndirect: lighting and direct light differ in size");
    std::vector<Rgb> ind(lighting.response.size());
    for (size_t i = 0; i < ind.size(); ++i)
        ind[i] = lighting.response[i] - Rgb::gray(direct.visible[i]);
    return ind;
}

namespace {

/// What renderPixelLight() sums at a pixel: the light of the photo's lamps now (kept), the
/// light the photo did not hold (fresh: lamps off in it, virtual lamps, what virtual
/// objects change) and the photo's (before).
struct PixelSums {
    Rgb kept, fresh, before;
};

/// renderPixelLight()'s arguments, checked, as the per-pixel sums read them.
struct PixelSumInputs {
    const DisplayMap& map;
    std::span<const float> pixelDirect, directNow;
    std::span<const Rgb> indirect, radianceNow, radianceInPhoto, changeIndirect;
    const PhotoPixels* pool;
    size_t L, Lnow;
    bool derived;  ///< the pool's per-pixel indirect parts (photoPixels()) are read
};

PixelSumInputs checkedInputs(const DisplayMap& map, std::span<const float> pixelDirect,
                             std::span<const Rgb> indirect, std::span<const Rgb> radianceNow,
                             std::span<const Rgb> radianceInPhoto, PixelLightChange change,
                             std::span<const float> reflectance, const PhotoPixels* pool,
                             int outWidth, int outHeight) {
    const size_t L = radianceInPhoto.size();  // the photo's lights
    const size_t pixels = static_cast<size_t>(map.width) * static_cast<size_t>(map.height);
    const std::span<const float> directNow = change.direct.empty() ? pixelDirect : change.direct;
    const size_t Lnow = radianceNow.size();
    const size_t vertices = L > 0 ? indirect.size() / L : change.indirect.size();
    if (Lnow < L || pixelDirect.size() != pixels * L || directNow.size() != pixels * Lnow ||
        (L > 0 && indirect.size() % L != 0) ||
        (!change.indirect.empty() && change.indirect.size() != vertices) ||
        (!reflectance.empty() && reflectance.size() != pixels * 3) || outWidth != map.width ||
        outHeight != map.height)
        throw std::invalid_argument("renderPixelLight: sizes do not match (" +
                                    std::to_string(pixelDirect.size()) + " direct values for " +
                                    std::to_string(pixels) + " pixels x " + std::to_string(L) +
                                    " lights, " + std::to_string(directNow.size()) + " for " +
                                    std::to_string(Lnow) + " lights now)");
    const bool derived = pool && pool->indirect.size() == 3 * pixels * L;
    return {map,  pixelDirect, directNow, indirect, radianceNow, radianceInPhoto, change.indirect,
            pool, L,           Lnow,      derived};
}

/// The sums at pixel px (drawn per pixel), light `skip`'s direct light now read as 0 (-1:
/// none; light being moved, pixelLightTerms()).
PixelSums pixelSums(const PixelSumInputs& in, size_t px, int skip) {
    const DisplayMap& map = in.map;
    const int k0 = map.start[px], k1 = map.start[px + 1];
    // The vertices' weights are read only to interpolate what the derived values lack.
    double wsum = 0;
    if (!in.derived || !in.changeIndirect.empty())
        for (int k = k0; k < k1; ++k)
            wsum += static_cast<double>(map.weight[static_cast<size_t>(k)]);
    auto interpolate = [&](auto&& value) {
        Rgb sum;
        for (int k = k0; k < k1; ++k)
            sum += value(static_cast<size_t>(map.vertex[static_cast<size_t>(k)])) *
                   (static_cast<double>(map.weight[static_cast<size_t>(k)]) / wsum);
        return sum;
    };
    const auto directNow = [&](size_t l) {
        return static_cast<int>(l) == skip ? 0.0
                                           : static_cast<double>(in.directNow[px * in.Lnow + l]);
    };
    // h_l(p) once per light, weighed by the edit's radiances and the photo's. The light
    // of the photo's lamps (kept) and the light the photo did not hold (fresh) apart, for
    // a merged reflectance.
    PixelSums s;
    for (size_t l = 0; l < in.L; ++l) {
        Rgb ind;
        if (in.derived) {  // the same sums from the derived per-pixel values (photoPixels())
            const float* f = in.pool->indirect.data() + (px * in.L + l) * 3;
            ind = Rgb{f[0], f[1], f[2]};
        } else {
            ind = interpolate([&](size_t v) { return in.indirect[v * in.L + l]; });
        }
        const Rgb h = in.radianceNow[l] * (Rgb::gray(directNow(l)) + ind);
        (in.radianceInPhoto[l].maxComponent() > 0 ? s.kept : s.fresh) += h;
        s.before += in.radianceInPhoto[l] *
                    (Rgb::gray(static_cast<double>(in.pixelDirect[px * in.L + l])) + ind);
    }
    for (size_t l = in.L; l < in.Lnow; ++l) s.fresh += in.radianceNow[l] * directNow(l);
    if (!in.changeIndirect.empty())
        s.fresh += interpolate([&](size_t v) { return in.changeIndirect[v]; });
    return s;
}

}  // namespace

void renderPixelLight(const DisplayMap& map, const Image& photo, std::span<const float> pixelDirect,
                      std::span<const Rgb> indirect, std::span<const Rgb> radianceNow,
                      std::span<const Rgb> radianceInPhoto, const Rgb& delta, Image& out,
                      PixelLightChange change, std::span<const float> reflectance,
                      const PhotoPixels* pool) {
    const PixelSumInputs in =
        checkedInputs(map, pixelDirect, indirect, radianceNow, radianceInPhoto, change, reflectance,
                      pool, out.width, out.height);
    const size_t pixels = static_cast<size_t>(map.width) * static_cast<size_t>(map.height);
    const bool pooling = reflectance.empty() && pool && pool->rho.size() == 3 * pixels &&
                         pool->light.size() == pixels;
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        // A lamp's face, samples that see nothing, or no leaf: the ratio display's value.
        if (!shownPerPixel(map, px)) return;
        const PixelSums s = pixelSums(in, px, -1);
        const float* t = photo.rgb.data() + px * 3;
        float* o = out.rgb.data() + px * 3;
        if (!reflectance.empty()) {
            // The photo's lamps through the photo, T H_kept / H_photo, as below: the photo's
            // noise scales with its light. The fresh light read with the reflectance merged
            // from all photos (photo_merge.h).
            const float* R = reflectance.data() + px * 3;
            for (int c = 0; c < 3; ++c) {
                const double r = guardedRatio(s.kept[c], s.before[c], delta[c]);
                o[c] = std::max(static_cast<float>(static_cast<double>(t[c]) * r +
                                                   static_cast<double>(R[c]) * s.fresh[c]),
                                0.0f);
            }
            return;
        }
        const Rgb now = s.kept + s.fresh;
        if (pooling && pooledPixel(map, *pool, px, now, s.before.luminance(), delta, o)) return;
        for (int c = 0; c < 3; ++c) {
            const double r = guardedRatio(now[c], s.before[c], delta[c]);
            o[c] = std::max(static_cast<float>(static_cast<double>(t[c]) * r), 0.0f);
        }
    });
}

PixelLightTerms pixelLightTerms(const DisplayMap& map, const Image& photo,
                                std::span<const float> pixelDirect, std::span<const Rgb> indirect,
                                std::span<const Rgb> radianceNow,
                                std::span<const Rgb> radianceInPhoto, const Rgb& delta,
                                PixelLightChange change, int light,
                                std::span<const float> reflectance, const PhotoPixels* pool,
                                std::shared_ptr<const std::vector<float>> pooled) {
    if (!reflectance.empty())
        throw std::invalid_argument(
            "pixelLightTerms: a merged reflectance reads the fresh light "
            "through it; draw it with renderPixelLight()");
    if (light < 0 || static_cast<size_t>(light) >= radianceNow.size())
        throw std::invalid_argument("pixelLightTerms: light " + std::to_string(light) + " of " +
                                    std::to_string(radianceNow.size()));
    const PixelSumInputs in =
        checkedInputs(map, pixelDirect, indirect, radianceNow, radianceInPhoto, change, reflectance,
                      pool, photo.width, photo.height);
    const size_t pixels = static_cast<size_t>(map.width) * static_cast<size_t>(map.height);
    const bool pooling = pool && pool->rho.size() == 3 * pixels && pool->light.size() == pixels;
    PixelLightTerms t;
    t.width = map.width;
    t.height = map.height;
    t.delta = delta;
    t.radiance = radianceNow[static_cast<size_t>(light)];
    for (auto* v : {&t.rest, &t.rho, &t.rhoPool}) v->assign(3 * pixels, 0.0f);
    t.photoLight.assign(pixels, 0.0f);
    t.drawn.assign(pixels, 0);
    if (pooling) {
        constexpr size_t radii = static_cast<size_t>(kMaxPoolRadius - kPoolRadius + 1);
        t.pooled = pooled && pooled->size() == 3 * pixels * radii
                       ? std::move(pooled)
                       : std::make_shared<const std::vector<float>>(pooledByRadius(map, *pool));
        std::copy(pool->rho.begin(), pool->rho.end(), t.rhoPool.begin());
    }
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        if (!shownPerPixel(map, px)) return;
        const PixelSums s = pixelSums(in, px, light);
        const Rgb rest = s.kept + s.fresh;
        for (size_t c = 0; c < 3; ++c) {
            t.rest[3 * px + c] = static_cast<float>(rest[static_cast<int>(c)]);
            t.rho[3 * px + c] = static_cast<float>(
                static_cast<double>(photo.rgb[3 * px + c]) /
                (std::max(s.before[static_cast<int>(c)], 0.0) + delta[static_cast<int>(c)]));
        }
        t.photoLight[px] = pooling ? static_cast<float>(s.before.luminance()) : 0.0f;
        t.drawn[px] = 1;
    });
    return t;
}

void evalPixelLightTerms(const PixelLightTerms& t, size_t px, double g, float* o) {
    const size_t pixels = static_cast<size_t>(t.width) * static_cast<size_t>(t.height);
    const float* r = t.rest.data() + 3 * px;
    const Rgb now = Rgb{r[0], r[1], r[2]} + t.radiance * g;
    const double photoLight = static_cast<double>(t.photoLight[px]);
    if (photoLight > 0 && now.luminance() > kPoolAbove * photoLight && t.pooled) {
        // pooledPixel()'s reflectance, from the table of pooled values by radius.
        const double w = kPoolAbove * photoLight / now.luminance();
        const int radius = std::min(
            kMaxPoolRadius, static_cast<int>(std::lround(kPoolRadius * std::sqrt(1.0 / w))));
        const float* pooled =
            t.pooled->data() + 3 * (static_cast<size_t>(radius - kPoolRadius) * pixels + px);
        for (size_t c = 0; c < 3; ++c) {
            const double R = w * static_cast<double>(t.rhoPool[3 * px + c]) +
                             (1 - w) * static_cast<double>(pooled[c]);
            o[c] = std::max(static_cast<float>(R * (std::max(now[static_cast<int>(c)], 0.0) +
                                                    t.delta[static_cast<int>(c)])),
                            0.0f);
        }
        return;
    }
    for (size_t c = 0; c < 3; ++c)
        o[c] = std::max(static_cast<float>(static_cast<double>(t.rho[3 * px + c]) *
                                           (std::max(now[static_cast<int>(c)], 0.0) +
                                            t.delta[static_cast<int>(c)])),
                        0.0f);
}

bool pooledPixel(const DisplayMap& map, const PhotoPixels& pool, size_t px, const Rgb& now,
                 double photoLight, const Rgb& delta, float* o,
                 std::span<const float> pooledByRadius) {
    if (!(now.luminance() > kPoolAbove * photoLight && photoLight > 0)) return false;
    // The pooled reflectance (header), weighed by the photo's confidence.
    const double w = kPoolAbove * photoLight / now.luminance();
    // The pool widens as the photo's noise is brightened more (its mean's noise falls as the
    // window's side grows).
    const int radius =
        std::min(kMaxPoolRadius, static_cast<int>(std::lround(kPoolRadius * std::sqrt(1.0 / w))));
    const size_t pixels = pool.light.size();
    const size_t at = 3 * (static_cast<size_t>(radius - kPoolRadius) * pixels + px);
    const Rgb pooled = at + 3 <= pooledByRadius.size()
                           ? Rgb{pooledByRadius[at], pooledByRadius[at + 1], pooledByRadius[at + 2]}
                           : pooledReflectance(map, pool, px, radius);
    for (int c = 0; c < 3; ++c) {
        const double R = w * static_cast<double>(pool.rho[3 * px + static_cast<size_t>(c)]) +
                         (1 - w) * pooled[c];
        o[c] = std::max(static_cast<float>(R * (std::max(now[c], 0.0) + delta[c])), 0.0f);
    }
    return true;
}

std::vector<float> pooledByRadius(const DisplayMap& map, const PhotoPixels& pool) {
    const size_t pixels = pool.light.size();
    constexpr size_t radii = static_cast<size_t>(kMaxPoolRadius - kPoolRadius + 1);
    std::vector<float> out(radii * pixels * 3, 0.0f);
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        if (!(pool.light[px] > 0)) return;
        for (size_t k = 0; k < radii; ++k) {
            const Rgb R = pooledReflectance(map, pool, px, kPoolRadius + static_cast<int>(k));
            for (int c = 0; c < 3; ++c)
                out[3 * (k * pixels + px) + static_cast<size_t>(c)] = static_cast<float>(R[c]);
        }
    });
    return out;
}

std::vector<float> poolGuide(int W, int H, const PhotoPixels& pool) {
    // The pool's test of "the same reflectance" compared each neighbour with the pixel's own
    // rho, which in a dim part of a noisy photo is off by as much as the tolerance (window
    // room: 17-25 % per pixel on the floor by the window against kPoolTolerance 30 %): the
    // pool then kept the neighbours that share the pixel's own error, and its mean kept
    // much of that error (the photo's 4.3 % per 4 x 4 block there, 2.9 % pooled, where the
    // sun moved to; bench/RESULTS.md, 2026-11-27, seventh session). A median of 9 pixels
    // cuts that noise about 2.5 times and still follows an edge (at a straight edge 6 of
    // the 9 lie on the pixel's own side).
    const size_t pixels = pool.light.size();
    std::vector<float> guide(pool.rho);
    if (pixels != static_cast<size_t>(W) * static_cast<size_t>(H) || pool.rho.size() != 3 * pixels)
        return guide;
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        if (!(pool.light[px] > 0)) return;
        const int x = static_cast<int>(px % static_cast<size_t>(W));
        const int y = static_cast<int>(px / static_cast<size_t>(W));
        for (size_t c = 0; c < 3; ++c) {
            std::array<float, 9> v{};
            size_t n = 0;
            for (int qy = std::max(y - 1, 0); qy <= std::min(y + 1, H - 1); ++qy)
                for (int qx = std::max(x - 1, 0); qx <= std::min(x + 1, W - 1); ++qx) {
                    const size_t q =
                        static_cast<size_t>(qy) * static_cast<size_t>(W) + static_cast<size_t>(qx);
                    if (pool.light[q] > 0) v[n++] = pool.rho[3 * q + c];
                }
            const auto mid = v.begin() + static_cast<std::ptrdiff_t>(n / 2);
            std::nth_element(v.begin(), mid, v.begin() + static_cast<std::ptrdiff_t>(n));
            guide[3 * px + c] = *mid;
        }
    });
    return guide;
}

Rgb pooledReflectance(const DisplayMap& map, const PhotoPixels& pool, size_t px, int radius) {
    const int W = map.width, H = map.height;
    const int x = static_cast<int>(px % static_cast<size_t>(W));
    const int y = static_cast<int>(px / static_cast<size_t>(W));
    const float* rp = &pool.rho[3 * px];
    // A neighbour of the same reflectance is one whose rho lies within the tolerance of the
    // pixel's guide (poolGuide), where there is one: the window is centred on a steadier
    // value than the pixel's own, and the neighbour's own rho still tells a texture's other
    // colour (comparing the guides instead blurred the courtyard's paving: sun_moved
    // 0.0285 -> 0.0297, against 0.0280 this way).
    const bool guided = pool.guide.size() == pool.rho.size();
    const float* gp = guided ? &pool.guide[3 * px] : rp;
    Rgb sum;
    double wsum = 0;
    // Wider pools are sampled on a coarser grid: always about (2 kPoolRadius + 1)^2 pixels.
    const int step = std::max(1, radius / kPoolRadius);
    for (int dy = -radius; dy <= radius; dy += step)
        for (int dx = -radius; dx <= radius; dx += step) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= W || qy >= H) continue;
            const size_t q =
                static_cast<size_t>(qy) * static_cast<size_t>(W) + static_cast<size_t>(qx);
            const float w = pool.light[q];
            if (!(w > 0)) continue;  // not a surface pixel of the per-pixel display
            // Only pixels of about the same reflectance: another surface, or a texture's
            // other colour, stays out.
            const float* rq = &pool.rho[3 * q];
            bool alike = true;
            for (int c = 0; c < 3 && alike; ++c)
                alike = std::abs(gp[c] - rq[c]) <=
                        static_cast<float>(kPoolTolerance) * std::max(gp[c], rq[c]);
            if (!alike) continue;
            for (int c = 0; c < 3; ++c) sum[c] += static_cast<double>(w * rq[c]);
            wsum += static_cast<double>(w);
        }
    return wsum > 0 ? sum * (1.0 / wsum) : Rgb{rp[0], rp[1], rp[2]};
}

Rgb photoIrradianceAt(const DisplayMap& map, size_t px, std::span<const float> pixelDirect,
                      std::span<const Rgb> indirect, std::span<const Rgb> radianceInPhoto,
                      Rgb* directPart) {
    const size_t L = radianceInPhoto.size();
    const int k0 = map.start[px], k1 = map.start[px + 1];
    double wsum = 0;
    for (int k = k0; k < k1; ++k) wsum += static_cast<double>(map.weight[static_cast<size_t>(k)]);
    Rgb H, D;
    if (wsum > 0)
        for (size_t l = 0; l < L; ++l) {
            if (!(radianceInPhoto[l].maxComponent() > 0)) continue;  // off in the photo
            Rgb ind;
            for (int k = k0; k < k1; ++k)
                ind += indirect[static_cast<size_t>(map.vertex[static_cast<size_t>(k)]) * L + l] *
                       (static_cast<double>(map.weight[static_cast<size_t>(k)]) / wsum);
            const Rgb direct = radianceInPhoto[l] * static_cast<double>(pixelDirect[px * L + l]);
            D += direct;
            H += direct + radianceInPhoto[l] * ind;
        }
    if (directPart) *directPart = D;
    return H;
}

namespace {

/// PhotoPixels::indirect at pixel px, as renderPixelLight() interpolates it.
void derivePixelIndirect(const DisplayMap& map, size_t px, std::span<const Rgb> indirect, size_t L,
                         PhotoPixels& out) {
    pixelIndirectParts(map, px, indirect, L, [&](size_t l, const Rgb& ind) {
        for (int c = 0; c < 3; ++c)
            out.indirect[(px * L + l) * 3 + static_cast<size_t>(c)] = static_cast<float>(ind[c]);
    });
}

}  // namespace

PhotoPixels photoPixels(const DisplayMap& map, const Image& photo,
                        std::span<const float> pixelDirect, std::span<const Rgb> indirect,
                        std::span<const Rgb> radianceInPhoto, const Rgb& delta) {
    const size_t L = radianceInPhoto.size();
    const size_t pixels = static_cast<size_t>(map.width) * static_cast<size_t>(map.height);
    PhotoPixels out;
    if (L == 0 || pixelDirect.size() != pixels * L || indirect.size() % L != 0) return out;
    out.rho.assign(3 * pixels, 0.0f);
    out.light.assign(pixels, 0.0f);
    const bool transfers = 3 * pixels * L <= kMaxPixelTransfers;
    if (transfers) out.indirect.assign(3 * pixels * L, 0.0f);
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        if (!shownPerPixel(map, px)) return;
        if (transfers) derivePixelIndirect(map, px, indirect, L, out);
        const Rgb H = photoIrradianceAt(map, px, pixelDirect, indirect, radianceInPhoto);
        Rgb Hd;
        for (int c = 0; c < 3; ++c) Hd[c] = std::max(H[c], 0.0) + delta[c];
        for (int c = 0; c < 3; ++c)
            out.rho[3 * px + static_cast<size_t>(c)] = static_cast<float>(
                static_cast<double>(photo.rgb[3 * px + static_cast<size_t>(c)]) / Hd[c]);
        out.light[px] = static_cast<float>(Hd.luminance());
    });
    out.guide = poolGuide(map.width, map.height, out);
    return out;
}

}  // namespace relight
