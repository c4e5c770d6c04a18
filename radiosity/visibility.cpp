// Visibility on Embree 3 (Wald et al. 2014, "Embree: a kernel framework for efficient CPU
// ray tracing"). One device, one static scene with a single quad geometry holding every
// polygon: Embree's quad primitive takes triangles as degenerate quads (v3 = v2), so one
// geometry type serves the whole scene and primID is the polygon index directly.
//
// Conventions followed (see docs/dependencies.md, "Embree 3 rays"): mask = 0xFFFFFFFF,
// flags = 0, tnear set, a fresh RTCIntersectContext per call (the context is per-query
// state, so sharing one between threads would race); rtcOccluded* marks an occluded ray by
// setting tfar = -inf.
#include "radiosity/visibility.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace radiosity {

namespace {
float f(double x) {
    return static_cast<float>(x);
}

/// The ray of intersect() and occluded(): origin `local` (relative to the scene's centre),
/// direction `dir`, from tMin (at least 0) to tMax (beyond float range: unbounded, +inf,
/// which Embree accepts for tfar).
RTCRay worldRay(const Vec3& local, const Vec3& dir, double tMin, double tMax) {
    RTCRay ray;
    ray.org_x = f(local.x);
    ray.org_y = f(local.y);
    ray.org_z = f(local.z);
    ray.dir_x = f(dir.x);
    ray.dir_y = f(dir.y);
    ray.dir_z = f(dir.z);
    ray.tnear = f(std::max(tMin, 0.0));
    ray.tfar = tMax >= static_cast<double>(std::numeric_limits<float>::max())
                   ? std::numeric_limits<float>::infinity()
                   : f(tMax);
    ray.time = 0;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    return ray;
}
}  // namespace

struct Visibility::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    // Centre of the scene's bounds (metres). Vertices and rays are sent to Embree relative
    // to it, so that float spacing follows the scene's size, not its distance from the
    // world origin (a room modelled at x = 40 m would otherwise lose 16x in precision).
    Vec3 origin{0, 0, 0};

    // Embree reports errors through a C callback; throwing through Embree's C API would
    // unwind C++ frames Embree does not expect to lose, so the callback only records the
    // error and check() throws it on our side of the call.
    std::atomic<bool> failed{false};
    std::mutex errorMutex;  // guards errorText; the callback may run on any thread
    std::string errorText;  // first error message, "Embree error <code>: <text>"

    // Occlusion queries so far ("Visibility/Rays"); own cache line so that the counter's
    // traffic does not evict the scene handle other threads read on every query.
    alignas(64) std::atomic<uint64_t> rays{0};

    // Scene::polygons index of primitive 0 of each geometry, by geomID (-1: free id). The
    // scene's own polygons are geometry 0; addPolygons() attaches one geometry per group.
    std::vector<int> geomFirst;
    std::vector<unsigned> groupGeom;  // by group id: its geomID, or RTC_INVALID_GEOMETRY_ID
    std::vector<size_t> groupCount;   // by group id: its number of polygons
    // hidePolygons(): the 12 floats of each hidden scene polygon (geometry 0) as they were.
    size_t scenePolygons = 0;
    std::vector<std::array<float, 12>> hiddenVertices;
    std::vector<char> isHidden;  // per scene polygon, sized at the first hide
    void setHidden(std::span<const int> polygons, bool hide);
    unsigned groupGeometry(int group) const;

    int polygonOf(unsigned geomID, unsigned primID) const {
        return geomFirst[geomID] + static_cast<int>(primID);
    }

    static void onError(void* self, RTCError code, const char* text) {
        auto* impl = static_cast<Impl*>(self);
        std::lock_guard<std::mutex> lock(impl->errorMutex);
        if (!impl->failed.load()) {
            impl->errorText = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                              (text ? text : "(no message)");
            impl->failed.store(true);
        }
    }

    void check(const char* where) {
        if (!failed.load(std::memory_order_relaxed)) return;
        std::lock_guard<std::mutex> lock(errorMutex);
        throw std::runtime_error(std::string("Visibility: ") + where + ": " + errorText);
    }

    // Creates a quad geometry for `polygons` (Scene::polygons indices from firstIndex on),
    // attaches it (the scene still needs a commit) and returns its geomID.
    unsigned attachQuads(std::span<const Polygon> polygons, int firstIndex) {
        for (size_t p = 0; p < polygons.size(); ++p) {
            const int count = polygons[p].vertexCount;
            if (count != 3 && count != 4)
                throw std::invalid_argument("Visibility: polygon " +
                                            std::to_string(firstIndex + p) + " has " +
                                            std::to_string(count) + " vertices, expected 3 or 4");
        }
        const size_t n = polygons.size();
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
        // 4 float3 per polygon (x y z, 12 bytes each); Embree pads the buffer's end itself.
        // Released on every path: the scene takes its own reference when attached.
        const std::unique_ptr<RTCGeometryTy, void (*)(RTCGeometry)> owner(geometry,
                                                                          &rtcReleaseGeometry);
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), 4 * n);
        // 4 vertex indices per polygon; a triangle repeats v2 as v3.
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), n));
        check("allocating geometry buffers");
        for (size_t p = 0; p < n; ++p) {
            const Polygon& poly = polygons[p];
            for (int k = 0; k < 4; ++k) {
                const unsigned base = static_cast<unsigned>(4 * p);
                indices[4 * p + k] =
                    base + static_cast<unsigned>(poly.vertexCount == 3 && k == 3 ? 2 : k);
            }
        }
        writeVertices(geometry, polygons);
        const unsigned id = rtcAttachGeometry(scene, geometry);
        check("building the geometry");
        if (geomFirst.size() <= id) geomFirst.resize(id + 1, -1);
        geomFirst[id] = firstIndex;
        return id;
    }

    void writeVertices(RTCGeometry geometry, std::span<const Polygon> polygons) {
        auto* vertices =
            static_cast<float*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0));
        for (size_t p = 0; p < polygons.size(); ++p) {
            const Polygon& poly = polygons[p];
            for (int k = 0; k < 4; ++k) {
                const Vec3 v = poly.v[std::min(k, poly.vertexCount - 1)] - origin;
                vertices[3 * (4 * p + k) + 0] = f(v.x);
                vertices[3 * (4 * p + k) + 1] = f(v.y);
                vertices[3 * (4 * p + k) + 2] = f(v.z);
            }
        }
        rtcCommitGeometry(geometry);
    }

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

