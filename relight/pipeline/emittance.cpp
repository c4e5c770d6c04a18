#include "relight/pipeline/emittance.h"

#include "radiosity/emitter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "relight/pipeline/leaf_texture.h"

namespace relight {

using radiosity::Rgb;

namespace {

/// A decoded sRGB value at or above this was clipped by the encoding (code 255 of 8 bits
/// decodes to 1; code 254 to 0.991).
constexpr double kSrgbClip = 0.999;

std::string rgbText(const Rgb& c) {
    char s[96];
    std::snprintf(s, sizeof s, "%.4g %.4g %.4g", c.r, c.g, c.b);
    return s;
}

/// The key of light l's strength in scene.json: its index there counts the lights of
/// scene.lights that start one (an emitter's components after its first are the same light).
std::string keyOf(const SceneFile& sf, size_t l) {
    const auto& lights = sf.scene.lights;
    size_t index = 0;
    for (size_t k = 1; k <= l && k < lights.size(); ++k)
        if (!lights[k].emitter || lights[k].component == 0) ++index;
    const char* key = "radiance";
    if (l < lights.size() && lights[l].emitter)
        key = lights[l].emitter->components() == 1 ? "irradiance" : "sh9";
    return (sf.dir / "scene.json").string() + ": key \"lights[" + std::to_string(index) + "]." +
           key + "\"";
}

/// A quad light whose radiance is "estimate": this file's (a sun's or sky's "estimate" is a
/// fit to the photo's shading, relight/pipeline/sky_estimate.h).
bool estimatedHere(const SceneFile& sf, size_t l) {
    return sf.estimateRadiance[l] && !sf.scene.lights[l].emitter;
}

double median(std::vector<double>& v) {
    const size_t n = v.size(), mid = n / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
    const double hi = v[mid];
    if (n % 2 == 1) return hi;
    const double lo = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
    return 0.5 * (lo + hi);
}

}  // namespace

bool EmittanceReport::anyEstimated() const {
    return std::any_of(lights.begin(), lights.end(), [](const LightEmittance& l) {
        return l.method != LightEmittance::Method::given;
    });
}

std::vector<std::string> EmittanceReport::summary() const {
    std::vector<std::string> out;
    for (const LightEmittance& l : lights) {
        if (l.method == LightEmittance::Method::photo)
            out.push_back("light \"" + l.name + "\": " + rgbText(l.radiance) + " from " +
                          std::to_string(l.pixels) + " photo pixels on its face");
        else if (l.method == LightEmittance::Method::ambient) {
            char s[200];
            std::snprintf(s, sizeof s,
                          " by Eq. (2'): rho^ %.3g, mean surface radiance %s over %.3g of "
                          "%.3g m^2",
                          averageReflectance, rgbText(meanSurfaceRadiance).c_str(), seenArea,
                          reflectingArea);
            out.push_back("light \"" + l.name + "\": " + rgbText(l.radiance) + s);
        }
    }
    return out;
}

void checkEstimableLights(const SceneFile& sf) {
    for (size_t l = 0; l < sf.estimateRadiance.size(); ++l)
        if (sf.estimateRadiance[l] && sf.photos.empty())
            throw InputError(keyOf(sf, l) + ": light \"" + sf.scene.lights[l].name +
                             "\" says \"estimate\" but the scene has no photo to estimate it "
                             "from; give its radiance as [r, g, b]");
    for (size_t l = 0; l < sf.estimateRadiance.size(); ++l)
        if (sf.estimateRadiance[l] && !sf.lightOnInPhoto(l))
            throw InputError(keyOf(sf, l) + ": light \"" + sf.scene.lights[l].name +
                             "\" says \"estimate\" but is off in the first photo (not in "
                             "photos[0].lights_on), so the photo cannot calibrate it; give "
                             "its radiance as [r, g, b]");
}

Rgb ambientRadiance(const Rgb& meanSurfaceRadiance, double rho, double areaReflecting,
                    const Rgb& knownPower, double areaEstimated, bool* negative) {
    if (negative) *negative = false;
    Rgb out;
    for (int c = 0; c < 3; ++c) {
        const double total = (1.0 - rho) / rho * meanSurfaceRadiance[c] * areaReflecting;
        const double v = (total - knownPower[c]) / areaEstimated;
        if (v < 0 || !std::isfinite(v)) {
            out[c] = 0;
            if (negative) *negative = true;
        } else {
            out[c] = v;
        }
    }
    return out;
}

LightFaceMap lightFaceMap(const ItemBuffer& items, const radiosity::Scene& scene) {
    LightFaceMap m;
    m.width = items.width;
    m.height = items.height;
    m.light.assign(static_cast<size_t>(m.width) * m.height, -1);
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            int light = -1;
            for (int s = 0; s < items.spp; ++s) {
                const int p = items.polygon[items.sampleIndex(x, y, s)];
                const int lp = p >= 0 ? scene.polygons[p].light : -1;
                if (lp < 0 || (s > 0 && lp != light)) {
                    light = -1;
                    break;
                }
                light = lp;
            }
            m.light[static_cast<size_t>(y) * m.width + x] = light;
        }
    return m;
}

