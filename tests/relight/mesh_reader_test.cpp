// Tests of geometry files other than OBJ (relight/io/mesh_reader.h): PLY (ASCII, binary
// little and big endian) and glTF (.gltf with an embedded or an external buffer, .glb),
// written here as text or bytes. They check positions, winding (the front side), object
// names, glTF node transforms (a mirrored node included), that the bundled room converted
// to PLY and to glTF loads as exactly the same polygons as from OBJ, that the edit loader
// takes them, and that each bad input is an InputError naming the file.
#include "relight/io/mesh_reader.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "relight/io/edit_file.h"
#include "relight/io/face_repair.h"
#include "relight/io/image.h"
#include "relight/io/json_reader.h"
#include "relight/io/obj_reader.h"
#include "relight/io/scene_file.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using radiosity::Vec3;
using relight::InputError;
using relight::MeshFile;
using relight::ObjFile;
using relight::readMesh;
using relight::SceneFile;
using relight::test::TempDir;

const fs::path kRoom = fs::path(RELIGHT_DATA_DIR) / "room";

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// readMesh()'s InputError message; fails the test when it reads the file.
std::string readError(const fs::path& file) {
    try {
        readMesh(file);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "readMesh() accepted " << file;
    return {};
}

/// The corners of face f.
std::vector<Vec3> corners(const ObjFile& obj, size_t f) {
    std::vector<Vec3> c;
    for (int i : obj.faces.at(f).vertices) c.push_back(obj.positions.at(static_cast<size_t>(i)));
    return c;
}

/// The front normal the engine will use: (v1 - v0) x (v2 - v0), normalised.
Vec3 frontNormal(const std::vector<Vec3>& c) {
    return glm::normalize(glm::cross(c[1] - c[0], c[2] - c[0]));
}

/// x rounded to float, as Assimp stores it. Through a volatile: GCC 12.2 (Debian 12) at
/// -O2/-O3 drops the round trip in `V{double(float(p.x)), double(float(p.y)), ...}` for the
/// lanes its SLP vectorizer pairs up (x and y come back unrounded).
double toFloat(double x) {
    volatile float f = static_cast<float>(x);
    return f;
}
Vec3 toFloat(const Vec3& p) {
    return Vec3(toFloat(p.x), toFloat(p.y), toFloat(p.z));
}

void expectNear(const Vec3& a, const Vec3& b, double tol = 1e-6) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// ---- writers --------------------------------------------------------------------------

/// A mesh to write: positions and polygons (0-based, counter-clockwise from the front).
struct Mesh {
    std::vector<Vec3> positions;
    std::vector<std::vector<int>> faces;
};

enum class PlyFormat { ascii, binaryLittle, binaryBig };

template <typename T>
void putBinary(std::string& out, T value, bool bigEndian) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (bigEndian != (std::endian::native == std::endian::big))
        std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

/// A PLY file holding `mesh`, coordinates as `float` or `double`.
std::string writePly(const Mesh& mesh, PlyFormat format, bool doubles = false) {
    const char* names[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    const std::string type = doubles ? "double" : "float";
    std::ostringstream h;
    h << "ply\nformat " << names[static_cast<int>(format)] << " 1.0\n"
      << "comment written by relight's mesh_reader_test\n"
      << "element vertex " << mesh.positions.size() << "\n"
      << "property " << type << " x\nproperty " << type << " y\nproperty " << type << " z\n"
      << "element face " << mesh.faces.size() << "\n"
      << "property list uchar int vertex_indices\nend_header\n";
    std::string out = h.str();
    if (format == PlyFormat::ascii) {
        std::ostringstream b;
        b.precision(17);
        for (const Vec3& p : mesh.positions)
            b << (doubles ? p.x : toFloat(p.x)) << " " << (doubles ? p.y : toFloat(p.y)) << " "
              << (doubles ? p.z : toFloat(p.z)) << "\n";
        for (const auto& f : mesh.faces) {
            b << f.size();
            for (int i : f) b << " " << i;
            b << "\n";
        }
        return out + b.str();
    }
    const bool big = format == PlyFormat::binaryBig;
    for (const Vec3& p : mesh.positions)
        for (double c : {p.x, p.y, p.z}) {
            if (doubles)
                putBinary(out, c, big);
            else
                putBinary(out, static_cast<float>(c), big);
        }
    for (const auto& f : mesh.faces) {
        putBinary(out, static_cast<uint8_t>(f.size()), big);
        for (int i : f) putBinary(out, static_cast<int32_t>(i), big);
    }
    return out;
}

std::string base64(const std::string& bytes) {
    static const char* const table =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t n = (uint32_t(uint8_t(bytes[i])) << 16) |
                           (uint32_t(uint8_t(bytes[i + 1])) << 8) | uint8_t(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out += table[(n >> (6 * k)) & 63];
    }
    if (i < bytes.size()) {
        uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += table[(n >> 18) & 63];
        out += table[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

/// A glTF 2.0 document: meshes (triangles only, as glTF has them) in one buffer; the
/// caller adds nodes and a scene. `bin` receives the buffer's bytes.
struct Gltf {
    json doc;
    std::string bin;

    Gltf() {
        doc = {{"asset", {{"version", "2.0"}}},
               {"buffers", json::array()},
               {"bufferViews", json::array()},
               {"accessors", json::array()},
               {"meshes", json::array()},
               {"nodes", json::array()},
               {"scenes", json::array({{{"nodes", json::array()}}})},
               {"scene", 0}};
    }
    /// Adds a mesh of triangles; returns its index. Positions are stored as float.
    int addMesh(const std::string& name, const Mesh& mesh) {
        while (bin.size() % 4 != 0) bin += '\0';
        const size_t posOffset = bin.size();
        Vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
        for (const Vec3& p : mesh.positions) {
            for (double c : {p.x, p.y, p.z}) putBinary(bin, static_cast<float>(c), false);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const size_t idxOffset = bin.size();
        size_t indexCount = 0;
        for (const auto& f : mesh.faces) {
            if (f.size() != 3) throw std::logic_error("glTF meshes are triangles");
            for (int i : f) putBinary(bin, static_cast<uint32_t>(i), false);
            indexCount += 3;
        }
        const int view = static_cast<int>(doc["bufferViews"].size());
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", posOffset}, {"byteLength", idxOffset - posOffset}});
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", idxOffset}, {"byteLength", bin.size() - idxOffset}});
        const int acc = static_cast<int>(doc["accessors"].size());
        doc["accessors"].push_back({{"bufferView", view},
                                    {"componentType", 5126},
                                    {"count", mesh.positions.size()},
                                    {"type", "VEC3"},
                                    {"min", {toFloat(lo.x), toFloat(lo.y), toFloat(lo.z)}},
                                    {"max", {toFloat(hi.x), toFloat(hi.y), toFloat(hi.z)}}});
        doc["accessors"].push_back({{"bufferView", view + 1},
                                    {"componentType", 5125},
                                    {"count", indexCount},
                                    {"type", "SCALAR"}});
        doc["meshes"].push_back({{"name", name},
                                 {"primitives", json::array({{{"attributes", {{"POSITION", acc}}},
                                                              {"indices", acc + 1},
                                                              {"mode", 4}}})}});
        return static_cast<int>(doc["meshes"].size()) - 1;
    }
    /// Adds a node (fields as in glTF: name, mesh, translation, ...); a root node when
    /// `root`. Returns its index.
    int addNode(json node, bool root = true) {
        doc["nodes"].push_back(std::move(node));
        const int index = static_cast<int>(doc["nodes"].size()) - 1;
        if (root) doc["scenes"][0]["nodes"].push_back(index);
        return index;
    }
    /// The .gltf text with the buffer as a data URI.
    std::string embedded() const {
        json d = doc;
        d["buffers"] =
            json::array({{{"byteLength", bin.size()},
                          {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
        return d.dump(1);
    }
    /// The .gltf text naming the buffer file `binName` (written by the caller).
    std::string external(const std::string& binName) const {
        json d = doc;
        d["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", binName}}});
        return d.dump(1);
    }
    /// The binary container (.glb): header, JSON chunk, BIN chunk.
    std::string glb() const {
        json d = doc;
        d["buffers"] = json::array({{{"byteLength", bin.size()}}});
        std::string text = d.dump();
        while (text.size() % 4 != 0) text += ' ';
        std::string data = bin;
        while (data.size() % 4 != 0) data += '\0';
        std::string out = "glTF";
        putBinary(out, uint32_t(2), false);
        putBinary(out, uint32_t(12 + 8 + text.size() + 8 + data.size()), false);
        putBinary(out, uint32_t(text.size()), false);
        out += "JSON";
        out += text;
        putBinary(out, uint32_t(data.size()), false);
        out += std::string("BIN\0", 4);
        out += data;
        return out;
    }
};

// ---- PLY ------------------------------------------------------------------------------

// A unit quad in the plane z = 1 facing +z, and a triangle facing -y. Their PLY has
// normals that point the other way, and colours: the reader must ignore both (the front is
// the counter-clockwise side, whatever the file's normals say).
const char* const kPlyAscii =
    "ply\n"
    "format ascii 1.0\n"
    "comment normals deliberately opposite to the winding\n"
    "element vertex 7\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "element face 2\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 1 0 0 -1 255 0 0\n"
    "1 0 1 0 0 -1 255 0 0\n"
    "1 1 1 0 0 -1 255 0 0\n"
    "0 1 1 0 0 -1 255 0 0\n"
    "0 2 0 0 1 0 0 255 0\n"
    "1 2 0 0 1 0 0 255 0\n"
    "0.5 2 0.75 0 1 0 0 255 0\n"
    "4 0 1 2 3\n"
    "3 4 5 6\n";

TEST(PlyReader, AsciiPositionsWindingAndObjectName) {
    TempDir dir;
    const MeshFile m = readMesh(dir.write("Scan_01.ply", kPlyAscii));
    const ObjFile& obj = m.geometry;
    // PLY names nothing: one object, named after the file's stem.
    ASSERT_EQ(obj.objects, std::vector<std::string>{"Scan_01"});
    ASSERT_EQ(obj.faces.size(), 2u);
    // The quad stays a quad (no triangulation): the same polygons as an OBJ quad.
    const std::vector<Vec3> quad = corners(obj, 0);
    ASSERT_EQ(quad.size(), 4u);
    const Vec3 expectedQuad[4] = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (size_t i = 0; i < 4; ++i) expectNear(quad[i], expectedQuad[i], 0);
    expectNear(frontNormal(quad), Vec3(0, 0, 1));  // not the file's (0, 0, -1)
    const std::vector<Vec3> tri = corners(obj, 1);
    ASSERT_EQ(tri.size(), 3u);
    expectNear(tri[0], Vec3(0, 2, 0), 0);
    expectNear(tri[1], Vec3(1, 2, 0), 0);
    expectNear(tri[2], Vec3(0.5, 2, 0.75), 0);
    expectNear(frontNormal(tri), Vec3(0, -1, 0));
    EXPECT_EQ(obj.faces[0].object, 0);
    EXPECT_EQ(obj.faces[1].object, 0);
    EXPECT_TRUE(obj.warnings.empty());
    EXPECT_EQ(m.files, std::vector<fs::path>{dir.path() / "Scan_01.ply"});
}

// A small non-symmetric mesh: a quad, a triangle and a pentagon, with coordinates that
// are not round in binary.
Mesh sampleMesh() {
    Mesh m;
    m.positions = {{0.1, 0.2, 0.3}, {1.7, 0.2, 0.3}, {1.7, 2.9, 0.3},    {0.1, 2.9, 0.3},
                   {-3, 1e-3, 2.5}, {-2, 1e-3, 2.5}, {-2.5, 1e-3, 3.25}, {5, 5, 5},
                   {6, 5, 5},       {6.5, 6, 5},     {5.5, 7, 5},        {4.5, 6, 5}};
    m.faces = {{0, 1, 2, 3}, {4, 6, 5}, {7, 8, 9, 10, 11}};
    return m;
}

void expectSameAsSample(const ObjFile& obj) {
    const Mesh sample = sampleMesh();
    ASSERT_EQ(obj.faces.size(), sample.faces.size());
    for (size_t f = 0; f < sample.faces.size(); ++f) {
        const std::vector<Vec3> c = corners(obj, f);
        ASSERT_EQ(c.size(), sample.faces[f].size()) << "face " << f;
        for (size_t i = 0; i < c.size(); ++i) {
            const Vec3& p = sample.positions[static_cast<size_t>(sample.faces[f][i])];
            // Assimp keeps coordinates as float, even from PLY doubles.
            const Vec3 expected = toFloat(p);
            EXPECT_EQ(c[i], expected) << "face " << f << " corner " << i;
        }
    }
}

TEST(PlyReader, AsciiAndBinaryOfBothEndiannessesGiveTheSameFaces) {
    TempDir dir;
    const Mesh sample = sampleMesh();
    for (bool doubles : {false, true}) {
        for (PlyFormat format : {PlyFormat::ascii, PlyFormat::binaryLittle, PlyFormat::binaryBig}) {
            SCOPED_TRACE("format " + std::to_string(static_cast<int>(format)) +
                         (doubles ? " double" : " float"));
            const ObjFile obj =
                readMesh(dir.write("sample.ply", writePly(sample, format, doubles))).geometry;
            expectSameAsSample(obj);
            EXPECT_EQ(obj.objects, std::vector<std::string>{"sample"});
        }
    }
}

TEST(PlyReader, ExtensionIsCaseInsensitive) {
    TempDir dir;
    const ObjFile obj = readMesh(dir.write("ROOM.PLY", kPlyAscii)).geometry;
    EXPECT_EQ(obj.faces.size(), 2u);
    EXPECT_EQ(obj.objects, std::vector<std::string>{"ROOM"});
}

// ---- glTF -----------------------------------------------------------------------------

// A unit right triangle in z = 0, counter-clockwise seen from +z.
Mesh unitTriangle() {
    return {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}};
}

/// Every face of `obj` that belongs to object `name`, as corner lists.
std::vector<std::vector<Vec3>> facesOf(const ObjFile& obj, const std::string& name) {
    std::vector<std::vector<Vec3>> out;
    for (size_t f = 0; f < obj.faces.size(); ++f)
        if (obj.objects.at(static_cast<size_t>(obj.faces[f].object)) == name)
            out.push_back(corners(obj, f));
    return out;
}

/// A scene exercising node names and transforms:
///   "Plain"    the triangle as it is;
///   "Parent"   translation (10, 0, 0), scale 2, no mesh, with child
///   "Child"    rotation 90 degrees about +x, the triangle: world = T S R;
///   "Mirror"   scale (-1, 1, 1), translation (0, 0, 5): the triangle mirrored, whose front
///              by glTF's rule stays the +z side;
///   "Matrix"   a column-major `matrix` translating by (0, 7, 0);
///   unnamed    the mesh "NamedMesh" under a node without a name: named after the mesh.
Gltf transformScene() {
    Gltf g;
    const int tri = g.addMesh("Tri", unitTriangle());
    const int named = g.addMesh("NamedMesh", unitTriangle());
    g.addNode({{"name", "Plain"}, {"mesh", tri}});
    const int child = g.addNode(
        {{"name", "Child"}, {"mesh", tri}, {"rotation", {std::sqrt(0.5), 0, 0, std::sqrt(0.5)}}},
        false);
    g.addNode({{"name", "Parent"},
               {"translation", {10, 0, 0}},
               {"scale", {2, 2, 2}},
               {"children", {child}}});
    g.addNode(
        {{"name", "Mirror"}, {"mesh", tri}, {"scale", {-1, 1, 1}}, {"translation", {0, 0, 5}}});
    g.addNode({{"name", "Matrix"},
               {"mesh", tri},
               {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 7, 0, 1}}});
    g.addNode({{"mesh", named}});
    return g;
}

void expectTransformScene(const ObjFile& obj) {
    const auto plain = facesOf(obj, "Plain");
    ASSERT_EQ(plain.size(), 1u);
    expectNear(plain[0][0], Vec3(0, 0, 0));
    expectNear(plain[0][1], Vec3(1, 0, 0));
    expectNear(plain[0][2], Vec3(0, 1, 0));
    expectNear(frontNormal(plain[0]), Vec3(0, 0, 1));

    // Child: R maps (x, y, z) to (x, -z, y); then scale 2, then translate by (10, 0, 0).
    const auto child = facesOf(obj, "Child");
    ASSERT_EQ(child.size(), 1u);
    expectNear(child[0][0], Vec3(10, 0, 0));
    expectNear(child[0][1], Vec3(12, 0, 0));
    expectNear(child[0][2], Vec3(10, 0, 2));
    expectNear(frontNormal(child[0]), Vec3(0, -1, 0));  // +z rotated about +x by 90 degrees
    EXPECT_TRUE(facesOf(obj, "Parent").empty());        // no mesh, no object

    // Mirror: the corners are mirrored in x; their order is reversed so that the front
    // (counter-clockwise side) is the glTF front, still +z.
    const auto mirror = facesOf(obj, "Mirror");
    ASSERT_EQ(mirror.size(), 1u);
    ASSERT_EQ(mirror[0].size(), 3u);
    expectNear(mirror[0][0], Vec3(0, 1, 5));
    expectNear(mirror[0][1], Vec3(-1, 0, 5));
    expectNear(mirror[0][2], Vec3(0, 0, 5));
    expectNear(frontNormal(mirror[0]), Vec3(0, 0, 1));

    const auto matrix = facesOf(obj, "Matrix");
    ASSERT_EQ(matrix.size(), 1u);
    expectNear(matrix[0][0], Vec3(0, 7, 0));
    expectNear(matrix[0][2], Vec3(0, 8, 0));

    ASSERT_EQ(facesOf(obj, "NamedMesh").size(), 1u);
    EXPECT_EQ(obj.faces.size(), 5u);
    EXPECT_EQ(obj.objects.size(), 5u);
}

TEST(GltfReader, NodeNamesAndTransformsEmbeddedBuffer) {
    TempDir dir;
    const MeshFile m = readMesh(dir.write("scene.gltf", transformScene().embedded()));
    expectTransformScene(m.geometry);
    EXPECT_EQ(m.files, std::vector<fs::path>{dir.path() / "scene.gltf"});
}

TEST(GltfReader, ExternalBufferIsReadAndListedAmongTheFiles) {
    TempDir dir;
    const Gltf g = transformScene();
    dir.write("scene.bin", g.bin);
    const MeshFile m = readMesh(dir.write("scene.gltf", g.external("scene.bin")));
    expectTransformScene(m.geometry);
    // A cache keyed on the .gltf alone would miss a change to its buffer.
    ASSERT_EQ(m.files.size(), 2u);
    EXPECT_EQ(m.files[0], dir.path() / "scene.gltf");
    EXPECT_EQ(m.files[1].filename(), "scene.bin");
}

TEST(GltfReader, BinaryGlb) {
    TempDir dir;
    const MeshFile m = readMesh(dir.write("scene.glb", transformScene().glb()));
    expectTransformScene(m.geometry);
}

TEST(GltfReader, MeshUsedByTwoNodesAndNodesSharingAName) {
    TempDir dir;
    Gltf g;
    const int tri = g.addMesh("Tri", unitTriangle());
    g.addNode({{"name", "chair"}, {"mesh", tri}, {"translation", {0, 0, 1}}});
    g.addNode({{"name", "chair"}, {"mesh", tri}, {"translation", {0, 0, 2}}});
    g.addNode({{"name", "table"}, {"mesh", tri}, {"translation", {0, 0, 3}}});
    const ObjFile obj = readMesh(dir.write("s.gltf", g.embedded())).geometry;
    // One copy per node; nodes of the same name are one object (as OBJ's `o` blocks).
    EXPECT_EQ(obj.objects, (std::vector<std::string>{"chair", "table"}));
    const auto chair = facesOf(obj, "chair");
    ASSERT_EQ(chair.size(), 2u);
    EXPECT_NE(chair[0][0].z, chair[1][0].z);
    EXPECT_EQ(facesOf(obj, "table").at(0)[0].z, 3);
}

TEST(GltfReader, LightsInTheFileAreIgnoredWithAWarning) {
    TempDir dir;
    Gltf g = transformScene();
    g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    g.doc["extensions"] = {
        {"KHR_lights_punctual",
         {{"lights", json::array({{{"type", "point"}, {"name", "bulb"}, {"intensity", 5}}})}}}};
    g.addNode({{"name", "bulbNode"}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    const ObjFile obj = readMesh(dir.write("lit.gltf", g.embedded())).geometry;
    EXPECT_EQ(obj.faces.size(), 5u);
    ASSERT_EQ(obj.warnings.size(), 1u);
    EXPECT_TRUE(contains(obj.warnings[0], "lit.gltf: 1 light(s) in the file ignored"))
        << obj.warnings[0];
}

// ---- the room in three formats --------------------------------------------------------

/// The bundled room's OBJ with its coordinates rounded to float (glTF stores floats and
/// Assimp reads PLY as float), so that every format holds exactly the same numbers.
ObjFile floatRoom() {
    ObjFile obj = relight::readObj(kRoom / "room.obj");
    for (Vec3& p : obj.positions) p = toFloat(p);
    return obj;
}

/// Object `o` of `obj` as a Mesh (its faces, the vertices they use renumbered).
Mesh objectMesh(const ObjFile& obj, int o, bool triangulate) {
    Mesh m;
    std::map<int, int> index;
    for (const auto& f : obj.faces) {
        if (f.object != o) continue;
        std::vector<int> face;
        for (int v : f.vertices) {
            auto [it, inserted] = index.emplace(v, static_cast<int>(m.positions.size()));
            if (inserted) m.positions.push_back(obj.positions[static_cast<size_t>(v)]);
            face.push_back(it->second);
        }
        if (triangulate && face.size() > 3) {
            for (size_t i = 1; i + 1 < face.size(); ++i)
                m.faces.push_back({face[0], face[i], face[i + 1]});
        } else {
            m.faces.push_back(face);
        }
    }
    return m;
}

/// An OBJ text of `obj`'s objects, optionally triangulated like objectMesh().
std::string writeObj(const ObjFile& obj, bool triangulate) {
    std::ostringstream s;
    s.precision(17);
    int base = 1;
    for (size_t o = 0; o < obj.objects.size(); ++o) {
        const Mesh m = objectMesh(obj, static_cast<int>(o), triangulate);
        s << "o " << obj.objects[o] << "\n";
        for (const Vec3& p : m.positions) s << "v " << p.x << " " << p.y << " " << p.z << "\n";
        for (const auto& f : m.faces) {
            s << "f";
            for (int v : f) s << " " << v + base;
            s << "\n";
        }
        base += static_cast<int>(m.positions.size());
    }
    return s.str();
}

/// A copy of the room's scene.json whose geometry is `files`, in folder `dir`.
void writeRoomScene(const TempDir& dir, const std::vector<std::string>& files) {
    std::ifstream in(kRoom / "scene.json");
    json scene = json::parse(in);
    scene["geometry"] = files;
    scene.erase("photos");  // the geometry is what is compared; photos stay in data/room
    dir.write("scene.json", scene.dump(1));
}

void expectSamePolygons(const SceneFile& a, const SceneFile& b) {
    ASSERT_EQ(a.scene.polygons.size(), b.scene.polygons.size());
    for (size_t i = 0; i < a.scene.polygons.size(); ++i) {
        SCOPED_TRACE("polygon " + std::to_string(i));
        const radiosity::Polygon& p = a.scene.polygons[i];
        const radiosity::Polygon& q = b.scene.polygons[i];
        ASSERT_EQ(p.vertexCount, q.vertexCount);
        for (int k = 0; k < p.vertexCount; ++k) EXPECT_EQ(p.v[k], q.v[k]) << "corner " << k;
        EXPECT_EQ(p.normal, q.normal);
        EXPECT_EQ(p.area, q.area);
        EXPECT_EQ(a.scene.objects.at(static_cast<size_t>(p.object)),
                  b.scene.objects.at(static_cast<size_t>(q.object)));
        EXPECT_EQ(p.rho, q.rho);
        EXPECT_EQ(p.light, q.light);
    }
    EXPECT_EQ(a.scene.lights.size(), b.scene.lights.size());
}

TEST(RoomFormats, PlyPerObjectGivesTheSamePolygonsAsObj) {
    const ObjFile room = floatRoom();
    TempDir objDir, plyAscii, plyBinary;
    objDir.write("room.obj", writeObj(room, false));
    writeRoomScene(objDir, {"room.obj"});
    // PLY names no objects: one file per object, named after it, keeps the names (and so
    // scene.json's per-object reflectance).
    std::vector<std::string> files;
    for (size_t o = 0; o < room.objects.size(); ++o) {
        const Mesh m = objectMesh(room, static_cast<int>(o), false);
        const std::string file = room.objects[o] + ".ply";
        plyAscii.write(file, writePly(m, PlyFormat::ascii));
        plyBinary.write(file, writePly(m, PlyFormat::binaryLittle));
        files.push_back(file);
    }
    writeRoomScene(plyAscii, files);
    writeRoomScene(plyBinary, files);

    const SceneFile fromObj = relight::loadScene(objDir.path());
    // 43 quads less the 4 table legs' tops inside the table top (radiosity/buried.h), 4 lamps.
    ASSERT_EQ(fromObj.scene.polygons.size(), 43u - 4u + 4u);
    // The float-rounded room is the bundled room within float precision.
    const SceneFile bundled = relight::loadScene(kRoom);
    ASSERT_EQ(bundled.scene.polygons.size(), fromObj.scene.polygons.size());
    for (size_t i = 0; i < bundled.scene.polygons.size(); ++i)
        expectNear(bundled.scene.polygons[i].v[2], fromObj.scene.polygons[i].v[2], 1e-6);

    for (const TempDir* dir : {&plyAscii, &plyBinary}) {
        const SceneFile fromPly = relight::loadScene(dir->path());
        expectSamePolygons(fromObj, fromPly);
        EXPECT_TRUE(fromPly.warnings.empty());
        EXPECT_EQ(fromPly.geometryFiles.size(), room.objects.size());
    }
}

TEST(RoomFormats, GltfAndGlbGiveTheSamePolygonsAsTheObjTriangulatedAlike) {
    const ObjFile room = floatRoom();
    // glTF holds triangles: its room is compared with the same triangles read from OBJ.
    TempDir objDir, gltfDir, glbDir;
    objDir.write("room.obj", writeObj(room, true));
    writeRoomScene(objDir, {"room.obj"});
    Gltf g;
    for (size_t o = 0; o < room.objects.size(); ++o) {
        const int mesh =
            g.addMesh(room.objects[o] + "_mesh", objectMesh(room, static_cast<int>(o), true));
        g.addNode({{"name", room.objects[o]}, {"mesh", mesh}});
    }
    gltfDir.write("room.bin", g.bin);
    gltfDir.write("room.gltf", g.external("room.bin"));
    writeRoomScene(gltfDir, {"room.gltf"});
    glbDir.write("room.glb", g.glb());
    writeRoomScene(glbDir, {"room.glb"});

    const SceneFile fromObj = relight::loadScene(objDir.path());
    ASSERT_EQ(fromObj.scene.polygons.size(), 2u * (43u - 4u) + 4u);  // as above, in triangles
    const SceneFile fromGltf = relight::loadScene(gltfDir.path());
    expectSamePolygons(fromObj, fromGltf);
    EXPECT_TRUE(fromGltf.warnings.empty());
    // The buffer is among the scene's files (the prepared cache keys on them).
    ASSERT_EQ(fromGltf.geometryFiles.size(), 2u);
    EXPECT_EQ(fromGltf.geometryFiles[1].filename(), "room.bin");
    expectSamePolygons(fromObj, relight::loadScene(glbDir.path()));

    // And the triangles cover the bundled room's quads: same objects, same area each.
    const SceneFile bundled = relight::loadScene(kRoom);
    EXPECT_EQ(bundled.scene.objects, fromGltf.scene.objects);
    std::vector<double> areaA(bundled.scene.objects.size()), areaB(areaA.size());
    for (const auto& p : bundled.scene.polygons) areaA[static_cast<size_t>(p.object)] += p.area;
    for (const auto& p : fromGltf.scene.polygons) areaB[static_cast<size_t>(p.object)] += p.area;
    for (size_t o = 0; o < areaA.size(); ++o) EXPECT_NEAR(areaA[o], areaB[o], 1e-5 * areaA[o]);
}

TEST(RoomFormats, EditLoaderTakesAPlyObject) {
    TempDir dir;
    // A 1 m cube's bottom and top (facing down and up), as PLY.
    Mesh box;
    box.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    box.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}};
    dir.write("box.ply", writePly(box, PlyFormat::binaryLittle));
    dir.write("edit.json", R"({"format": "relight-edit/1", "add_objects": [
        {"name": "box", "file": "box.ply", "reflectance": [0.5, 0.5, 0.5],
         "transform": [[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]]}]})");
    const SceneFile room = relight::loadScene(kRoom);
    const relight::EditFile edit = relight::loadEdit(dir.path() / "edit.json", room);
    ASSERT_EQ(edit.addObjects.size(), 1u);
    const auto& polys = edit.addObjects[0].polygons;
    ASSERT_EQ(polys.size(), 2u);
    EXPECT_EQ(polys[0].vertexCount, 4);
    expectNear(polys[0].normal, Vec3(0, 0, -1));
    expectNear(polys[1].normal, Vec3(0, 0, 1));
    expectNear(polys[1].v[0], Vec3(1, 1, 1));
}

// ---- repairs: the same as for OBJ faces -----------------------------------------------

TEST(PlyReader, RepairsAreThoseOfObjFacesAndNameTheFace) {
    TempDir dir;
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},   {0, 1, 0},   // a good quad
                   {0, 0, 1}, {1, 0, 1}, {2, 0, 1},                // collinear: degenerate
                   {0, 0, 2}, {1, 0, 2}, {1, 1, 2.5}, {0, 1, 2}};  // non-planar quad
    m.faces = {{0, 1, 2, 3}, {4, 5, 6}, {7, 8, 9, 10}};
    const fs::path file = dir.write("bad.ply", writePly(m, PlyFormat::ascii));
    // The same faces as OBJ, loaded into a scene through the same code.
    dir.write("bad.obj",
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 2 0 1\n"
              "v 0 0 2\nv 1 0 2\nv 1 1 2.5\nv 0 1 2\nf 1 2 3 4\nf 5 6 7\nf 8 9 10 11\n");
    std::map<std::string, std::vector<std::string>> warnings;
    std::map<std::string, size_t> polygons;
    for (const std::string name : {"bad.ply", "bad.obj"}) {
        const ObjFile obj = readMesh(dir.path() / name).geometry;
        radiosity::Scene scene;
        scene.objects.push_back("bad");
        const std::vector<int> toObject(obj.objects.size(), 0);
        relight::addObjFaces(
            obj, toObject, [](int) { return radiosity::Rgb::gray(0.5); }, scene, warnings[name]);
        polygons[name] = scene.polygons.size();
    }
    EXPECT_EQ(polygons["bad.ply"], polygons["bad.obj"]);
    EXPECT_EQ(polygons["bad.ply"], 3u);  // the quad, the non-planar quad's two halves
    ASSERT_EQ(warnings["bad.ply"].size(), 2u);
    ASSERT_EQ(warnings["bad.obj"].size(), 2u);
    EXPECT_EQ(warnings["bad.ply"][0],
              file.string() + ": face 2: degenerate face (zero area or repeated vertices) dropped");
    EXPECT_EQ(warnings["bad.obj"][0], (dir.path() / "bad.obj").string() +
                                          ":13: degenerate face (zero area or repeated "
                                          "vertices) dropped");
    // The same message after the location.
    const auto tail = [](const std::string& w) { return w.substr(w.find(": face")); };
    EXPECT_TRUE(contains(warnings["bad.ply"][1], file.string() + ": face 3: "));
    EXPECT_TRUE(contains(warnings["bad.ply"][1], "quad split into 2 triangles"));
    EXPECT_EQ(warnings["bad.ply"][1].substr(warnings["bad.ply"][1].find("face 3: ") + 8),
              warnings["bad.obj"][1].substr(warnings["bad.obj"][1].find(":14: ") + 5));
    (void)tail;
}

TEST(GltfReader, DegenerateTriangleNamesMeshNodeAndFace) {
    TempDir dir;
    Gltf g;
    Mesh m = unitTriangle();
    m.positions.push_back({2, 0, 0});
    m.faces.push_back({0, 1, 3});  // collinear
    g.addNode({{"name", "shelf"}, {"mesh", g.addMesh("Shelf_mesh", m)}});
    const fs::path file = dir.write("d.gltf", g.embedded());
    const ObjFile obj = readMesh(file).geometry;
    radiosity::Scene scene;
    scene.objects.push_back("shelf");
    std::vector<std::string> warnings;
    relight::addObjFaces(
        obj, std::vector<int>{0}, [](int) { return radiosity::Rgb::gray(0.5); }, scene, warnings);
    EXPECT_EQ(scene.polygons.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], file.string() +
                               ": mesh \"Shelf_mesh\" of node \"shelf\" face 2: degenerate face "
                               "(zero area or repeated vertices) dropped");
}

