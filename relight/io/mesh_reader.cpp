#include "relight/io/mesh_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <utility>

#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "relight/io/input_file.h"

namespace relight {

namespace fs = std::filesystem;
using radiosity::Vec3;

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string quoted(const std::string& s) {
    return "\"" + s + "\"";
}

/// Assimp's file access, recording every file an importer opens: a .gltf reads its
/// buffers from other files, which must be part of a cache's key like the .gltf itself.
class RecordingIOSystem : public Assimp::DefaultIOSystem {
  public:
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        Assimp::IOStream* stream = DefaultIOSystem::Open(file, mode);
        if (stream != nullptr) opened.emplace_back(file);
        return stream;
    }
    std::vector<std::string> opened;
};

/// A row-major 4x4 affine transform in double: node transforms are composed in double so
/// that a deep node tree does not add float rounding to every vertex.
using Mat4 = std::array<double, 16>;

Mat4 toMat4(const aiMatrix4x4& m) {
    return {m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4,
            m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4};
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
    Mat4 c{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) c[i * 4 + j] += a[i * 4 + k] * b[k * 4 + j];
    return c;
}

double det3(const Mat4& m) {
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
           m[2] * (m[4] * m[9] - m[5] * m[8]);
}

Vec3 transformPoint(const Mat4& m, const aiVector3D& p) {
    const double x = p.x, y = p.y, z = p.z;
    return Vec3(m[0] * x + m[1] * y + m[2] * z + m[3], m[4] * x + m[5] * y + m[6] * z + m[7],
                m[8] * x + m[9] * y + m[10] * z + m[11]);
}

std::string formatPoint(const aiVector3D& p) {
    std::ostringstream s;
    s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
    return s.str();
}

// ---- PLY structure ---------------------------------------------------------------------
//
// Assimp 5.2's PLY reader trusts the header: on a truncated ASCII body it returns a mesh
// made of what it found (faces silently lost, or indices into vertices it never read), and
// on a file cut inside its header it loops forever. So the file's structure is checked
// here first: a header we understand, and a body that holds every element the header
// announces. Values are not interpreted (Assimp reads them); only counts and sizes.

struct PlyProperty {
    std::string name;
    bool list = false;
    int countSize = 0;         ///< bytes of a list's count (binary)
    bool countSigned = false;  ///< whether a list's count type is signed
    int size = 0;              ///< bytes of the value, or of each list item (binary)
};

struct PlyElement {
    std::string name;
    unsigned long long count = 0;
    std::vector<PlyProperty> properties;
};

/// Bytes of a PLY scalar type (both spellings), 0 when unknown; `isSigned` for list counts.
int plyTypeSize(const std::string& t, bool& isSigned) {
    isSigned =
        t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" ||
        t == "float32")
        return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}

