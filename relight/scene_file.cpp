// Scene package loading ("relight-scene/1", ../shared/spec/scene-format.md).
//
// Reading is strict: the spec is an interchange format, so a key we do not know is more
// likely a typo (whose setting would silently be lost) than an extension; it is an error
// naming the key path. Every message names scene.json or the OBJ file and the key path or
// line, so the user can go straight to the problem. The JSON helpers (parsing with
// duplicate-key detection, typed access) are shared with the edit loader: json_reader.h.
#include "relight/scene_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include <glm/geometric.hpp>

#include "relight/json_reader.h"
#include "relight/obj_reader.h"

namespace relight {

namespace fs = std::filesystem;
using jsonio::child;
using jsonio::element;
using jsonio::JsonReader;
using jsonio::parseJsonFile;
using nlohmann::json;
using radiosity::checkPolygon;
using radiosity::makePolygon;
using radiosity::PolygonCheck;
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

// ---- polygons --------------------------------------------------------------------------

Vec3 newellNormal(const std::vector<Vec3>& c) {
    Vec3 n{0, 0, 0};
    for (size_t i = 0; i < c.size(); ++i) n += glm::cross(c[i], c[(i + 1) % c.size()]);
    return n;  // length = twice the area
}

double longestEdge(const std::vector<Vec3>& c) {
    double longest = 0;
    for (size_t i = 0; i < c.size(); ++i)
        longest = std::max(longest, glm::length(c[(i + 1) % c.size()] - c[i]));
    return longest;
}

using Triangle = std::array<int, 3>;

/// Fan from corner 0 of a convex planar polygon.
std::vector<Triangle> fan(size_t n) {
    std::vector<Triangle> t;
    for (size_t i = 1; i + 1 < n; ++i)
        t.push_back({0, static_cast<int>(i), static_cast<int>(i + 1)});
    return t;
}

/// Ear clipping of a planar, simple, possibly non-convex polygon. For a quad it cuts along
/// the diagonal through the reflex corner, the one that keeps both halves convex. Returns
/// nothing when the polygon is self-intersecting (the triangles would not cover it once).
std::optional<std::vector<Triangle>> earClip(const std::vector<Vec3>& c) {
    const Vec3 newell = newellNormal(c);
    const double area = 0.5 * glm::length(newell);
    if (!(area > 0)) return std::nullopt;
    const Vec3 n = newell / (2 * area);
    const double longest = longestEdge(c);
    const double eps = 1e-12 * longest * longest;
    auto turn = [&](int a, int b, int d) {
        return glm::dot(glm::cross(c[b] - c[a], c[d] - c[b]), n);
    };

    std::vector<int> ring(c.size());
    for (size_t i = 0; i < c.size(); ++i) ring[i] = static_cast<int>(i);
    std::vector<Triangle> out;
    while (ring.size() > 3) {
        const size_t m = ring.size();
        bool clipped = false;
        for (size_t k = 0; k < m && !clipped; ++k) {
            const int a = ring[(k + m - 1) % m], b = ring[k], d = ring[(k + 1) % m];
            if (!(turn(a, b, d) > eps)) continue;  // reflex or straight corner: not an ear
            // No other corner inside the ear or on its border: a reflex corner touching
            // the cut a-d would leave the cut outside the polygon.
            bool empty = true;
            for (int p : ring) {
                if (p == a || p == b || p == d || c[p] == c[a] || c[p] == c[b] || c[p] == c[d])
                    continue;
                if (turn(a, b, p) >= -eps && turn(b, d, p) >= -eps && turn(d, a, p) >= -eps) {
                    empty = false;
                    break;
                }
            }
            if (!empty) continue;
            out.push_back({a, b, d});
            ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
            clipped = true;
        }
        if (!clipped) return std::nullopt;
    }
    out.push_back({ring[0], ring[1], ring[2]});
    // A simple polygon's ears add up to its area, all facing the same way.
    double sum = 0;
    for (const Triangle& t : out) {
        const Vec3 tn = glm::cross(c[t[1]] - c[t[0]], c[t[2]] - c[t[0]]);
        if (glm::dot(tn, n) < -eps) return std::nullopt;
        sum += 0.5 * glm::length(tn);
    }
    if (std::abs(sum - area) > 1e-6 * area) return std::nullopt;
    return out;
}

/// Removes consecutive repeated corners (OBJ exporters write them for collapsed edges),
/// so that no polygon has a zero-length edge. Returns how many were removed.
size_t removeRepeatedCorners(std::vector<Vec3>& c) {
    const double tol = 1e-9 * longestEdge(c);
    size_t removed = 0;
    for (size_t i = 0; i < c.size() && c.size() > 1;) {
        if (glm::length(c[(i + 1) % c.size()] - c[i]) <= tol) {
            c.erase(c.begin() + static_cast<std::ptrdiff_t>(i));
            ++removed;
        } else {
            ++i;
        }
    }
    return removed;
}

struct PolygonSink {
    radiosity::Scene& scene;
    int object;
    Rgb rho;
    int light = -1;