FaceReading readLightFromPhoto(const LightFaceMap& faces, const Image& photo, bool srgb, int light,
                               int minPixels) {
    const int w = faces.width, h = faces.height;
    auto clean = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= w || y >= h) return false;
        if (faces.at(x, y) != light) return false;
        const float* px = photo.at(x, y);
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(px[c]) || (srgb && static_cast<double>(px[c]) >= kSrgbClip))
                return false;
        return true;
    };
    FaceReading out;
    std::vector<std::pair<int, int>> all, interior;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (faces.at(x, y) != light) continue;
            ++out.covered;
            if (!clean(x, y)) continue;
            all.emplace_back(x, y);
            if (clean(x - 1, y) && clean(x + 1, y) && clean(x, y - 1) && clean(x, y + 1))
                interior.emplace_back(x, y);
        }
    out.clean = static_cast<int>(all.size());
    const auto& use = static_cast<int>(interior.size()) >= minPixels ? interior : all;
    if (static_cast<int>(use.size()) < minPixels) return out;
    std::vector<double> v(use.size());
    for (int c = 0; c < 3; ++c) {
        for (size_t i = 0; i < use.size(); ++i) v[i] = photo.at(use[i].first, use[i].second)[c];
        out.radiance[c] = median(v);
    }
    out.used = static_cast<int>(use.size());
    return out;
}

SurfaceRadiance measureSurfaceRadiance(const ItemBuffer& items, const radiosity::Scene& scene,
                                       const Image& photo) {
    // Each polygon's mean over its clean pixels, then their area-weighted mean.
    const std::vector<uint8_t> usable = usablePixels(items, scene, photo);
    std::vector<Rgb> sum(scene.polygons.size());
    std::vector<int> count(scene.polygons.size(), 0);
    for (int y = 0; y < items.height; ++y)
        for (int x = 0; x < items.width; ++x) {
            if (!usable[static_cast<size_t>(y) * items.width + x]) continue;
            const int p = items.polygon[items.sampleIndex(x, y, 0)];
            if (scene.polygons[p].light >= 0) continue;
            const float* px = photo.at(x, y);
            sum[p] += Rgb(px[0], px[1], px[2]);
            ++count[p];
        }
    SurfaceRadiance out;
    Rgb weighted;
    for (size_t p = 0; p < scene.polygons.size(); ++p) {
        if (scene.polygons[p].light >= 0) continue;
        out.reflectingArea += scene.polygons[p].area;
        if (count[p] == 0) continue;
        weighted += sum[p] * (scene.polygons[p].area / count[p]);
        out.seenArea += scene.polygons[p].area;
    }
    if (out.seenArea > 0) out.mean = weighted * (1.0 / out.seenArea);
    return out;
}

namespace {

/// Way 1 for every "estimate" light; returns which lights are known after it (given in
/// scene.json, or read from the photo). The others are marked `ambient` for way 2.
std::vector<bool> estimateFromPhoto(const SceneFile& sf, const radiosity::Scene& scene,
                                    const ItemBuffer& items, const Image& photo,
                                    const EmittanceOptions& o, EmittanceReport& rep) {
    const bool srgb = !sf.photos.empty() && sf.photos.front().encoding == PhotoSpec::Encoding::srgb;
    const LightFaceMap faces = lightFaceMap(items, scene);
    std::vector<bool> known(scene.lights.size(), false);
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        if (!estimatedHere(sf, l)) {
            known[l] = true;
            continue;
        }
        const FaceReading reading =
            readLightFromPhoto(faces, photo, srgb, static_cast<int>(l), o.minPixels);
        if (reading.used > 0) {
            rep.lights[l].method = LightEmittance::Method::photo;
            rep.lights[l].radiance = reading.radiance;
            rep.lights[l].pixels = reading.used;
            known[l] = true;
            continue;
        }
        rep.lights[l].method = LightEmittance::Method::ambient;
        rep.lights[l].pixels = reading.clean;
        if (reading.covered >= o.minPixels)
            rep.warnings.push_back(
                keyOf(sf, l) + ": light \"" + scene.lights[l].name +
                "\": the photo sees its face on " + std::to_string(reading.covered) +
                " pixels but only " + std::to_string(reading.clean) +
                " are usable (clipped or not finite); estimated from the power balance instead");
    }
    return known;
}

