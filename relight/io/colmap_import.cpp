#include "relight/io/colmap_import.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "relight/errors.h"
#include "relight/io/atomic_write.h"
#include "relight/io/colmap_camera.h"
#include "relight/io/colmap_model.h"
#include "relight/io/input_file.h"
#include "relight/io/json_reader.h"
#include "relight/io/light_reader.h"
#include "relight/io/scene_file.h"
#include "relight/io/undistort.h"

namespace relight {

namespace fs = std::filesystem;
using jsonio::child;
using jsonio::element;
using jsonio::JsonReader;
using nlohmann::json;

namespace {

// ---- the inputs -------------------------------------------------------------------------

/// The lights of `file` (the format's "lights" array), each checked as scene.json's are,
/// with messages naming `file` and the key.
json readLightsFile(const fs::path& file) {
    const JsonReader r(file.string());
    const json root = jsonio::parseJsonFile(file);
    // The array itself, or the "lights" of an object holding one (another scene.json).
    const std::string path = root.is_object() ? "lights" : "";
    const json& lights = root.is_object() ? r.require(root, "", "lights") : root;
    if (!lights.is_array())
        r.fail(path, "expected the format's \"lights\" array (or an object holding one)");
    std::set<std::string> names;
    for (size_t i = 0; i < lights.size(); ++i) {
        const LightJson l = readLightJson(r, lights[i], element(path, i), true, true);
        if (!names.insert(l.name).second)
            r.fail(child(element(path, i), "name"), "duplicate light name \"" + l.name + "\"");
    }
    return lights;
}

/// The objects settings of `file`, checked against the mesh's objects.
json readObjectsFile(const fs::path& file, const radiosity::Scene& mesh) {
    const JsonReader r(file.string());
    const json root = jsonio::parseJsonFile(file);
    // The object itself, or the "objects" of a scene.json (which says its "format").
    const bool scene = root.is_object() && root.contains("format");
    const std::string path = scene ? "objects" : "";
    const json& objects = scene ? r.require(root, "", "objects") : root;
    if (!objects.is_object()) r.fail(path, "expected the format's \"objects\" object");
    for (auto o = objects.begin(); o != objects.end(); ++o) {
        const std::string oPath = child(path, o.key());
        r.checkKeys(o.value(), oPath, {"reflectance", "removable"});
        if (auto refl = o->find("reflectance"); refl != o->end()) {
            const radiosity::Rgb rho = r.rgb(*refl, child(oPath, "reflectance"));
            for (int k = 0; k < 3; ++k)
                if (!(rho[k] >= 0 && rho[k] <= 1))
                    r.fail(element(child(oPath, "reflectance"), static_cast<size_t>(k)),
                           "must be in [0, 1]");
        }
        if (auto rem = o->find("removable"); rem != o->end())
            r.boolean(*rem, child(oPath, "removable"));
        if (mesh.findObject(o.key()) < 0) r.fail(oPath, "no object of this name in the mesh");
    }
    return objects;
}

/// The photo's size from its header, which must be its camera's.
void checkPhotoSize(const fs::path& photo, const colmap::Camera& camera) {
    requireRegularFile(photo, "photo", "a photo");
    auto in = OIIO::ImageInput::open(photo.string());
    if (!in) throw InputError(photo.string() + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width != camera.width || spec.height != camera.height)
        throw InputError(photo.string() + ": photo is " + std::to_string(spec.width) + "x" +
                         std::to_string(spec.height) + " but its camera (" + camera.where +
                         ") is " + std::to_string(camera.width) + "x" +
                         std::to_string(camera.height));
}

/// "linear" or "srgb": the option, else the file type's (as the scene loader infers it),
/// else 8- and 16-bit integers are sRGB and floats linear.
std::string photoEncoding(const fs::path& photo, const std::string& option) {
    if (!option.empty()) return option;
    std::string ext = photo.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".exr" || ext == ".hdr" || ext == ".pfm") return "linear";
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") return "srgb";
    auto in = OIIO::ImageInput::open(photo.string());
    return in && in->spec().format.is_floating_point() ? "linear" : "srgb";
}

// ---- the scene --------------------------------------------------------------------------

using ordered_json = nlohmann::ordered_json;

ordered_json cameraJson(const Camera& c) {
    ordered_json w = ordered_json::array();
    for (int row = 0; row < 3; ++row)
        w.push_back({c.cameraFromWorldR[0][row], c.cameraFromWorldR[1][row],
                     c.cameraFromWorldR[2][row], c.cameraFromWorldT[row]});
    return {{"width", c.width},
            {"height", c.height},
            {"K", {{c.fx, 0.0, c.cx}, {0.0, c.fy, c.cy}, {0.0, 0.0, 1.0}}},
            {"world_to_camera", w}};
}

/// The names of the lights on in the photo: the option's, each a light of `lights`, or all.
json lightsOnJson(const json& lights, const std::optional<std::vector<std::string>>& option) {
    json on = json::array();
    std::set<std::string> names;
    for (const json& l : lights) names.insert(l["name"].get<std::string>());
    if (!option) {
        for (const json& l : lights) on.push_back(l["name"]);
        return on;
    }
    for (const std::string& name : *option) {
        if (!names.count(name))
            throw InputError("--lights-on: no light named \"" + name + "\" in the lights file");
        on.push_back(name);
    }
    return on;
}

// ---- the output -------------------------------------------------------------------------

void checkOutputFolder(const fs::path& dir, bool force) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) return;
    if (!fs::is_directory(dir, ec)) throw OutputError(dir.string() + ": is not a folder");
    if (!force && !fs::is_empty(dir, ec))
        throw OutputError(dir.string() + ": the folder is not empty (--force writes into it)");
}

