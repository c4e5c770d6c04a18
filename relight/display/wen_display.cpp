#include "relight/display/wen_display.h"

#include <stdexcept>
#include <string>

#include "radiosity/parallel.h"
#include "radiosity/sh9.h"
#include "relight/pipeline/pixel_light.h"

namespace relight {

using radiosity::Rgb;

std::vector<float> unoccludedSkyDirect(const PreparedImage& p, std::span<const float> direct,
                                       size_t lights) {
    const size_t pixels =
        static_cast<size_t>(p.display.width) * static_cast<size_t>(p.display.height);
    if (p.pixelDirect.empty() || p.pixelNormal.size() != 3 * pixels ||
        p.skyCoefficient.size() != p.photoRadiance.size())
        throw std::invalid_argument(
            "the wen display needs a preparation with per-pixel light (and its normals)");
    if (direct.size() != pixels * lights || lights < p.skyCoefficient.size())
        throw std::invalid_argument("unoccludedSkyDirect: " + std::to_string(direct.size()) +
                                    " values for " + std::to_string(pixels) + " pixels x " +
                                    std::to_string(lights) + " lights");
    std::vector<float> out(direct.begin(), direct.end());
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        const float* n = &p.pixelNormal[3 * px];
        const bool normal = n[0] != 0 || n[1] != 0 || n[2] != 0;
        // A_l Y_k(n) for every k (Ramamoorthi & Hanrahan 2001, Eq. 7; Wen et al. 2003,
        // Eq. (15)): the irradiance per unit coefficient of a sky nothing occludes.
        const radiosity::Sh9 A =
            normal ? radiosity::sh9CosineTransfer(radiosity::Vec3{n[0], n[1], n[2]})
                   : radiosity::Sh9{};
        for (size_t l = 0; l < p.skyCoefficient.size(); ++l) {
            const int k = p.skyCoefficient[l];
            if (k >= 0) out[px * lights + l] = static_cast<float>(A[static_cast<size_t>(k)]);
        }
    });
    return out;
}

std::vector<Rgb> indirectWithoutSky(const PreparedImage& p) {
    std::vector<Rgb> ind = p.vertexIndirect;
    const size_t L = p.skyCoefficient.size();
    if (L == 0 || ind.size() % L != 0) return ind;
    for (size_t i = 0; i < ind.size(); ++i)
        if (p.skyCoefficient[i % L] >= 0) ind[i] = Rgb{};
    return ind;
}

void renderWen(const PreparedImage& p, std::span<const Rgb> radiance, Image& out) {
    const size_t L = p.photoRadiance.size();
    const std::vector<float> direct = unoccludedSkyDirect(p, p.pixelDirect, L);
    const std::vector<Rgb> indirect = indirectWithoutSky(p);
    // The pixels the per-pixel display leaves (lamps' faces, samples that see nothing)
    // keep the ratio display, as in DisplayMode::pixel.
    renderRatio(p.display, p.photo, vertexRatio(p, vertexIrradiance(p, radiance)), radiance,
                p.photoRadiance, out, {}, /*leafRuns=*/false);
    // The pooled reflectance reads T / H_photo: here H_photo is Wen's, so the pool too.
    const Rgb delta = ratioFloor(p.D);
    const PhotoPixels pool =
        photoPixels(p.display, p.photo, direct, indirect, p.photoRadiance, delta);
    renderPixelLight(p.display, p.photo, direct, indirect, radiance, p.photoRadiance, delta, out,
                     {}, p.pixelReflectance, &pool);
}

}  // namespace relight
