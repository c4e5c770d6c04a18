// Scene package loading ("relight-scene/1", docs/scene-format.md).
//
// Reading is strict: the spec is an interchange format, so a key we do not know is more
// likely a typo (whose setting would silently be lost) than an extension; it is an error
// naming the key path. Every message names scene.json or the OBJ file and the key path or
// line, so the user can go straight to the problem. The JSON helpers (parsing with
// duplicate-key detection, typed access) are shared with the edit loader: json_reader.h.
#include "relight/io/scene_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "radiosity/buried.h"
#include "radiosity/stopwatch.h"
#include "radiosity/visibility.h"
#include "relight/io/face_repair.h"
#include "relight/io/json_reader.h"
#include "relight/io/light_reader.h"
#include "relight/io/mesh_reader.h"

namespace relight {

namespace fs = std::filesystem;
using jsonio::child;
using jsonio::element;
using jsonio::JsonReader;
using jsonio::parseJsonFile;
using nlohmann::json;
using radiosity::Vec3;

namespace {

// ---- camera ----------------------------------------------------------------------------

Camera readCamera(const JsonReader& r, const json& cam) {
    const std::string path = "camera";
    r.checkKeys(cam, path, {"width", "height", "K", "world_to_camera"});
    Camera c;
    c.width = r.positiveInt(r.require(cam, path, "width"), child(path, "width"));
    c.height = r.positiveInt(r.require(cam, path, "height"), child(path, "height"));

    const std::string kPath = child(path, "K");
    const auto K = r.matrix(r.require(cam, path, "K"), kPath, 3, 3);
    // The spec's pinhole has no skew: K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]].
    auto expect = [&](size_t row, size_t col, double value) {
        if (std::abs(K[row][col] - value) > 1e-9)
            r.fail(element(element(kPath, row), col),
                   "must be " + std::to_string(static_cast<int>(value)) +
                       " (a pinhole K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]])");
    };
    expect(0, 1, 0);
    expect(1, 0, 0);
    expect(2, 0, 0);
    expect(2, 1, 0);
    expect(2, 2, 1);
    c.fx = K[0][0];
    c.fy = K[1][1];
    c.cx = K[0][2];
    c.cy = K[1][2];
    if (!(c.fx > 0)) r.fail(kPath + "[0][0]", "fx must be positive");
    if (!(c.fy > 0)) r.fail(kPath + "[1][1]", "fy must be positive");

    const std::string wPath = child(path, "world_to_camera");
    const auto W = r.matrix(r.require(cam, path, "world_to_camera"), wPath, 3, 4);
    // R must be a rotation: R R^T = I within 1e-4 (measured cameras carry rounding), and
    // det R = +1 (a reflection would flip the image and every face's front side).
    double worst = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double dot = 0;
            for (int k = 0; k < 3; ++k) dot += W[i][k] * W[j][k];
            worst = std::max(worst, std::abs(dot - (i == j ? 1.0 : 0.0)));
        }
    if (worst > 1e-4)
        r.fail(wPath, "the left 3x3 block R is not a rotation (R R^T differs from I by " +
                          std::to_string(worst) + ")");
    const double det = W[0][0] * (W[1][1] * W[2][2] - W[1][2] * W[2][1]) -
                       W[0][1] * (W[1][0] * W[2][2] - W[1][2] * W[2][0]) +
                       W[0][2] * (W[1][0] * W[2][1] - W[1][1] * W[2][0]);
    if (!(det > 0)) r.fail(wPath, "the left 3x3 block R has determinant -1 (a reflection)");
    // glm is column-major: m[col][row]. Xc = R X + t needs m[c][r] = R[r][c].
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            c.cameraFromWorldR[col][row] = W[static_cast<size_t>(row)][static_cast<size_t>(col)];
    c.cameraFromWorldT = Vec3(W[0][3], W[1][3], W[2][3]);
    return c;
}

// ---- the readers of loadScene, in the order it calls them -------------------------------

/// The format first: a file of another kind (an edit, a newer version) is then named as
/// such rather than reported as a list of unknown keys.
void checkFormatAndKeys(const JsonReader& r, const json& root) {
    if (!root.is_object()) r.fail("", "the top level must be a JSON object");
    const json& format = r.require(root, "", "format");
    if (!format.is_string() || format.get<std::string>() != "relight-scene/1")
        r.fail("format", "expected \"relight-scene/1\", got " + format.dump());
    r.checkKeys(
        root, "",
        {"format", "geometry", "objects", "camera", "photos", "lights", "average_reflectance"});
}

std::optional<double> readAverageReflectance(const JsonReader& r, const json& root) {
    const auto it = root.find("average_reflectance");
    if (it == root.end()) return std::nullopt;
    const double a = r.number(*it, "average_reflectance");
    // Below 1: a closed room of reflectance 1 never loses energy (no converged solution).
    if (!(a >= 0 && a < 1)) r.fail("average_reflectance", "must be in [0, 1)");
    return a;
}

/// One entry of "objects".
ObjectSettings readObjectSettings(const JsonReader& r, const json& o, const std::string& path,
                                  std::vector<std::string>& warnings) {
    r.checkKeys(o, path, {"reflectance", "removable"});
    ObjectSettings s;
    if (auto refl = o.find("reflectance"); refl != o.end()) {
        const std::string rPath = child(path, "reflectance");
        Rgb rho = r.rgb(*refl, rPath);
        bool clamped = false;
        for (int k = 0; k < 3; ++k) {
            if (!(rho[k] >= 0 && rho[k] <= 1))
                r.fail(element(rPath, static_cast<size_t>(k)), "must be in [0, 1]");
            // The spec allows 1, but a surface that reflects everything makes a closed
            // scene's radiosity iteration diverge; 0.99 keeps it convergent.
            if (rho[k] >= 1) {
                rho[k] = 0.99;
                clamped = true;
            }
        }
        if (clamped)
            warnings.push_back(r.message(
                rPath,
                "reflectance 1 clamped to 0.99 (the radiosity solution would not converge)"));
        s.reflectance = rho;
    }
    if (auto rem = o.find("removable"); rem != o.end())
        s.removable = r.boolean(*rem, child(path, "removable"));
    return s;
}

/// "objects", read before the geometry because they set its reflectance; their names are
/// checked against the geometry afterwards (readGeometry).
void readObjects(const JsonReader& r, const json& root, SceneFile& sf) {
    const auto it = root.find("objects");
    if (it == root.end()) return;
    if (!it->is_object()) r.fail("objects", "expected an object of object names");
    for (auto o = it->begin(); o != it->end(); ++o)
        sf.objectSettings[o.key()] =
            readObjectSettings(r, o.value(), child("objects", o.key()), sf.warnings);
}

/// "geometry": OBJ, PLY or glTF files relative to the scene folder (mesh_reader.h). Objects
/// of the same name in several files are one object. Reflectance: the object's from
/// "objects", else average_reflectance (grey), else 0.5.
void readGeometry(const JsonReader& r, const json& root, SceneFile& sf) {
    auto reflectanceOf = [&](const std::string& object) {
        if (auto it = sf.objectSettings.find(object);
            it != sf.objectSettings.end() && it->second.reflectance)
            return *it->second.reflectance;
        return Rgb::gray(sf.averageReflectance.value_or(0.5));
    };
    const json& geometry = r.array(r.require(root, "", "geometry"), "geometry", 0);
    for (size_t g = 0; g < geometry.size(); ++g) {
        const std::string gPath = element("geometry", g);
        const std::string name = r.string(geometry[g], gPath);
        if (name.empty()) r.fail(gPath, "empty file name");
        const fs::path objPath = sf.dir / name;
        std::error_code ec;
        if (!fs::exists(objPath, ec))
            r.fail(gPath, "geometry file \"" + objPath.string() + "\" not found");
        MeshFile mesh = readMesh(objPath);
        // The file and any it drew on (a .gltf's buffers): all are the scene's content.
        for (const fs::path& f : mesh.files)
            if (std::find(sf.geometryFiles.begin(), sf.geometryFiles.end(), f) ==
                sf.geometryFiles.end())
                sf.geometryFiles.push_back(f);
        const ObjFile& obj = mesh.geometry;
        sf.warnings.insert(sf.warnings.end(), obj.warnings.begin(), obj.warnings.end());
        std::vector<int> globalObject;
        for (const std::string& o : obj.objects) {
            int index = sf.scene.findObject(o);
            if (index < 0) {
                index = static_cast<int>(sf.scene.objects.size());
                sf.scene.objects.push_back(o);
            }
            globalObject.push_back(index);
        }
        addObjFaces(
            obj, globalObject,
            [&](int object) {
                return reflectanceOf(sf.scene.objects[static_cast<size_t>(object)]);
            },
            sf.scene, sf.warnings);
    }
    for (const auto& [name, settings] : sf.objectSettings)
        if (sf.scene.findObject(name) < 0)
            r.fail(child("objects", name), "no object of this name in the geometry");
}

/// "lights": emitting faces appended after the geometry, reflectance 0 (spec: "A light's
/// emitting face reflects nothing"), each light its own object "light:NAME".
void readLights(const JsonReader& r, const json& root, SceneFile& sf) {
    const json& lights = r.array(r.require(root, "", "lights"), "lights", 0);
    for (size_t i = 0; i < lights.size(); ++i) {
        const std::string path = element("lights", i);
        const LightJson lightJson =
            readLightJson(r, lights[i], path, /*typeRequired=*/true, /*estimateAllowed=*/true);
        radiosity::Light light;
        light.name = lightJson.name;
        if (sf.scene.findLight(light.name) >= 0)
            r.fail(child(path, "name"), "duplicate light name \"" + light.name + "\"");
        if (lightJson.emitter) {
            // A sun, point lamp or sky: one light per component, no faces
            // (radiosity::Light::emitter); their strengths are the nominal radiances.
            const std::vector<Rgb> s = lightJson.emitter->strengths();
            for (size_t c = 0; c < s.size(); ++c) {
                radiosity::Light part = light;
                part.radiance = s[c];
                part.emitter = lightJson.emitter;
                part.component = static_cast<int>(c);
                sf.scene.lights.push_back(std::move(part));
                sf.nominalRadiance.push_back(s[c]);
                sf.estimateRadiance.push_back(lightJson.estimate);
            }
            continue;
        }
        const std::string objectName = "light:" + light.name;
        if (sf.scene.findObject(objectName) >= 0)
            r.fail(child(path, "name"),
                   "the geometry already has an object \"" + objectName + "\"");
        const int object = static_cast<int>(sf.scene.objects.size());
        sf.scene.objects.push_back(objectName);
        const int lightIndex = static_cast<int>(sf.scene.lights.size());
        light.polygons = addLightFaces(lightJson.corners, object, lightIndex, sf.scene);
        sf.scene.lights.push_back(std::move(light));
        sf.nominalRadiance.push_back(lightJson.radiance);
        sf.estimateRadiance.push_back(lightJson.estimate);
    }
}

/// One entry of "photos": the file is only named here; the photo pipeline opens it.
PhotoSpec readPhoto(const JsonReader& r, const json& pj, const std::string& path,
                    const fs::path& dir, const radiosity::Scene& scene) {
    r.checkKeys(pj, path, {"file", "encoding", "lights_on"});
    PhotoSpec photo;
    const std::string name = r.string(r.require(pj, path, "file"), child(path, "file"));
    if (name.empty()) r.fail(child(path, "file"), "empty file name");
    photo.file = dir / name;
    if (auto e = pj.find("encoding"); e != pj.end()) {
        const std::string enc = r.string(*e, child(path, "encoding"));
        if (enc == "linear")
            photo.encoding = PhotoSpec::Encoding::linear;
        else if (enc == "srgb")
            photo.encoding = PhotoSpec::Encoding::srgb;
        else
            r.fail(child(path, "encoding"), "expected \"linear\" or \"srgb\", got \"" + enc + "\"");
    } else {
        // Not in the spec's example only by omission: infer it where the file type leaves
        // no doubt.
        bool known = false;
        photo.encoding = encodingFromExtension(photo.file, known);
        if (!known)
            r.fail(child(path, "encoding"),
                   "missing required key (cannot tell from the file's extension)");
    }
    const std::string onPath = child(path, "lights_on");
    const json& on = r.array(r.require(pj, path, "lights_on"), onPath, 0);
    for (size_t k = 0; k < on.size(); ++k) {
        const std::string lightName = r.string(on[k], element(onPath, k));
        if (scene.findLight(lightName) < 0)
            r.fail(element(onPath, k), "no light named \"" + lightName + "\"");
        if (std::find(photo.lightsOn.begin(), photo.lightsOn.end(), lightName) !=
            photo.lightsOn.end())
            r.fail(element(onPath, k), "light \"" + lightName + "\" listed twice");
        photo.lightsOn.push_back(lightName);
    }
    return photo;
}

/// "photos", after the lights, whose names lights_on refers to.
void readPhotos(const JsonReader& r, const json& root, SceneFile& sf) {
    const auto it = root.find("photos");
    if (it == root.end()) return;
    const json& photos = r.array(*it, "photos", 0);
    for (size_t i = 0; i < photos.size(); ++i)
        sf.photos.push_back(readPhoto(r, photos[i], element("photos", i), sf.dir, sf.scene));
}

}  // namespace

