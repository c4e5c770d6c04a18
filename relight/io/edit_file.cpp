// Edit loading ("relight-edit/1", docs/scene-format.md, "Edit"). Strict like the
// scene loader and with the same messages (json_reader.h): a misspelt key or light name
// would otherwise be an edit that silently does nothing.
#include "relight/io/edit_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "relight/io/face_repair.h"
#include "relight/io/json_reader.h"
#include "relight/io/light_reader.h"
#include "relight/io/mesh_reader.h"

namespace relight {

namespace fs = std::filesystem;
using jsonio::child;
using jsonio::element;
using jsonio::JsonReader;
using nlohmann::json;

namespace {

/// "A, B, C, D": the names a user may write under "lights", for the unknown-light message.
std::string lightNames(const SceneFile& sf) {
    if (sf.scene.lights.empty()) return "no lights";
    std::string names;
    for (const radiosity::Light& light : sf.scene.lights)
        if (light.component == 0) names += (names.empty() ? "" : ", ") + light.name;
    return names;
}

/// "1e+308 x [13, 11.2, 9]": a scale and the radiance it multiplies, as a message shows
/// them (with snprintf, as GCC 12 warns wrongly (-Wrestrict) on short string sums).
std::string productText(double scale, const Rgb& c) {
    char s[128];
    std::snprintf(s, sizeof s, "%.6g x [%.6g, %.6g, %.6g]", scale, c.r, c.g, c.b);
    return s;
}

/// A sun's, point lamp's or sky's edit: its fields, then checked by applying it to the
/// scene's light (radiosity::Emitter::apply refuses a field the type lacks, naming it).
LightEdit readEmitterEdit(const JsonReader& r, const json& entry, const std::string& path,
                          const std::shared_ptr<const radiosity::Emitter>& light) {
    r.checkKeys(entry, path,
                {"scale", "irradiance", "intensity", "sh9", "direction", "position", "rotate"});
    if (entry.empty()) r.fail(path, "says nothing; give \"scale\" or a field of the light's type");
    radiosity::EmitterEdit e;
    if (auto s = entry.find("scale"); s != entry.end()) {
        e.scale = r.number(*s, child(path, "scale"));
        if (*e.scale < 0) r.fail(child(path, "scale"), "scale must not be negative");
    }
    for (const char* key : {"irradiance", "intensity"})
        if (auto c = entry.find(key); c != entry.end()) {
            if (e.strength) r.fail(path, "has both \"irradiance\" and \"intensity\"");
            e.strength = r.rgb(*c, child(path, key));
            for (int k = 0; k < 3; ++k)
                if ((*e.strength)[k] < 0)
                    r.fail(element(child(path, key), static_cast<size_t>(k)),
                           "must not be negative");
        }
    if (auto j = entry.find("sh9"); j != entry.end()) e.sh9 = readSh9(r, *j, child(path, "sh9"));
    if (auto j = entry.find("direction"); j != entry.end())
        e.direction = r.point(*j, child(path, "direction"));
    if (auto j = entry.find("position"); j != entry.end())
        e.position = r.point(*j, child(path, "position"));
    if (auto j = entry.find("rotate"); j != entry.end()) {
        const std::string rPath = child(path, "rotate");
        r.checkKeys(*j, rPath, {"axis", "degrees"});
        e.rotate = radiosity::EmitterEdit::Rotation{
            r.point(r.require(*j, rPath, "axis"), child(rPath, "axis")),
            r.number(r.require(*j, rPath, "degrees"), child(rPath, "degrees"))};
    }
    try {
        light->clone()->apply(e);
    } catch (const std::invalid_argument& ex) {
        r.fail(path, ex.what());
    }
    LightEdit edit;
    edit.scale = e.scale;
    edit.emitter = e;
    edit.light = light;
    return edit;
}

LightEdit readLightEdit(const JsonReader& r, const json& entry, const std::string& path) {
    r.checkKeys(entry, path, {"scale", "radiance"});
    const auto scale = entry.find("scale");
    const auto radiance = entry.find("radiance");
    // Both would leave it to us which one wins; neither is most likely a typo'd key that
    // checkKeys cannot catch (an empty object). Both are errors rather than guesses.
    if (scale != entry.end() && radiance != entry.end())
        r.fail(path, "has both \"scale\" and \"radiance\"; give one of them");
    if (scale == entry.end() && radiance == entry.end())
        r.fail(path, "says nothing; give \"scale\" or \"radiance\"");

    LightEdit edit;
    if (scale != entry.end()) {
        const std::string sPath = child(path, "scale");
        const double s = r.number(*scale, sPath);
        if (s < 0) r.fail(sPath, "scale must not be negative");
        edit.scale = s;
    } else {
        const std::string rPath = child(path, "radiance");
        const Rgb rad = r.rgb(*radiance, rPath);
        for (int k = 0; k < 3; ++k)
            if (rad[k] < 0)
                r.fail(element(rPath, static_cast<size_t>(k)), "radiance must not be negative");
        edit.radiance = rad;
    }
    return edit;
}

VirtualLight readVirtualLight(const JsonReader& r, const json& lj, const std::string& path) {
    LightJson l = readLightJson(r, lj, path, /*typeRequired=*/false, /*estimateAllowed=*/false);
    return {std::move(l.name), std::move(l.corners), l.radiance, std::move(l.emitter)};
}

/// "specular": {"ks": [r, g, b], "shininess": s} (an engine extension, docs/scene-format.md):
/// ks finite and >= 0, s finite and > 0.
Specular readSpecular(const JsonReader& r, const json& sj, const std::string& path) {
    if (!sj.is_object()) r.fail(path, "expected an object {\"ks\": [r, g, b], \"shininess\": s}");
    r.checkKeys(sj, path, {"ks", "shininess"});
    Specular s;
    const std::string kPath = child(path, "ks");
    s.ks = r.rgb(r.require(sj, path, "ks"), kPath);
    for (int k = 0; k < 3; ++k)
        if (!(s.ks[k] >= 0)) r.fail(element(kPath, static_cast<size_t>(k)), "ks must be >= 0");
    const std::string sPath = child(path, "shininess");
    s.shininess = r.number(r.require(sj, path, "shininess"), sPath);
    if (!(s.shininess > 0)) r.fail(sPath, "shininess must be > 0 (the lobe's exponent)");
    // (n.h)^s of a double underflows to 0 past about 1e5 at n.h = 0.99: refused as a
    // highlight no pixel could show rather than drawn as nothing.
    if (s.shininess > 1e5) r.fail(sPath, "shininess must be <= 100000");
    return s;
}

VirtualObject readVirtualObject(const JsonReader& r, const json& oj, const std::string& path,
                                const fs::path& editFile, std::vector<std::string>& warnings) {
    r.checkKeys(oj, path, {"name", "file", "reflectance", "transform", "specular"});
    VirtualObject v;
    v.name = r.string(r.require(oj, path, "name"), child(path, "name"));
    if (v.name.empty()) r.fail(child(path, "name"), "empty object name");

    const std::string rPath = child(path, "reflectance");
    v.reflectance = r.rgb(r.require(oj, path, "reflectance"), rPath);
    for (int k = 0; k < 3; ++k)
        if (!(v.reflectance[k] >= 0 && v.reflectance[k] < 1))
            r.fail(element(rPath, static_cast<size_t>(k)),
                   "reflectance must be in [0, 1): a surface reflects less than it receives, and "
                   "1 would make the radiosity system singular");

    const std::string tPath = child(path, "transform");
    const auto M = r.matrix(r.require(oj, path, "transform"), tPath, 4, 4);
    for (size_t c = 0; c < 4; ++c)
        if (std::abs(M[3][c] - (c == 3 ? 1.0 : 0.0)) > 1e-9)
            r.fail(element(element(tPath, 3), c),
                   "the last row must be [0, 0, 0, 1] (an affine placement, no projection)");
    double scale = 0;
    for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j) scale = std::max(scale, std::abs(M[i][j]));
    const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                       M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                       M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    // Relative to the matrix's own scale: a 1 mm-thick flattening of a 1 m box is legal.
    if (!(std::abs(det) > 1e-9 * scale * scale * scale))
        r.fail(tPath, "the transform is singular (it flattens the object to a plane or less)");
    for (size_t i = 0; i < 4; ++i)
        for (size_t j = 0; j < 4; ++j) v.transform[i][j] = M[i][j];
    if (auto it = oj.find("specular"); it != oj.end())
        v.specular = readSpecular(r, *it, child(path, "specular"));