std::vector<std::string> splitWords(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

/// Throws the InputError of a problem in PLY file `name`, at header or body line `line`
/// when it is positive.
struct PlyProblem {
    const std::string& name;
    [[noreturn]] void operator()(int line, const std::string& what) const {
        throw InputError(name + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                         what);
    }
    [[noreturn]] void truncated(const PlyElement& e, unsigned long long i) const {
        (*this)(0, "the PLY file is cut short: it ends in element \"" + e.name + "\" " +
                       std::to_string(i + 1) + " of " + std::to_string(e.count) +
                       " (the header announces more than the file holds)");
    }
};

enum class PlyFormat { none, ascii, little, big };

struct PlyHeader {
    PlyFormat format = PlyFormat::none;
    std::vector<PlyElement> elements;
    size_t bodyStart = 0;  ///< byte offset of the body
    int lines = 0;         ///< lines of the header
};

/// A "property" line: a scalar ("property TYPE NAME") or a list ("property list COUNT_TYPE
/// ITEM_TYPE NAME").
PlyProperty readPlyProperty(const std::vector<std::string>& w, const std::string& text, int line,
                            const PlyProblem& fail) {
    PlyProperty prop;
    bool isSigned = false;
    if (w.size() == 5 && w[1] == "list") {
        prop.list = true;
        prop.countSize = plyTypeSize(w[2], prop.countSigned);
        prop.size = plyTypeSize(w[3], isSigned);
        prop.name = w[4];
        if (prop.countSize == 0 || prop.countSize == 8 || w[2] == "float" || w[2] == "float32")
            fail(line, "bad PLY list count type \"" + w[2] + "\"");
    } else if (w.size() == 3) {
        prop.size = plyTypeSize(w[1], isSigned);
        prop.name = w[2];
    } else {
        fail(line, "bad PLY property line \"" + text + "\"");
    }
    if (prop.size == 0) fail(line, "unknown PLY type in \"" + text + "\"");
    return prop;
}

/// The header: "ply", "format F 1.0", comments, elements with their properties,
/// "end_header".
PlyHeader readPlyHeader(const std::string& data, const PlyProblem& fail) {
    PlyHeader header;
    size_t& pos = header.bodyStart;
    int& line = header.lines;
    for (bool ended = false; !ended;) {
        const size_t eol = data.find('\n', pos);
        if (eol == std::string::npos)
            fail(0, line == 0 ? "empty file, not a PLY file"
                              : "the PLY header has no end_header line (cut short?)");
        std::string text = data.substr(pos, eol - pos);
        if (!text.empty() && text.back() == '\r') text.pop_back();
        pos = eol + 1;
        ++line;
        const std::vector<std::string> w = splitWords(text);
        if (line == 1) {
            if (w.size() != 1 || w[0] != "ply") fail(1, "not a PLY file (no \"ply\" line first)");
            continue;
        }
        if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "format") {
            if (w.size() != 3 || w[2] != "1.0") fail(line, "bad PLY format line \"" + text + "\"");
            if (w[1] == "ascii")
                header.format = PlyFormat::ascii;
            else if (w[1] == "binary_little_endian")
                header.format = PlyFormat::little;
            else if (w[1] == "binary_big_endian")
                header.format = PlyFormat::big;
            else
                fail(line, "unknown PLY format \"" + w[1] + "\"");
        } else if (w[0] == "element") {
            if (w.size() != 3) fail(line, "bad PLY element line \"" + text + "\"");
            PlyElement e;
            e.name = w[1];
            const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
            if (ec != std::errc() || p != w[2].data() + w[2].size())
                fail(line, "bad PLY element count \"" + w[2] + "\"");
            header.elements.push_back(e);
        } else if (w[0] == "property") {
            if (header.elements.empty()) fail(line, "PLY property before any element");
            header.elements.back().properties.push_back(readPlyProperty(w, text, line, fail));
        } else if (w[0] == "end_header" && w.size() == 1) {
            ended = true;
        } else {
            fail(line, "unknown PLY header line \"" + text + "\"");
        }
    }
    if (header.format == PlyFormat::none) fail(0, "the PLY header has no format line");
    return header;
}

/// A photogrammetry point cloud is a common mistake for a mesh: say so, rather than
/// Assimp's "Unable to extract mesh data".
void checkPlyHasFaces(const PlyHeader& header, const PlyProblem& fail) {
    unsigned long long faces = 0, vertices = 0;
    for (const PlyElement& e : header.elements) {
        if (e.name == "face") faces += e.count;
        if (e.name == "vertex") vertices += e.count;
    }
    if (faces == 0)
        fail(0, "no faces in this PLY file" +
                    (vertices > 0 ? " (only " + std::to_string(vertices) +
                                        " vertices: a point cloud has no surfaces; mesh it first)"
                                  : std::string()));
}

