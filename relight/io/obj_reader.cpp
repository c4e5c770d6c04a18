#include "relight/io/obj_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <system_error>

#include "relight/io/input_file.h"

namespace relight {

namespace {

/// One logical statement: its tokens and the line it starts on.
struct Statement {
    int line = 0;
    std::vector<std::string> tokens;
};

std::vector<std::string> splitWhitespace(const std::string& s) {
    std::vector<std::string> out;
    size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
        size_t j = i;
        while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
        if (j > i) out.emplace_back(s.substr(i, j - i));
        i = j;
    }
    return out;
}

/// Splits the text into statements: strips comments and CR (files written on Windows),
/// joins backslash continuations, drops blank lines.
std::vector<Statement> readStatements(std::istream& in) {
    std::vector<Statement> out;
    std::string raw, pending;
    int lineNo = 0, startLine = 0;
    while (std::getline(in, raw)) {
        ++lineNo;
        if (!raw.empty() && raw.back() == '\r') raw.pop_back();
        if (size_t hash = raw.find('#'); hash != std::string::npos) raw.erase(hash);
        if (pending.empty()) startLine = lineNo;
        // A trailing backslash continues the statement on the next line.
        size_t end = raw.find_last_not_of(" \t");
        if (end != std::string::npos && raw[end] == '\\') {
            pending += raw.substr(0, end) + ' ';
            continue;
        }
        pending += raw;
        std::vector<std::string> tokens = splitWhitespace(pending);
        pending.clear();
        if (!tokens.empty()) out.push_back({startLine, std::move(tokens)});
    }
    if (!pending.empty()) {
        std::vector<std::string> tokens = splitWhitespace(pending);
        if (!tokens.empty()) out.push_back({startLine, std::move(tokens)});
    }
    return out;
}

/// Parses a whole token as a double; false when it is not a number. std::from_chars does
/// not take a leading '+', which some exporters write.
bool parseDouble(std::string_view s, double& value, bool& outOfRange) {
    outOfRange = false;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
    const char* end = s.data() + s.size();
    auto [ptr, ec] = std::from_chars(s.data(), end, value);
    if (ec == std::errc::result_out_of_range && ptr == end) {
        outOfRange = true;
        return false;
    }
    return ec == std::errc() && ptr == end;
}

bool parseInteger(std::string_view s, long long& value) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
    const char* end = s.data() + s.size();
    auto [ptr, ec] = std::from_chars(s.data(), end, value);
    return ec == std::errc() && ptr == end;
}

/// Statements the scene format has no use for: texture coordinates, normals, smoothing
/// groups, lines, points and materials (reflectance comes from the photo, see the spec).
bool isIgnoredKeyword(const std::string& k) {
    static const std::set<std::string> ignored = {"vt", "vn", "vp",     "s",
                                                  "l",  "p",  "usemtl", "mtllib"};
    return ignored.count(k) > 0;
}

std::string joinFrom(const std::vector<std::string>& tokens, size_t first) {
    std::string s;
    for (size_t i = first; i < tokens.size(); ++i) {
        if (i > first) s += ' ';
        s += tokens[i];
    }
    return s;
}

}  // namespace

std::string ObjFile::where(int line) const {
    return name + ":" + std::to_string(line) + ": ";
}

std::string ObjFile::whereFace(const ObjFace& face) const {
    if (face.part < 0) return where(face.line);
    const std::string& part = parts.at(static_cast<size_t>(face.part));
    return name + ": " + (part.empty() ? "" : part + " ") + "face " + std::to_string(face.line) +
           ": ";
}

