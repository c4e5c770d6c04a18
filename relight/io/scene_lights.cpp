#include "relight/io/scene_lights.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "relight/errors.h"
#include "relight/io/atomic_write.h"
#include "relight/io/json_reader.h"
#include "relight/io/scene_file.h"

namespace relight {

namespace fs = std::filesystem;
using radiosity::Vec3;
using ordered_json = nlohmann::ordered_json;

std::vector<Vec3> lampQuad(const Vec3& centre, const Vec3& normal, double width, double height) {
    const double length = glm::length(normal);
    if (!(length > 0)) throw std::invalid_argument("lampQuad: zero normal");
    const Vec3 n = normal / length;
    const Vec3 a = std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 t = glm::normalize(a - n * glm::dot(a, n));
    const Vec3 b = glm::cross(n, t);  // (t, b, n) right-handed: t to b turns about n
    const Vec3 u = t * (0.5 * width), v = b * (0.5 * height);
    return {centre - u - v, centre + u - v, centre + u + v, centre - u + v};
}

namespace {

ordered_json lampJson(const RealLamp& lamp) {
    ordered_json vertices = ordered_json::array();
    for (const Vec3& c : lamp.corners) vertices.push_back({c.x, c.y, c.z});
    ordered_json j = {{"name", lamp.name}, {"type", "quad"}, {"vertices", vertices}};
    if (lamp.radiance)
        j["radiance"] = {lamp.radiance->r, lamp.radiance->g, lamp.radiance->b};
    else
        j["radiance"] = "estimate";
    return j;
}

}  // namespace

void addLampsToScene(const fs::path& dir, const std::vector<RealLamp>& lamps) {
    const fs::path file = dir / "scene.json";
    jsonio::parseJsonFile(file);  // its own errors (syntax, duplicate keys) first
    std::ifstream in(file);
    // ordered_json keeps the file's order of keys, so that only the lights change.
    ordered_json scene = ordered_json::parse(in);
    if (!scene.is_object() || !scene.contains("lights") || !scene["lights"].is_array())
        throw InputError(file.string() + ": key \"lights\": expected an array of lights");
    // The first photo's lights_on, when scene.json has one (the loader checks its form).
    ordered_json* lightsOn = nullptr;
    if (auto photos = scene.find("photos"); photos != scene.end() && photos->is_array() &&
                                            !photos->empty() && (*photos)[0].is_object()) {
        auto on = (*photos)[0].find("lights_on");
        if (on != (*photos)[0].end() && on->is_array()) lightsOn = &*on;
    }
    for (const RealLamp& lamp : lamps) {
        scene["lights"].push_back(lampJson(lamp));
        if (lamp.onInPhoto && lightsOn) lightsOn->push_back(lamp.name);
    }
    const std::string text = scene.dump(2) + "\n";
    std::istringstream check(text);
    parseScene(check, dir);  // the scene as it will be: InputError naming the key
    writeTextAtomic(file, text);
}

}  // namespace relight