// ---- bad input: an InputError naming the file, never a crash --------------------------

TEST(MeshReaderErrors, UnknownExtensionNamesTheFileAndTheFormats) {
    TempDir dir;
    for (const std::string name : {"room.fbx", "room", "room.stl"}) {
        const fs::path file = dir.write(name, kPlyAscii);
        const std::string msg = readError(file);
        EXPECT_TRUE(contains(msg, file.string() + ": unknown geometry format")) << msg;
        EXPECT_TRUE(contains(msg, ".obj, .ply, .gltf, .glb")) << msg;
    }
}

TEST(MeshReaderErrors, MissingFileAndDirectory) {
    TempDir dir;
    std::string msg = readError(dir.path() / "none.ply");
    EXPECT_TRUE(contains(msg, (dir.path() / "none.ply").string() + ": geometry file not found"))
        << msg;
    fs::create_directories(dir.path() / "dir.gltf");
    msg = readError(dir.path() / "dir.gltf");
    EXPECT_TRUE(contains(msg, (dir.path() / "dir.gltf").string() + ": is a directory")) << msg;
}

TEST(MeshReaderErrors, ADeviceIsNotReadWithoutEnd) {
    // A file that is a link to a device (or a pipe) never ends: reading it as an OBJ, PLY or
    // glTF would hang. It is refused by name, as are scene.json, an edit or a photo.
    TempDir dir;
    for (const std::string name : {"zero.obj", "zero.ply", "zero.gltf"}) {
        const fs::path link = dir.path() / name;
        fs::create_symlink("/dev/zero", link);
        const std::string msg = readError(link);
        EXPECT_TRUE(contains(msg, link.string() + ": is not a regular file")) << msg;
    }
    const fs::path sceneJson = dir.path() / "scene.json";
    fs::create_symlink("/dev/zero", sceneJson);
    try {
        (void)relight::jsonio::parseJsonFile(sceneJson);
        ADD_FAILURE() << "a device was read as JSON";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), sceneJson.string() + ": is not a regular file")) << e.what();
    }
    const fs::path photo = dir.path() / "photo.exr";
    fs::create_symlink("/dev/zero", photo);
    try {
        (void)relight::readImage(photo, false);
        ADD_FAILURE() << "a device was read as an image";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), photo.string() + ": is not a regular file")) << e.what();
    }
}