/// `source` copied (atomically) or linked to `target`; nothing when they are one file.
void placeFile(const fs::path& source, const fs::path& target, bool link) {
    std::error_code ec;
    if (fs::exists(target, ec) && fs::equivalent(source, target, ec)) return;
    if (link) {
        fs::remove(target, ec);
        fs::create_symlink(fs::absolute(source), target, ec);
        if (ec) throw OutputError(target.string() + ": cannot link: " + ec.message());
        return;
    }
    writeAtomic(target, "cannot copy", [&](const fs::path& tmp) -> std::string {
        std::error_code e;
        fs::copy_file(source, tmp, fs::copy_options::overwrite_existing, e);
        return e ? e.message() : std::string();
    });
}

/// The mesh and the files it drew on (a .gltf's buffers), at the same places relative to
/// it. Returns the mesh's name in the scene folder.
std::string placeMesh(const std::vector<fs::path>& files, const fs::path& outDir, bool link) {
    const fs::path base = files.front().parent_path();
    for (const fs::path& f : files) {
        const fs::path rel = f.lexically_relative(base);
        if (rel.empty() || *rel.begin() == "..")
            throw InputError(f.string() +
                             ": the mesh draws on a file outside its folder; copy "
                             "them into one folder first");
        std::error_code ec;
        fs::create_directories((outDir / rel).parent_path(), ec);
        placeFile(f, outDir / rel, link);
    }
    return files.front().filename().string();
}

}  // namespace

namespace {

/// What the import reads and checks before it writes anything.
struct Checked {
    colmap::Camera colmapCamera;
    colmap::Lens lens, pinhole;
    Camera camera;
    fs::path photo;
    std::string encoding;
    json lights = json::array(), objects;
    SceneFile scene;  ///< the scene loaded from the inputs where they are
};

/// The scene.json of the package, its keys in the order of the format's example; `geometry`
/// and `photo` are file names in it.
ordered_json sceneJson(const ColmapImportOptions& o, const Checked& c, const std::string& geometry,
                       const std::string& photo, const std::string& encoding) {
    ordered_json j = {{"format", "relight-scene/1"}, {"geometry", {geometry}}};
    if (!c.objects.is_null()) j["objects"] = ordered_json::parse(c.objects.dump());
    j["camera"] = cameraJson(c.camera);
    j["photos"] = {{{"file", photo},
                    {"encoding", encoding},
                    {"lights_on", ordered_json::parse(lightsOnJson(c.lights, o.lightsOn).dump())}}};
    j["lights"] = ordered_json::parse(c.lights.dump());
    if (o.averageReflectance) j["average_reflectance"] = *o.averageReflectance;
    return j;
}

Checked readInputs(const ColmapImportOptions& o, ColmapImportResult& result) {
    Checked c;
    const colmap::Model model = colmap::readModel(o.sparseDir);
    const colmap::Image& image = model.image(o.image);
    c.colmapCamera = model.cameraOf(image);
    c.lens = colmap::lensOf(c.colmapCamera);
    c.photo = o.imagesDir / o.image;
    checkPhotoSize(c.photo, c.colmapCamera);
    c.encoding = photoEncoding(c.photo, o.encoding);
    c.pinhole = c.lens.distorted() ? undistortedLens(c.lens, c.colmapCamera.where) : c.lens;
    c.camera = colmap::sceneCamera(image, c.pinhole);
    if (!o.lights.empty()) c.lights = readLightsFile(o.lights);
    // The scene as it will be, its files where they are now (absolute names): the mesh
    // must load and the lights must fit with it. Messages name the scene.json to be.
    requireRegularFile(o.mesh, "mesh", "a mesh");
    const json probe =
        sceneJson(o, c, fs::absolute(o.mesh).string(), fs::absolute(c.photo).string(), c.encoding);
    std::istringstream text(probe.dump());
    c.scene = parseScene(text, o.output);
    if (!o.objects.empty()) c.objects = readObjectsFile(o.objects, c.scene.scene);
    result.modelFile = model.imagesFile;
    result.cameraModel = c.colmapCamera.model;
    return c;
}

}  // namespace

ColmapImportResult importColmap(const ColmapImportOptions& o) {
    ColmapImportResult result;
    checkOutputFolder(o.output, o.force);
    const Checked c = readInputs(o, result);

    std::error_code ec;
    fs::create_directories(o.output, ec);
    if (ec) throw OutputError(o.output.string() + ": cannot create the folder: " + ec.message());
    const std::string mesh = placeMesh(c.scene.geometryFiles, o.output, o.link);
    std::string photo = fs::path(o.image).filename().string(), encoding = c.encoding;
    if (c.lens.distorted()) {
        photo = fs::path(photo).stem().string() + ".undistorted.exr";
        encoding = "linear";
        undistortPhoto(c.photo, c.encoding == "srgb", c.lens, c.pinhole, o.output / photo);
    } else {
        placeFile(c.photo, o.output / photo, o.link);
    }
    result.sceneJson = o.output / "scene.json";
    writeTextAtomic(result.sceneJson, sceneJson(o, c, mesh, photo, encoding).dump(2) + "\n");

    result.camera = c.camera;
    result.focalScale = c.pinhole.fx / c.lens.fx;
    result.undistorted = c.lens.distorted();
    result.photo = o.output / photo;
    result.lights = c.lights.size();
    result.warnings = c.scene.warnings;
    return result;
}

}  // namespace relight
