#include "relight/io/light_reader.h"

#include <nlohmann/json.hpp>

#include "radiosity/scene.h"

namespace relight {

using jsonio::child;
using jsonio::element;

namespace {

/// The format's lights at a point or at infinity (docs/scene-format.md: sun, point,
/// environment) are valid input that relight does not light with yet. They are refused by
/// name and type before their keys are checked, as a quad's: "unknown key direction" would
/// not say what is wrong.
void refuseTypesNotSupportedYet(const jsonio::JsonReader& r, const nlohmann::json& lj,
                                const std::string& path) {
    if (!lj.is_object()) return;  // checkKeys() says so
    const auto t = lj.find("type");
    if (t == lj.end() || !t->is_string()) return;
    const std::string type = t->get<std::string>();
    if (type != "sun" && type != "point" && type != "environment") return;
    // Appended piece by piece: gcc 12 warns (-Wrestrict, falsely) on "'" + name + "'".
    std::string what = "light ";
    if (const auto n = lj.find("name"); n != lj.end() && n->is_string()) {
        what += '\'';
        what += n->get<std::string>();
        what += '\'';
    } else {
        what += "without a name";
    }
    what += ": type '";
    what += type;
    what += "' is not supported yet (relight lights scenes with quad lights only)";
    r.fail(child(path, "type"), what);
}

}  // namespace

LightJson readLightJson(const jsonio::JsonReader& r, const nlohmann::json& lj,
                        const std::string& path, bool typeRequired, bool estimateAllowed) {
    refuseTypesNotSupportedYet(r, lj, path);
    r.checkKeys(lj, path, {"name", "type", "vertices", "radiance"});
    LightJson l;
    l.name = r.string(r.require(lj, path, "name"), child(path, "name"));
    if (l.name.empty()) r.fail(child(path, "name"), "empty light name");
    if (auto t = lj.find("type"); typeRequired || t != lj.end()) {
        const std::string tPath = child(path, "type");
        const std::string type = r.string(typeRequired ? r.require(lj, path, "type") : *t, tPath);
        if (type != "quad") r.fail(tPath, "light type " + type + " not supported");
    }

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