/// A binary body: every element's rows, with each list's length read from the file, fit in
/// what the file holds.
void checkPlyBinaryBody(const std::string& data, const PlyHeader& header, const PlyProblem& fail) {
    const bool big = header.format == PlyFormat::big;
    size_t pos = header.bodyStart;
    auto readCount = [&](const PlyProperty& p) -> long long {
        unsigned long long v = 0;
        for (int b = 0; b < p.countSize; ++b) {
            const auto byte = static_cast<unsigned char>(data[pos + static_cast<size_t>(b)]);
            const int shift = 8 * (big ? p.countSize - 1 - b : b);
            v |= static_cast<unsigned long long>(byte) << shift;
        }
        if (p.countSigned && p.countSize < 8 && (v >> (8 * p.countSize - 1)) != 0)
            return -1;  // negative
        return static_cast<long long>(v);
    };
    for (const PlyElement& e : header.elements) {
        bool fixed = true;
        unsigned long long row = 0;
        for (const PlyProperty& p : e.properties) {
            fixed = fixed && !p.list;
            row += static_cast<unsigned long long>(p.size);
        }
        const unsigned long long left = data.size() - pos;
        if (fixed) {  // every row the same size: one check for the whole element
            if (row > 0 && e.count > left / row) fail.truncated(e, left / row);
            pos += static_cast<size_t>(row * e.count);
            continue;
        }
        for (unsigned long long i = 0; i < e.count; ++i)
            for (const PlyProperty& p : e.properties) {
                if (!p.list) {
                    if (data.size() - pos < static_cast<size_t>(p.size)) fail.truncated(e, i);
                    pos += static_cast<size_t>(p.size);
                    continue;
                }
                if (data.size() - pos < static_cast<size_t>(p.countSize)) fail.truncated(e, i);
                const long long n = readCount(p);
                if (n < 0)
                    fail(0, "negative list length in PLY element \"" + e.name + "\" " +
                                std::to_string(i + 1));
                pos += static_cast<size_t>(p.countSize);
                const unsigned long long bytes =
                    static_cast<unsigned long long>(n) * static_cast<unsigned>(p.size);
                if (data.size() - pos < bytes) fail.truncated(e, i);
                pos += static_cast<size_t>(bytes);
            }
    }
}

/// An ASCII body: the values, one token each (a list: its length, then its items), must all
/// be numbers and all be there.
void checkPlyAsciiBody(const std::string& data, const PlyHeader& header, const PlyProblem& fail) {
    size_t pos = header.bodyStart;
    size_t tokenLine = static_cast<size_t>(header.lines) + 1;
    auto nextToken = [&](std::string_view& token) {
        while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) {
            if (data[pos] == '\n') ++tokenLine;
            ++pos;
        }
        if (pos >= data.size()) return false;
        const size_t start = pos;
        while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
        token = std::string_view(data).substr(start, pos - start);
        return true;
    };
    auto badToken = [&](std::string_view token, const PlyElement& e) {
        fail(static_cast<int>(tokenLine),
             "bad number \"" + std::string(token) + "\" in PLY element \"" + e.name + "\"");
    };
    for (const PlyElement& e : header.elements)
        for (unsigned long long i = 0; i < e.count; ++i)
            for (const PlyProperty& p : e.properties) {
                std::string_view token;
                if (!nextToken(token)) fail.truncated(e, i);
                if (!p.list) {
                    double value = 0;
                    const auto [q, ec] =
                        std::from_chars(token.data(), token.data() + token.size(), value);
                    // A value out of double's range is left to Assimp (it reads floats).
                    if ((ec != std::errc() && ec != std::errc::result_out_of_range) ||
                        q != token.data() + token.size())
                        badToken(token, e);
                    continue;
                }
                unsigned long long n = 0;
                const auto [q, ec] = std::from_chars(token.data(), token.data() + token.size(), n);
                if (ec != std::errc() || q != token.data() + token.size()) badToken(token, e);
                for (unsigned long long k = 0; k < n; ++k) {
                    if (!nextToken(token)) fail.truncated(e, i);
                    long long index = 0;
                    const auto [r, ec2] =
                        std::from_chars(token.data(), token.data() + token.size(), index);
                    if (ec2 != std::errc() || r != token.data() + token.size()) badToken(token, e);
                }
            }
}