TEST(MeshReaderErrors, CoordinatesThatOverflowAreAnErrorNamingTheLine) {
    // Finite, but their products overflow: the face's normal came out NaN and passed.
    TempDir dir;
    const fs::path file = dir.write("huge.obj", "v 0 0 0\nv 1e154 0 0\nv 1e154 1e154 0\nf 1 2 3\n");
    const ObjFile obj = readMesh(file).geometry;
    radiosity::Scene scene;
    scene.objects.push_back("huge");
    std::vector<std::string> warnings;
    try {
        relight::addObjFaces(
            obj, std::vector<int>{0}, [](int) { return radiosity::Rgb::gray(0.5); }, scene,
            warnings);
        ADD_FAILURE() << "a face whose normal overflows was accepted";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), file.string() + ":4:")) << e.what();
        EXPECT_TRUE(contains(e.what(), "beyond +-1e12")) << e.what();
    }
}

TEST(MeshReaderErrors, TruncatedPly) {
    // Assimp 5.2 alone returns part of a cut ASCII body as a mesh, and loops forever on a
    // file cut inside its header: the reader's own structure check must catch each.
    TempDir dir;
    const std::string binary = writePly(sampleMesh(), PlyFormat::binaryLittle);
    const std::string ascii = writePly(sampleMesh(), PlyFormat::ascii);
    const size_t binaryBody = binary.find("end_header\n") + 11;
    const size_t asciiBody = ascii.find("end_header\n") + 11;
    const std::string cut = ": the PLY file is cut short: it ends in element ";
    // 12 vertices of 12 bytes; faces of 1 + 4n bytes; ASCII faces one per line.
    const std::map<std::string, std::pair<std::string, std::string>> cases = {
        {"binary_in_faces.ply", {binary.substr(0, binary.size() - 10), cut + "\"face\" 3 of 3"}},
        {"binary_in_vertices.ply", {binary.substr(0, binaryBody + 20), cut + "\"vertex\" 2 of 12"}},
        {"ascii_in_vertices.ply", {ascii.substr(0, asciiBody + 30), cut + "\"vertex\" "}},
        {"ascii_in_faces.ply", {ascii.substr(0, ascii.size() - 12), cut + "\"face\" 3 of 3"}},
        {"header_only.ply",
         {ascii.substr(0, 60), ": the PLY header has no end_header line (cut short?)"}},
    };
    for (const auto& [name, test] : cases) {
        const fs::path file = dir.write(name, test.first);
        const std::string msg = readError(file);
        EXPECT_TRUE(contains(msg, file.string() + test.second)) << name << ": " << msg;
    }
    // A bad number in the body names its line: the header has 11 lines, then vertices.
    std::string bad = ascii;
    bad.replace(asciiBody, bad.find(' ', asciiBody) - asciiBody, "0,1");  // the first x
    const fs::path file = dir.write("comma.ply", bad);
    EXPECT_EQ(readError(file), file.string() + ":11: bad number \"0,1\" in PLY element \"vertex\"");
}

