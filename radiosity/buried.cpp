// findBuriedPolygons / removeBuriedPolygons (radiosity/buried.h).
#include "radiosity/buried.h"

#include <algorithm>
#include <cmath>

#include "radiosity/detail/hemisphere.h"
#include "radiosity/detail/rng.h"
#include "radiosity/parallel.h"

namespace radiosity {

namespace {

struct RayWalk {
    const Scene& scene;
    const Visibility& vis;
    const BuriedContext& context;
    int maxPairs;
    double tStart;  ///< skips the faces the origin lies on (a touching solid's face)

    /// A face that does not count as solid matter about polygon `self`: a light's, or one of
    /// another object that an edit may remove (self's own object leaves with it).
    bool notSolid(int p, int self) const {
        const Polygon& q = scene.polygons[static_cast<size_t>(p)];
        if (q.light >= 0) return true;
        const auto o = static_cast<size_t>(q.object);
        return q.object >= 0 && q.object != scene.polygons[static_cast<size_t>(self)].object &&
               o < context.mayVanish.size() && context.mayVanish[o];
    }
    bool facesRay(int p, const Vec3& dir) const {
        return glm::dot(scene.polygons[static_cast<size_t>(p)].normal, dir) < 0;
    }

    /// True when the ray from org (on polygon `self`) sees out (buried.h); false when it
    /// ends on the back of a face, inside solid matter.
    bool seesOut(const Vec3& org, const Vec3& dir, int self) const {
        double tMin = tStart;
        for (int pair = 0; pair <= maxPairs; ++pair) {
            const Visibility::Hit hit = vis.intersect(org, dir, tMin, 1e30, self);
            if (hit.polygon < 0 || notSolid(hit.polygon, self)) return true;
            const bool front = facesRay(hit.polygon, dir);
            const Visibility::Hit twin = vis.intersect(org, dir, std::max(tMin, hit.t - kTwinGap),
                                                       hit.t + kTwinGap, hit.polygon);
            if (twin.polygon < 0 || twin.polygon == self || facesRay(twin.polygon, dir) == front)
                return front;
            if (notSolid(twin.polygon, self)) return true;
            // A sheet's two faces or two solids touching: decided beyond the pair.
            tMin = std::max(hit.t, twin.t) + kTwinGap;
        }
        return true;
    }
};

/// Points on polygon q where its rays start: its centroid, and its corners and the middles
/// of its edges drawn a tenth of the way in (a ray from a corner would graze the faces that
/// meet there).
std::vector<Vec3> samplePoints(const Polygon& q) {
    const Vec3 c = q.centroid();
    std::vector<Vec3> points{c};
    const auto in = [&](const Vec3& x) { return x + 0.1 * (c - x); };
    for (int i = 0; i < q.vertexCount; ++i) {
        const Vec3& a = q.v[static_cast<size_t>(i)];
        const Vec3& b = q.v[static_cast<size_t>((i + 1) % q.vertexCount)];
        points.push_back(in(a));
        points.push_back(in(0.5 * (a + b)));
    }
    return points;
}

bool buried(const RayWalk& walk, int p, const BuriedOptions& options) {
    const Polygon& q = walk.scene.polygons[static_cast<size_t>(p)];
    const std::vector<Vec3> points = samplePoints(q);
    Rng rng(0x6275726965640000ull ^ static_cast<uint64_t>(p));
    const int k = strataSide(options.raysPerPoint);
    for (const double side : {1.0, -1.0}) {
        const HemisphereFrame frame(side * q.normal);
        for (const Vec3& x : points)
            for (int r = 0; r < options.raysPerPoint; ++r)
                if (walk.seesOut(x, cosineDirection(frame, r, k, rng), p)) return false;
    }
    const std::optional<Vec3>& eye = walk.context.eye;
    if (eye && glm::dot(*eye - q.centroid(), q.normal) > 0)
        for (const Vec3& x : points)
            if (walk.vis.visible(*eye, x, -1, p)) return false;
    return true;
}

}  // namespace

std::vector<int> findBuriedPolygons(const Scene& scene, size_t count, const Visibility& vis,
                                    const BuriedContext& context, const BuriedOptions& options) {
    count = std::min(count, scene.polygons.size());
    const Bounds3 b = scene.bounds();
    const double diagonal = glm::length(b.hi - b.lo);
    // Beyond Embree's float rounding of the faces through the origin (visibility.h: ~6e-8 of
    // the scene's size): a solid's face that touches the polygon is not what its ray meets.
    const RayWalk walk{scene, vis, context, options.maxPairs, 1e-5 * diagonal + 1e-7};
    std::vector<char> out(count, 0);
    parallelFor(count, 64, [&](size_t i) {
        if (scene.polygons[i].light < 0) out[i] = buried(walk, static_cast<int>(i), options);
    });
    std::vector<int> result;
    for (size_t i = 0; i < count; ++i)
        if (out[i]) result.push_back(static_cast<int>(i));
    return result;
}

double removeBuriedPolygons(Scene& scene, const std::vector<int>& buried) {
    if (buried.empty()) return 0;
    std::vector<char> drop(scene.polygons.size(), 0);
    double area = 0;
    for (const int p : buried) {
        drop.at(static_cast<size_t>(p)) = 1;
        area += scene.polygons[static_cast<size_t>(p)].area;
    }
    // New index of every polygon kept: its old one less the buried before it.
    std::vector<int> renumber(scene.polygons.size(), -1);
    std::vector<Polygon> kept;
    kept.reserve(scene.polygons.size() - buried.size());
    for (size_t i = 0; i < scene.polygons.size(); ++i) {
        if (drop[i]) continue;
        renumber[i] = static_cast<int>(kept.size());
        kept.push_back(scene.polygons[i]);
    }
    scene.polygons = std::move(kept);
    for (Light& light : scene.lights)
        for (int& p : light.polygons) p = renumber.at(static_cast<size_t>(p));
    return area;
}

}  // namespace radiosity