double maxAbs(const Vec3& p) {
    return std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
}

// Intersect context that also carries the two polygons a segment's end points lie on.
// Embree hands the context pointer back to the filter, which recovers the ids from it
// (the context is the first member, so the two addresses coincide).
struct EndContext {
    RTCIntersectContext context;     // first member: &EndContext == &EndContext::context
    int ignoreA = -1;                // polygon of the end point a, or -1
    int ignoreB = -1;                // polygon of the end point b, or -1
    const int* geomFirst = nullptr;  // Visibility::Impl::geomFirst

    EndContext(int polygonA, int polygonB, const std::vector<int>& first) {
        rtcInitIntersectContext(&context);
        ignoreA = polygonA;
        ignoreB = polygonB;
        geomFirst = first.data();
        // Only pay for the filter call when there is something to ignore.
        if (polygonA >= 0 || polygonB >= 0) context.filter = &ignoreEndPolygons;
    }

    // A segment from a point of a planar convex polygon meets that polygon's plane only at
    // the point (or lies in the plane, where the polygon is seen edge-on and has zero
    // thickness): its own polygon can never block it, so hits on it are rejected outright.
    // This is exact at any grazing angle, unlike the end shrink alone.
    static void ignoreEndPolygons(const RTCFilterFunctionNArguments* args) {
        const auto* self = reinterpret_cast<const EndContext*>(args->context);
        for (unsigned i = 0; i < args->N; ++i) {
            if (args->valid[i] != -1) continue;
            const int polygon = self->geomFirst[RTCHitN_geomID(args->hit, args->N, i)] +
                                static_cast<int>(RTCHitN_primID(args->hit, args->N, i));
            if (polygon == self->ignoreA || polygon == self->ignoreB) args->valid[i] = 0;
        }
    }
};

// A segment a-b as Embree traces it: org = a, dir = b - a (t = 0 at a, t = 1 at b), both
// relative to `origin`, with the open interval (tNear, tFar) pulled in at both ends.
struct FloatSegment {
    float org[3], dir[3];  // x y z, metres relative to Impl::origin
    float tNear, tFar;     // in units of the segment: 0 at a, 1 at b
};

