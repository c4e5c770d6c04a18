// Scene: the input of the radiosity layer: planar convex polygons (triangles and quads),
// the objects they belong to, and the light sources.
//
// Units: metres for geometry. Radiosity B and emittance E are in the photo's linear
// radiance units times pi ("radiosity units"): a Lambertian surface of radiosity B shows
// radiance B / pi. Reflectance rho is per RGB channel in [0, 1).
//
// Surfaces are one-sided: a polygon reflects and receives light on its front only, the
// side from which its vertices run counter-clockwise (normal = (v1 - v0) x (v2 - v0)).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "radiosity/rgb.h"
#include "radiosity/vec.h"

namespace radiosity {

class Emitter;  // radiosity/emitter.h

/// One input polygon. Built by makePolygon(), which fills normal and area.
struct Polygon {
    std::array<Vec3, 4> v{};  ///< corners, counter-clockwise seen from the front (metres)
    int vertexCount = 0;      ///< 3 (triangle) or 4 (planar convex quad)
    Vec3 normal{0, 0, 1};     ///< unit front normal
    double area = 0;          ///< m^2
    int object = -1;          ///< index into Scene::objects
    int light = -1;           ///< index into Scene::lights when this is an emitting face, else -1
    Rgb rho;                  ///< reflectance per channel in [0, 1); 0 for emitting faces

    Vec3 centroid() const;
    Bounds3 bounds() const;
};

/// A light source: one or more emitting polygons sharing one radiance, or one component
/// of a light that is not faces (a sun, a point lamp, one of a sky's 9 coefficients).
struct Light {
    std::string name;
    std::vector<int> polygons;  ///< indices into Scene::polygons
    /// Emitted radiance, photo units; 0 when switched off. For a component of an emitter:
    /// its strength (irradiance, intensity, a sky's coefficient, which may be negative).
    Rgb radiance;
    /// A light that is not faces (radiosity/emitter.h): its shape, shared by the lights of
    /// its components (consecutive, `component` 0, 1, ...); null for emitting faces. Its
    /// direct irradiance per unit strength is emitter->unitIrradiance()[component]: every
    /// layer asks the emitter, never the light's type.
    std::shared_ptr<const Emitter> emitter{};
    int component = 0;
    /// Emittance in radiosity units: a Lambertian emitter of radiance L has E = pi L.
    Rgb emittance() const;
};

struct Scene {
    std::vector<Polygon> polygons;
    std::vector<std::string> objects;  ///< object names, indexed by Polygon::object
    std::vector<Light> lights;

    /// Emittance E of polygon p in radiosity units (0 for non-emitters).
    Rgb emittance(int p) const;
    /// Total emitted power sum(E * A) over all lights, per channel (radiosity units x m^2).
    Rgb emittedPower() const;
    Bounds3 bounds() const;
    double totalArea() const;
    int findLight(const std::string& name) const;   ///< -1 when absent
    int findObject(const std::string& name) const;  ///< -1 when absent
};

/// The largest coordinate a polygon may have, in metres (checkPolygon): the squares and
/// products of coordinates stay far from overflow.
inline constexpr double kMaxCoordinate = 1e12;

/// Result of checking a candidate polygon.
struct PolygonCheck {
    enum class Status {
        ok,          ///< planar, convex, non-degenerate
        nonFinite,   ///< a coordinate is NaN, infinite or beyond kMaxCoordinate
        tooFew,      ///< fewer than 3 vertices
        degenerate,  ///< (near) zero area or repeated vertices
        nonPlanar,   ///< a vertex lies off the plane of the others
        nonConvex,   ///< planar but not convex, or not counter-clockwise about its normal
    };
    Status status = Status::ok;
    std::string message;  ///< human-readable reason, empty when ok
    Vec3 normal{0, 0, 1};
    double area = 0;
};

/// Checks a polygon given by its corners (counter-clockwise seen from the front).
/// Tolerances are relative to the polygon's size: a vertex counts as off the plane when it
/// is farther than 1e-4 of the longest edge from it (a 0.1 mm bow on a 1 m wall), and the
/// polygon is degenerate when its area is below 1e-10 of its longest edge squared.
PolygonCheck checkPolygon(const std::vector<Vec3>& corners);

/// Builds a Polygon from 3 or 4 corners that checkPolygon() accepted.
Polygon makePolygon(const std::vector<Vec3>& corners, int object, const Rgb& rho);

}  // namespace radiosity
