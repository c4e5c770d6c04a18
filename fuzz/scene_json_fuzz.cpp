// Fuzz target: scene.json's reader (relight::parseScene). The bytes are scene.json's text;
// the geometry it names is looked up in a folder holding the bundled scenes' OBJ files.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "relight/io/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    try {
        relight::parseScene(in, RELIGHT_FUZZ_SCENE_DIR);
    } catch (const relight::InputError&) {
        // The documented answer to bad input; any other exception escapes and is a finding.
    }
    return 0;
}