    /// Adds the triangles that are not degenerate (a fan over collinear corners has some);
    /// returns how many were added.
    size_t addTriangles(const std::vector<Vec3>& c, const std::vector<Triangle>& tris) {
        size_t added = 0;
        for (const Triangle& t : tris) {
            std::vector<Vec3> tri{c[t[0]], c[t[1]], c[t[2]]};
            if (checkPolygon(tri).status != PolygonCheck::Status::ok) continue;
            add(tri);
            ++added;
        }
        return added;
    }
    void add(const std::vector<Vec3>& corners) {
        radiosity::Polygon p = makePolygon(corners, object, rho);
        p.light = light;
        scene.polygons.push_back(p);
    }
};

/// Checks one OBJ face and adds it, repaired as documented in scene_file.h.
void addFace(const ObjFile& obj, const ObjFace& face, PolygonSink& sink,
             std::vector<std::string>& warnings) {
    using S = PolygonCheck::Status;
    const std::string at = obj.where(face.line);
    std::vector<Vec3> c;
    for (int i : face.vertices) c.push_back(obj.positions[static_cast<size_t>(i)]);
    const size_t given = c.size();
    if (size_t removed = removeRepeatedCorners(c); removed > 0 && c.size() >= 3)
        warnings.push_back(at + "removed " + std::to_string(removed) +
                           " repeated vertex(es) from a face with " + std::to_string(given) +
                           " vertices");
    const PolygonCheck check = checkPolygon(c);
    const size_t n = c.size();
    switch (check.status) {
        case S::ok:
            if (n <= 4) {
                sink.add(c);
            } else {
                const size_t k = sink.addTriangles(c, fan(n));
                warnings.push_back(at + "convex face with " + std::to_string(n) +
                                   " vertices split into a fan of " + std::to_string(k) +
                                   " triangles");
            }
            return;
        case S::nonFinite:  // the reader rejects these already; kept for safety
            throw InputError(at + check.message);
        case S::tooFew:  // only after removing repeated corners: nothing left to draw
        case S::degenerate:
            warnings.push_back(at + "degenerate face (zero area or repeated vertices) dropped");
            return;
        case S::nonPlanar: {
            if (n != 4)
                throw InputError(at + check.message + "; only non-planar quads are repaired: " +
                                 "split this " + std::to_string(n) + "-vertex face into triangles");
            // The shorter diagonal gives the smaller fold between the two halves.
            const bool d02 = glm::length(c[2] - c[0]) <= glm::length(c[3] - c[1]);
            const std::vector<Triangle> tris = d02 ? std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}
                                                   : std::vector<Triangle>{{1, 2, 3}, {1, 3, 0}};
            const size_t k = sink.addTriangles(c, tris);
            warnings.push_back(at + check.message + "; quad split into " + std::to_string(k) +
                               " triangles along its shorter diagonal");
            return;
        }
        case S::nonConvex: {
            const auto tris = earClip(c);
            if (!tris)
                throw InputError(at + "face is self-intersecting (its edges cross); fix the mesh");
            const size_t k = sink.addTriangles(c, *tris);
            warnings.push_back(at + "non-convex face with " + std::to_string(n) +
                               " vertices split into " + std::to_string(k) +
                               " triangles that are each convex");
            return;
        }
    }
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

SceneFile loadScene(const fs::path& dir) {
    SceneFile sf;
    sf.dir = dir;
    const fs::path jsonPath = dir / "scene.json";
    const std::string file = jsonPath.string();
    const json root = parseJsonFile(jsonPath);
    const JsonReader r(file);
    if (!root.is_object()) r.fail("", "the top level must be a JSON object");

    // The format first: a file of another kind (an edit, a newer version) is then named as
    // such rather than reported as a list of unknown keys.
    const json& format = r.require(root, "", "format");
    if (!format.is_string() || format.get<std::string>() != "relight-scene/1")
        r.fail("format", "expected \"relight-scene/1\", got " + format.dump());
    r.checkKeys(
        root, "",
        {"format", "geometry", "objects", "camera", "photos", "lights", "average_reflectance"});

    sf.camera = readCamera(r, r.require(root, "", "camera"));

    if (auto it = root.find("average_reflectance"); it != root.end()) {
        const double a = r.number(*it, "average_reflectance");
        // Below 1: a closed room of reflectance 1 never loses energy (no converged solution).
        if (!(a >= 0 && a < 1)) r.fail("average_reflectance", "must be in [0, 1)");
        sf.averageReflectance = a;
    }

    // Object settings, read before the geometry because they set its reflectance; their
    // names are checked against the geometry afterwards.
    if (auto it = root.find("objects"); it != root.end()) {
        if (!it->is_object()) r.fail("objects", "expected an object of object names");
        for (auto o = it->begin(); o != it->end(); ++o) {
            const std::string path = child("objects", o.key());
            r.checkKeys(o.value(), path, {"reflectance", "removable"});
            ObjectSettings s;
            if (auto refl = o->find("reflectance"); refl != o->end()) {
                const std::string rPath = child(path, "reflectance");
                Rgb rho = r.rgb(*refl, rPath);
                bool clamped = false;
                for (int k = 0; k < 3; ++k) {
                    if (!(rho[k] >= 0 && rho[k] <= 1))
                        r.fail(element(rPath, static_cast<size_t>(k)), "must be in [0, 1]");
                    // The spec allows 1, but a surface that reflects everything makes a
                    // closed scene's radiosity iteration diverge; 0.99 keeps it convergent.
                    if (rho[k] >= 1) {
                        rho[k] = 0.99;
                        clamped = true;
                    }
                }
                if (clamped)
                    sf.warnings.push_back(
                        r.message(rPath,
                                  "reflectance 1 clamped to 0.99 (the radiosity solution would "
                                  "not converge)"));
                s.reflectance = rho;
            }
            if (auto rem = o->find("removable"); rem != o->end())
                s.removable = r.boolean(*rem, child(path, "removable"));
            sf.objectSettings[o.key()] = s;
        }
    }
    auto reflectanceOf = [&](const std::string& object) {
        if (auto it = sf.objectSettings.find(object);
            it != sf.objectSettings.end() && it->second.reflectance)
            return *it->second.reflectance;
        return Rgb::gray(sf.averageReflectance.value_or(0.5));
    };

    // Geometry: OBJ files relative to the scene folder. Objects of the same name in
    // several files are one object.
    const json& geometry = r.array(r.require(root, "", "geometry"), "geometry", 0);
    for (size_t g = 0; g < geometry.size(); ++g) {
        const std::string gPath = element("geometry", g);
        const std::string name = r.string(geometry[g], gPath);
        if (name.empty()) r.fail(gPath, "empty file name");
        const fs::path objPath = dir / name;
        std::error_code ec;
        if (!fs::exists(objPath, ec))
            r.fail(gPath, "OBJ file \"" + objPath.string() + "\" not found");
        sf.geometryFiles.push_back(objPath);
        const ObjFile obj = readObj(objPath);
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
        for (const ObjFace& face : obj.faces) {
            const int object = globalObject[static_cast<size_t>(face.object)];
            PolygonSink sink{sf.scene, object,
                             reflectanceOf(sf.scene.objects[static_cast<size_t>(object)])};
            addFace(obj, face, sink, sf.warnings);
        }
    }
    for (const auto& [name, settings] : sf.objectSettings)
        if (sf.scene.findObject(name) < 0)
            r.fail(child("objects", name), "no object of this name in the geometry");

    // Lights: emitting faces appended after the geometry, reflectance 0 (spec: "A light's
    // emitting face reflects nothing"), each light its own object "light:NAME".
    const json& lights = r.array(r.require(root, "", "lights"), "lights", 0);
    for (size_t i = 0; i < lights.size(); ++i) {
        const std::string path = element("lights", i);
        const json& lj = lights[i];
        r.checkKeys(lj, path, {"name", "type", "vertices", "radiance"});
        radiosity::Light light;
        light.name = r.string(r.require(lj, path, "name"), child(path, "name"));
        if (light.name.empty()) r.fail(child(path, "name"), "empty light name");
        if (sf.scene.findLight(light.name) >= 0)
            r.fail(child(path, "name"), "duplicate light name \"" + light.name + "\"");
        const std::string type = r.string(r.require(lj, path, "type"), child(path, "type"));
        if (type != "quad") r.fail(child(path, "type"), "light type " + type + " not supported");

        const std::string vPath = child(path, "vertices");
        const json& vj = r.array(r.require(lj, path, "vertices"), vPath, 0, 3);
        std::vector<Vec3> corners;
        for (size_t k = 0; k < vj.size(); ++k) corners.push_back(r.point(vj[k], element(vPath, k)));
        const PolygonCheck check = checkPolygon(corners);
        if (check.status != PolygonCheck::Status::ok)
            r.fail(vPath,
                   "a light must be a planar convex polygon of non-zero area: " + check.message);

        const std::string radPath = child(path, "radiance");
        const json& rj = r.require(lj, path, "radiance");
        Rgb radiance;
        bool estimate = false;
        if (rj.is_string()) {
            if (rj.get<std::string>() != "estimate")
                r.fail(radPath, "expected an RGB array or \"estimate\", got " + rj.dump());
            estimate = true;
        } else {
            radiance = r.rgb(rj, radPath);
            for (int k = 0; k < 3; ++k)
                if (radiance[k] < 0)
                    r.fail(element(radPath, static_cast<size_t>(k)),
                           "radiance must not be negative");
        }

        const std::string objectName = "light:" + light.name;
        if (sf.scene.findObject(objectName) >= 0)
            r.fail(child(path, "name"),
                   "the geometry already has an object \"" + objectName + "\"");
        const int object = static_cast<int>(sf.scene.objects.size());
        sf.scene.objects.push_back(objectName);
        const int lightIndex = static_cast<int>(sf.scene.lights.size());
        PolygonSink sink{sf.scene, object, Rgb{}, lightIndex};
        const size_t first = sf.scene.polygons.size();
        if (corners.size() <= 4)
            sink.add(corners);
        else
            sink.addTriangles(corners, fan(corners.size()));
        for (size_t p = first; p < sf.scene.polygons.size(); ++p)
            light.polygons.push_back(static_cast<int>(p));
        sf.scene.lights.push_back(std::move(light));
        sf.nominalRadiance.push_back(radiance);
        sf.estimateRadiance.push_back(estimate);
    }

    // Photos: files are only named here; the photo pipeline opens them.
    if (auto it = root.find("photos"); it != root.end()) {
        const json& photos = r.array(*it, "photos", 0);
        for (size_t i = 0; i < photos.size(); ++i) {
            const std::string path = element("photos", i);
            const json& pj = photos[i];
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
                    r.fail(child(path, "encoding"),
                           "expected \"linear\" or \"srgb\", got \"" + enc + "\"");
            } else {
                // Not in the spec's example only by omission: infer it where the file type
                // leaves no doubt.
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
                if (sf.scene.findLight(lightName) < 0)
                    r.fail(element(onPath, k), "no light named \"" + lightName + "\"");
                if (std::find(photo.lightsOn.begin(), photo.lightsOn.end(), lightName) !=
                    photo.lightsOn.end())
                    r.fail(element(onPath, k), "light \"" + lightName + "\" listed twice");
                photo.lightsOn.push_back(lightName);
            }
            sf.photos.push_back(std::move(photo));
        }
    }

    sf.setPhotoLightState();
    return sf;
}

}  // namespace relight
