#include "radiosity/scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace radiosity {

Vec3 Polygon::centroid() const {
    // Area centroid: fan triangles from v0, weighted by their areas.
    if (vertexCount == 3) return (v[0] + v[1] + v[2]) / 3.0;
    Vec3 c{0, 0, 0};
    double w = 0;
    for (int i = 1; i + 1 < vertexCount; ++i) {
        double a = glm::length(glm::cross(v[i] - v[0], v[i + 1] - v[0]));
        c += a * (v[0] + v[i] + v[i + 1]) / 3.0;
        w += a;
    }
    return w > 0 ? c / w : (v[0] + v[1] + v[2] + v[3]) / 4.0;
}

Bounds3 Polygon::bounds() const {
    Bounds3 b;
    for (int i = 0; i < vertexCount; ++i) b.extend(v[i]);
    return b;
}

Rgb Light::emittance() const {
    return radiance * std::numbers::pi;
}

Rgb Scene::emittance(int p) const {
    int l = polygons[p].light;
    return l < 0 ? Rgb{} : lights[l].emittance();
}

Rgb Scene::emittedPower() const {
    Rgb power;
    for (const Light& l : lights)
        for (int p : l.polygons) power += l.emittance() * polygons[p].area;
    return power;
}

Bounds3 Scene::bounds() const {
    Bounds3 b;
    for (const Polygon& p : polygons) b.extend(p.bounds());
    return b;
}

double Scene::totalArea() const {
    double a = 0;
    for (const Polygon& p : polygons) a += p.area;
    return a;
}

int Scene::findLight(const std::string& name) const {
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].name == name) return static_cast<int>(i);
    return -1;
}

int Scene::findObject(const std::string& name) const {
    for (size_t i = 0; i < objects.size(); ++i)
        if (objects[i] == name) return static_cast<int>(i);
    return -1;
}

PolygonCheck checkPolygon(const std::vector<Vec3>& corners) {
    using S = PolygonCheck::Status;
    PolygonCheck r;
    const size_t n = corners.size();
    if (n < 3) {
        r.status = S::tooFew;
        r.message = "a polygon needs at least 3 vertices, got " + std::to_string(n);
        return r;
    }
    for (const Vec3& p : corners) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            r.status = S::nonFinite;
            r.message = "vertex coordinate is NaN or infinite";
            return r;
        }
        // Beyond this the products of coordinates that areas, normals and form factors take
        // can overflow (at 1e154 the normal came out NaN and the polygon passed); no room is
        // a billion kilometres wide, whatever its unit.
        if (std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxCoordinate) {
            r.status = S::nonFinite;
            r.message = "vertex coordinate beyond +-1e12 (the scene's unit is the metre)";
            return r;
        }
    }
    // Newell's normal: robust for any planar polygon, its length is twice the area.
    Vec3 newell{0, 0, 0};
    double longest = 0;
    for (size_t i = 0; i < n; ++i) {
        const Vec3& a = corners[i];
        const Vec3& b = corners[(i + 1) % n];
        newell += glm::cross(a, b);
        longest = std::max(longest, glm::length(b - a));
    }
    const double area = 0.5 * glm::length(newell);
    if (!(longest > 0) || !(area > 1e-10 * longest * longest)) {
        r.status = S::degenerate;
        r.message = "degenerate polygon (zero area or repeated vertices)";
        return r;
    }
    const Vec3 nrm = newell / (2.0 * area);
    // Planarity: every vertex within 1e-4 * longest edge of the plane through the centroid.
    Vec3 c{0, 0, 0};
    for (const Vec3& p : corners) c += p;
    c /= static_cast<double>(n);
    for (const Vec3& p : corners) {
        double off = std::abs(glm::dot(p - c, nrm));
        if (off > 1e-4 * longest) {
            r.status = S::nonPlanar;
            r.message = "non-planar polygon: a vertex lies " + std::to_string(off) +
                        " m off the plane of the others";
            return r;
        }
    }
    // Convexity: every corner turns left about the normal.
    for (size_t i = 0; i < n; ++i) {
        const Vec3& a = corners[i];
        const Vec3& b = corners[(i + 1) % n];
        const Vec3& d = corners[(i + 2) % n];
        double turn = glm::dot(glm::cross(b - a, d - b), nrm);
        if (turn < -1e-12 * longest * longest) {
            r.status = S::nonConvex;
            r.message = "polygon is not convex";
            return r;
        }
    }
    r.normal = nrm;
    r.area = area;
    return r;
}

Polygon makePolygon(const std::vector<Vec3>& corners, int object, const Rgb& rho) {
    PolygonCheck check = checkPolygon(corners);
    Polygon p;
    p.vertexCount = static_cast<int>(std::min<size_t>(corners.size(), 4));
    for (int i = 0; i < p.vertexCount; ++i) p.v[i] = corners[i];
    p.normal = check.normal;
    p.area = check.area;
    p.object = object;
    p.rho = rho;
    return p;
}

}  // namespace radiosity
