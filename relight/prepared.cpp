#include "relight/prepared.h"

#include <cstdio>

namespace relight {

using radiosity::Rgb;

std::vector<Rgb> vertexIrradiance(const PreparedImage& p, std::span<const Rgb> radiance) {
    const int n = static_cast<int>(p.lighting.vertexCount());
    std::vector<Rgb> B(static_cast<size_t>(n));
    for (int v = 0; v < n; ++v) B[v] = p.lighting.irradiance(v, radiance);
    return B;
}

std::vector<Rgb> vertexRatio(const PreparedImage& p, std::span<const Rgb> H) {
    auto ratio = displayRatio(H, p.D);
    if (p.textureFactor.size() == ratio.size())
        for (size_t v = 0; v < ratio.size(); ++v)
            for (int c = 0; c < 3; ++c) ratio[v][c] *= p.textureFactor[v][c];
    return ratio;
}

Image renderEdit(const PreparedImage& p, std::span<const Rgb> radiance) {
    Image out;
    renderEdit(p, radiance, out);
    return out;
}

void renderEdit(const PreparedImage& p, std::span<const Rgb> radiance, Image& out) {
    const auto ratio = vertexRatio(p, vertexIrradiance(p, radiance));
    renderRatio(p.display, p.photo, ratio, radiance, p.photoRadiance, out);
}

std::string stepTimes(const PrepareTimes& t) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "item buffer %.3f, solve %.3f, reflectance %.3f, refinement %.3f, responses "
                  "%.3f, vertex lighting %.3f, shadow removal %.3f, display map %.3f",
                  t.itemBuffer, t.solve, t.reflectance, t.refinement, t.responses, t.vertexLighting,
                  t.shadowRemoval, t.displayMap);
    return text;
}

}  // namespace relight