// False when the segment is too short to hold a blocker. See visible() in the header for
// the tolerance and why.
bool makeSegment(const Vec3& a, const Vec3& b, const Vec3& origin, FloatSegment& s) {
    constexpr double kRelative = 1e-5;       // of the segment length
    constexpr double kAbsolute = 1e-7;       // metres
    constexpr double kFloatRounding = 1e-6;  // of the largest coordinate, 16 float ulps
    const Vec3 la = a - origin, lb = b - origin;
    const double length = glm::length(lb - la);
    const double eps =
        kRelative * length + kAbsolute + kFloatRounding * std::max(maxAbs(la), maxAbs(lb));
    if (!(length > 2 * eps)) return false;  // also catches NaN lengths
    for (int k = 0; k < 3; ++k) {
        // dir from the rounded end points, not rounded from b - a: the ray then ends where
        // float(b) is, and b lying on an axis-aligned polygon stays on its rounded plane.
        s.org[k] = f(la[k]);
        s.dir[k] = f(static_cast<double>(f(lb[k])) - static_cast<double>(s.org[k]));
    }
    s.tNear = f(eps / length);
    s.tFar = f(1.0 - eps / length);
    return true;
}

}  // namespace

Visibility::Visibility(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device)
        throw std::runtime_error("Visibility: rtcNewDevice failed, Embree error " +
                                 std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))));
    rtcSetDeviceErrorFunction(impl_->device, &Impl::onError, impl_.get());

    impl_->scene = rtcNewScene(impl_->device);
    // Static scene, built once: spend the build time for faster traversal.
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
    // ROBUST keeps Embree from trading watertightness for speed, so rays through the shared
    // edge of two wall quads do not leak light; CONTEXT_FILTER_FUNCTION lets visible()
    // ignore the end points' own polygons.
    rtcSetSceneFlags(
        impl_->scene,
        static_cast<RTCSceneFlags>(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
    impl_->check("creating the scene");

    const size_t n = scene.polygons.size();
    for (size_t p = 0; p < n; ++p) {
        const int count = scene.polygons[p].vertexCount;
        if (count != 3 && count != 4)
            throw std::invalid_argument("Visibility: polygon " + std::to_string(p) + " has " +
                                        std::to_string(count) + " vertices, expected 3 or 4");
    }
    if (n > 0) {
        impl_->origin = scene.bounds().centre();
        impl_->attachQuads(scene.polygons, 0);  // geomID 0
    }
    impl_->scenePolygons = n;
    rtcCommitScene(impl_->scene);
    impl_->check("committing the scene");
}

int Visibility::addPolygons(std::span<const Polygon> polygons, int firstIndex) {
    if (polygons.empty()) throw std::invalid_argument("Visibility::addPolygons: no polygon");
    const unsigned id = impl_->attachQuads(polygons, firstIndex);
    rtcCommitScene(impl_->scene);
    impl_->check("committing the scene");
    impl_->groupGeom.push_back(id);
    impl_->groupCount.push_back(polygons.size());
    return static_cast<int>(impl_->groupGeom.size()) - 1;
}

unsigned Visibility::Impl::groupGeometry(int group) const {
    if (group < 0 || group >= static_cast<int>(groupGeom.size()) ||
        groupGeom[group] == RTC_INVALID_GEOMETRY_ID)
        throw std::invalid_argument("Visibility: no polygon group " + std::to_string(group));
    return groupGeom[group];
}

void Visibility::movePolygons(int group, std::span<const Polygon> polygons) {
    const unsigned id = impl_->groupGeometry(group);
    if (impl_->groupCount[group] != polygons.size())
        throw std::invalid_argument("Visibility::movePolygons: the group has " +
                                    std::to_string(impl_->groupCount[group]) + " polygons, not " +
                                    std::to_string(polygons.size()));
    RTCGeometry g = rtcGetGeometry(impl_->scene, id);
    impl_->writeVertices(g, polygons);
    rtcUpdateGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(g);
    rtcCommitScene(impl_->scene);
    impl_->check("moving polygons");
}

void Visibility::removePolygons(int group) {
    const unsigned id = impl_->groupGeometry(group);
    rtcDetachGeometry(impl_->scene, id);
    rtcCommitScene(impl_->scene);
    impl_->check("removing polygons");
    impl_->geomFirst[id] = -1;
    impl_->groupGeom[group] = RTC_INVALID_GEOMETRY_ID;
}

void Visibility::Impl::setHidden(std::span<const int> polygons, bool hide) {
    for (int p : polygons)
        if (p < 0 || static_cast<size_t>(p) >= scenePolygons)
            throw std::invalid_argument("Visibility: cannot hide polygon " + std::to_string(p) +
                                        ": the scene has " + std::to_string(scenePolygons));
    if (polygons.empty()) return;
    if (isHidden.empty()) {
        isHidden.assign(scenePolygons, 0);
        hiddenVertices.resize(scenePolygons);
    }
    RTCGeometry g = rtcGetGeometry(scene, 0);
    auto* v = static_cast<float*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_VERTEX, 0));
    for (int p : polygons) {
        const auto i = static_cast<size_t>(p);
        if ((isHidden[i] != 0) == hide) continue;
        float* quad = v + 12 * i;
        if (hide) {
            std::copy_n(quad, 12, hiddenVertices[i].begin());
            // Every corner on the first: a point, which no ray hits.
            for (int k = 1; k < 4; ++k) std::copy_n(quad, 3, quad + 3 * k);
        } else {
            std::copy_n(hiddenVertices[i].begin(), 12, quad);
        }
        isHidden[i] = hide ? 1 : 0;
    }
    rtcUpdateGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(g);
    rtcCommitScene(scene);
    check(hide ? "hiding polygons" : "showing polygons");
}

