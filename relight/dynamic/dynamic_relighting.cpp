#include "relight/dynamic/dynamic_relighting.h"
#include "relight/dynamic/overlay_samples.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "radiosity/detail/form_factor.h"
#include "radiosity/direct_light.h"
#include "radiosity/final_gather.h"
#include "radiosity/parallel.h"
#include "radiosity/stopwatch.h"
#include "relight/display/wen_display.h"
#include "relight/dynamic/quick_light.h"
#include "relight/pipeline/pixel_light.h"

namespace relight {

using radiosity::Node;
using radiosity::Vec3;

using radiosity::Clock;
using radiosity::parallelFor;
using radiosity::secondsSince;

namespace {
constexpr double kPi = std::numbers::pi;
// Seeds of the shadow rays of the virtual objects' vertices, apart from the scene's.
constexpr uint64_t kObjectSeed = 0x0b1ec7ull << 24;
// Seeds of the specular pass's light samples, apart from both.
constexpr uint64_t kSpecularSeed = 0x5bec01ull << 32;

// What a node reflects, as the final gathers read it: an emitter's own emission is direct
// light (radiosity/final_gather.h).
Rgb reflectedBy(const Node& e) {
    return e.emitting ? e.B - e.E : e.B;
}
}  // namespace

DynamicRelighting::DynamicRelighting(Relighting& r, std::span<const Rgb> radiance,
                                     GeometryCache* cache)
    : r_(r), solver_(*r.solver), cache_(cache) {
    if (!r.solver || !r.mesh)
        throw std::invalid_argument("DynamicRelighting: the relighting is not prepared");
    if (solver_.insertedObjects() > 0)
        throw std::logic_error("DynamicRelighting: the solver already holds virtual parts");
    realLights_ = static_cast<int>(solver_.scene().lights.size());
    if (static_cast<int>(radiance.size()) != realLights_)
        throw std::invalid_argument("DynamicRelighting: one radiance per real light expected");
    radiance_.assign(radiance.begin(), radiance.end());
    realPolygons_ = solver_.scene().polygons.size();
    realNodes_ = solver_.hierarchy().nodes.size();
    prepared_ = solver_.lightState();  // put back at the end, bit for bit
    // The solution at the edit's radiances: the "before" of every indirect change.
    solver_.setLightRadiances(radiance_);
    const size_t nv = r_.mesh->vertices().size();
    base_.resize(nv);
    for (size_t v = 0; v < nv; ++v)
        base_[v] = r_.prepared.lighting.irradiance(static_cast<int>(v), radiance_);
    realDirect_.assign(nv, Rgb{});
    virtualDirect_.assign(nv, Rgb{});
    indirect_.assign(nv, Rgb{});
    indirect0_ = indirectPerNode();
    reflected0_.resize(realNodes_);
    for (size_t n = 0; n < realNodes_; ++n)
        reflected0_[n] = reflectedBy(solver_.hierarchy().nodes[n]);
    if (cache_ && r_.responses) makeUnitSources();
    // The leaves under a new shadow are split down to the display's pieces (Loscos et al.
    // 2000, Fig. 24(a)): finer than the pieces no vertex would show it.
    const radiosity::LeafMesh* mesh = r_.mesh.get();
    solver_.setNewShadowSplits([mesh, n = realNodes_](int leaf) {
        return static_cast<size_t>(leaf) < n ? mesh->splits(leaf) : 0;
    });
    maskGrowth_ = defaultMaskGrowth(r.items.width, r.items.height);
    // The indirect part of each vertex's response: the prepared one, or, prepared without
    // per-pixel light, the same difference taken here (pipeline/pixel_light.h).
    if (r.prepared.vertexIndirect.empty())
        ownIndirectParts_ = vertexIndirect(r.prepared.lighting, r.direct);
    indirectParts_ = r.prepared.vertexIndirect.empty()
                         ? std::span<const Rgb>(ownIndirectParts_)
                         : std::span<const Rgb>(r.prepared.vertexIndirect);
}

DynamicRelighting::~DynamicRelighting() {
    // The relighting's solver goes back to the scene as prepared (bit for bit: removal
    // restores each insertion's snapshot), with the photo's radiances.
    try {
        while (solver_.insertedObjects() > 0) solver_.removeLastObject();
        if (solver_.scene().lights.size() > static_cast<size_t>(realLights_))
            solver_.removeEmitterLights(realLights_);  // virtual suns, lamps, skies
        solver_.setNewShadowSplits({});
        // The solution as the session found it (a gather again at the photo's radiances
        // would differ within its tolerance: the next session's "before" would not be the
        // preparation's, by up to 7e-4 in the room's relit image with a point lamp added).
        solver_.restoreLightState(prepared_);
    } catch (...) {
        // A destructor must not throw; the solver is left as the failed step left it.
    }
}

void DynamicRelighting::makeUnitSources() {
    // With links and subdivision fixed, radiosity is linear in the lights' emittances
    // (Loscos et al. 2000, §5.4; radiosity/light_response.h): per unit radiance of light l a
    // node reflects R_l, and a cluster's B holds its lamps' emission too, pulled as the
    // solver pulls B (area-weighted), pi per unit radiance (Light::emittance).
    const radiosity::LightResponses& R = *r_.responses;
    const auto& nodes = solver_.hierarchy().nodes;
    const auto& polygons = solver_.scene().polygons;
    const size_t L = static_cast<size_t>(realLights_), N = realNodes_;
    if (R.lights() != realLights_ || N == 0 || L == 0 || !R.covers(static_cast<int>(N) - 1)) return;
    std::vector<Rgb> emission(N * L);
    for (size_t n = N; n-- > 0;) {  // the children come after their parent
        const Node& e = nodes[n];
        if (!e.isCluster()) {
            const int l = polygons[static_cast<size_t>(e.polygon)].light;
            if (l >= 0 && l < realLights_)
                emission[n * L + static_cast<size_t>(l)] = Rgb::gray(kPi);
            continue;
        }
        double area = 0;
        for (int k = 0; k < e.childCount; ++k)
            area += nodes[static_cast<size_t>(e.firstChild + k)].area;
        if (!(area > 0)) continue;  // guard: a cluster of nothing
        for (int k = 0; k < e.childCount; ++k) {
            const size_t c = static_cast<size_t>(e.firstChild + k);
            for (size_t l = 0; l < L; ++l)
                emission[n * L + l] += (nodes[c].area / area) * emission[c * L + l];
        }
    }
    unitReflected_.assign(N * L, Rgb{});
    for (size_t n = 0; n < N; ++n) {
        const std::span<const Rgb> r = R.reflected(static_cast<int>(n));
        for (size_t l = 0; l < L; ++l)
            unitReflected_[n * L + l] = nodes[n].isCluster() ? r[l] + emission[n * L + l] : r[l];
    }
    // H_ind per unit radiance: indirectPerNode()'s gather of these sources.
    unitIndirect_.assign(N * L, Rgb{});
    for (size_t l = 0; l < L; ++l) {
        const std::vector<Rgb> H = solver_.gatherDown(
            [&](int s) {
                const Node& S = nodes[static_cast<size_t>(s)];
                if (static_cast<size_t>(s) >= N || (!S.isCluster() && S.emitting)) return Rgb{};
                return unitReflected_[static_cast<size_t>(s) * L + l];
            },
            /*bounded=*/true);
        for (size_t n = 0; n < N; ++n) unitIndirect_[n * L + l] = H[n];
    }
}

bool DynamicRelighting::setRealRadiances(std::span<const Rgb> radiance) {
    const auto& scene = solver_.scene();
    if (!cache_ || objectPreview_ || unitIndirect_.empty() ||
        radiance.size() != static_cast<size_t>(realLights_) ||
        scene.lights.size() != radiance.size() || !solver_.removedObjects().empty() ||
        !gatherDelta_.empty() || !gatherDeltaRays_.empty())
        return false;
    for (const auto& light : scene.lights)
        if (light.emitter) return false;
    const auto t0 = Clock::now();
    const size_t L = static_cast<size_t>(realLights_);
    std::vector<Rgb> change(L);
    for (size_t l = 0; l < L; ++l) change[l] = radiance[l] - radiance_[l];
    radiance_.assign(radiance.begin(), radiance.end());
    solver_.setLightRadiances(radiance_);  // gather/push-pull on the links as they are
    times_ = FrameTimes{};
    times_.radiosity = secondsSince(t0);
    const auto t1 = Clock::now();
    for (size_t v = 0; v < base_.size(); ++v)
        base_[v] = r_.prepared.lighting.irradiance(static_cast<int>(v), radiance_);
    // The "before" of every indirect change, at the new radiances.
    for (size_t n = 0; n < realNodes_; ++n)
        for (size_t l = 0; l < L; ++l) {
            indirect0_[n] += change[l] * unitIndirect_[n * L + l];
            reflected0_[n] += change[l] * unitReflected_[n * L + l];
        }
    refreshDirect(directVertices_, /*virtualOnly=*/false);  // the cache's G: no ray
    refreshIndirect(false);
    times_.vertices = secondsSince(t1);
    return true;
}

std::vector<Rgb> DynamicRelighting::indirectPerNode() const {
    // H_ind(node): what the node and its ancestors gather through links whose source is not
    // an emitting element (light links are the direct light, evaluated per vertex).
    const auto& nodes = solver_.hierarchy().nodes;
    std::vector<Rgb> H = solver_.gatherDown(
        [&](int s) {
            const Node& S = nodes[s];
            return !S.isCluster() && S.emitting ? Rgb{} : S.B;
        },
        /*bounded=*/true);
    // A leaf of the scene that an insertion split (under a new shadow, or by an object's
    // links) is displayed as one: the area-weighted mean of what its leaves gather. The
    // children come after their parent, so from the last node back every child is done.
    for (size_t n = nodes.size(); n-- > 0;) {
        const Node& e = nodes[n];
        if (e.isCluster() || e.isLeaf() || static_cast<size_t>(e.firstChild) < realNodes_ ||
            static_cast<size_t>(e.polygon) >= realPolygons_)
            continue;
        Rgb sum;
        double area = 0;
        for (int k = 0; k < e.childCount; ++k) {
            const Node& c = nodes[static_cast<size_t>(e.firstChild + k)];
            sum += c.area * H[static_cast<size_t>(e.firstChild + k)];
            area += c.area;
        }
        if (area > 0) H[n] = (1.0 / area) * sum;
    }
    return H;
}

int DynamicRelighting::addLight(const VirtualLight& light) {
    noPreview("addLight");
    completeVertexGather();
    if (light.emitter) {
        // A sun, point lamp or sky (radiosity/emitter.h): no face, no link; its direct light
        // enters the leaves (the solver's Hx) and is carried by the links as they are.
        const auto t0 = Clock::now();
        const int first = solver_.addEmitter(light.emitter);
        radiosity::DynamicUpdate u;
        u.sweeps = solver_.gatherPushPull();
        u.timeGather = secondsSince(t0);
        for (const Rgb& s : light.emitter->strengths()) radiance_.push_back(s);
        afterUpdate(u, /*allVertices=*/true);
        return first;
    }
    std::vector<Vec3> corners(light.corners.begin(), light.corners.end());
    radiosity::Polygon p = radiosity::makePolygon(corners, -1, Rgb{});
    radiosity::DynamicUpdate u;
    solver_.insertObject(light.name, {p}, &light.radiance, &u);
    radiance_.push_back(light.radiance);
    afterUpdate(u, /*allVertices=*/true);
    return static_cast<int>(radiance_.size()) - 1;
}

void DynamicRelighting::addObject(const VirtualObject& object) {
    noPreview("addObject");
    completeVertexGather();
    radiosity::DynamicUpdate u;
    solver_.insertObject(object.name, object.polygons, nullptr, &u);
    // The solver gave the object the next index of its scene's objects (an object taken
    // out frees its index, which the next one reuses: the entry is set either way).
    objectSpecular_.resize(solver_.scene().objects.size());
    objectSpecular_.back() = object.specular;
    afterUpdate(u, false);
}

int DynamicRelighting::setObjectSpecular(const std::string& name,
                                         const std::optional<Specular>& specular) {
    const auto& objects = solver_.scene().objects;
    const size_t firstVirtual = r_.scene.scene.objects.size();
    int set = 0;
    for (size_t i = firstVirtual; i < objects.size() && i < objectSpecular_.size(); ++i)
        if (objects[i] == name) {
            objectSpecular_[i] = specular;
            ++set;
        }
    return set;
}

Rgb DynamicRelighting::specularAt(const SpecularLights* lights, int polygon, const Vec3& point,
                                  const Vec3& dir, uint64_t sample) const {
    if (!lights) return {};
    const auto& poly = solver_.scene().polygons[static_cast<size_t>(polygon)];
    const size_t object = static_cast<size_t>(poly.object);
    if (poly.object < 0 || object >= objectSpecular_.size() || !objectSpecular_[object]) return {};
    // The direct light's shadow rays (Relighting::directOptions): maxRays per lamp face.
    return lights->radiance(*objectSpecular_[object], solver_.visibility(),
                            {point, poly.normal, polygon}, -dir, r_.directOptions.maxRays,
                            kSpecularSeed + sample);
}

void DynamicRelighting::moveLastObject(std::vector<radiosity::Polygon> polygons) {
    noPreview("moveLastObject");
    completeVertexGather();
    radiosity::DynamicUpdate u;
    solver_.moveLastObject(std::move(polygons), &u);
    afterUpdate(u, false);
}

void DynamicRelighting::removeObject(const std::string& name) {
    noPreview("removeObject");
    completeVertexGather();
    const auto& scene = solver_.scene();
    const int object = scene.findObject(name);
    if (object < 0 || name.starts_with("light:") ||
        static_cast<size_t>(object) >= r_.scene.scene.objects.size())
        throw std::invalid_argument("the scene has no object \"" + name + "\"");
    radiosity::DynamicUpdate u;
    solver_.removeRealObject(object, &u);
    afterUpdate(u, false);
}

void DynamicRelighting::removeLast() {
    noPreview("removeLast");
    completeVertexGather();
    const bool removal = solver_.lastIsRemoval();
    const bool light = !removal && static_cast<int>(solver_.scene().lights.size()) > realLights_ &&
                       solver_.scene().polygons.back().light >= 0;
    radiosity::DynamicUpdate u;
    solver_.removeLastObject(&u);
    if (light) radiance_.pop_back();
    objectSpecular_.resize(std::min(objectSpecular_.size(), solver_.scene().objects.size()));
    afterUpdate(u, light);
}

void DynamicRelighting::refreshRemoved(const radiosity::DynamicUpdate& u, bool allLights) {
    const auto t0 = Clock::now();
    const std::vector<int> removed = solver_.removedObjects();
    if (removed.empty()) {
        removed_ = RemovedRegion{};
        regionObjects_.clear();
        times_.fill = secondsSince(t0);
        return;
    }
    // A removal (or its undoing) builds the region again; other changes measure its direct
    // light again where they may have changed it.
    const bool fresh = removed != regionObjects_;
    if (fresh) {
        removed_ = buildRemovedRegion(r_, removed, realNodes_, maskGrowth_, synthesis_);
        regionObjects_ = removed;
    }
    if (fresh || allLights) {
        measureRegionDirect(removed_, r_, radiance_);
    } else {
        std::vector<char> changed(realNodes_, 0);
        for (int leaf : u.shadowLeaves) {
            while (leaf >= 0 && static_cast<size_t>(leaf) >= realNodes_)
                leaf = solver_.hierarchy().nodes[leaf].parent;
            if (leaf >= 0) changed[static_cast<size_t>(leaf)] = 1;
        }
        measureRegionDirect(removed_, r_, radiance_, &changed);
    }
    times_.fill = secondsSince(t0);
}

radiosity::Rgb DynamicRelighting::indirectAt(int leaf, const Vec3& x) const {
    const size_t L = static_cast<size_t>(realLights_);
    const auto st = r_.mesh->stencil(leaf, x);
    Rgb sum;
    for (int i = 0; i < st.count; ++i) {
        const auto v = static_cast<size_t>(st.vertex[static_cast<size_t>(i)]);
        // The per-pixel display's indirect light (the prepared parts are its).
        Rgb ind = pixelIndirect()[v];
        for (size_t l = 0; l < L; ++l) ind += radiance_[l] * indirectParts_[v * L + l];
        sum += ind * st.weight[static_cast<size_t>(i)];
    }
    return sum;
}

radiosity::Rgb DynamicRelighting::removedIndirect(const RemovedRegion& gone, size_t pixel,
                                                  size_t i) const {
    if (gone.lights <= 0 || gone.gathered.empty() || !gone.gathered[pixel])
        return indirectAt(gone.leaf[i], gone.point[i]);
    // Gathered at the revealed point itself, with the objects out, for the edit's radiances.
    const size_t L = static_cast<size_t>(std::min(gone.lights, realLights_));
    Rgb sum;
    for (size_t l = 0; l < L; ++l)
        sum += radiance_[l] * gone.indirect[pixel * static_cast<size_t>(gone.lights) + l];
    return sum;
}

void DynamicRelighting::afterUpdate(const radiosity::DynamicUpdate& u, bool allVertices) {
    last_ = u;
    markChangedLeaves(u.shadowLeaves);
    times_ = FrameTimes{};
    times_.shafts = u.timeShafts;
    times_.visibility = u.timeVisibility;
    times_.links = u.timeLinks;
    times_.radiosity = u.timeGather;
    const auto t0 = Clock::now();
    std::vector<int> vertices;
    const auto& mesh = *r_.mesh;
    if (allVertices) {
        vertices.resize(mesh.vertices().size());
        for (size_t v = 0; v < vertices.size(); ++v) vertices[v] = static_cast<int>(v);
    } else {
        std::vector<char> seen(mesh.vertices().size(), 0);
        for (int leaf : u.shadowLeaves) {
            if (static_cast<size_t>(leaf) >= realNodes_) continue;
            for (int v : mesh.vertexIds(leaf))
                if (!seen[v]) {
                    seen[v] = 1;
                    vertices.push_back(v);
                }
        }
    }
    if (directSeen_.size() != mesh.vertices().size()) directSeen_.assign(mesh.vertices().size(), 0);
    if (!allVertices)
        for (const int v : vertices)
            if (!directSeen_[static_cast<size_t>(v)]) {
                directSeen_[static_cast<size_t>(v)] = 1;
                directVertices_.push_back(v);
            }
    refreshDirect(vertices, /*virtualOnly=*/allVertices);
    refreshIndirect(allVertices);
    times_.vertices = secondsSince(t0);
    refreshRemoved(u, allVertices);
}

void DynamicRelighting::refreshDirect(const std::vector<int>& vertices, bool virtualOnly) {
    const auto& mesh = *r_.mesh;
    const radiosity::DirectLight direct(solver_);
    const auto& scene = solver_.scene();
    const int lights = static_cast<int>(scene.lights.size());
    const VertexDirect& before = r_.direct;
    GeometryCache* const cache = geometryCache();
    const size_t L = static_cast<size_t>(lights);
    if (cache && cache->vertexFrom.size() != mesh.vertices().size()) {
        cache->vertexG.assign(mesh.vertices().size() * L, 0.0);
        cache->vertexFrom.assign(mesh.vertices().size(), 0);
    }
    std::atomic<uint64_t> hits{0};
    const auto& correction = r_.removal.linkCorrection;
    radiosity::parallelForChunks(vertices.size(), 16, [&](size_t first, size_t last) {
        std::vector<double> G(static_cast<size_t>(lights));
        for (size_t i = first; i != last; ++i) {
            const int v = vertices[i];
            const int p = mesh.vertices()[v].polygon;
            if (scene.polygons[p].light >= 0) continue;  // shown, not lit
            // A virtual light added or removed changes the virtual lights' direct
            // light only; a moved object may change every light's.
            const int from = virtualOnly ? realLights_ : 0;
            const size_t at = static_cast<size_t>(v) * L;
            int* const known = cache ? &cache->vertexFrom[static_cast<size_t>(v)] : nullptr;
            if (known && *known > 0 && *known - 1 <= from) {
                // Measured in this geometry before (the same rays: the same G).
                std::copy_n(cache->vertexG.begin() + static_cast<std::ptrdiff_t>(at), L, G.begin());
                hits.fetch_add(1, std::memory_order_relaxed);
            } else {
                direct.geometry(p, mesh.insidePoint(v), static_cast<uint64_t>(v), G.data(), nullptr,
                                from);
                if (known) {
                    std::copy_n(G.begin(), L,
                                cache->vertexG.begin() + static_cast<std::ptrdiff_t>(at));
                    *known = from + 1;
                }
            }
            if (!virtualOnly) {
                const Rgb c = correction.empty() ? Rgb::gray(1.0) : correction[v];
                Rgb d;
                for (int l = 0; l < realLights_; ++l) {
                    const double was = before.visible[static_cast<size_t>(v) * realLights_ + l];
                    d += radiance_[l] * c * (kPi * G[l] - was);
                }
                realDirect_[v] = d;
            }
            Rgb d;
            for (int l = realLights_; l < lights; ++l) d += radiance_[l] * (kPi * G[l]);
            virtualDirect_[v] = d;
        }
    });
    if (cache) cache->vertexHits += hits.load();
}

std::vector<double> DynamicRelighting::geometryKey() const {
    // What the direct light's geometry terms depend on beyond the prepared scene: the faces
    // put in (virtual objects' and lamps'), the objects taken out, the emitters' shapes
    // (their fields, strengths among them: a key that changes more often than it must is
    // safe). Radiances are left out: that is the point.
    const auto& scene = solver_.scene();
    std::vector<double> key{static_cast<double>(scene.polygons.size()),
                            static_cast<double>(scene.lights.size())};
    for (size_t p = realPolygons_; p < scene.polygons.size(); ++p) {
        const auto& poly = scene.polygons[p];
        key.push_back(poly.vertexCount);
        key.push_back(poly.light);
        for (int i = 0; i < poly.vertexCount; ++i)
            for (int c = 0; c < 3; ++c) key.push_back(poly.v[static_cast<size_t>(i)][c]);
    }
    for (const int o : solver_.removedObjects()) key.push_back(o);
    key.push_back(-1);
    for (const auto& light : scene.lights) {
        if (!light.emitter || light.component != 0) continue;
        for (const radiosity::EmitterField& f : light.emitter->fields())
            key.insert(key.end(), f.values.begin(), f.values.end());
    }
    return key;
}

GeometryCache* DynamicRelighting::geometryCache() {
    if (!cache_) return nullptr;
    std::vector<double> key = geometryKey();
    if (key != cache_->key || cache_->lights != solver_.scene().lights.size()) {
        cache_->key = std::move(key);
        cache_->lights = solver_.scene().lights.size();
        cache_->pixelDirect.clear();
        cache_->pixelFrom.clear();
        cache_->vertexG.clear();
        cache_->vertexFrom.clear();
    }
    return cache_;
}

std::vector<Rgb> DynamicRelighting::reflectedChange() const {
    // Per node: what it reflects now less what it reflected before any virtual part. A leaf
    // of the scene split since inherits its ancestor's "before" (the children come after
    // their parent); a virtual part reflected nothing before; a cluster is the area-weighted
    // mean of its children, as the solver pulls B (Hierarchy::pullAverages).
    const auto& nodes = solver_.hierarchy().nodes;
    std::vector<Rgb> before(nodes.size()), change(nodes.size());
    for (size_t n = 0; n < nodes.size(); ++n) {
        const Node& e = nodes[n];
        if (e.isCluster()) continue;
        if (static_cast<size_t>(e.polygon) < realPolygons_)
            before[n] = n < realNodes_ ? reflected0_[n] : before[static_cast<size_t>(e.parent)];
        change[n] = reflectedBy(e) - before[n];
    }
    const auto pull = [&](const auto& self, int node) -> void {
        const Node& c = nodes[static_cast<size_t>(node)];
        if (!c.isCluster()) return;
        Rgb sum;
        double area = 0;
        for (int k = 0; k < c.childCount; ++k) {
            self(self, c.firstChild + k);
            const Node& ch = nodes[static_cast<size_t>(c.firstChild + k)];
            sum += ch.area * change[static_cast<size_t>(c.firstChild + k)];
            area += ch.area;
        }
        change[static_cast<size_t>(node)] = area > 0 ? (1.0 / area) * sum : Rgb{};
    };
    pull(pull, radiosity::Hierarchy::kRoot);
    return change;
}

std::optional<std::vector<int>> DynamicRelighting::addedLampFaces() const {
    // The rays of the preparation still meet what they met if nothing was taken out and
    // every part put in is a lamp's face (returned: each may block a ray); an object or a
    // removal changes what the rays meet (nullopt).
    if (!solver_.removedObjects().empty()) return std::nullopt;
    const auto& polygons = solver_.scene().polygons;
    std::vector<int> faces;
    for (size_t p = realPolygons_; p < polygons.size(); ++p) {
        if (polygons[p].light < 0) return std::nullopt;
        faces.push_back(static_cast<int>(p));
    }
    return faces;
}

std::vector<Rgb> DynamicRelighting::gatherChangeAtVertices(std::span<const Rgb> change, bool byRays,
                                                           const std::vector<int>* only) const {
    const auto& mesh = *r_.mesh;
    const auto& scene = solver_.scene();
    std::vector<Rgb> out(mesh.vertices().size());
    const size_t rays = static_cast<size_t>(r_.gatherSide) * static_cast<size_t>(r_.gatherSide);
    const auto lamps =
        byRays && r_.vertexRayHits.size() == out.size() * rays ? addedLampFaces() : std::nullopt;
    // The lamps' faces that x may see (either side: the back blocks too): met by x's rays.
    auto facesSeen = [&](const Vec3& x, const Vec3& n, std::vector<int>& seen) {
        seen.clear();
        for (const int f : *lamps) {
            const auto& P = scene.polygons[static_cast<size_t>(f)];
            bool ahead = false;
            for (int k = 0; k < P.vertexCount; ++k)
                ahead = ahead || glm::dot(P.v[static_cast<size_t>(k)] - x, n) > 0;
            if (ahead) seen.push_back(f);
        }
    };
    const std::span<const int32_t> hits(r_.vertexRayHits);
    parallelFor(only ? only->size() : out.size(), 16, [&](size_t i) {
        const size_t v = only ? static_cast<size_t>((*only)[i]) : i;
        const int p = mesh.vertices()[v].polygon;
        if (scene.polygons[p].light >= 0) return;
        const radiosity::Vec3 x = mesh.insidePoint(static_cast<int>(v));
        // As the preparation gathered the photo's indirect light: through the links for the
        // vertex lighting, by rays for the per-pixel display (Relighting::gatherSide). The
        // gathers are linear in what the sources reflect: one gather of the change, where
        // gathering before and after would cast every ray twice; where nothing new blocks
        // them, along the preparation's own rays, without casting them.
        if (lamps) {
            thread_local std::vector<int> seen;
            facesSeen(x, scene.polygons[p].normal, seen);
            out[v] = radiosity::rayGatherField(solver_, change, p, x, r_.gatherSide, v,
                                               hits.subspan(v * rays, rays), seen);
            return;
        }
        out[v] = byRays ? radiosity::rayGatherField(solver_, change, p, x, r_.gatherSide, v)
                        : radiosity::finalGatherField(solver_, change, p, x, 4, v);
    });
    return out;
}

void DynamicRelighting::refreshIndirect(bool full) {
    const std::vector<Rgb> now = indirectPerNode();
    const std::vector<Rgb> leaf =
        r_.mesh->averageOfLeaves([&](int n) { return now[n] - indirect0_[n]; });
    if (full && solver_.scene().lights.size() == static_cast<size_t>(realLights_)) {
        // The last virtual light gone: objects count at the leaves again, as before any light
        // came (so that taking them out too brings back the photo's light exactly).
        gatherDelta_.clear();
        gatherDeltaRays_.clear();
        indirectPixel_.clear();
        gatherChange_.clear();
        gatherWaiting_.clear();
    } else if (full) {
        // A light changes the indirect light everywhere: gather it per vertex, as the
        // prepared lighting does for the scene's lights.
        std::vector<Rgb> change = reflectedChange();
        if (r_.gatherSide > 0) {
            // The per-pixel display gathers by rays; the vertices' gather waits for a vertex
            // display (completeVertexGather): inserting a lamp for `render` does not wait for it.
            gatherDeltaRays_ = gatherChangeAtVertices(change, /*byRays=*/true);
            gatherDelta_.assign(leaf.size(), Rgb{});
            gatherWaiting_.assign(leaf.size(), 1);
            gatherChange_ = std::move(change);
        } else {
            gatherDelta_ = gatherChangeAtVertices(change);
        }
        leafAtFull_ = leaf;
    }
    for (size_t v = 0; v < indirect_.size(); ++v)
        indirect_[v] = gatherDelta_.empty() ? leaf[v] : gatherDelta_[v] + leaf[v] - leafAtFull_[v];
    if (!gatherDeltaRays_.empty()) {
        indirectPixel_.resize(indirect_.size());
        for (size_t v = 0; v < indirect_.size(); ++v)
            indirectPixel_[v] = gatherDeltaRays_[v] + leaf[v] - leafAtFull_[v];
    }
    if (static_cast<size_t>(solver_.hierarchy().nodes.size()) <= realNodes_) {
        objectMesh_.reset();
        objectRadiance_.clear();
        objectIndirect_.clear();
        return;
    }
    // The virtual objects' surfaces: rho H / pi at their leaf corners, H from the direct
    // light per vertex and the leaves' indirect light.
    const auto& h = solver_.hierarchy();
    objectMesh_ = std::make_unique<radiosity::LeafMesh>(h, static_cast<int>(realNodes_),
                                                        radiosity::LeafMesh::SplitRule{},
                                                        static_cast<int>(realPolygons_));
    objectIndirect_ = objectMesh_->averageOfLeaves([&](int n) { return now[n]; });
    const std::vector<Rgb>& indirectAtCorners = objectIndirect_;
    const auto& scene = solver_.scene();
    const int lights = static_cast<int>(scene.lights.size());
    const radiosity::DirectLight direct(solver_);
    const size_t nv = objectMesh_->vertices().size();
    objectRadiance_.assign(nv, Rgb{});
    radiosity::parallelForChunks(nv, 8, [&](size_t first, size_t last) {
        std::vector<double> G(static_cast<size_t>(lights));
        for (size_t v = first; v != last; ++v) {
            const int p = objectMesh_->vertices()[v].polygon;
            if (scene.polygons[p].light >= 0) continue;
            direct.geometry(p, objectMesh_->insidePoint(static_cast<int>(v)), kObjectSeed + v,
                            G.data());
            Rgb H = indirectAtCorners[v];
            for (int l = 0; l < lights; ++l) H += radiance_[l] * (kPi * G[l]);
            objectRadiance_[v] = scene.polygons[p].rho * H * (1.0 / kPi);
        }
    });
}

void DynamicRelighting::completeVertexGather(const std::vector<int>* only) const {
    if (gatherWaiting_.empty()) return;
    std::vector<int> todo;
    const auto waiting = [&](int v) { return gatherWaiting_[static_cast<size_t>(v)] != 0; };
    if (only) {
        std::copy_if(only->begin(), only->end(), std::back_inserter(todo), waiting);
    } else {
        for (size_t v = 0; v < gatherWaiting_.size(); ++v)
            if (gatherWaiting_[v]) todo.push_back(static_cast<int>(v));
    }
    const std::vector<Rgb> d = gatherChangeAtVertices(gatherChange_, false, &todo);
    for (const int v : todo) {
        const auto i = static_cast<size_t>(v);
        gatherDelta_[i] = d[i];
        indirect_[i] += d[i];  // it held the gather as 0
        gatherWaiting_[i] = 0;
    }
    if (!only) {
        gatherWaiting_.clear();
        gatherChange_.clear();
    }
}

}  // namespace relight