void SceneFile::setPhotoLightState() {
    // Spec, "Edit": a light that is not in the first photo's lights_on is off in that photo.
    // Without a photo there is nothing to match: every light is on.
    for (size_t i = 0; i < scene.lights.size() && i < nominalRadiance.size(); ++i)
        scene.lights[i].radiance = lightOnInPhoto(i) ? nominalRadiance[i] : Rgb{};
}

bool SceneFile::lightOnInPhoto(size_t i) const {
    if (photos.empty()) return true;
    const auto& names = photos.front().lightsOn;
    return std::find(names.begin(), names.end(), scene.lights.at(i).name) != names.end();
}

namespace {

/// The geometry's faces inside closed solids (radiosity/buried.h), polygons [0, geometry),
/// taken out of the scene, with the lights' faces renumbered: after the lights, whose faces
/// count as seeing out.
void leaveOutBuried(SceneFile& sf, size_t geometry) {
    const auto t0 = radiosity::Clock::now();
    radiosity::BuriedContext context;
    context.eye = sf.camera.position();
    for (const std::string& name : sf.scene.objects) {
        const auto it = sf.objectSettings.find(name);
        context.mayVanish.push_back(it != sf.objectSettings.end() && it->second.removable);
    }
    std::vector<int> buried;
    {
        const radiosity::Visibility vis(sf.scene);
        buried = radiosity::findBuriedPolygons(sf.scene, geometry, vis, context);
    }
    sf.buriedPolygons = static_cast<int>(buried.size());
    sf.buriedArea = radiosity::removeBuriedPolygons(sf.scene, buried);
    sf.buriedSeconds = radiosity::secondsSince(t0);
}

/// loadScene() after parsing: `root` is <dir>/scene.json's document.
SceneFile readScene(const json& root, const fs::path& dir) {
    SceneFile sf;
    sf.dir = dir;
    const JsonReader r((dir / "scene.json").string());
    checkFormatAndKeys(r, root);
    sf.camera = readCamera(r, r.require(root, "", "camera"));
    sf.averageReflectance = readAverageReflectance(r, root);
    readObjects(r, root, sf);
    readGeometry(r, root, sf);
    // Before the lights: their faces are neither cut nor cut along, and stay after the
    // geometry's polygons and their pieces.
    const auto t0 = radiosity::Clock::now();
    sf.contactSplit = radiosity::splitAtContacts(sf.scene.polygons, sf.scene.polygons.size());
    sf.contactSplitSeconds = radiosity::secondsSince(t0);
    const size_t geometry = sf.scene.polygons.size();
    readLights(r, root, sf);
    leaveOutBuried(sf, geometry);
    readPhotos(r, root, sf);
    sf.setPhotoLightState();
    return sf;
}

}  // namespace

