#include "relight/pipeline/sky_estimate.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "relight/errors.h"
#include "relight/pipeline/leaf_texture.h"
#include "relight/pipeline/lighting_buffer.h"
#include "relight/pipeline/reflectance.h"
#include "relight/pipeline/sky_fit.h"

namespace relight {

using radiosity::kSh9Count;
using radiosity::Rgb;

namespace {

/// An estimated emitter: its first component's index in scene.lights and its JSON key.
struct Target {
    int first = -1;  ///< -1: none
    std::string key;
};

std::string rgbText(const Rgb& c) {
    char s[96];
    std::snprintf(s, sizeof s, "%.4g %.4g %.4g", c.r, c.g, c.b);
    return s;
}

/// The estimated sky and sun of `sf`; InputError for a second one of either.
void findTargets(const SceneFile& sf, Target& sky, Target& sun) {
    const auto& lights = sf.scene.lights;
    size_t index = 0;  // scene.json's index of light l
    for (size_t l = 0; l < lights.size(); ++l) {
        if (l > 0 && (!lights[l].emitter || lights[l].component == 0)) ++index;
        if (!sf.estimateRadiance[l] || !lights[l].emitter || lights[l].component != 0) continue;
        const bool isSky = lights[l].emitter->components() == kSh9Count;
        Target& t = isSky ? sky : sun;
        const std::string key = (sf.dir / "scene.json").string() + ": key \"lights[" +
                                std::to_string(index) + "]." + (isSky ? "sh9" : "irradiance") +
                                "\"";
        if (t.first >= 0)
            throw InputError(key + ": only one " + (isSky ? "sky" : "sun") +
                             " may be \"estimate\" (the photo's shading cannot tell two apart)");
        t.first = static_cast<int>(l);
        t.key = key;
    }
}

/// One clean photo pixel: what the fit reads of it.
struct PixelData {
    Rgb radiance, rho;
    Rgb modelRho;  ///< the solver's (scene.json's) reflectance of its polygon
    int object = -1;
    Rgb knownDirect;  ///< sum over the lights of known strength of E_l G_l (radiosity units)
    double G[kSh9Count + 1] = {};  ///< unit-strength direct light, sky's 9 then the sun
    int gather = -1;               ///< the gather point of its samples (one polygon)
};

std::vector<PixelData> collectPixels(const ItemBuffer& items, const radiosity::Scene& scene,
                                     const Image& photo, const LightingBuffer& buf,
                                     const Target& sky, const Target& sun, int stride) {
    const std::vector<uint8_t> usable = usablePixels(items, scene, photo, stride);
    std::vector<PixelData> out;
    const double inv = 1.0 / items.spp;
    for (int y = 0; y < items.height; y += stride)
        for (int x = 0; x < items.width; x += stride) {
            if (!usable[static_cast<size_t>(y) * items.width + x]) continue;
            PixelData d;
            const float* I = photo.at(x, y);
            d.radiance = {I[0], I[1], I[2]};
            for (int s = 0; s < items.spp; ++s) {
                const int idx = items.sampleIndex(x, y, s);
                const float* G = buf.direct(idx);
                d.gather = buf.gatherPointOf(idx);
                const radiosity::Polygon& poly = scene.polygons[items.polygon[idx]];
                d.rho = d.modelRho = poly.rho;
                d.object = poly.object;
                auto g = [&](int l) { return static_cast<double>(G[l]) * inv; };
                for (int l = 0; l < buf.lights; ++l)
                    d.knownDirect += scene.lights[static_cast<size_t>(l)].emittance() * g(l);
                for (int k = 0; sky.first >= 0 && k < kSh9Count; ++k) d.G[k] += g(sky.first + k);
                if (sun.first >= 0) d.G[kSh9Count] += g(sun.first);
            }
            out.push_back(d);
        }
    return out;
}

/// H_p of the fitted strengths: the estimated components' direct light plus H0_p.
Rgb fittedIrradiance(const PixelData& d, const LightingBuffer& buf, const SkyFitResult& f) {
    constexpr double pi = std::numbers::pi;
    Rgb H = d.knownDirect;
    if (d.gather >= 0 && static_cast<size_t>(d.gather) < buf.indirect.size())
        H += buf.indirect[static_cast<size_t>(d.gather)];
    for (int k = 0; k < kSh9Count; ++k) H += f.sky.c[static_cast<size_t>(k)] * (pi * d.G[k]);
    return H + f.sunIrradiance * (pi * d.G[kSh9Count]);
}

/// The reflectance step of the alternation: per object, the engine's estimate
/// rho = pi sum(I) / sum(H) over its pixels (relight/pipeline/reflectance.h), H of the
/// current fit; then all scaled, per channel, so that their mean over the pixels is that of
/// the model's reflectance (the gauge: the photo fixes rho L only, in each channel).
void estimateObjectReflectance(std::vector<PixelData>& px, const LightingBuffer& buf,
                               const SkyFitResult& f, size_t objects) {
    std::vector<Rgb> sumI(objects), sumH(objects);
    for (const PixelData& d : px) {
        sumI[static_cast<size_t>(d.object)] += d.radiance;
        sumH[static_cast<size_t>(d.object)] += fittedIrradiance(d, buf, f);
    }
    Rgb model, estimated;
    for (PixelData& d : px) {
        const size_t o = static_cast<size_t>(d.object);
        for (int c = 0; c < 3; ++c)
            if (sumH[o][c] > 0 && sumI[o][c] >= 0)
                d.rho[c] = std::min(std::numbers::pi * sumI[o][c] / sumH[o][c], kMaxReflectance);
        model += d.modelRho;
        estimated += d.rho;
    }
    for (int c = 0; c < 3; ++c)
        if (!(estimated[c] > 0)) return;
    for (PixelData& d : px)
        for (int c = 0; c < 3; ++c) d.rho[c] *= model[c] / estimated[c];
}

/// The least squares of the pixels on the estimated components' columns, the rest of the
/// irradiance (known direct light, indirect light) taken off each pixel's radiance.
SkyFitResult fitOnce(const std::vector<PixelData>& px, const LightingBuffer& buf, const Target& sky,
                     const Target& sun, const SkyEstimateOptions& o) {
    constexpr double pi = std::numbers::pi;
    std::vector<SkyFitPixel> fit;
    fit.reserve(px.size());
    for (const PixelData& d : px) {
        Rgb H0 = d.knownDirect;
        if (d.gather >= 0 && static_cast<size_t>(d.gather) < buf.indirect.size())
            H0 += buf.indirect[static_cast<size_t>(d.gather)];
        SkyFitPixel p;
        p.radiance = d.radiance - d.rho * H0 * (1 / pi);
        p.reflectance = d.rho;
        for (int k = 0; k < kSh9Count; ++k) p.transfer[static_cast<size_t>(k)] = pi * d.G[k];
        p.sunFactor = pi * d.G[kSh9Count];
        fit.push_back(p);
    }
    if (sky.first >= 0) {
        SkyFitOptions fo;
        fo.fitSun = sun.first >= 0;
        fo.ridge = o.ridge;
        fo.rankTolerance = o.rankTolerance;
        fo.nonNegative = o.nonNegative;
        return fitSky(fit, fo);
    }
    // The sun alone: one unknown per channel, s = sum(a I) / sum(a^2), a = rho f / pi.
    SkyFitResult r;
    r.unknowns = r.rank = 1;
    Rgb num, den;
    for (const SkyFitPixel& p : fit) {
        const Rgb a = p.reflectance * (p.sunFactor / pi);
        num += a * p.radiance;
        den += a * a;
    }
    for (int c = 0; c < 3; ++c) {
        if (!(den[c] > 0)) r.rank = 0;
        r.sunIrradiance[c] = den[c] > 0 ? num[c] / den[c] : 0;
    }
    return r;
}

/// Writes the fit into the scene's lights (nominal = photo state: they are on in the photo)
/// and gives every light's radiance to the solver. A negative sun channel is set to 0.
void applyFit(const SkyFitResult& f, const Target& sky, const Target& sun, SceneFile& sf,
              radiosity::HierarchicalSolver& solver) {
    auto set = [&](int l, const Rgb& v) {
        sf.nominalRadiance[static_cast<size_t>(l)] = v;
        sf.scene.lights[static_cast<size_t>(l)].radiance = v;
    };
    for (int k = 0; sky.first >= 0 && k < kSh9Count; ++k)
        set(sky.first + k, f.sky.c[static_cast<size_t>(k)]);
    if (sun.first >= 0) {
        Rgb s = f.sunIrradiance;
        for (int c = 0; c < 3; ++c) s[c] = std::max(s[c], 0.0);
        set(sun.first, s);
    }
    std::vector<Rgb> radiance;
    for (const radiosity::Light& l : sf.scene.lights) radiance.push_back(l.radiance);
    solver.setLightRadiances(radiance);
}

}  // namespace

bool hasSkyEstimate(const SceneFile& sf) {
    for (size_t l = 0; l < sf.estimateRadiance.size(); ++l)
        if (sf.estimateRadiance[l] && sf.scene.lights[l].emitter) return true;
    return false;
}

std::vector<std::string> SkyEstimateReport::summary() const {
    std::vector<std::string> out;
    char s[240];
    if (!skyName.empty()) {
        out.push_back("sky \"" + skyName + "\" sh9 (Wen et al. 2003 §4, least squares):");
        for (int k = 0; k < kSh9Count; ++k)
            out.push_back("  L" + std::to_string(k) + " " + rgbText(sky.c[static_cast<size_t>(k)]));
    }
    if (!sunName.empty()) out.push_back("sun \"" + sunName + "\" irradiance " + rgbText(sun));
    std::snprintf(s, sizeof s,
                  "from %d photo pixels, %d fits; rank %d of %d%s; %d directions held at radiance "
                  "0; rms residual %s",
                  pixels, rounds, rank, unknowns, regularised ? " (ridge)" : "", activeConstraints,
                  rgbText(rmsResidual).c_str());
    out.push_back(s);
    return out;
}

SkyEstimateReport estimateSkyFromPhoto(SceneFile& sf, radiosity::HierarchicalSolver& solver,
                                       const ItemBuffer& items, const Image& photo,
                                       const SkyEstimateOptions& o) {
    Target sky, sun;
    findTargets(sf, sky, sun);
    SkyEstimateReport rep;
    if (sky.first < 0 && sun.first < 0) return rep;
    auto say = [&](const std::string& m) {
        if (o.progress) o.progress(m);
    };
    LightingBuffer buf = computeLightingBuffer(items, solver, o.direct, o.stride);
    std::vector<PixelData> px =
        collectPixels(items, solver.scene(), photo, buf, sky, sun, std::max(o.stride, 1));
    if (px.empty())
        throw InputError((sky.first >= 0 ? sky.key : sun.key) +
                         ": \"estimate\" needs clean photo pixels on reflecting surfaces; the "
                         "photo shows none");
    SkyFitResult f;
    // Lights and the objects' reflectance in turn (alternating least squares of the
    // bilinear I = rho H(L) / pi), the indirect light held.
    auto alternate = [&] {
        f = fitOnce(px, buf, sky, sun, o);
        for (int a = 0; a < o.alternations; ++a) {
            estimateObjectReflectance(px, buf, f, solver.scene().objects.size());
            f = fitOnce(px, buf, sky, sun, o);
        }
    };
    try {
        alternate();
        for (int round = 1; round <= o.rounds; ++round) {
            applyFit(f, sky, sun, sf, solver);
            say("  round " + std::to_string(round) + ": indirect light of the fitted lights");
            if (round == 1) solver.solve();
            updateIndirect(buf, solver);
            alternate();
            ++rep.rounds;
        }
    } catch (const SkyFitError& e) {
        throw InputError((sky.first >= 0 ? sky.key : sun.key) + ": " + e.what());
    }
    if (f.rank == 0)
        throw InputError(sun.key + ": no clean photo pixel is lit by the sun; give its irradiance");
    applyFit(f, sky, sun, sf, solver);
    ++rep.rounds;
    if (sky.first >= 0) rep.skyName = sf.scene.lights[static_cast<size_t>(sky.first)].name;
    if (sun.first >= 0) {
        rep.sunName = sf.scene.lights[static_cast<size_t>(sun.first)].name;
        rep.sun = sf.nominalRadiance[static_cast<size_t>(sun.first)];
        if (!(rep.sun == f.sunIrradiance))
            rep.warnings.push_back(sun.key + ": the fit gave a negative irradiance " +
                                   rgbText(f.sunIrradiance) + ", set to 0 there");
    }
    rep.sky = f.sky;
    rep.pixels = static_cast<int>(px.size());
    rep.rank = f.rank;
    rep.unknowns = f.unknowns;
    rep.regularised = f.regularised;
    rep.activeConstraints = f.activeConstraints;
    rep.rmsResidual = f.rmsResidual;
    return rep;
}

}  // namespace relight