    const std::string fPath = child(path, "file");
    const std::string name = r.string(r.require(oj, path, "file"), fPath);
    if (name.empty()) r.fail(fPath, "empty file name");
    v.file = editFile.parent_path() / name;
    std::error_code ec;
    if (!fs::exists(v.file, ec))
        r.fail(fPath, "geometry file \"" + v.file.string() + "\" not found");
    // Any format the scene's geometry may have (OBJ, PLY, glTF: mesh_reader.h).
    ObjFile obj = readMesh(v.file).geometry;
    warnings.insert(warnings.end(), obj.warnings.begin(), obj.warnings.end());
    placeObject(v, obj, warnings);
    if (v.polygons.empty()) r.fail(fPath, "\"" + v.file.string() + "\" has no usable face");
    return v;
}

/// Light i's strength after `e`: its emitter with the nominal strengths of its components,
/// edited (a sky's sh9 set, turned or scaled; a sun's irradiance; a lamp's intensity).
/// Light i's emitter with the nominal strengths of its components, edited by `e` (a sky's
/// sh9 set, turned or scaled; a sun's irradiance or direction; a lamp's intensity or place).
std::unique_ptr<radiosity::Emitter> editedEmitter(const SceneFile& sf, size_t i,
                                                  const radiosity::EmitterEdit& e,
                                                  const std::vector<Rgb>& nominal,
                                                  const EditFile& edit) {
    const radiosity::Light& light = sf.scene.lights[i];
    const size_t first = i - static_cast<size_t>(light.component);
    std::unique_ptr<radiosity::Emitter> em = light.emitter->clone();
    const size_t n = static_cast<size_t>(em->components());
    em->setStrengths({nominal.data() + first, n});
    try {
        em->apply(e);
    } catch (const std::invalid_argument& ex) {
        JsonReader(edit.file.string()).fail(child("lights", light.name), ex.what());
    }
    return em;
}

/// Light i's strength after `e`.
Rgb editedStrength(const SceneFile& sf, size_t i, const radiosity::EmitterEdit& e,
                   const std::vector<Rgb>& nominal, const EditFile& edit) {
    return editedEmitter(sf, i, e, nominal, edit)
        ->strengths()
        .at(static_cast<size_t>(sf.scene.lights[i].component));
}

}  // namespace

