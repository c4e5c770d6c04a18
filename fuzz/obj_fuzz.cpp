// Fuzz target: the strict OBJ reader (relight::parseObj), then the face checks and repairs
// every OBJ file of a scene or edit goes through (relight::addObjFaces).
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "relight/io/face_repair.h"
#include "relight/io/obj_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    try {
        const relight::ObjFile obj = relight::parseObj(in, "fuzz.obj");
        // One scene object per OBJ object, as loadScene() makes them.
        radiosity::Scene scene;
        scene.objects = obj.objects;
        std::vector<int> sceneObject(obj.objects.size());
        std::iota(sceneObject.begin(), sceneObject.end(), 0);
        std::vector<std::string> warnings;
        relight::addObjFaces(
            obj, sceneObject, [](int) { return radiosity::Rgb::gray(0.5); }, scene, warnings);
    } catch (const relight::InputError&) {
        // The documented answer to bad input; any other exception escapes and is a finding.
    }
    return 0;
}