TEST(MeshReaderErrors, GltfWithAMissingBuffer) {
    TempDir dir;
    const fs::path file = dir.write("room.gltf", transformScene().external("room.bin"));
    const std::string msg = readError(file);
    EXPECT_TRUE(contains(msg, file.string() + ": cannot read this glTF file: ")) << msg;
    EXPECT_TRUE(contains(msg, "room.bin")) << msg;  // Assimp's message names the buffer
}

TEST(MeshReaderErrors, CorruptGltfAndGlb) {
    TempDir dir;
    for (const auto& [name, text] :
         std::map<std::string, std::string>{{"syntax.gltf", "{\"asset\": {\"version\": "},
                                            {"notjson.gltf", "hello"},
                                            {"short.glb", transformScene().glb().substr(0, 40)},
                                            {"empty.glb", ""}}) {
        const fs::path file = dir.write(name, text);
        const std::string msg = readError(file);
        EXPECT_TRUE(contains(msg, file.string() + ": ")) << msg;
    }
}

TEST(MeshReaderErrors, NaNVertex) {
    TempDir dir;
    Mesh m = sampleMesh();
    m.positions[5].y = std::numeric_limits<double>::quiet_NaN();
    for (PlyFormat format : {PlyFormat::binaryLittle, PlyFormat::ascii}) {
        const fs::path file = dir.write("nan.ply", writePly(m, format));
        const std::string msg = readError(file);
        EXPECT_TRUE(contains(msg, file.string() + ": vertex 6 ")) << msg;
        EXPECT_TRUE(contains(msg, "is not finite")) << msg;
    }
    Gltf g;
    Mesh t = unitTriangle();
    t.positions[1].x = std::numeric_limits<double>::infinity();
    g.addNode({{"name", "n"}, {"mesh", g.addMesh("m", t)}});
    g.doc["accessors"][0].erase("min");  // the bounds would be infinite too
    g.doc["accessors"][0].erase("max");
    const fs::path file = dir.write("inf.glb", g.glb());
    const std::string msg = readError(file);
    EXPECT_TRUE(contains(msg, file.string() + ": mesh \"m\" of node \"n\" vertex 2 ")) << msg;
}

