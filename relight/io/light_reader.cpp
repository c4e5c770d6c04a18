#include "relight/io/light_reader.h"

#include <nlohmann/json.hpp>

#include "radiosity/scene.h"

#include <stdexcept>

namespace relight {

using jsonio::child;
using jsonio::element;

radiosity::Sh9Rgb readSh9(const jsonio::JsonReader& r, const nlohmann::json& j,
                          const std::string& path) {
    if (j.is_string())
        r.fail(path, "\"" + j.get<std::string>() +
                         "\" is not supported yet here: give the 9 coefficients");
    const nlohmann::json& rows = r.array(j, path, radiosity::kSh9Count);
    radiosity::Sh9Rgb L;
    for (size_t k = 0; k < rows.size(); ++k) L.c[k] = r.rgb(rows[k], element(path, k));
    return L;
}

namespace {

/// Whether `j` is the format's "estimate" where `estimateAllowed` (a scene's sun or sky:
/// fitted to the photo, relight/pipeline/sky_estimate.h); any other string is refused.
bool isEstimate(const jsonio::JsonReader& r, const nlohmann::json& j, const std::string& path,
                bool estimateAllowed, const char* what) {
    if (!j.is_string()) return false;
    if (j.get<std::string>() != "estimate")
        r.fail(path, "expected " + std::string(what) + " or \"estimate\", got " + j.dump());
    if (!estimateAllowed)
        r.fail(path, "a virtual light's strength must be given (\"estimate\" needs a photo of it)");
    return true;
}

/// A light's RGB strength ("irradiance", "intensity"): three finite numbers >= 0.
/// A point lamp's "estimate" is refused (the format allows it for a sun and a sky only).
radiosity::Rgb readStrength(const jsonio::JsonReader& r, const nlohmann::json& lj,
                            const std::string& path, const char* key) {
    const std::string kPath = child(path, key);
    const nlohmann::json& j = r.require(lj, path, key);
    if (j.is_string())
        r.fail(kPath,
               "\"" + j.get<std::string>() + "\" is not supported here: give the light's " + key);
    const radiosity::Rgb c = r.rgb(j, kPath);
    for (int k = 0; k < 3; ++k)
        if (c[k] < 0) r.fail(element(kPath, static_cast<size_t>(k)), "must not be negative");
    return c;
}

/// The emitter's own checks (radiosity/emitter.h) as an InputError at `path`.
template <class Make>
std::shared_ptr<radiosity::Emitter> made(const jsonio::JsonReader& r, const std::string& path,
                                         Make&& make) {
    try {
        return make();
    } catch (const std::invalid_argument& e) {
        r.fail(path, e.what());
    }
}

/// A sun; "irradiance": "estimate" (where allowed) gives irradiance 0 and sets `estimate`.
std::shared_ptr<radiosity::Emitter> readSun(const jsonio::JsonReader& r, const nlohmann::json& lj,
                                            const std::string& path, const std::string& name,
                                            bool estimateAllowed, bool& estimate) {
    r.checkKeys(lj, path, {"name", "type", "direction", "angle", "irradiance"});
    const radiosity::Vec3 d = r.point(r.require(lj, path, "direction"), child(path, "direction"));
    const double angle = r.number(r.require(lj, path, "angle"), child(path, "angle"));
    estimate = isEstimate(r, r.require(lj, path, "irradiance"), child(path, "irradiance"),
                          estimateAllowed, "an RGB array");
    const radiosity::Rgb E = estimate ? radiosity::Rgb{} : readStrength(r, lj, path, "irradiance");
    return made(r, path, [&] { return radiosity::makeSun(name, d, angle, E); });
}

std::shared_ptr<radiosity::Emitter> readPoint(const jsonio::JsonReader& r, const nlohmann::json& lj,
                                              const std::string& path, const std::string& name) {
    r.checkKeys(lj, path, {"name", "type", "position", "intensity"});
    const radiosity::Vec3 x = r.point(r.require(lj, path, "position"), child(path, "position"));
    const radiosity::Rgb I = readStrength(r, lj, path, "intensity");
    return made(r, path, [&] { return radiosity::makePointLamp(name, x, I); });
}

std::shared_ptr<radiosity::Emitter> readEnvironment(const jsonio::JsonReader& r,
                                                    const nlohmann::json& lj,
                                                    const std::string& path,
                                                    const std::string& name, bool estimateAllowed,
                                                    bool& estimate) {
    r.checkKeys(lj, path, {"name", "type", "sh9"});
    const nlohmann::json& j = r.require(lj, path, "sh9");
    estimate = isEstimate(r, j, child(path, "sh9"), estimateAllowed, "9 RGB rows");
    const radiosity::Sh9Rgb L = estimate ? radiosity::Sh9Rgb{} : readSh9(r, j, child(path, "sh9"));
    return made(r, path, [&] { return radiosity::makeEnvironment(name, L); });
}

}  // namespace

LightJson readLightJson(const jsonio::JsonReader& r, const nlohmann::json& lj,
                        const std::string& path, bool typeRequired, bool estimateAllowed) {
    if (!lj.is_object()) r.checkKeys(lj, path, {});  // says it is not an object
    LightJson l;
    l.name = r.string(r.require(lj, path, "name"), child(path, "name"));
    if (l.name.empty()) r.fail(child(path, "name"), "empty light name");
    if (auto t = lj.find("type"); typeRequired || t != lj.end()) {
        const std::string tPath = child(path, "type");
        const std::string type = r.string(typeRequired ? r.require(lj, path, "type") : *t, tPath);
        if (type == "sun") {
            l.emitter = readSun(r, lj, path, l.name, estimateAllowed, l.estimate);
            return l;
        }
        if (type == "point") {
            l.emitter = readPoint(r, lj, path, l.name);
            return l;
        }
        if (type == "environment") {
            l.emitter = readEnvironment(r, lj, path, l.name, estimateAllowed, l.estimate);
            return l;
        }
        if (type != "quad")
            r.fail(tPath,
                   "light type " + type + " not supported (quad, sun, point or environment)");
    }
    r.checkKeys(lj, path, {"name", "type", "vertices", "radiance"});

    const std::string vPath = child(path, "vertices");
    const nlohmann::json& vj = r.array(r.require(lj, path, "vertices"), vPath, 0, 3);
    for (size_t k = 0; k < vj.size(); ++k) l.corners.push_back(r.point(vj[k], element(vPath, k)));
    const radiosity::PolygonCheck check = radiosity::checkPolygon(l.corners);
    if (check.status != radiosity::PolygonCheck::Status::ok)
        r.fail(vPath, "a light must be a planar convex polygon of non-zero area: " + check.message);

    const std::string radPath = child(path, "radiance");
    const nlohmann::json& rj = r.require(lj, path, "radiance");
    if (rj.is_string()) {
        if (!estimateAllowed)
            r.fail(radPath,
                   "a virtual light's radiance must be given (\"estimate\" needs a photo of it)");
        if (rj.get<std::string>() != "estimate")
            r.fail(radPath, "expected an RGB array or \"estimate\", got " + rj.dump());
        l.estimate = true;
        return l;
    }
    l.radiance = r.rgb(rj, radPath);
    for (int k = 0; k < 3; ++k)
        if (l.radiance[k] < 0)
            r.fail(element(radPath, static_cast<size_t>(k)), "radiance must not be negative");
    return l;
}

}  // namespace relight