/// rho^ of Eq. (2'): scene.json's, or the default with a warning. Throws for 0.
double averageReflectanceOf(const SceneFile& sf, EmittanceReport& rep) {
    double rho = kDefaultAverageReflectance;
    if (sf.averageReflectance) {
        rho = *sf.averageReflectance;
    } else {
        char s[64];
        std::snprintf(s, sizeof s, "%.2g", kDefaultAverageReflectance);
        rep.warnings.push_back((sf.dir / "scene.json").string() +
                               ": key \"average_reflectance\" is absent; the power balance "
                               "(Eq. (2')) assumes " +
                               s);
    }
    if (!(rho > 0))
        throw InputError((sf.dir / "scene.json").string() +
                         ": key \"average_reflectance\": 0 (black surfaces) leaves the photo "
                         "nothing to estimate the \"estimate\" lights' power from");
    return rho;
}

/// Way 2 for the lights way 1 left unknown: one common radiance from Eq. (2').
void estimateFromPowerBalance(const SceneFile& sf, const radiosity::Scene& scene,
                              const ItemBuffer& items, const Image& photo,
                              const std::vector<bool>& known, EmittanceReport& rep) {
    double areaEstimated = 0;  // summed face by face over the lights to estimate
    for (size_t l = 0; l < scene.lights.size(); ++l)
        if (!known[l])
            for (int p : scene.lights[l].polygons) areaEstimated += scene.polygons[p].area;
    if (areaEstimated <= 0) return;

    rep.ambientUsed = true;
    rep.averageReflectance = averageReflectanceOf(sf, rep);
    const SurfaceRadiance seen = measureSurfaceRadiance(items, scene, photo);
    rep.reflectingArea = seen.reflectingArea;
    rep.seenArea = seen.seenArea;
    if (!(rep.seenArea > 0))
        throw InputError(sf.photos.front().file.string() +
                         ": the photo shows no reflecting surface on a clean pixel, so the "
                         "radiance of the \"estimate\" lights cannot be estimated");
    rep.meanSurfaceRadiance = seen.mean;
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        if (!known[l]) continue;
        double area = 0;
        for (int p : scene.lights[l].polygons) area += scene.polygons[p].area;
        rep.knownPower += rep.lights[l].radiance * area;
    }
    bool negative = false;
    const Rgb value = ambientRadiance(rep.meanSurfaceRadiance, rep.averageReflectance,
                                      rep.reflectingArea, rep.knownPower, areaEstimated, &negative);
    if (negative)
        rep.warnings.push_back(
            "Eq. (2'): the lights of known radiance emit more than the power balance of the "
            "photo allows (" +
            rgbText(rep.knownPower) + " > " +
            rgbText(rep.meanSurfaceRadiance * ((1.0 - rep.averageReflectance) /
                                               rep.averageReflectance * rep.reflectingArea)) +
            " in photo units x m^2); the estimated radiance is clamped to 0 where negative");
    for (size_t l = 0; l < scene.lights.size(); ++l)
        if (!known[l]) rep.lights[l].radiance = value;
}

}  // namespace

EmittanceReport estimateEmittance(const SceneFile& sf, const radiosity::Scene& scene,
                                  const ItemBuffer& items, const Image& photo,
                                  const EmittanceOptions& o) {
    checkEstimableLights(sf);
    EmittanceReport rep;
    rep.lights.resize(scene.lights.size());
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        rep.lights[l].name = scene.lights[l].name;
        rep.lights[l].radiance = scene.lights[l].radiance;  // the photo's state
    }
    bool any = false;
    for (size_t l = 0; l < scene.lights.size(); ++l) any = any || estimatedHere(sf, l);
    if (!any) return rep;
    // Way 1 first: a light the photo shows is read there, and its power is then known to
    // the balance of way 2.
    const std::vector<bool> known = estimateFromPhoto(sf, scene, items, photo, o, rep);
    estimateFromPowerBalance(sf, scene, items, photo, known, rep);
    return rep;
}

}  // namespace relight