void Visibility::hidePolygons(std::span<const int> polygons) {
    impl_->setHidden(polygons, true);
}

void Visibility::showPolygons(std::span<const int> polygons) {
    impl_->setHidden(polygons, false);
}

bool Visibility::hidden(int polygon) const {
    return polygon >= 0 && static_cast<size_t>(polygon) < impl_->isHidden.size() &&
           impl_->isHidden[static_cast<size_t>(polygon)] != 0;
}

Visibility::~Visibility() = default;

bool Visibility::visible(const Vec3& a, const Vec3& b, int polygonA, int polygonB) const {
    impl_->rays.fetch_add(1, std::memory_order_relaxed);
    FloatSegment s;
    if (!makeSegment(a, b, impl_->origin, s)) return true;
    RTCRay ray;
    ray.org_x = s.org[0];
    ray.org_y = s.org[1];
    ray.org_z = s.org[2];
    ray.dir_x = s.dir[0];
    ray.dir_y = s.dir[1];
    ray.dir_z = s.dir[2];
    ray.tnear = s.tNear;
    ray.tfar = s.tFar;
    ray.time = 0;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    EndContext context(polygonA, polygonB, impl_->geomFirst);
    rtcOccluded1(impl_->scene, &context.context, &ray);
    impl_->check("rtcOccluded1");
    return ray.tfar >= 0;  // -inf when occluded
}

int Visibility::visibleBatch(const Vec3* from, const Vec3* to, int n, bool* out, int polygonA,
                             int polygonB) const {
    if (n <= 0) return 0;
    impl_->rays.fetch_add(static_cast<uint64_t>(n), std::memory_order_relaxed);
    constexpr int kWidth = 16;
    int visibleCount = 0;
    EndContext context(polygonA, polygonB, impl_->geomFirst);
    for (int start = 0; start < n; start += kWidth) {
        const int count = std::min(kWidth, n - start);
        RTCRay16 packet;    // RTC_ALIGN(64) in the type, so the stack slot is aligned
        int valid[kWidth];  // -1: lane traced, 0: lane ignored by Embree
        bool trivial[kWidth];
        for (int k = 0; k < kWidth; ++k) {
            valid[k] = 0;
            trivial[k] = true;
            // Fill every lane, including ignored ones, so that Embree's SIMD loads read
            // defined values.
            packet.org_x[k] = packet.org_y[k] = packet.org_z[k] = 0;
            packet.dir_x[k] = packet.dir_y[k] = 0;
            packet.dir_z[k] = 1;
            packet.tnear[k] = 0;
            packet.tfar[k] = 0;
            packet.time[k] = 0;
            packet.mask[k] = 0xFFFFFFFFu;
            packet.id[k] = static_cast<unsigned>(k);
            packet.flags[k] = 0;
            if (k >= count) continue;
            FloatSegment s;
            if (!makeSegment(from[start + k], to[start + k], impl_->origin, s)) continue;
            packet.org_x[k] = s.org[0];
            packet.org_y[k] = s.org[1];
            packet.org_z[k] = s.org[2];
            packet.dir_x[k] = s.dir[0];
            packet.dir_y[k] = s.dir[1];
            packet.dir_z[k] = s.dir[2];
            packet.tnear[k] = s.tNear;
            packet.tfar[k] = s.tFar;
            valid[k] = -1;
            trivial[k] = false;
        }
        rtcOccluded16(valid, impl_->scene, &context.context, &packet);
        impl_->check("rtcOccluded16");
        for (int k = 0; k < count; ++k) {
            const bool v = trivial[k] || packet.tfar[k] >= 0;
            visibleCount += v ? 1 : 0;
            if (out) out[start + k] = v;
        }
    }
    return visibleCount;
}

