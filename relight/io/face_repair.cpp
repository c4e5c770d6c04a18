#include "relight/io/face_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

namespace relight {

using radiosity::checkPolygon;
using radiosity::makePolygon;
using radiosity::PolygonCheck;
using radiosity::Rgb;
using radiosity::Vec3;

namespace {

Vec3 newellNormal(const std::vector<Vec3>& c) {
    Vec3 n{0, 0, 0};
    for (size_t i = 0; i < c.size(); ++i) n += glm::cross(c[i], c[(i + 1) % c.size()]);
    return n;  // length = twice the area
}

double longestEdge(const std::vector<Vec3>& c) {
    double longest = 0;
    for (size_t i = 0; i < c.size(); ++i)
        longest = std::max(longest, glm::length(c[(i + 1) % c.size()] - c[i]));
    return longest;
}

using Triangle = std::array<int, 3>;

/// Fan from corner 0 of a convex planar polygon.
std::vector<Triangle> fan(size_t n) {
    std::vector<Triangle> t;
    for (size_t i = 1; i + 1 < n; ++i)
        t.push_back({0, static_cast<int>(i), static_cast<int>(i + 1)});
    return t;
}

/// Ear clipping of a planar, simple, possibly non-convex polygon. For a quad it cuts along
/// the diagonal through the reflex corner, the one that keeps both halves convex. Returns
/// nothing when the polygon is self-intersecting (the triangles would not cover it once).
std::optional<std::vector<Triangle>> earClip(const std::vector<Vec3>& c) {
    const Vec3 newell = newellNormal(c);
    const double area = 0.5 * glm::length(newell);
    if (!(area > 0)) return std::nullopt;
    const Vec3 n = newell / (2 * area);
    const double longest = longestEdge(c);
    const double eps = 1e-12 * longest * longest;
    auto turn = [&](int a, int b, int d) {
        return glm::dot(glm::cross(c[b] - c[a], c[d] - c[b]), n);
    };

    std::vector<int> ring(c.size());
    for (size_t i = 0; i < c.size(); ++i) ring[i] = static_cast<int>(i);
    std::vector<Triangle> out;
    while (ring.size() > 3) {
        const size_t m = ring.size();
        bool clipped = false;
        for (size_t k = 0; k < m && !clipped; ++k) {
            const int a = ring[(k + m - 1) % m], b = ring[k], d = ring[(k + 1) % m];
            if (!(turn(a, b, d) > eps)) continue;  // reflex or straight corner: not an ear
            // No other corner inside the ear or on its border: a reflex corner touching
            // the cut a-d would leave the cut outside the polygon.
            bool empty = true;
            for (int p : ring) {
                if (p == a || p == b || p == d || c[p] == c[a] || c[p] == c[b] || c[p] == c[d])
                    continue;
                if (turn(a, b, p) >= -eps && turn(b, d, p) >= -eps && turn(d, a, p) >= -eps) {
                    empty = false;
                    break;
                }
            }
            if (!empty) continue;
            out.push_back({a, b, d});
            ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
            clipped = true;
        }
        if (!clipped) return std::nullopt;
    }
    out.push_back({ring[0], ring[1], ring[2]});
    // A simple polygon's ears add up to its area, all facing the same way.
    double sum = 0;
    for (const Triangle& t : out) {
        const Vec3 tn = glm::cross(c[t[1]] - c[t[0]], c[t[2]] - c[t[0]]);
        if (glm::dot(tn, n) < -eps) return std::nullopt;
        sum += 0.5 * glm::length(tn);
    }
    if (std::abs(sum - area) > 1e-6 * area) return std::nullopt;
    return out;
}

/// Removes consecutive repeated corners (OBJ exporters write them for collapsed edges),
/// so that no polygon has a zero-length edge. Returns how many were removed.
size_t removeRepeatedCorners(std::vector<Vec3>& c) {
    const double tol = 1e-9 * longestEdge(c);
    size_t removed = 0;
    for (size_t i = 0; i < c.size() && c.size() > 1;) {
        if (glm::length(c[(i + 1) % c.size()] - c[i]) <= tol) {
            c.erase(c.begin() + static_cast<std::ptrdiff_t>(i));
            ++removed;
        } else {
            ++i;
        }
    }
    return removed;
}

struct PolygonSink {
    radiosity::Scene& scene;
    int object;
    Rgb rho;
    int light = -1;