void placeObject(VirtualObject& v, ObjFile obj, std::vector<std::string>& warnings) {
    const auto& M = v.transform;
    const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                       M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                       M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    for (radiosity::Vec3& p : obj.positions)
        p = radiosity::Vec3(M[0][0] * p.x + M[0][1] * p.y + M[0][2] * p.z + M[0][3],
                            M[1][0] * p.x + M[1][1] * p.y + M[1][2] * p.z + M[1][3],
                            M[2][0] * p.x + M[2][1] * p.y + M[2][2] * p.z + M[2][3]);
    // A mirroring transform turns counter-clockwise faces clockwise: turn them back, so
    // that each face's front side stays the one the file meant.
    if (det < 0)
        for (ObjFace& f : obj.faces) std::reverse(f.vertices.begin(), f.vertices.end());
    radiosity::Scene faces;
    faces.objects.push_back(v.name);
    const std::vector<int> toObject(obj.objects.size(), 0);
    addObjFaces(
        obj, toObject, [&](int) { return v.reflectance; }, faces, warnings);
    v.polygons = std::move(faces.polygons);
}

namespace {

/// loadEdit() after parsing: `root` is the edit file's document.
EditFile readEdit(const json& root, const fs::path& file, const SceneFile& sf) {
    EditFile edit;
    edit.file = file;
    const JsonReader r(file.string());
    if (!root.is_object()) r.fail("", "the top level must be a JSON object");

    // The format first: a scene.json given by mistake is then named as such rather than
    // reported as a list of unknown keys.
    const json& format = r.require(root, "", "format");
    if (!format.is_string() || format.get<std::string>() != "relight-edit/1")
        r.fail("format", "expected \"relight-edit/1\", got " + format.dump());
    r.checkKeys(root, "", {"format", "lights", "add_lights", "add_objects", "remove_objects"});

    if (auto it = root.find("lights"); it != root.end()) {
        if (!it->is_object())
            r.fail("lights", "expected an object of light names, got " + JsonReader::describe(*it));
        for (auto l = it->begin(); l != it->end(); ++l) {
            const std::string path = child("lights", l.key());
            if (sf.scene.findLight(l.key()) < 0)
                r.fail(path,
                       "unknown light \"" + l.key() + "\" (the scene has " + lightNames(sf) + ")");
            const radiosity::Light& light = sf.scene.lights[sf.scene.findLight(l.key())];
            edit.lights[l.key()] = light.emitter
                                       ? readEmitterEdit(r, l.value(), path, light.emitter)
                                       : readLightEdit(r, l.value(), path);
        }
    }

    if (auto it = root.find("add_lights"); it != root.end()) {
        const json& list = r.array(*it, "add_lights", 0);
        for (size_t i = 0; i < list.size(); ++i) {
            VirtualLight v = readVirtualLight(r, list[i], element("add_lights", i));
            const std::string nPath = child(element("add_lights", i), "name");
            if (sf.scene.findLight(v.name) >= 0)
                r.fail(nPath, "the scene already has a light \"" + v.name + "\"");
            for (const VirtualLight& other : edit.addLights)
                if (other.name == v.name) r.fail(nPath, "duplicate light name \"" + v.name + "\"");
            edit.addLights.push_back(std::move(v));
        }
    }
    if (auto it = root.find("add_objects"); it != root.end()) {
        const json& list = r.array(*it, "add_objects", 0);
        for (size_t i = 0; i < list.size(); ++i) {
            const std::string path = element("add_objects", i);
            VirtualObject v = readVirtualObject(r, list[i], path, file, edit.warnings);
            const std::string nPath = child(path, "name");
            if (sf.scene.findObject(v.name) >= 0)
                r.fail(nPath, "the scene already has an object \"" + v.name + "\"");
            for (const VirtualObject& other : edit.addObjects)
                if (other.name == v.name) r.fail(nPath, "duplicate object name \"" + v.name + "\"");
            edit.addObjects.push_back(std::move(v));
        }
    }
    if (auto it = root.find("remove_objects"); it != root.end()) {
        const json& list = r.array(*it, "remove_objects", 0);
        for (size_t i = 0; i < list.size(); ++i) {
            const std::string path = element("remove_objects", i);
            const std::string name = r.string(list[i], path);
            const auto settings = sf.objectSettings.find(name);
            if (sf.scene.findObject(name) < 0 || name.starts_with("light:"))
                r.fail(path, "the scene has no object \"" + name + "\"");
            if (settings == sf.objectSettings.end() || !settings->second.removable)
                r.fail(path, "object \"" + name +
                                 "\" is not marked \"removable\" in scene.json (removing it needs "
                                 "the photo behind it to be filled in)");
            if (std::find(edit.removeObjects.begin(), edit.removeObjects.end(), name) !=
                edit.removeObjects.end())
                r.fail(path, "object \"" + name + "\" is removed twice");
            edit.removeObjects.push_back(name);
        }
    }
    // A scale that overflows scene.json's radiance fails here, before the preparation; that
    // of an "estimate" light (nominal 0 until estimated) when editRadiance() applies it.
    editedRadiance(sf, edit, sf.nominalRadiance);
    return edit;
}

}  // namespace