void checkPly(const fs::path& path, const std::string& name) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open: " + std::strerror(errno));
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(name + ": read error");
    const PlyProblem fail{name};
    const PlyHeader header = readPlyHeader(data, fail);
    checkPlyHasFaces(header, fail);
    if (header.format == PlyFormat::ascii)
        checkPlyAsciiBody(data, header, fail);
    else
        checkPlyBinaryBody(data, header, fail);
}

/// Whether `name` is empty or the id Assimp's glTF importer gives an unnamed node or mesh
/// ("nodes[3]", "meshes[0]"): those name no object. (They still locate a face in messages.)
bool isGeneratedId(const std::string& name, const std::string& array) {
    if (name.empty()) return true;
    if (name.size() < array.size() + 3 || name.compare(0, array.size() + 1, array + "[") != 0 ||
        name.back() != ']')
        return false;
    return std::all_of(name.begin() + static_cast<std::ptrdiff_t>(array.size()) + 1, name.end() - 1,
                       [](unsigned char c) { return std::isdigit(c) != 0; });
}

/// The Assimp-read formats: their name in messages.
std::string formatName(const std::string& ext) {
    if (ext == ".ply") return "PLY";
    return "glTF";
}

/// The files an importer opened (`path`, then what it drew on, such as a .gltf's buffers),
/// normalised and each once.
std::vector<fs::path> filesRead(const fs::path& path, const RecordingIOSystem& io) {
    std::vector<fs::path> files{path};
    for (const std::string& opened : io.opened) {
        const fs::path p = fs::path(opened).lexically_normal();
        if (std::find(files.begin(), files.end(), p) == files.end() && p != path.lexically_normal())
            files.push_back(p);
    }
    return files;
}

/// The index of object `n` in `obj`, added when new.
int objectIndex(ObjFile& obj, const std::string& n) {
    const auto it = std::find(obj.objects.begin(), obj.objects.end(), n);
    if (it != obj.objects.end()) return static_cast<int>(it - obj.objects.begin());
    obj.objects.push_back(n);
    return static_cast<int>(obj.objects.size()) - 1;
}

/// Appends `mesh`'s vertices, through its node's transform `world`, and its faces (those of
/// 3 or more indices) to `obj` as a new part named `part`, in object `object`.
void addAssimpMesh(const aiMesh* mesh, const Mat4& world, int object, const std::string& part,
                   const std::string& name, ObjFile& obj) {
    const int partIndex = static_cast<int>(obj.parts.size());
    obj.parts.push_back(part);
    const size_t base = obj.positions.size();
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const aiVector3D& p = mesh->mVertices[v];
        const Vec3 q = transformPoint(world, p);
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) ||
            !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
            throw InputError(name + ": " + (part.empty() ? "" : part + " ") + "vertex " +
                             std::to_string(v + 1) + " " + formatPoint(p) +
                             (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)
                                  ? " is not finite once its node's transform is applied"
                                  : " is not finite"));
        obj.positions.push_back(q);
    }
    // glTF: "If the determinant [of the node's global transform] is a positive value, the
    // winding order [of] triangle faces is counterclockwise; in the opposite case, the
    // winding order is clockwise." The engine's front is counter-clockwise, so a mirrored
    // node's faces are turned back.
    const bool mirrored = det3(world) < 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices < 3) continue;
        ObjFace of;
        of.object = object;
        of.part = partIndex;
        of.line = static_cast<int>(f + 1);
        for (unsigned i = 0; i < face.mNumIndices; ++i) {
            const unsigned index = face.mIndices[i];
            if (index >= mesh->mNumVertices)
                throw InputError(obj.whereFace(of) + "vertex index " + std::to_string(index) +
                                 " out of range (the mesh has " +
                                 std::to_string(mesh->mNumVertices) + " vertices)");
            of.vertices.push_back(static_cast<int>(base + index));
        }
        if (mirrored) std::reverse(of.vertices.begin(), of.vertices.end());
        obj.faces.push_back(std::move(of));
    }
}

