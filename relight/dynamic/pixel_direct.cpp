// DynamicRelighting's per-pixel direct light (dynamic_relighting.h, pixelDirect): the
// photo's, measured again where a virtual part changes it, each virtual light's at every
// pixel; and the quick looks of a drag, a sun or point lamp moved (previewEmitter) or the
// object added last moved (previewLastObject), which replace or scale its columns.
#include <algorithm>
#include <atomic>
#include <numbers>
#include <stdexcept>
#include <string>

#include "radiosity/parallel.h"
#include "radiosity/stopwatch.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/dynamic/quick_light.h"

namespace relight {

using radiosity::Clock;
using radiosity::parallelFor;
using radiosity::secondsSince;

namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

void DynamicRelighting::markChangedLeaves(const std::vector<int>& leaves) {
    if (leafPending_.empty()) {
        leafPending_.assign(realNodes_, 0);
        leafEver_.assign(realNodes_, 0);
    }
    const auto& nodes = solver_.hierarchy().nodes;
    for (int leaf : leaves) {
        // A leaf the insertion made by subdividing one of the scene's: that one.
        while (leaf >= 0 && static_cast<size_t>(leaf) >= realNodes_) leaf = nodes[leaf].parent;
        if (leaf < 0) continue;
        leafPending_[static_cast<size_t>(leaf)] = 1;
        leafEver_[static_cast<size_t>(leaf)] = 1;
    }
}

std::span<const float> DynamicRelighting::pixelDirect() {
    return pixelDirectExcept(-1);
}

std::span<const float> DynamicRelighting::pixelDirectExcept(int unmeasured) {
    const PreparedImage& P = r_.prepared;
    const ItemBuffer& items = r_.items;
    const auto& scene = solver_.scene();
    const auto& h = solver_.hierarchy();
    const size_t Lr = static_cast<size_t>(realLights_), L = scene.lights.size();
    const size_t pixels = static_cast<size_t>(items.width) * static_cast<size_t>(items.height);
    if (P.pixelDirect.size() != pixels * Lr)
        throw std::invalid_argument(
            "DynamicRelighting: the per-pixel display needs a preparation with per-pixel light");
    if (leafPending_.empty()) markChangedLeaves({});
    if (sampleLeaf_.empty() && cache_ && cache_->sampleLeaf.size() == items.polygon.size())
        sampleLeaf_ = cache_->sampleLeaf;  // the prepared scene's leaves: any edit's
    if (sampleLeaf_.empty()) {
        sampleLeaf_.assign(items.polygon.size(), -1);
        parallelFor(sampleLeaf_.size(), 4096, [&](size_t i) {
            int leaf = locateSample(items, h, scene, static_cast<int>(i)).leaf;
            while (leaf >= 0 && static_cast<size_t>(leaf) >= realNodes_)
                leaf = h.nodes[leaf].parent;
            sampleLeaf_[i] = leaf;
        });
        if (cache_) cache_->sampleLeaf = sampleLeaf_;
    }
    GeometryCache* const cache = geometryCache();
    if (cache && cache->pixelFrom.size() != pixels) {
        cache->pixelDirect.assign(pixels * L, 0.0f);
        cache->pixelFrom.assign(pixels, 0);
    }
    // A light added or removed: start again from the photo's light, every virtual light at
    // every pixel, the real lights where any part ever changed them.
    const bool full = pixelLights_ != L || pixelDirect_.size() != pixels * L;
    const std::vector<char>& changed = full ? leafEver_ : leafPending_;
    if (full) {
        pixelDirect_.assign(pixels * L, 0.0f);
        for (size_t px = 0; px < pixels; ++px)
            std::copy_n(P.pixelDirect.begin() + static_cast<std::ptrdiff_t>(px * Lr), Lr,
                        pixelDirect_.begin() + static_cast<std::ptrdiff_t>(px * L));
        pixelLights_ = L;
    }
    const radiosity::DirectLight direct(solver_, r_.directOptions);
    const int spp = items.spp;
    std::atomic<uint64_t> hits{0};
    radiosity::parallelForChunks(pixels, 64, [&](size_t first, size_t last) {
        std::vector<double> G(L), sum(L);
        for (size_t px = first; px != last; ++px) {
            const int x = static_cast<int>(px % static_cast<size_t>(items.width));
            const int y = static_cast<int>(px / static_cast<size_t>(items.width));
            bool dirty = false;
            for (int s = 0; s < spp && !dirty; ++s) {
                const int leaf = sampleLeaf_[static_cast<size_t>(items.sampleIndex(x, y, s))];
                dirty = leaf >= 0 && changed[static_cast<size_t>(leaf)];
            }
            // Only the virtual lights where nothing blocks anew.
            const size_t firstLight = dirty ? 0 : Lr;
            if (firstLight == L || (!dirty && !full)) continue;
            const auto at = static_cast<std::ptrdiff_t>(px * L + firstLight);
            const auto count = static_cast<std::ptrdiff_t>(L - firstLight);
            if (cache && cache->pixelFrom[px] > 0 &&
                static_cast<size_t>(cache->pixelFrom[px] - 1) <= firstLight) {
                // Measured in this geometry before: the same rays would give the same values.
                std::copy_n(cache->pixelDirect.begin() + at, count, pixelDirect_.begin() + at);
                hits.fetch_add(1, std::memory_order_relaxed);
                continue;
            }
            std::fill(sum.begin(), sum.end(), 0.0);
            int n = 0;
            for (int s = 0; s < spp; ++s) {
                const int idx = items.sampleIndex(x, y, s);
                const int p = items.polygon[static_cast<size_t>(idx)];
                if (p < 0 || scene.polygons[static_cast<size_t>(p)].light >= 0) continue;
                // Seeded by the sample, as the preparation's rays (pipeline/lighting_buffer.h):
                // where no part blocks, the same value.
                direct.geometry(p, items.point[static_cast<size_t>(idx)],
                                static_cast<uint64_t>(idx), G.data(), nullptr,
                                static_cast<int>(firstLight));
                // Each sample's value rounded to float before the sum, as the preparation
                // stores it (pipeline/lighting_buffer.h, LightingBuffer::G, summed by
                // pixel_light.h's pixelDirect): summed in double, a pixel whose objects are
                // all back came out up to 4e-9 off the photo's (data/furnished), where an
                // undone edit must give the photo's display back bit for bit.
                for (size_t l = firstLight; l < L; ++l)
                    sum[l] += static_cast<double>(static_cast<float>(G[l]));
                ++n;
            }
            for (size_t l = firstLight; l < L; ++l)
                pixelDirect_[px * L + l] = n > 0 ? static_cast<float>(kPi * sum[l] / n) : 0.0f;
            if (cache) {
                std::copy_n(pixelDirect_.begin() + at, count, cache->pixelDirect.begin() + at);
                cache->pixelFrom[px] = static_cast<int>(firstLight) + 1;
            }
        }
    });
    if (cache) cache->pixelHits += hits.load();
    std::fill(leafPending_.begin(), leafPending_.end(), 0);
    if (previews_.empty() && !objectPreview_) return pixelDirect_;
    // The lights shown moved (previewEmitter): their columns from the quick measurement,
    // made now where it was not yet.
    for (Preview& q : previews_)
        if (q.direct.empty() && q.light != unmeasured) {
            const auto t0 = Clock::now();
            q.direct = quickPixelLight(r_.items, solver_.scene(), solver_.visibility(), *q.emitter);
            times_.display += secondsSince(t0);
        }
    pixelShown_ = pixelDirect_;
    for (const Preview& q : previews_)
        for (size_t px = 0; px < pixels; ++px)
            for (int c = 0; c < q.count; ++c)
                pixelShown_[px * L + static_cast<size_t>(q.light + c)] =
                    q.direct.empty()
                        ? 0.0f
                        : q.direct[px * static_cast<size_t>(q.count) + static_cast<size_t>(c)];
    // The object shown moved (previewLastObject): the share of each light it lets through.
    if (objectPreview_ && objectPreview_->transmission.size() == pixelShown_.size())
        for (size_t i = 0; i < pixelShown_.size(); ++i)
            pixelShown_[i] *= objectPreview_->transmission[i];
    return pixelShown_;
}

void DynamicRelighting::previewEmitter(int light, const radiosity::Emitter& moved) {
    noPreview("previewEmitter");
    const auto& lights = solver_.scene().lights;
    if (light < 0 || static_cast<size_t>(light) >= lights.size())
        throw std::invalid_argument("previewEmitter: no light at that index");
    const radiosity::Light& held = lights[static_cast<size_t>(light)];
    // A light of faces (a quad lamp) is shown as a quad emitter of one component.
    const int heldCount = held.emitter ? held.emitter->components() : 1;
    if (!held.emitter && (held.polygons.empty() || std::string(moved.type()) != "quad"))
        throw std::invalid_argument("previewEmitter: \"" + held.name +
                                    "\" is a lamp of faces: it is shown moved as a quad");
    const int count = moved.components();
    if (count != heldCount || static_cast<size_t>(light + count) > lights.size())
        throw std::invalid_argument("previewEmitter: \"" + moved.name() +
                                    "\" has another number of components");
    // Measured when the image is made (pixelDirect()): a display that measures the light
    // itself (the viewer's GPU frames, movedLightFrame) never asks for it.
    const auto it = std::find_if(previews_.begin(), previews_.end(),
                                 [&](const Preview& q) { return q.light == light; });
    std::shared_ptr<const radiosity::Emitter> shown = moved.clone();
    if (it != previews_.end()) {
        it->direct.clear();
        it->emitter = std::move(shown);
    } else {
        previews_.push_back({light, count, {}, std::move(shown)});
    }
    times_ = FrameTimes{};
}

void DynamicRelighting::noPreview(const char* what) const {
    if (objectPreview_)
        throw std::logic_error(std::string("DynamicRelighting::") + what +
                               ": an object is shown moved (previewLastObject); insert the "
                               "parts again first");
}

bool DynamicRelighting::startObjectPreview(const std::vector<radiosity::Polygon>& polygons) {
    const auto& scene = solver_.scene();
    const size_t count = polygons.size();
    if (solver_.insertedObjects() == 0 || solver_.lastIsRemoval() ||
        !solver_.removedObjects().empty() || count == 0 ||
        scene.polygons.size() < realPolygons_ + count)
        return false;
    const size_t first = scene.polygons.size() - count;
    const int object = scene.polygons[first].object;
    for (size_t p = first; p < scene.polygons.size(); ++p)
        if (scene.polygons[p].light >= 0 || scene.polygons[p].object != object) return false;
    if (first > realPolygons_ && scene.polygons[first - 1].object == object)
        return false;  // another face count than the object's
    if (object >= 0 && static_cast<size_t>(object) < objectSpecular_.size() &&
        objectSpecular_[static_cast<size_t>(object)])
        return false;  // the specular pass is not drawn quickly
    auto q = std::make_unique<ObjectPreview>();
    // What the faces gathered as last solved: the mean over each face's leaf corners.
    q->rho.resize(count);
    q->indirect.assign(count, Rgb{});
    std::vector<double> corners(count, 0.0);
    if (objectMesh_ && objectIndirect_.size() == objectMesh_->vertices().size())
        for (size_t v = 0; v < objectIndirect_.size(); ++v) {
            const int p = objectMesh_->vertices()[v].polygon;
            if (p < static_cast<int>(first)) continue;
            q->indirect[static_cast<size_t>(p) - first] += objectIndirect_[v];
            corners[static_cast<size_t>(p) - first] += 1;
        }
    for (size_t i = 0; i < count; ++i) {
        q->rho[i] = scene.polygons[first + i].rho;
        if (corners[i] > 0) q->indirect[i] = q->indirect[i] * (1.0 / corners[i]);
    }
    // The object out of the solver: the rest exactly as without it (one update).
    completeVertexGather();
    radiosity::DynamicUpdate u;
    solver_.removeLastObject(&u);
    objectSpecular_.resize(std::min(objectSpecular_.size(), solver_.scene().objects.size()));
    afterUpdate(u, false);
    // The object alone, in an Embree scene of its own (moved by movePolygons).
    q->vis = std::make_unique<radiosity::Visibility>(radiosity::Scene{});
    q->group = q->vis->addPolygons(polygons, 0);
    objectPreview_ = std::move(q);
    return true;
}

bool DynamicRelighting::previewLastObject(const std::vector<radiosity::Polygon>& polygons) {
    const auto t0 = Clock::now();
    if (!objectPreview_) {
        if (!startObjectPreview(polygons)) return false;
    } else {
        if (polygons.size() != objectPreview_->polygons.size()) return false;
        objectPreview_->vis->movePolygons(objectPreview_->group, polygons);
        times_ = FrameTimes{};
    }
    ObjectPreview& q = *objectPreview_;
    q.polygons = polygons;
    q.transmission = quickTransmission(r_.items, solver_.scene(), *q.vis,
                                       boundingSphere(q.polygons), kPreviewRays);
    times_.visibility += secondsSince(t0);
    return true;
}

}  // namespace relight