EditFile loadEdit(const fs::path& file, const SceneFile& sf) {
    return readEdit(jsonio::parseJsonFile(file), file, sf);
}

EditFile parseEdit(std::istream& editJson, const fs::path& file, const SceneFile& sf) {
    return readEdit(jsonio::parseJson(editJson, file.string()), file, sf);
}

std::vector<Rgb> editedRadiance(const SceneFile& sf, const EditFile& edit,
                                const std::vector<Rgb>& nominal) {
    const auto& lights = sf.scene.lights;
    if (nominal.size() != lights.size())
        throw std::invalid_argument("editedRadiance: " + std::to_string(nominal.size()) +
                                    " nominal radiances for " + std::to_string(lights.size()) +
                                    " lights");
    for (const auto& [name, change] : edit.lights)
        if (sf.scene.findLight(name) < 0)
            throw std::invalid_argument("editedRadiance: " + edit.file.string() +
                                        " names light \"" + name +
                                        "\", which this scene does not have");

    std::vector<Rgb> out(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        if (auto it = edit.lights.find(lights[i].name); it != edit.lights.end()) {
            const LightEdit& change = it->second;
            if (change.emitter && lights[i].emitter) {
                // A moved light is off where it was; movedLights() puts it where it went.
                out[i] =
                    change.moves() ? Rgb{} : editedStrength(sf, i, *change.emitter, nominal, edit);
                continue;
            }
            out[i] = change.scale ? nominal[i] * *change.scale : *change.radiance;
            // A scale may overflow the radiance (a given radiance was checked finite): an
            // infinite radiance makes every pixel it reaches inf, or NaN where inf meets 0.
            if (change.scale &&
                !(std::isfinite(out[i].r) && std::isfinite(out[i].g) && std::isfinite(out[i].b)))
                JsonReader(edit.file.string())
                    .fail(child(child("lights", lights[i].name), "scale"),
                          "the relit image is not finite: the light's radiance overflows (" +
                              productText(*change.scale, nominal[i]) + ")");
            continue;
        }
        // The photo's state, applied to the given nominal radiance (maybe an estimated one).
        out[i] = sf.lightOnInPhoto(i) ? nominal[i] : Rgb{};
    }
    return out;
}

std::vector<VirtualLight> movedLights(const SceneFile& sf, const EditFile& edit) {
    std::vector<VirtualLight> out;
    const auto& lights = sf.scene.lights;
    for (size_t i = 0; i < lights.size(); ++i) {
        if (!lights[i].emitter || lights[i].component != 0) continue;
        const auto it = edit.lights.find(lights[i].name);
        if (it == edit.lights.end() || !it->second.moves()) continue;
        out.push_back({lights[i].name,
                       {},
                       Rgb{},
                       editedEmitter(sf, i, *it->second.emitter, sf.nominalRadiance, edit)});
    }
    return out;
}

}  // namespace relight