/// What the node walk skips, for the messages: faces of fewer than 3 indices (points,
/// lines), and meshes with no face at all.
struct AssimpSkipped {
    size_t pointsAndLines = 0, emptyMeshes = 0;
};

/// The meshes of one node: each one's object (PLY has no names: the file is one object, as
/// an OBJ without `o` or `g`; glTF: the node's name, else the mesh's, else the file's) and
/// part (the mesh and node, to locate a face in messages).
void addNodeMeshes(const aiScene* scene, const aiNode* node, const Mat4& world, bool isPly,
                   const std::string& name, const std::string& stem, ObjFile& obj,
                   AssimpSkipped& skipped) {
    const std::string nodeName = node->mName.C_Str();
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        const unsigned meshIndex = node->mMeshes[k];
        if (meshIndex >= scene->mNumMeshes)
            throw InputError(name + ": node " + quoted(nodeName) + " names mesh " +
                             std::to_string(meshIndex) + ", but the file has " +
                             std::to_string(scene->mNumMeshes));
        const aiMesh* mesh = scene->mMeshes[meshIndex];
        const std::string meshName = mesh->mName.C_Str();
        const std::string objectName = isPly                                ? stem
                                       : !isGeneratedId(nodeName, "nodes")  ? nodeName
                                       : !isGeneratedId(meshName, "meshes") ? meshName
                                                                            : stem;
        std::string part;
        if (!isPly) {
            part = "mesh " + quoted(meshName);
            if (!nodeName.empty() && nodeName != meshName) part += " of node " + quoted(nodeName);
        }
        size_t meshFaces = 0;
        for (unsigned f = 0; f < mesh->mNumFaces; ++f)
            meshFaces += mesh->mFaces[f].mNumIndices >= 3 ? 1 : 0;
        skipped.pointsAndLines += mesh->mNumFaces - meshFaces;
        if (meshFaces == 0) {
            skipped.emptyMeshes += mesh->mNumFaces == 0 ? 1 : 0;
            continue;
        }
        addAssimpMesh(mesh, world, objectIndex(obj, objectName), part, name, obj);
    }
}

/// The node tree, walked without recursion (a file may nest nodes deeply), transforms
/// composed in double. Each node is visited once even if a broken file made the tree share
/// one.
void walkAssimpNodes(const aiScene* scene, bool isPly, const std::string& name,
                     const std::string& stem, ObjFile& obj, AssimpSkipped& skipped) {
    std::vector<std::pair<const aiNode*, Mat4>> stack{
        {scene->mRootNode, toMat4(scene->mRootNode->mTransformation)}};
    std::set<const aiNode*> visited;
    while (!stack.empty()) {
        const auto [node, world] = stack.back();
        stack.pop_back();
        if (!visited.insert(node).second) continue;
        for (unsigned c = node->mNumChildren; c-- > 0;) {
            const aiNode* child = node->mChildren[c];
            if (child != nullptr)
                stack.emplace_back(child, multiply(world, toMat4(child->mTransformation)));
        }
        addNodeMeshes(scene, node, world, isPly, name, stem, obj, skipped);
    }
}

