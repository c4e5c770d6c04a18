// Visibility: segment occlusion and first-hit queries against the scene's polygons, on Embree 3.
//
// API
//   Visibility vis(scene);                 // builds one Embree device + BVH (once, ~50 ms/100k)
//   vis.visible(a, b)                      // true when nothing blocks the open segment a-b
//   vis.visibleBatch(from, to, n, out)     // the same for n segments, 16-ray packets; returns
//                                          // how many are visible
//   vis.intersect(org, dir, tMin, tMax)    // first polygon hit along a ray and its distance (m)
//   vis.raysCast()                         // counter "Visibility/Rays": occlusion rays so far
//
// All positions are world space, metres, in double; Embree traces in float, relative to the
// centre of the scene's bounds, so answers are exact only up to float rounding (~6e-8
// relative to the scene's size, ~0.3 um in a 10 m room), which is why the segment ends are
// pulled in (see visible()).
//
// Every polygon occludes, emitting faces included (a lamp's shade casts a shadow), and both
// of its sides occlude: the one-sided convention of scene.h is about light transfer, not
// about opacity. The Embree primitive id of a polygon is its index in Scene::polygons.
//
// Thread safety: after construction every query is const and may be called concurrently
// from any number of threads (Embree's traversal of a committed scene is re-entrant; the
// counter is atomic).
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "radiosity/scene.h"
#include "radiosity/vec.h"

namespace radiosity {

class Visibility {
  public:
    /// Name under which raysCast() is reported by statistics printers.
    static constexpr const char* kRaysCounterName = "Visibility/Rays";

    /// Builds one Embree device and a static scene holding every polygon of `scene`
    /// (triangles and quads, all as RTC_GEOMETRY_TYPE_QUAD: a triangle is a quad with
    /// v3 = v2, which Embree supports). Emitting faces are included: they occlude.
    /// primID = polygon index. Embree errors (reported through a device error callback)
    /// are turned into std::runtime_error. An empty scene is allowed: nothing occludes.
    explicit Visibility(const Scene& scene);
    ~Visibility();
    Visibility(const Visibility&) = delete;
    Visibility& operator=(const Visibility&) = delete;

    /// Segment visibility V(a, b) in {0, 1}: true when no polygon blocks the open segment
    /// between a and b (metres). Both ends are pulled in along the segment by
    ///     eps = 1e-5 |b - a| + 1e-7 m + 1e-6 max(|a - c|_inf, |b - c|_inf)
    /// (c: centre of the scene's bounds, the origin of Embree's float coordinates) so that
    /// the polygons the end points lie on do not count: the relative term covers end points
    /// interpolated on their element, the absolute term tiny segments, the last term the
    /// float rounding of coordinates in Embree (16 times the ~6e-8 relative float error).
    /// Blockers closer than eps to an end are ignored: ~0.1 mm on a 10 m segment, ~15 um
    /// on a 1 m one in a 10 m room. Segments shorter than 2 eps are visible. At grazing angle theta
    /// to an end point's polygon the clearance from that polygon is only eps sin(theta): end points
    /// lying exactly on an axis-aligned polygon stay exact (same float rounding as its vertices),
    /// but on a rotated polygon they may self-block below ~5 degrees (measured: 0.4% of segments at
    /// sin(theta) in [0.01, 0.1], 20-50% below) -- hence polygonA / polygonB.
    ///
    /// polygonA / polygonB (optional, -1 for none): the Scene::polygons indices a and b
    /// lie on. Hits on them are ignored, which is exact at any grazing angle (a segment
    /// leaving a point of a planar convex polygon cannot cross it again); pass them
    /// whenever known, e.g. the input polygons of a link's receiver and source elements.
    /// Counts one ray.
    bool visible(const Vec3& a, const Vec3& b, int polygonA = -1, int polygonB = -1) const;

    /// Batch form: for i in [0, n), out[i] = visible(from[i], to[i]) (out may be null);
    /// returns how many segments are visible. Traced as rtcOccluded16 packets, faster than
    /// n single calls (~2x). polygonA / polygonB as in visible(), the same for all n
    /// segments: from[i] lies on polygonA, to[i] on polygonB (one link's rays). Counts n
    /// rays.
    int visibleBatch(const Vec3* from, const Vec3* to, int n, bool* out = nullptr,
                     int polygonA = -1, int polygonB = -1) const;