TEST(MeshReaderErrors, TransformThatOverflowsIsNotFinite) {
    // Transforms are composed in double: it takes a deep chain of 1e38 scales (float's
    // limit) to overflow, and then the vertices are not finite.
    TempDir dir;
    Gltf g;
    const int mesh = g.addMesh("m", unitTriangle());
    int child =
        g.addNode({{"name", "deepest"}, {"mesh", mesh}, {"scale", {1e38, 1e38, 1e38}}}, false);
    for (int k = 0; k < 8; ++k)
        child = g.addNode({{"name", "level" + std::to_string(k)},
                           {"scale", {1e38, 1e38, 1e38}},
                           {"children", {child}}},
                          k == 7);
    const fs::path file = dir.write("huge.gltf", g.embedded());
    const std::string msg = readError(file);
    EXPECT_TRUE(
        contains(msg, file.string() + ": mesh \"m\" of node \"deepest\" vertex 1 (0, 0, 0)"))
        << msg;
    EXPECT_TRUE(contains(msg, "not finite once its node's transform is applied")) << msg;
}

TEST(MeshReaderErrors, EmptyMeshesAndPointClouds) {
    TempDir dir;
    // No vertices, no faces.
    Mesh empty;
    fs::path file = dir.write("empty.ply", writePly(empty, PlyFormat::ascii));
    std::string msg = readError(file);
    EXPECT_EQ(msg, file.string() + ": no faces in this PLY file");
    // A photogrammetry point cloud: vertices only.
    Mesh cloud;
    cloud.positions = sampleMesh().positions;
    file = dir.write("cloud.ply", writePly(cloud, PlyFormat::binaryLittle));
    msg = readError(file);
    EXPECT_EQ(msg, file.string() +
                       ": no faces in this PLY file (only 12 vertices: a point cloud has no "
                       "surfaces; mesh it first)");
    // A glTF with nodes but no mesh.
    Gltf g;
    g.addNode({{"name", "lonely"}});
    file = dir.write("nomesh.gltf", g.embedded());
    msg = readError(file);
    EXPECT_TRUE(contains(msg, file.string() + ": no faces")) << msg;
    // A glTF whose only primitive is lines.
    Gltf lines;
    lines.addNode({{"name", "wire"}, {"mesh", lines.addMesh("wire", unitTriangle())}});
    lines.doc["meshes"][0]["primitives"][0]["mode"] = 1;  // LINES
    lines.doc["accessors"][1]["count"] = 2;
    file = dir.write("lines.gltf", lines.embedded());
    msg = readError(file);
    EXPECT_TRUE(contains(msg, file.string() + ": no faces")) << msg;
}

TEST(MeshReaderErrors, SceneLoaderNamesTheGeometryFile) {
    TempDir dir;
    writeRoomScene(dir, {"room.ply"});
    dir.write("room.ply", writePly(sampleMesh(), PlyFormat::binaryLittle).substr(0, 300));
    try {
        relight::loadScene(dir.path());
        ADD_FAILURE() << "loadScene() accepted a truncated PLY";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), (dir.path() / "room.ply").string() + ": ")) << e.what();
    }
    writeRoomScene(dir, {"room.fbx"});
    dir.write("room.fbx", "whatever");
    try {
        relight::loadScene(dir.path());
        ADD_FAILURE() << "loadScene() accepted an FBX";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(
            e.what(), (dir.path() / "room.fbx").string() + ": unknown geometry format \".fbx\""))
            << e.what();
    }
}

}  // namespace
