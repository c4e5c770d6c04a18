// Faces of the scene format's geometry, checked and repaired (scene_file.h lists the
// repairs): faces read from OBJ, PLY or glTF (mesh_reader.h) go into a radiosity::Scene as
// triangles and planar convex quads, each repair reported as a warning naming the file and
// the line (OBJ) or the mesh and face number (PLY, glTF). Shared by the scene loader and the
// edit loader (virtual objects, virtual lights).
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "radiosity/scene.h"
#include "relight/io/obj_reader.h"

namespace relight {

/// Adds every face of `obj` to `scene`: face f goes to object sceneObject[f.object] with
/// reflectance reflectanceOf(that object). Repairs are appended to `warnings`; a face that
/// cannot be repaired is an InputError naming the file and line.
void addObjFaces(const ObjFile& obj, std::span<const int> sceneObject,
                 const std::function<radiosity::Rgb(int)>& reflectanceOf, radiosity::Scene& scene,
                 std::vector<std::string>& warnings);

/// Adds the emitting face of light `light` (a planar convex polygon that checkPolygon
/// accepts; fan-split beyond 4 corners) to `scene` as object `object`, reflectance 0.
/// Returns the polygons' indices.
std::vector<int> addLightFaces(const std::vector<radiosity::Vec3>& corners, int object, int light,
                               radiosity::Scene& scene);

}  // namespace relight
