// Geometry files of any format the scene and edit loaders take, by extension:
//   .obj           the strict OBJ reader (relight/io/obj_reader.h), messages "FILE:LINE: ..."
//   .ply           Assimp: one object named after the file's stem (PLY has no names)
//   .gltf, .glb    Assimp: one object per node (its name; failing that its mesh's name,
//                  failing that the file's stem); nodes of the same name are one object
// Anything else is an InputError naming the file. The result has the same shape as an OBJ
// file's (named objects with their faces), so faces are checked and repaired by the same
// code (relight/io/face_repair.h), with the same messages; where a message would name a line
// it names the mesh and the face's number in it instead ("room.glb: mesh "Table" of node
// "table" face 12: degenerate face ... dropped").
//
// What is kept as the file has it, on purpose:
//   - winding: a face's front is the side from which its vertices run counter-clockwise
//     (scene format, "geometry"). Nothing may generate or flip normals or "fix" winding: a
//     room's walls are seen from inside, which a normal-fixing heuristic gets wrong. The
//     one exception is the glTF spec's own rule: a node whose world transform mirrors
//     (negative determinant) has clockwise front faces, so their order is reversed.
//   - polygons: PLY faces with 4 or more corners stay polygons (not Assimp's
//     triangulation), so a quad room in PLY gives the same polygons as in OBJ and
//     non-planar or non-convex faces get the documented repairs and warnings. glTF holds
//     triangles only.
//   - units: metres. glTF is in metres by its spec; PLY has no units, its numbers are
//     taken as metres. No axis is changed (glTF's +Y up stays +Y: the scene format assumes
//     no "up").
// glTF node transforms are applied (the node tree is walked; a mesh used by several nodes
// gives one copy per node). Points and lines (a point cloud, glTF LINES/POINTS
// primitives) are ignored with a warning; a file with no face at all, non-finite
// coordinates, or a file Assimp cannot read (its message included) is an InputError naming
// the file. Lamps and cameras inside a glTF are ignored with a warning: the scene's lights
// and camera are described in scene.json.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "relight/io/obj_reader.h"

namespace relight {

/// What readMesh() read: the faces, and every file they came from.
struct MeshFile {
    ObjFile geometry;
    /// The file itself, then any other file the reader opened (a .gltf's .bin buffers),
    /// each once: what a cache of the scene must key on (relight/io/prepared_cache.h).
    std::vector<std::filesystem::path> files;
};

/// The extensions readMesh() takes, lower case with the dot: ".obj", ".ply", ...
const std::vector<std::string>& meshExtensions();

/// Reads a geometry file by its extension (case-insensitive). Throws InputError naming
/// the file.
MeshFile readMesh(const std::filesystem::path& path);

}  // namespace relight