SceneFile copyWithoutPolygons(SceneFile& sf) {
    // Set aside, so that the copy never holds them; put back once it is made, or when the
    // copy throws (out of memory): the caller's scene keeps its polygons either way.
    struct SetAside {
        std::vector<radiosity::Polygon>& slot;
        std::vector<radiosity::Polygon> held = std::move(slot);
        ~SetAside() { slot = std::move(held); }
    } aside{sf.scene.polygons};
    sf.scene.polygons.clear();  // a moved-from vector is valid but unspecified
    return SceneFile(sf);
}

std::string contactSplitLine(const SceneFile& sf) {
    const radiosity::ContactSplitReport& c = sf.contactSplit;
    if (c.polygonsCut == 0 && sf.buriedPolygons == 0) return {};
    std::string out = "geometry: ";
    char part[256];
    if (c.polygonsCut > 0) {
        std::snprintf(part, sizeof part,
                      "%d polygons cut along %d lines where other surfaces meet them (%d pieces "
                      "added%s), %.2f s",
                      c.polygonsCut, c.lines, c.piecesAdded,
                      c.piecesLimited > 0 ? ", some at the most pieces a polygon may have" : "",
                      sf.contactSplitSeconds);
        out += part;
    }
    if (sf.buriedPolygons > 0) {
        std::snprintf(part, sizeof part, "%s%d faces inside solids left out (%.3g m^2), %.2f s",
                      c.polygonsCut > 0 ? "; " : "", sf.buriedPolygons, sf.buriedArea,
                      sf.buriedSeconds);
        out += part;
    }
    return out;
}

PhotoSpec::Encoding encodingFromExtension(const fs::path& file, bool& known) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    known = true;
    if (ext == ".exr" || ext == ".hdr" || ext == ".pfm") return PhotoSpec::Encoding::linear;
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") return PhotoSpec::Encoding::srgb;
    known = false;
    return PhotoSpec::Encoding::linear;
}

SceneFile loadScene(const fs::path& dir) {
    return readScene(parseJsonFile(dir / "scene.json"), dir);
}

SceneFile parseScene(std::istream& sceneJson, const fs::path& dir) {
    return readScene(jsonio::parseJson(sceneJson, (dir / "scene.json").string()), dir);
}

}  // namespace relight
