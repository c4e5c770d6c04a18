// Edit loading ("relight-edit/1", ../shared/spec/scene-format.md, "Edit"). Strict like the
// scene loader and with the same messages (json_reader.h): a misspelt key or light name
// would otherwise be an edit that silently does nothing.
#include "relight/edit_file.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "relight/json_reader.h"

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
        names += (names.empty() ? "" : ", ") + light.name;
    return names;
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

}  // namespace

EditFile loadEdit(const fs::path& file, const SceneFile& sf) {
    EditFile edit;
    edit.file = file;
    const json root = jsonio::parseJsonFile(file);
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
            edit.lights[l.key()] = readLightEdit(r, l.value(), path);
        }
    }

    // Virtual lights, virtual objects and removals: only their type is checked here; the
    // version that renders them reads their content.
    auto present = [&](const char* key) {
        auto it = root.find(key);
        return it != root.end() && !r.array(*it, key, 0).empty();
    };
    edit.hasAddLights = present("add_lights");
    edit.hasAddObjects = present("add_objects");
    edit.hasRemoveObjects = present("remove_objects");
    return edit;
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
            out[i] = it->second.scale ? nominal[i] * *it->second.scale : *it->second.radiance;
            continue;
        }
        // The photo's state, applied to the given nominal radiance (maybe an estimated one).
        out[i] = sf.lightOnInPhoto(i) ? nominal[i] : Rgb{};
    }
    return out;
}

void requireLightsOnly(const EditFile& edit) {
    std::vector<std::string> parts;
    if (edit.hasAddLights) parts.push_back("\"add_lights\"");
    if (edit.hasAddObjects) parts.push_back("\"add_objects\"");
    if (edit.hasRemoveObjects) parts.push_back("\"remove_objects\"");
    if (parts.empty()) return;
    std::string list;
    for (size_t i = 0; i < parts.size(); ++i)
        list += (i == 0 ? "" : (i + 1 == parts.size() ? " and " : ", ")) + parts[i];
    throw InputError(edit.file.string() + ": " + list + (parts.size() == 1 ? " is" : " are") +
                     " not supported yet (this version changes real lights only)");
}

}  // namespace relight
