// Strict JSON reading shared by the scene and edit loaders (see json_reader.h).
#include "relight/io/json_reader.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "relight/io/input_file.h"

namespace relight::jsonio {

namespace fs = std::filesystem;

std::string child(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
}

std::string element(const std::string& path, size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

// ---- parsing with duplicate-key detection ----------------------------------------------

json parseJsonFile(const fs::path& path) {
    const std::string file = path.string();
    requireRegularFile(path, "file", "a JSON file");
    std::ifstream in(path);
    if (!in) throw InputError(file + ": cannot open: " + std::strerror(errno));
    return parseJson(in, file);
}

json parseJson(std::istream& in, const std::string& file) {
    // The parser callback sees keys and values in order; a stack of open objects and
    // arrays gives each key its path, and each object remembers the keys it has seen.
    struct Frame {
        bool isArray = false;
        size_t next = 0;      // arrays: index of the next element
        std::string path;     // key path of this object or array
        std::string lastKey;  // objects: the key whose value is being read
        std::set<std::string> keys;
    };
    std::vector<Frame> stack;
    std::string duplicate;
    auto label = [&]() -> std::string {
        if (stack.empty()) return "";
        const Frame& top = stack.back();
        return top.isArray ? element(top.path, top.next) : child(top.path, top.lastKey);
    };
    auto endElement = [&] {
        if (!stack.empty() && stack.back().isArray) ++stack.back().next;
    };
    json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start:
            case json::parse_event_t::array_start: {
                Frame f;
                f.isArray = event == json::parse_event_t::array_start;
                f.path = label();
                stack.push_back(std::move(f));
                break;
            }
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                if (!stack.empty()) stack.pop_back();
                endElement();
                break;
            case json::parse_event_t::key:
                if (!stack.empty() && parsed.is_string()) {
                    Frame& top = stack.back();
                    top.lastKey = parsed.get<std::string>();
                    if (!top.keys.insert(top.lastKey).second && duplicate.empty())
                        duplicate = child(top.path, top.lastKey);
                }
                break;
            case json::parse_event_t::value:
                endElement();
                break;
        }
        return true;
    };

    json root;
    try {
        root = json::parse(in, callback);
    } catch (const json::exception& e) {
        // e.what() reads "[json.exception.parse_error.101] parse error at line 3, column
        // 5: ..."; keep the part from "parse error", which names the line and column.
        std::string what = e.what();
        if (size_t close = what.find("] "); close != std::string::npos) what.erase(0, close + 2);
        throw InputError(file + ": invalid JSON: " + what);
    }
    if (!duplicate.empty()) throw InputError(file + ": key \"" + duplicate + "\": duplicate key");
    return root;
}

// ---- typed access ----------------------------------------------------------------------

void JsonReader::fail(const std::string& path, const std::string& what) const {
    if (path.empty()) throw InputError(file_ + ": " + what);
    throw InputError(message(path, what));
}

std::string JsonReader::message(const std::string& path, const std::string& what) const {
    return file_ + ": key \"" + path + "\": " + what;
}

void JsonReader::checkKeys(const json& obj, const std::string& path,
                           std::initializer_list<const char*> allowed) const {
    if (!obj.is_object()) fail(path, "expected an object, got " + describe(obj));
    for (auto it = obj.begin(); it != obj.end(); ++it) {
        bool known = false;
        for (const char* a : allowed) known = known || it.key() == a;
        if (!known) fail(child(path, it.key()), "unknown key");
    }
}

const json& JsonReader::require(const json& obj, const std::string& path, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(child(path, key), "missing required key");
    return *it;
}

double JsonReader::number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "expected a number, got " + describe(j));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "number is not finite");
    return v;
}

int JsonReader::positiveInt(const json& j, const std::string& path) const {
    const double v = number(j, path);
    if (!(v >= 1 && v <= 1e6 && v == std::floor(v)))
        fail(path, "expected a positive integer, got " + j.dump());
    return static_cast<int>(v);
}

std::string JsonReader::string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "expected a string, got " + describe(j));
    return j.get<std::string>();
}

bool JsonReader::boolean(const json& j, const std::string& path) const {
    if (!j.is_boolean()) fail(path, "expected true or false, got " + describe(j));
    return j.get<bool>();
}

const json& JsonReader::array(const json& j, const std::string& path, size_t size,
                              size_t minSize) const {
    if (!j.is_array()) fail(path, "expected an array, got " + describe(j));
    if (size != 0 && j.size() != size)
        fail(path, "expected an array of " + std::to_string(size) + " elements, got " +
                       std::to_string(j.size()));
    if (j.size() < minSize)
        fail(path, "expected an array of at least " + std::to_string(minSize) + " elements, got " +
                       std::to_string(j.size()));
    return j;
}

radiosity::Vec3 JsonReader::point(const json& j, const std::string& path) const {
    array(j, path, 3);
    return {number(j[0], element(path, 0)), number(j[1], element(path, 1)),
            number(j[2], element(path, 2))};
}

radiosity::Rgb JsonReader::rgb(const json& j, const std::string& path) const {
    array(j, path, 3);
    return {number(j[0], element(path, 0)), number(j[1], element(path, 1)),
            number(j[2], element(path, 2))};
}

std::vector<std::vector<double>> JsonReader::matrix(const json& j, const std::string& path,
                                                    size_t rows, size_t cols) const {
    array(j, path, rows);
    std::vector<std::vector<double>> m(rows, std::vector<double>(cols));
    for (size_t r = 0; r < rows; ++r) {
        const std::string rowPath = element(path, r);
        array(j[r], rowPath, cols);
        for (size_t c = 0; c < cols; ++c) m[r][c] = number(j[r][c], element(rowPath, c));
    }
    return m;
}

std::string JsonReader::describe(const json& j) {
    std::string d = j.dump();
    if (d.size() > 40) d = d.substr(0, 37) + "...";
    return std::string(j.type_name()) + " " + d;
}

}  // namespace relight::jsonio
