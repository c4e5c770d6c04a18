#include "relight/dynamic/specular.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "radiosity/detail/rng.h"

namespace relight {

using radiosity::Vec3;

double blinnPhongLobe(const Vec3& n, const Vec3& toEye, double shininess, const Vec3& w) {
    if (glm::dot(n, w) <= 0 || glm::dot(n, toEye) <= 0) return 0;
    const Vec3 sum = w + toEye;
    const double len = glm::length(sum);
    if (!(len > 1e-12)) return 0;  // guard: light and eye opposite (grazing on both sides)
    const double nh = std::max(0.0, glm::dot(n, sum / len));
    // Real-Time Rendering 4th ed., Eq. (9.52): (s + 8) / (8 pi) keeps the lobe's reflected
    // share near ks as s changes.
    return (shininess + 8) / (8 * std::numbers::pi) * std::pow(nh, shininess);
}

SpecularLights::SpecularLights(const radiosity::Scene& scene, std::span<const Rgb> strength) {
    const auto& lights = scene.lights;
    for (size_t l = 0; l < lights.size() && l < strength.size(); ++l) {
        const radiosity::Light& light = lights[l];
        if (light.emitter) {
            if (light.component != 0) continue;  // the emitter's entry is its first component's
            Entry e{light.emitter, {}};
            const size_t n = static_cast<size_t>(light.emitter->components());
            for (size_t c = 0; c < n; ++c)
                e.strengths.push_back(l + c < strength.size() ? strength[l + c] : Rgb{});
            lights_.push_back(std::move(e));
            continue;
        }
        if (light.polygons.empty() || strength[l].maxComponent() <= 0) continue;
        std::vector<std::vector<Vec3>> faces;
        for (int p : light.polygons) {
            const radiosity::Polygon& poly = scene.polygons[static_cast<size_t>(p)];
            faces.emplace_back(poly.v.begin(), poly.v.begin() + poly.vertexCount);
        }
        lights_.push_back(
            {radiosity::makeQuadLamp(light.name, std::move(faces), light.polygons, Rgb{1, 1, 1}),
             {strength[l]}});
    }
}

Rgb SpecularLights::radiance(const Specular& s, const radiosity::Visibility& vis,
                             const radiosity::ReceiverPoint& p, const Vec3& toEye, int rays,
                             uint64_t seed) const {
    if (s.ks.maxComponent() <= 0) return {};
    const radiosity::Emitter::Lobe lobe = [&](const Vec3& w) {
        return blinnPhongLobe(p.n, toEye, s.shininess, w);
    };
    Rgb sum;
    double out[radiosity::kMaxEmitterComponents];
    for (size_t i = 0; i < lights_.size(); ++i) {
        const Entry& e = lights_[i];
        bool on = false;
        for (const Rgb& c : e.strengths) on = on || c.r != 0 || c.g != 0 || c.b != 0;
        if (!on) continue;
        // One generator per light, seeded by the point and the light's place in the list.
        radiosity::Rng rng(seed * 0x9E3779B97F4A7C15ull + i + 1);
        e.emitter->unitGlossy(vis, p, lobe, rays, rng, out);
        for (size_t c = 0; c < e.strengths.size(); ++c) sum += e.strengths[c] * out[c];
    }
    for (int c = 0; c < 3; ++c) sum[c] *= s.ks[c];
    return sum;
}

}  // namespace relight