namespace {

/// "v x y z [w]": three finite coordinates (a fourth, the weight, is checked and ignored).
void readVertex(const Statement& st, ObjFile& obj) {
    if (st.tokens.size() < 4)
        throw InputError(obj.where(st.line) + "vertex needs 3 coordinates, got " +
                         std::to_string(st.tokens.size() - 1));
    double xyz[3] = {0, 0, 0};
    for (size_t i = 1; i < st.tokens.size(); ++i) {
        double value = 0;
        bool outOfRange = false;
        if (!parseDouble(st.tokens[i], value, outOfRange))
            throw InputError(obj.where(st.line) + "bad number \"" + st.tokens[i] + "\"" +
                             (outOfRange ? " (out of range)" : ""));
        if (!std::isfinite(value))
            throw InputError(obj.where(st.line) + "vertex coordinate \"" + st.tokens[i] +
                             "\" is not finite");
        if (i <= 3) xyz[i - 1] = value;
    }
    obj.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
    obj.positionLines.push_back(st.line);
}

/// A positive index that points past the vertices read so far (some exporters write faces
/// first): checked once the whole file is read.
struct ForwardIndex {
    size_t face;
    long long index;  ///< 1-based
};

/// "f v1 v2 v3 ...", each item v, v/vt, v//vn or v/vt/vn: a face of object `object`.
void readFace(const Statement& st, int object, ObjFile& obj, std::vector<ForwardIndex>& forward) {
    if (st.tokens.size() < 4)
        throw InputError(obj.where(st.line) + "face needs at least 3 vertices, got " +
                         std::to_string(st.tokens.size() - 1));
    ObjFace face;
    face.object = object;
    face.line = st.line;
    for (size_t i = 1; i < st.tokens.size(); ++i) {
        const std::string& item = st.tokens[i];
        // The position index is before the first slash.
        const std::string_view vpart = std::string_view(item).substr(0, item.find('/'));
        long long index = 0;
        if (!parseInteger(vpart, index))
            throw InputError(obj.where(st.line) + "bad vertex index \"" + item + "\"");
        const long long count = static_cast<long long>(obj.positions.size());
        if (index == 0)
            throw InputError(obj.where(st.line) + "vertex index 0 (OBJ indices start at 1)");
        if (index < 0) {
            // Relative: -1 is the last vertex read so far.
            // Compared as index < -count: -index overflows for the most negative long long.
            if (index < -count)
                throw InputError(obj.where(st.line) + "face references vertex " +
                                 std::to_string(index) + ", but only " + std::to_string(count) +
                                 " are defined so far");
            face.vertices.push_back(static_cast<int>(count + index));
        } else {
            if (index > count) forward.push_back({obj.faces.size(), index});
            // Clamp so that an unchecked value never fits in an int by accident.
            face.vertices.push_back(static_cast<int>(std::min<long long>(index - 1, 0x7fffffff)));
        }
    }
    obj.faces.push_back(std::move(face));
}

}  // namespace

ObjFile parseObj(std::istream& in, const std::string& name) {
    ObjFile obj;
    obj.name = name;
    const std::vector<Statement> statements = readStatements(in);
    if (in.bad()) throw InputError(name + ": read error");

    // The spec: every `o` block is one object, or, failing that, every `g` block. So
    // whether `g` names objects depends on whether the file has any `o` at all.
    bool hasO = false;
    for (const Statement& st : statements) hasO = hasO || st.tokens[0] == "o";
    const std::string blockKeyword = hasO ? "o" : "g";
    const std::string defaultName = std::filesystem::path(name).stem().string();

    std::map<std::string, int> objectIndex;
    auto objectNamed = [&](const std::string& n) {
        auto [it, inserted] = objectIndex.emplace(n, static_cast<int>(obj.objects.size()));
        if (inserted) obj.objects.push_back(n);
        return it->second;
    };
    int current = -1;  // created lazily: the default object exists only if it has faces
    std::vector<ForwardIndex> forward;
    std::set<std::string> warnedKeywords;
    for (const Statement& st : statements) {
        const std::string& key = st.tokens[0];
        if (key == "v") {
            readVertex(st, obj);
        } else if (key == "f") {
            if (current < 0) current = objectNamed(defaultName);
            readFace(st, current, obj, forward);
        } else if (key == "o" || key == "g") {
            if (key != blockKeyword) continue;  // `g` inside `o` blocks: sub-groups
            const std::string objectName = joinFrom(st.tokens, 1);
            // An unnamed block (`g` alone means the default group) keeps the file's name.
            current = objectNamed(objectName.empty() ? defaultName : objectName);
        } else if (!isIgnoredKeyword(key)) {
            if (warnedKeywords.insert(key).second)
                obj.warnings.push_back(obj.where(st.line) + "unknown statement \"" + key +
                                       "\" ignored (warned once per file)");
        }
    }

    const long long count = static_cast<long long>(obj.positions.size());
    for (const ForwardIndex& f : forward) {
        if (f.index > count)
            throw InputError(obj.where(obj.faces[f.face].line) + "face references vertex " +
                             std::to_string(f.index) + ", but only " + std::to_string(count) +
                             " are defined");
    }
    return obj;
}

ObjFile readObj(const std::filesystem::path& path) {
    const std::string name = path.string();
    requireRegularFile(path, "OBJ file", "an OBJ file");
    std::ifstream in(path);
    if (!in) throw InputError(name + ": cannot open: " + std::strerror(errno));
    return parseObj(in, name);
}

}  // namespace relight