    /// Adds the triangles that are not degenerate (a fan over collinear corners has some);
    /// returns how many were added.
    size_t addTriangles(const std::vector<Vec3>& c, const std::vector<Triangle>& tris) {
        size_t added = 0;
        for (const Triangle& t : tris) {
            std::vector<Vec3> tri{c[t[0]], c[t[1]], c[t[2]]};
            if (checkPolygon(tri).status != PolygonCheck::Status::ok) continue;
            add(tri);
            ++added;
        }
        return added;
    }
    void add(const std::vector<Vec3>& corners) {
        radiosity::Polygon p = makePolygon(corners, object, rho);
        p.light = light;
        scene.polygons.push_back(p);
    }
};

/// Checks one face (of any format) and adds it, repaired as documented in scene_file.h.
void addFace(const ObjFile& obj, const ObjFace& face, PolygonSink& sink,
             std::vector<std::string>& warnings) {
    using S = PolygonCheck::Status;
    const std::string at = obj.whereFace(face);
    std::vector<Vec3> c;
    for (int i : face.vertices) c.push_back(obj.positions[static_cast<size_t>(i)]);
    const size_t given = c.size();
    // Coordinates so large that lengths overflow would make every corner a repeat of the
    // next: refused as they are, before the repairs measure anything.
    if (const PolygonCheck raw = checkPolygon(c); raw.status == S::nonFinite)
        throw InputError(at + raw.message);
    if (size_t removed = removeRepeatedCorners(c); removed > 0 && c.size() >= 3)
        warnings.push_back(at + "removed " + std::to_string(removed) +
                           " repeated vertex(es) from a face with " + std::to_string(given) +
                           " vertices");
    const PolygonCheck check = checkPolygon(c);
    const size_t n = c.size();
    switch (check.status) {
        case S::ok:
            if (n <= 4) {
                sink.add(c);
            } else {
                const size_t k = sink.addTriangles(c, fan(n));
                warnings.push_back(at + "convex face with " + std::to_string(n) +
                                   " vertices split into a fan of " + std::to_string(k) +
                                   " triangles");
            }
            return;
        case S::nonFinite:  // the reader rejects these already; kept for safety
            throw InputError(at + check.message);
        case S::tooFew:  // only after removing repeated corners: nothing left to draw
        case S::degenerate:
            warnings.push_back(at + "degenerate face (zero area or repeated vertices) dropped");
            return;
        case S::nonPlanar: {
            if (n != 4)
                throw InputError(at + check.message + "; only non-planar quads are repaired: " +
                                 "split this " + std::to_string(n) + "-vertex face into triangles");
            // The shorter diagonal gives the smaller fold between the two halves.
            const bool d02 = glm::length(c[2] - c[0]) <= glm::length(c[3] - c[1]);
            const std::vector<Triangle> tris = d02 ? std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}
                                                   : std::vector<Triangle>{{1, 2, 3}, {1, 3, 0}};
            const size_t k = sink.addTriangles(c, tris);
            warnings.push_back(at + check.message + "; quad split into " + std::to_string(k) +
                               " triangles along its shorter diagonal");
            return;
        }
        case S::nonConvex: {
            const auto tris = earClip(c);
            if (!tris)
                throw InputError(at + "face is self-intersecting (its edges cross); fix the mesh");
            const size_t k = sink.addTriangles(c, *tris);
            warnings.push_back(at + "non-convex face with " + std::to_string(n) +
                               " vertices split into " + std::to_string(k) +
                               " triangles that are each convex");
            return;
        }
    }
}

}  // namespace

void addObjFaces(const ObjFile& obj, std::span<const int> sceneObject,
                 const std::function<Rgb(int)>& reflectanceOf, radiosity::Scene& scene,
                 std::vector<std::string>& warnings) {
    for (const ObjFace& face : obj.faces) {
        const int object = sceneObject[static_cast<size_t>(face.object)];
        PolygonSink sink{scene, object, reflectanceOf(object)};
        addFace(obj, face, sink, warnings);
    }
}

std::vector<int> addLightFaces(const std::vector<Vec3>& corners, int object, int light,
                               radiosity::Scene& scene) {
    PolygonSink sink{scene, object, Rgb{}, light};
    const size_t first = scene.polygons.size();
    if (corners.size() <= 4)
        sink.add(corners);
    else
        sink.addTriangles(corners, fan(corners.size()));
    std::vector<int> out;
    for (size_t p = first; p < scene.polygons.size(); ++p) out.push_back(static_cast<int>(p));
    return out;
}

}  // namespace relight