    /// Adaptive visibility of n segments (one link's or one point's rays): the first
    /// `first` are cast; only when they disagree (penumbra) are the rest cast too. Returns
    /// the number of visible segments and sets `cast` to the number cast. polygonA /
    /// polygonB as in visibleBatch().
    int visibleAdaptive(const Vec3* from, const Vec3* to, int first, int n, int& cast,
                        int polygonA = -1, int polygonB = -1) const;

    /// First hit along the ray org + t dir with t in (tMin, tMax). `dir` should be unit
    /// length, so that t is a distance in metres (it is in units of |dir| otherwise).
    struct Hit {
        int polygon = -1;  ///< index into Scene::polygons; -1 when nothing is hit
        double t = 0;      ///< ray parameter of the hit (metres for a unit dir)
    };
    /// Hits on polygon `ignore` (>= 0) are passed through.
    Hit intersect(const Vec3& org, const Vec3& dir, double tMin = 0, double tMax = 1e30,
                  int ignore = -1) const;
    /// Whether intersect(org, dir, tMin, tMax, ignore) would hit anything: the same ray and
    /// filter, traced as an occlusion query (rtcOccluded1, which stops at the first hit
    /// found, not the closest). For the shadow rays of lights at infinity (a sun's disc, a
    /// sky's directions), where only "any hit" matters. Not counted in raysCast().
    bool occluded(const Vec3& org, const Vec3& dir, double tMin = 0, double tMax = 1e30,
                  int ignore = -1) const;
    /// The same for n rays from one origin to infinity (tMin 0): out[i] = occluded(org,
    /// dirs[i], 0, 1e30, ignore), traced as rtcOccluded16 packets (a sun's disc from one
    /// point: coherent rays). Not counted in raysCast().
    void occludedBatch(const Vec3& org, const Vec3* dirs, int n, int ignore, bool* out) const;

    /// Dynamic geometry (virtual objects and lights, Loscos et al. 2000, §5.1-5.2): adds
    /// `polygons` as one group whose Scene::polygons indices are firstIndex, firstIndex + 1,
    /// ... (what hits and the polygonA / polygonB filters report), and rebuilds the BVH.
    /// Returns the group's id. Not thread safe: no query may run meanwhile.
    int addPolygons(std::span<const Polygon> polygons, int firstIndex);
    /// Moves the group's polygons to new positions (the same count, same order).
    void movePolygons(int group, std::span<const Polygon> polygons);
    /// Takes the group out of the scene.
    void removePolygons(int group);

    /// Real-object removal (Loscos et al. 1999, §5.3): the scene's own polygons at these
    /// indices (Scene::polygons, not a group's) stop occluding and being hit until
    /// showPolygons() puts them back; the BVH is refitted. Each is collapsed to a point
    /// (a quad of zero area, which Embree's ray-quad test never reports), its vertices kept
    /// aside. Hiding a hidden polygon or showing a shown one changes nothing. Throws
    /// std::invalid_argument for an index outside the scene's polygons. Not thread safe.
    void hidePolygons(std::span<const int> polygons);
    void showPolygons(std::span<const int> polygons);
    /// Whether the scene's polygon is hidden.
    bool hidden(int polygon) const;

    /// Number of occlusion rays cast so far by visible() and visibleBatch(), all threads
    /// together (intersect() rays are not counted). Counter "Visibility/Rays".
    uint64_t raysCast() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// The first front face along the ray (surfaces are one-sided: the back of a polygon shows
/// and sends nothing). A thin part modelled as two faces back to back is hit on either at the
/// same distance: where the first hit is a back face, a front face within kTwinGap of it
/// (the back face passed through) is taken instead; otherwise the hit is the back face
/// (Hit::polygon set, `front` false).
struct FrontHit {
    Visibility::Hit hit;
    bool front = false;
};
inline constexpr double kTwinGap = 1e-4;  ///< metres: a sheet's two faces, within rounding
FrontHit intersectFront(const Visibility& vis, const Scene& scene, const Vec3& org, const Vec3& dir,
                        double tMin = 0);

}  // namespace radiosity
