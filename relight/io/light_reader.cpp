#include "relight/io/light_reader.h"

#include <nlohmann/json.hpp>

#include "radiosity/scene.h"

namespace relight {

using jsonio::child;
using jsonio::element;

LightJson readLightJson(const jsonio::JsonReader& r, const nlohmann::json& lj,
                        const std::string& path, bool typeRequired, bool estimateAllowed) {
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
