// A small Wavefront OBJ reader for the scene format's geometry
// (docs/scene-format.md, "geometry").
//
// Hand-written rather than tinyobjloader because every error and every repair must name
// the file and the line it comes from. Only what the scene format needs is read:
//   v x y z [w | r g b]   position (extra numbers are checked, then ignored)
//   f a b c ...           face; each item is v, v/vt, v//vn or v/vt/vn: only v is used;
//                         1-based, negative = relative to the vertices read so far
//   o NAME, g NAME        objects: every `o` block is one object; a file without any `o`
//                         uses its `g` blocks instead; faces before the first block go to
//                         an object named after the file's stem
// vt vn vp s l p usemtl mtllib and comments are ignored silently (materials come from the
// photo); any other statement is ignored with a warning (one per keyword and file).
// Lines ending in a backslash continue on the next line.
//
// Errors (InputError, "FILE:LINE: ..."): unreadable file, a malformed or non-finite
// number, a face with fewer than 3 vertices, a vertex index out of range.
// The reader does not judge face shapes: loadScene() checks and repairs them.
#pragma once

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "radiosity/vec.h"
#include "relight/errors.h"

namespace relight {

struct ObjFace {
    int object = -1;            ///< index into ObjFile::objects
    std::vector<int> vertices;  ///< 0-based indices into ObjFile::positions
    /// OBJ: 1-based line of the `f` statement. Formats without lines (PLY, glTF, read by
    /// relight/io/mesh_reader.h): the face's 1-based number within its part (ObjFile::parts).
    int line = 0;
    int part = -1;  ///< index into ObjFile::parts; -1 for OBJ faces
};

/// The faces of one geometry file, as named objects. Made by readObj() for OBJ, and by
/// readMesh() (relight/io/mesh_reader.h) for every format the scene loader takes: the scene
/// and edit loaders consume this whatever the file's format was.
struct ObjFile {
    std::string name;                        ///< the file as named in messages
    std::vector<radiosity::Vec3> positions;  ///< metres
    std::vector<int> positionLines;          ///< 1-based line of each `v` (OBJ only)
    std::vector<std::string> objects;        ///< object names, in order of first appearance
    std::vector<ObjFace> faces;
    std::vector<std::string> warnings;  ///< "FILE:LINE: ..." for ignored statements
    /// Formats without lines: where each face comes from, e.g. `mesh "Chair" of node
    /// "Chair.001"`, so that a message can point into the file. Empty for OBJ.
    std::vector<std::string> parts;

    /// "NAME:LINE: " — the prefix of every message about a line of this OBJ file.
    std::string where(int line) const;
    /// The prefix of every message about `face`: where(face.line) for OBJ faces,
    /// "NAME: PART face N: " (or "NAME: face N: " for a one-part file) otherwise.
    std::string whereFace(const ObjFace& face) const;
};

/// Reads an OBJ file; messages name it as path.string(). Throws InputError.
ObjFile readObj(const std::filesystem::path& path);

/// Parses OBJ text from a stream; `name` names it in messages and its stem names the
/// default object. Throws InputError.
ObjFile parseObj(std::istream& in, const std::string& name);

}  // namespace relight