/// A file without a face is an error saying why; what was skipped is a warning.
void reportSkipped(const aiScene* scene, const std::string& name, const std::string& format,
                   const AssimpSkipped& skipped, ObjFile& obj) {
    if (obj.faces.empty()) {
        std::string why = "no faces in this " + format + " file";
        if (skipped.pointsAndLines > 0)
            why += " (only " + std::to_string(skipped.pointsAndLines) +
                   " points or lines: a point cloud has no surfaces; mesh it first)";
        else if (skipped.emptyMeshes > 0)
            why += " (its meshes are empty)";
        throw InputError(name + ": " + why);
    }
    if (skipped.pointsAndLines > 0)
        obj.warnings.push_back(name + ": " + std::to_string(skipped.pointsAndLines) +
                               " points or lines ignored (only faces are surfaces)");
    if (scene->mNumLights > 0)
        obj.warnings.push_back(name + ": " + std::to_string(scene->mNumLights) +
                               " light(s) in the file ignored: lamps are described in "
                               "scene.json (\"lights\")");
    if (scene->mNumCameras > 0)
        obj.warnings.push_back(name + ": " + std::to_string(scene->mNumCameras) +
                               " camera(s) in the file ignored: the camera is described in "
                               "scene.json (\"camera\")");
}

MeshFile readWithAssimp(const fs::path& path, const std::string& ext) {
    const std::string name = path.string();
    const std::string format = formatName(ext);
    const bool isPly = ext == ".ply";
    if (isPly) checkPly(path, name);

    Assimp::Importer importer;
    auto* io = new RecordingIOSystem;  // owned by the importer from here on
    importer.SetIOHandler(io);
    // Deliberately absent, because each would change the surfaces the file describes:
    //   aiProcess_Triangulate: the engine takes triangles and planar convex polygons;
    //     its own repair (face_repair.h) splits the other polygons and says so, as for OBJ.
    //     Assimp's triangulation would double a quad room's elements and split non-planar
    //     or non-convex faces silently;
    //   aiProcess_GenNormals/GenSmoothNormals, FixInfacingNormals, FlipWindingOrder,
    //     MakeLeftHanded: a face's front is given by its vertex order alone;
    //   aiProcess_FindDegenerates, FindInvalidData: degenerate faces are reported by
    //     face_repair with the messages OBJ faces get;
    //   aiProcess_PreTransformVertices: it merges meshes by material, losing node names
    //     (the objects); the node tree is walked instead (walkAssimpNodes).
    // ValidateDataStructure makes Assimp check its own output (indices in range, ...).
    const unsigned flags = aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure;
    const aiScene* scene = importer.ReadFile(name, flags);
    if (scene == nullptr)
        throw InputError(name + ": cannot read this " + format +
                         " file: " + importer.GetErrorString());
    if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mRootNode == nullptr)
        throw InputError(name + ": no faces in this " + format + " file (no mesh in it)");

    MeshFile out;
    out.files = filesRead(path, *io);
    out.geometry.name = name;
    AssimpSkipped skipped;
    walkAssimpNodes(scene, isPly, name, path.stem().string(), out.geometry, skipped);
    reportSkipped(scene, name, format, skipped, out.geometry);
    return out;
}

}  // namespace

const std::vector<std::string>& meshExtensions() {
    static const std::vector<std::string> extensions = {".obj", ".ply", ".gltf", ".glb"};
    return extensions;
}

MeshFile readMesh(const fs::path& path) {
    const std::string name = path.string();
    const std::string ext = lower(path.extension().string());
    const auto& known = meshExtensions();
    if (std::find(known.begin(), known.end(), ext) == known.end()) {
        std::string list;
        for (const std::string& e : known) list += (list.empty() ? "" : ", ") + e;
        throw InputError(name + ": unknown geometry format " +
                         (ext.empty() ? std::string("(no extension)") : quoted(ext)) +
                         "; relight reads " + list);
    }
    if (ext == ".obj") return {readObj(path), {path}};

    // The same checks as readObj's, so that a missing file is not reported in Assimp's
    // words ("Unable to open file") but in the loader's.
    requireRegularFile(path, "geometry file", "a geometry file");
    return readWithAssimp(path, ext);
}

}  // namespace relight
