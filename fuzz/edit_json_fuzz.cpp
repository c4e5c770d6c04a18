// Fuzz target: the edit reader (relight::parseEdit). The bytes are an edit's text, read
// against each bundled scene (their light and object names differ) as if it lay in the
// scene's edits/ folder, where the bundled edits' virtual objects resolve.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "relight/io/edit_file.h"

namespace {

struct Scene {
    std::filesystem::path dir;
    relight::SceneFile file;
};

const std::vector<Scene>& scenes() {
    static const std::vector<Scene> loaded = [] {
        std::vector<Scene> s;
        for (const char* name : {"room", "cornell"}) {
            const std::filesystem::path dir = std::filesystem::path(RELIGHT_DATA_DIR) / name;
            s.push_back({dir, relight::loadScene(dir)});
        }
        return s;
    }();
    return loaded;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    for (const Scene& scene : scenes()) {
        std::istringstream in(text);
        try {
            relight::parseEdit(in, scene.dir / "edits" / "fuzz.json", scene.file);
        } catch (const relight::InputError&) {
            // The documented answer to bad input; any other exception escapes and is a
            // finding.
        }
    }
    return 0;
}
