// Edit saving ("relight-edit/1", docs/scene-format.md, "Edit"): the inverse of
// loadEdit() in edit_file.cpp, which reads every key written here.
#include "relight/io/edit_writer.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <system_error>

#include "relight/io/atomic_write.h"
#include "relight/io/json_file.h"
#include "relight/io/json_reader.h"

namespace relight {

namespace fs = std::filesystem;
using jsonio::child;
using jsonio::element;
using nlohmann::json;

namespace {

/// `v` as a JSON number. JSON has no NaN or infinity: nlohmann would write null, which
/// loadEdit rejects, so the edit could be saved but never loaded again.
json number(double v, const std::string& path) {
    if (!std::isfinite(v))
        throw std::invalid_argument("editJson: key \"" + path + "\": " + std::to_string(v) +
                                    " is not a finite number");
    return v;
}

json rgb(const Rgb& c, const std::string& path) {
    return {number(c.r, element(path, 0)), number(c.g, element(path, 1)),
            number(c.b, element(path, 2))};
}

/// `f`'s numbers at `path`, shaped as the format has them (radiosity::EmitterField).
json fieldValue(const radiosity::EmitterField& f, const std::string& path) {
    using Shape = radiosity::EmitterField::Shape;
    if (f.shape == Shape::number && f.values.size() == 1) return number(f.values[0], path);
    if (f.values.empty() || f.values.size() % 3 != 0 ||
        (f.shape != Shape::rows && f.values.size() != 3))
        throw std::invalid_argument("editJson: key \"" + path + "\": " +
                                    std::to_string(f.values.size()) + " numbers are not rows of 3");
    json out = json::array();
    for (size_t k = 0; k < f.values.size(); k += 3) {
        const std::string rowPath = f.shape == Shape::rows ? element(path, k / 3) : path;
        json row = {number(f.values[k], element(rowPath, 0)),
                    number(f.values[k + 1], element(rowPath, 1)),
                    number(f.values[k + 2], element(rowPath, 2))};
        if (f.shape != Shape::rows) return row;
        out.push_back(std::move(row));
    }
    return out;
}

/// Puts the light's fields into `obj` (at `path`): a key "rotate.axis" goes to
/// obj["rotate"]["axis"]. Which fields a light has is the light's own business
/// (radiosity::Emitter::fields, editFields); this only writes them.
void putFields(json& obj, const std::vector<radiosity::EmitterField>& fields,
               const std::string& path) {
    for (const radiosity::EmitterField& f : fields) {
        json* at = &obj;
        std::string fPath = path;
        size_t start = 0;
        for (size_t dot = f.key.find('.'); dot != std::string::npos;
             start = dot + 1, dot = f.key.find('.', start)) {
            const std::string part = f.key.substr(start, dot - start);
            fPath = child(fPath, part);
            at = &(*at)[part];
        }
        const std::string last = f.key.substr(start);
        (*at)[last] = fieldValue(f, child(fPath, last));
    }
}

json lightEdit(const LightEdit& l, const std::string& path) {
    if (l.emitter) {
        // A sun's, point lamp's or sky's edit: its fields under the keys of its type.
        if (!l.light)
            throw std::invalid_argument("editJson: key \"" + path +
                                        "\": the edit does not say which light it edits");
        json out = json::object();
        putFields(out, radiosity::editFields(*l.light, *l.emitter), path);
        if (out.empty())
            throw std::invalid_argument("editJson: key \"" + path + "\": the edit says nothing");
        return out;
    }
    // loadEdit refuses both and neither (edit_file.cpp, readLightEdit).
    if (l.scale.has_value() == l.radiance.has_value())
        throw std::invalid_argument("editJson: key \"" + path + "\": give exactly one of scale " +
                                    "and radiance");
    if (l.scale) return {{"scale", number(*l.scale, child(path, "scale"))}};
    return {{"radiance", rgb(*l.radiance, child(path, "radiance"))}};
}

json virtualLight(const VirtualLight& v, const std::string& path) {
    if (v.emitter) {
        // A sun, point lamp or sky: "type" and the fields the light says it has.
        json out = {{"name", v.name}, {"type", v.emitter->type()}};
        putFields(out, v.emitter->fields(), path);
        return out;
    }
    const std::string vPath = child(path, "vertices");
    json vertices = json::array();
    for (size_t k = 0; k < v.corners.size(); ++k) {
        const radiosity::Vec3& p = v.corners[k];
        const std::string pPath = element(vPath, k);
        vertices.push_back({number(p.x, element(pPath, 0)), number(p.y, element(pPath, 1)),
                            number(p.z, element(pPath, 2))});
    }
    // "type" is optional in an edit (light_reader.h) but written, as the spec's example has it.
    return {{"name", v.name},
            {"type", "quad"},
            {"vertices", std::move(vertices)},
            {"radiance", rgb(v.radiance, child(path, "radiance"))}};
}

/// `file` as loadEdit will find it from `editFolder` (it reads editFolder / name).
/// fs::relative works on the weakly canonical forms: the OS resolves a symbolic link before
/// the ".." that follows it, so a purely lexical relative path would point elsewhere when
/// the edit's folder (or the object's) is reached through a link. Forward slashes, so that
/// the file reads the same on every system.
std::string objectFileName(const fs::path& file, const fs::path& editFolder) {
    std::error_code ec;
    const fs::path rel = fs::relative(file, editFolder.empty() ? fs::path(".") : editFolder, ec);
    if (!ec && !rel.empty()) return rel.generic_string();
    // No relative path (another drive on Windows, or a folder we may not look into): an
    // absolute one, which loadEdit's editFolder / name leaves as it is.
    return fs::absolute(file, ec).generic_string();
}

json virtualObject(const VirtualObject& v, const std::string& path, const fs::path& editFolder) {
    if (v.file.empty())
        throw std::invalid_argument("editJson: key \"" + child(path, "file") +
                                    "\": the object has no OBJ file");
    const std::string tPath = child(path, "transform");
    json transform = json::array();
    for (size_t i = 0; i < 4; ++i) {
        json row = json::array();
        for (size_t j = 0; j < 4; ++j)
            row.push_back(number(v.transform[i][j], element(element(tPath, i), j)));
        transform.push_back(std::move(row));
    }
    json o = {{"name", v.name},
              {"file", objectFileName(v.file, editFolder)},
              {"reflectance", rgb(v.reflectance, child(path, "reflectance"))},
              {"transform", std::move(transform)}};
    if (v.specular) {
        const std::string sPath = child(path, "specular");
        o["specular"] = {{"ks", rgb(v.specular->ks, child(sPath, "ks"))},
                         {"shininess", number(v.specular->shininess, child(sPath, "shininess"))}};
    }
    return o;
}

}  // namespace

json editJson(const EditFile& edit, const fs::path& editFolder) {
    json j = {{"format", "relight-edit/1"}};
    // Empty parts are left out (every part is optional): a lights-only edit stays as short
    // as the hand-written ones.
    if (!edit.lights.empty()) {
        json lights = json::object();
        for (const auto& [name, change] : edit.lights)
            lights[name] = lightEdit(change, child("lights", name));
        j["lights"] = std::move(lights);
    }
    if (!edit.addLights.empty()) {
        json list = json::array();
        for (size_t i = 0; i < edit.addLights.size(); ++i)
            list.push_back(virtualLight(edit.addLights[i], element("add_lights", i)));
        j["add_lights"] = std::move(list);
    }
    if (!edit.addObjects.empty()) {
        json list = json::array();
        for (size_t i = 0; i < edit.addObjects.size(); ++i)
            list.push_back(
                virtualObject(edit.addObjects[i], element("add_objects", i), editFolder));
        j["add_objects"] = std::move(list);
    }
    if (!edit.removeObjects.empty()) j["remove_objects"] = edit.removeObjects;
    return j;
}

void writeEdit(const fs::path& file, const EditFile& edit) {
    // The JSON is made first: an edit it cannot say throws before the file is touched.
    writeJsonAtomic(file, editJson(edit, file.parent_path()));
}

const char* unitBoxObjText() {
    // data/room/objects/box.obj's vertices and faces, divided by its 0.3 m side: the faces
    // are counter-clockwise seen from outside, so that the fronts (obj_reader.h) face out.
    return "# unit cube, base centred on the origin at z = 0, fronts outward\n"
           "o box\n"
           "v -0.5 -0.5 1\n"
           "v -0.5 0.5 1\n"
           "v -0.5 0.5 0\n"
           "v -0.5 -0.5 0\n"
           "v 0.5 -0.5 0\n"
           "v 0.5 0.5 0\n"
           "v 0.5 0.5 1\n"
           "v 0.5 -0.5 1\n"
           "f 1 2 3 4\n"
           "f 5 6 7 8\n"
           "f 4 5 8 1\n"
           "f 2 7 6 3\n"
           "f 3 6 5 4\n"
           "f 1 8 7 2\n";
}

void writeUnitBoxObj(const fs::path& file) {
    writeTextAtomic(file, unitBoxObjText());
}

}  // namespace relight