Visibility::Hit Visibility::intersect(const Vec3& org, const Vec3& dir, double tMin, double tMax,
                                      int ignore) const {
    RTCRayHit rayHit;
    RTCRay& ray = rayHit.ray;
    ray = worldRay(org - impl_->origin, dir, tMin, tMax);
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    Hit result;
    if (!(ray.tnear < ray.tfar)) return result;
    EndContext context(ignore, -1, impl_->geomFirst);
    rtcIntersect1(impl_->scene, &context.context, &rayHit);
    impl_->check("rtcIntersect1");
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return result;
    result.polygon = impl_->polygonOf(rayHit.hit.geomID, rayHit.hit.primID);
    result.t = static_cast<double>(ray.tfar);
    return result;
}

bool Visibility::occluded(const Vec3& org, const Vec3& dir, double tMin, double tMax,
                          int ignore) const {
    // The ray exactly as intersect() builds it, so that both agree on whether it hits.
    RTCRay ray = worldRay(org - impl_->origin, dir, tMin, tMax);
    if (!(ray.tnear < ray.tfar)) return false;
    EndContext context(ignore, -1, impl_->geomFirst);
    rtcOccluded1(impl_->scene, &context.context, &ray);
    impl_->check("rtcOccluded1");
    return ray.tfar < 0;  // -inf when occluded
}

void Visibility::occludedBatch(const Vec3& org, const Vec3* dirs, int n, int ignore,
                               bool* out) const {
    constexpr int kWidth = 16;
    EndContext context(ignore, -1, impl_->geomFirst);
    const Vec3 localOrg = org - impl_->origin;
    for (int start = 0; start < n; start += kWidth) {
        const int count = std::min(kWidth, n - start);
        RTCRay16 packet;  // RTC_ALIGN(64) in the type, so the stack slot is aligned
        int valid[kWidth];
        for (int k = 0; k < kWidth; ++k) {
            // Every lane filled (Embree's SIMD loads), each traced one as occluded() builds it.
            const Vec3 dir = k < count ? dirs[start + k] : Vec3(0, 0, 1);
            packet.org_x[k] = f(localOrg.x);
            packet.org_y[k] = f(localOrg.y);
            packet.org_z[k] = f(localOrg.z);
            packet.dir_x[k] = f(dir.x);
            packet.dir_y[k] = f(dir.y);
            packet.dir_z[k] = f(dir.z);
            packet.tnear[k] = 0;
            packet.tfar[k] = std::numeric_limits<float>::infinity();
            packet.time[k] = 0;
            packet.mask[k] = 0xFFFFFFFFu;
            packet.id[k] = static_cast<unsigned>(k);
            packet.flags[k] = 0;
            valid[k] = k < count ? -1 : 0;
        }
        rtcOccluded16(valid, impl_->scene, &context.context, &packet);
        impl_->check("rtcOccluded16");
        for (int k = 0; k < count; ++k) out[start + k] = packet.tfar[k] < 0;
    }
}

uint64_t Visibility::raysCast() const {
    return impl_->rays.load(std::memory_order_relaxed);
}

int Visibility::visibleAdaptive(const Vec3* from, const Vec3* to, int first, int n, int& cast,
                                int polygonA, int polygonB) const {
    first = std::clamp(first, 0, n);
    int visible = visibleBatch(from, to, first, nullptr, polygonA, polygonB);
    cast = first;
    if (visible != 0 && visible != first && n > first) {
        visible += visibleBatch(from + first, to + first, n - first, nullptr, polygonA, polygonB);
        cast = n;
    }
    return visible;
}

FrontHit intersectFront(const Visibility& vis, const Scene& scene, const Vec3& org, const Vec3& dir,
                        double tMin) {
    FrontHit out;
    out.hit = vis.intersect(org, dir, tMin);
    if (out.hit.polygon < 0) return out;
    const auto facesRay = [&](int p) {
        return glm::dot(scene.polygons[static_cast<size_t>(p)].normal, dir) < 0;
    };
    out.front = facesRay(out.hit.polygon);
    if (out.front) return out;
    // The twin face may lie at the very same distance (the same corners, reversed): search
    // from just before the back face, passing it through.
    const Visibility::Hit twin = vis.intersect(org, dir, std::max(tMin, out.hit.t - kTwinGap),
                                               out.hit.t + kTwinGap, out.hit.polygon);
    if (twin.polygon >= 0 && facesRay(twin.polygon)) {
        out.hit = twin;
        out.front = true;
    }
    return out;
}

}  // namespace radiosity
