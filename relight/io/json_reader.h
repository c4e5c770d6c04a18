// Strict JSON reading shared by the scene loader (scene_file.cpp) and the edit loader
// (edit_file.cpp), so that both report problems the same way:
//   "<file>: key \"<key path>\": <what is wrong>"
// where a key path reads like "lights[2].radiance[0]" or "lights.A.scale".
//
// Reading is strict on purpose: the formats are interchange formats, so a key we do not
// know is more likely a typo (whose setting would silently be lost) than an extension.
#pragma once

#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <iosfwd>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <utility>
#include <vector>

#include "radiosity/rgb.h"
#include "radiosity/vec.h"
#include "relight/errors.h"

namespace relight::jsonio {

using nlohmann::json;

/// "camera" + "K" -> "camera.K"; at the top level just the key.
std::string child(const std::string& path, const std::string& key);

/// "lights" + 2 -> "lights[2]".
std::string element(const std::string& path, size_t i);

/// Parses a JSON file; messages name it as path.string(). nlohmann::json keeps only the
/// last of duplicate keys, which would silently drop e.g. a first "lights" list, so the
/// first duplicate is an error naming its key path. Throws InputError (file not found, a
/// directory, unreadable, invalid JSON with line and column, duplicate key).
json parseJsonFile(const std::filesystem::path& path);

/// parseJsonFile() of text read from `in`; messages name it as `file`. Throws InputError
/// (invalid JSON with line and column, duplicate key).
json parseJson(std::istream& in, const std::string& file);

/// Typed access to JSON values; every error is an InputError naming the file and key path.
class JsonReader {
  public:
    explicit JsonReader(std::string file) : file_(std::move(file)) {}

    const std::string& file() const { return file_; }

    /// Throws "<file>: key \"<path>\": <what>", or "<file>: <what>" when path is empty.
    [[noreturn]] void fail(const std::string& path, const std::string& what) const;
    /// The text fail() would throw, for warnings.
    std::string message(const std::string& path, const std::string& what) const;

    /// Requires an object and rejects any of its keys that is not in `allowed`.
    void checkKeys(const json& obj, const std::string& path,
                   std::initializer_list<const char*> allowed) const;

    /// obj[key], which must be present.
    const json& require(const json& obj, const std::string& path, const char* key) const;

    /// A finite number. JSON has no NaN, but an overflowing literal (1e999) may read as inf.
    double number(const json& j, const std::string& path) const;

    /// A positive integer (an integral float such as 320.0 is accepted).
    int positiveInt(const json& j, const std::string& path) const;

    std::string string(const json& j, const std::string& path) const;
    bool boolean(const json& j, const std::string& path) const;

    /// An array; size must be `size` when it is non-zero, at least `minSize` otherwise.
    const json& array(const json& j, const std::string& path, size_t size,
                      size_t minSize = 0) const;

    /// Three finite numbers.
    radiosity::Vec3 point(const json& j, const std::string& path) const;
    radiosity::Rgb rgb(const json& j, const std::string& path) const;

    /// rows x cols finite numbers, row-major as in the spec.
    std::vector<std::vector<double>> matrix(const json& j, const std::string& path, size_t rows,
                                            size_t cols) const;

    /// "<type> <value>", the value cut to 40 characters, for "expected X, got Y".
    static std::string describe(const json& j);

  private:
    std::string file_;
};

}  // namespace relight::jsonio
