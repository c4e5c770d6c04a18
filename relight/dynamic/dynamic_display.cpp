// What a DynamicRelighting session shows (relight/dynamic/dynamic_relighting.h): the
// irradiance and ratios at the display's vertices, the relit image in each display mode,
// and the virtual objects' overlay. The edits, and the updates of light they make, stay in
// dynamic_relighting.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "radiosity/parallel.h"
#include "radiosity/stopwatch.h"
#include "relight/display/wen_display.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/dynamic/overlay_samples.h"
#include "relight/dynamic/quick_light.h"
#include "relight/pipeline/pixel_light.h"

namespace relight {

namespace {
/// Grows the pixel box [x0, x1] x [y0, y1] over what `polygons` project to; the whole image
/// when a corner is behind the camera.
void growProjectedBox(const Camera& camera, std::span<const radiosity::Polygon> polygons, int& x0,
                      int& y0, int& x1, int& y1) {
    for (const radiosity::Polygon& poly : polygons)
        for (int i = 0; i < poly.vertexCount; ++i) {
            double u = 0, v = 0, depth = 0;
            if (!camera.project(poly.v[static_cast<size_t>(i)], u, v, depth) || !(depth > 0)) {
                x0 = y0 = 0;
                x1 = camera.width - 1;
                y1 = camera.height - 1;
                continue;
            }
            x0 = std::min(x0, static_cast<int>(std::floor(u)));
            y0 = std::min(y0, static_cast<int>(std::floor(v)));
            x1 = std::max(x1, static_cast<int>(std::ceil(u)));
            y1 = std::max(y1, static_cast<int>(std::ceil(v)));
        }
}

/// An overlay over the pixel box [x0, x1] x [y0, y1] clipped to the image, its pixels
/// cleared; with no pixels (width and height 0) when nothing of the box is in the image.
VirtualOverlay clippedOverlay(const Camera& camera, int x0, int y0, int x1, int y1) {
    VirtualOverlay o;
    o.x0 = std::max(x0, 0);
    o.y0 = std::max(y0, 0);
    o.width = std::min(x1, camera.width - 1) - o.x0 + 1;
    o.height = std::min(y1, camera.height - 1) - o.y0 + 1;
    if (o.empty()) {
        o.width = o.height = 0;
        return o;
    }
    o.rgba.assign(static_cast<size_t>(o.width) * static_cast<size_t>(o.height) * 4, 0.0f);
    return o;
}
}  // namespace

using radiosity::Clock;
using radiosity::parallelFor;
using radiosity::secondsSince;

const std::vector<int>& DynamicRelighting::ratioPixelVertices() {
    if (ratioPixelVerticesMade_) return ratioPixelVertices_;
    const DisplayMap& map = r_.prepared.display;
    std::vector<char> seen(base_.size(), 0);
    const size_t pixels = map.start.empty() ? 0 : map.start.size() - 1;
    for (size_t px = 0; px < pixels; ++px) {
        if (shownPerPixel(map, px)) continue;
        for (int k = map.start[px]; k < map.start[px + 1]; ++k) {
            const int v = map.vertex[static_cast<size_t>(k)];
            if (!seen[static_cast<size_t>(v)]) ratioPixelVertices_.push_back(v);
            seen[static_cast<size_t>(v)] = 1;
        }
    }
    ratioPixelVerticesMade_ = true;
    return ratioPixelVertices_;
}

std::vector<Rgb> DynamicRelighting::vertexIrradiance() const {
    completeVertexGather();
    return irradianceAsItStands();
}

std::vector<Rgb> DynamicRelighting::irradianceAsItStands() const {
    const size_t nv = base_.size();
    std::vector<Rgb> H(nv);
    for (size_t v = 0; v < nv; ++v)
        H[v] = base_[v] + realDirect_[v] + virtualDirect_[v] + indirect_[v];
    return H;
}

std::vector<Rgb> DynamicRelighting::vertexRatios() const {
    return vertexRatio(r_.prepared, vertexIrradiance());
}

VertexDisplay DynamicRelighting::vertexDisplay(DisplayMode mode) const {
    const std::span<const Rgb> real(radiance_.data(), static_cast<size_t>(realLights_));
    // Fresh light: lamps off in the photo, and all that the virtual parts change (their
    // lamps' light, the light objects block or reflect).
    completeVertexGather();
    SplitIrradiance H = splitIrradiance(r_.prepared, real);
    for (size_t v = 0; v < H.fresh.size(); ++v)
        H.fresh[v] += realDirect_[v] + virtualDirect_[v] + indirect_[v];
    return relight::vertexDisplay(r_.prepared, H, mode);
}

Image DynamicRelighting::render(DisplayMode mode) {
    const auto t0 = Clock::now();
    const PreparedImage& P = r_.prepared;
    const std::span<const Rgb> real(radiance_.data(), static_cast<size_t>(realLights_));
    Image img;
    if (drawsPerPixel(mode)) {
        // The ratio display stays where the per-pixel display does not draw (a lamp's face,
        // nothing, an edge): only those pixels' vertices need the vertices' gather, and the
        // leaf runs, all drawn per pixel, are left out (renderRatio's leafRuns). The same for
        // every per-pixel display.
        completeVertexGather(&ratioPixelVertices());
        renderRatio(P.display, P.photo, vertexRatio(P, irradianceAsItStands()), real,
                    P.photoRadiance, img, {}, /*leafRuns=*/false);
    }
    const Rgb delta = ratioFloor(P.D);
    if (mode == DisplayMode::pixel) {
        renderPixelLight(P.display, P.photo, P.pixelDirect, P.vertexIndirect, radiance_,
                         P.photoRadiance, delta, img,
                         PixelLightChange{pixelDirect(), pixelIndirect()}, P.pixelReflectance,
                         &P.photoPixels);
    } else if (mode == DisplayMode::ratioMap) {
        // ../shared/seeds/000, Eq. (3): the direct irradiance alone, now and in the photo.
        const std::vector<Rgb> noIndirect(P.vertexIndirect.size());
        renderPixelLight(P.display, P.photo, P.pixelDirect, noIndirect, radiance_, P.photoRadiance,
                         delta, img, PixelLightChange{pixelDirect(), {}});
    } else if (mode == DisplayMode::wen) {
        // Wen et al. 2003 (relight/display/wen_display.h): the sky unoccluded and not
        // reflected, in the photo and now (a virtual object does not shade it either); the
        // other lights' light and the virtual parts' bounces as in the per-pixel display.
        const size_t L = P.photoRadiance.size();
        const std::vector<float> photoDirect = unoccludedSkyDirect(P, P.pixelDirect, L);
        const std::span<const float> now = pixelDirect();  // real lights, then virtual ones
        const std::vector<float> nowDirect = unoccludedSkyDirect(P, now, radiance_.size());
        const std::vector<Rgb> indirect = indirectWithoutSky(P);
        const PhotoPixels pool =
            photoPixels(P.display, P.photo, photoDirect, indirect, P.photoRadiance, delta);
        renderPixelLight(P.display, P.photo, photoDirect, indirect, radiance_, P.photoRadiance,
                         delta, img, PixelLightChange{nowDirect, pixelIndirect()},
                         P.pixelReflectance, &pool);
    } else if (mode == DisplayMode::ratio) {
        img = renderRatio(P.display, P.photo, vertexRatios(), real, P.photoRadiance);
    } else {
        const VertexDisplay d = vertexDisplay(mode);
        renderRatio(P.display, P.photo, d.ratio, real, P.photoRadiance, img, d.added);
    }
    const double tRatio = secondsSince(t0);
    applyOverlay(img, overlay());
    if (objectPreview_) applyOverlay(img, previewOverlay());
    times_.display += tRatio;
    return img;
}

std::optional<radiosity::ShadowSource> DynamicRelighting::shownSource(int light) const {
    const auto& lights = solver_.scene().lights;
    if (light < 0 || static_cast<size_t>(light) >= lights.size()) return std::nullopt;
    for (const Preview& q : previews_)  // shown moved: where previewEmitter() put it
        if (q.light == light && q.emitter) return q.emitter->shadowSource();
    const radiosity::Light& l = lights[static_cast<size_t>(light)];
    if (l.emitter) return l.emitter->shadowSource();
    if (l.polygons.size() != 1) return std::nullopt;
    // A lamp of one face, as the quad lamp's model has it.
    const radiosity::Polygon& face = solver_.scene().polygons[static_cast<size_t>(l.polygons[0])];
    return radiosity::makeQuadLamp(l.name, {{face.v.begin(), face.v.begin() + face.vertexCount}},
                                   l.polygons, Rgb{1, 1, 1})
        ->shadowSource();
}

std::vector<float> DynamicRelighting::faceOccluders(int light) const {
    // The overlay's first hits (overlay(): the virtual parts, the moved face passed where the
    // solver holds it), one ray through each pixel's centre.
    const Camera& camera = r_.scene.camera;
    const Vec3 eye = camera.position();
    const auto& polygons = solver_.scene().lights[static_cast<size_t>(light)].polygons;
    const int passed = polygons.size() == 1 ? polygons[0] : -1;
    const size_t width = static_cast<size_t>(camera.width);
    std::vector<float> out(3 * width * static_cast<size_t>(camera.height));
    parallelFor(static_cast<size_t>(camera.height), 1, [&](size_t y) {
        for (size_t x = 0; x < width; ++x) {
            const Vec3 dir = camera.rayDirection(static_cast<double>(x), static_cast<double>(y));
            const auto hit = solver_.visibility().intersect(eye, dir, 0, 1e30, passed);
            const Vec3 at = eye + (hit.polygon >= 0 ? hit.t : 1e6) * dir;
            for (int c = 0; c < 3; ++c)
                out[3 * (y * width + x) + static_cast<size_t>(c)] = static_cast<float>(at[c]);
        }
    });
    return out;
}

std::optional<MovedLightFrame> DynamicRelighting::movedLightFrame(int light) {
    const PreparedImage& P = r_.prepared;
    const auto& lights = solver_.scene().lights;
    if (objectPreview_ || !P.pixelReflectance.empty() || P.pixelDirect.empty() || light < 0 ||
        static_cast<size_t>(light) >= lights.size())
        return std::nullopt;
    const std::optional<radiosity::ShadowSource> source = shownSource(light);
    if (!source) return std::nullopt;
    MovedLightFrame f;
    f.source = *source;
    f.camera = r_.scene.camera;
    f.samplesPerSide = OverlaySamples(r_.items.spp).k;
    // The ratio display where the per-pixel display does not draw, as render() makes it.
    const auto t0 = Clock::now();
    completeVertexGather(&ratioPixelVertices());
    const std::span<const Rgb> real(radiance_.data(), static_cast<size_t>(realLights_));
    Image img;
    renderRatio(P.display, P.photo, vertexRatio(P, irradianceAsItStands()), real, P.photoRadiance,
                img, {}, /*leafRuns=*/false);
    f.terms = pixelLightTerms(
        P.display, P.photo, P.pixelDirect, P.vertexIndirect, radiance_, P.photoRadiance,
        ratioFloor(P.D), PixelLightChange{pixelDirectExcept(light), pixelIndirect()}, light,
        P.pixelReflectance, &P.photoPixels, cache_ ? cache_->pooledByRadius : nullptr);
    if (cache_) cache_->pooledByRadius = f.terms.pooled;
    f.receivers = quickReceivers(r_.items, solver_.scene());
    if (f.source.kind == radiosity::ShadowSource::Kind::face) f.surface = faceOccluders(light);
    const auto& polygons = solver_.scene().polygons;
    for (size_t p = 0; p < polygons.size(); ++p) {
        const radiosity::Polygon& poly = polygons[p];
        // A lamp's own faces do not block it (where the solver holds them while it moves).
        if (solver_.visibility().hidden(static_cast<int>(p)) || poly.light == light) continue;
        for (int k = 1; k + 1 < poly.vertexCount; ++k)  // a fan: the polygons are convex
            for (const int i : {0, k, k + 1})
                for (int c = 0; c < 3; ++c)
                    f.blockers.push_back(static_cast<float>(poly.v[static_cast<size_t>(i)][c]));
    }
    // image = scale * out + offset: out where drawn per pixel, the ratio display's value
    // elsewhere; the overlay (applyOverlay) on both.
    const size_t pixels = f.terms.drawn.size();
    f.scale.assign(3 * pixels, 1.0f);
    f.offset.assign(3 * pixels, 0.0f);
    for (size_t px = 0; px < pixels; ++px)
        if (!f.terms.drawn[px])
            for (size_t c = 0; c < 3; ++c) {
                f.scale[3 * px + c] = 0.0f;
                f.offset[3 * px + c] = img.rgb[3 * px + c];
            }
    // The moved lamp's face is the GPU's to draw, where it is at each frame.
    const VirtualOverlay o = overlay(/*movedFaces=*/false);
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            const float* a = &o.rgba[(static_cast<size_t>(y) * o.width + x) * 4];
            const size_t px = static_cast<size_t>(o.y0 + y) * static_cast<size_t>(img.width) +
                              static_cast<size_t>(o.x0 + x);
            for (size_t c = 0; c < 3; ++c) {
                f.scale[3 * px + c] *= a[3];
                f.offset[3 * px + c] = a[3] * f.offset[3 * px + c] + a[c];
            }
        }
    times_.display += secondsSince(t0);
    return f;
}

void applyOverlay(Image& img, const VirtualOverlay& o) {
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            const float* a = &o.rgba[(static_cast<size_t>(y) * o.width + x) * 4];
            float* px = img.at(o.x0 + x, o.y0 + y);
            for (int c = 0; c < 3; ++c) px[c] = a[3] * px[c] + a[c];
        }
}

std::vector<DynamicRelighting::MovedFace> DynamicRelighting::movedFaces() const {
    std::vector<MovedFace> out;
    for (const Preview& q : previews_) {
        const radiosity::Light& l = solver_.scene().lights[static_cast<size_t>(q.light)];
        if (l.emitter || l.polygons.size() != 1 || !q.emitter) continue;
        const std::optional<radiosity::ShadowSource> s = q.emitter->shadowSource();
        if (s && s->kind == radiosity::ShadowSource::Kind::face)
            out.push_back({q.light, l.polygons[0], s->corners});
    }
    return out;
}

VirtualOverlay DynamicRelighting::overlay(bool drawMoved) {
    const auto t0 = Clock::now();
    // The item buffer again, in the projected box of the virtual parts only (the pixels of
    // an old position outside it are the ratio display's).
    const Camera& camera = r_.scene.camera;
    const auto& scene = solver_.scene();
    int x0 = camera.width, y0 = camera.height, x1 = -1, y1 = -1;
    growProjectedBox(camera, std::span(scene.polygons).subspan(realPolygons_), x0, y0, x1, y1);
    // A lamp's face shown moved: the camera's rays pass it where the solver holds it (one
    // such face: Visibility::intersect ignores one polygon), and meet it where it now is.
    const std::vector<MovedFace> moved = movedFaces();
    const int passed = moved.empty() ? -1 : moved.back().polygon;
    if (drawMoved && !moved.empty()) {
        radiosity::Polygon now;
        now.vertexCount = static_cast<int>(std::min<size_t>(moved.back().corners.size(), 4));
        std::copy_n(moved.back().corners.begin(), now.vertexCount, now.v.begin());
        growProjectedBox(camera, std::span(&now, 1), x0, y0, x1, y1);
    }
    // The pixels of the real objects taken out.
    const RemovedRegion& gone = removed_;
    if (!gone.empty()) {
        x0 = std::min(x0, gone.x0);
        y0 = std::min(y0, gone.y0);
        x1 = std::max(x1, gone.x0 + gone.width - 1);
        y1 = std::max(y1, gone.y0 + gone.height - 1);
    }
    VirtualOverlay o = clippedOverlay(camera, x0, y0, x1, y1);
    if (o.empty()) {
        times_.display = secondsSince(t0);
        return o;
    }
    const OverlaySamples samples(r_.items.spp);
    const int k = samples.k;
    const Vec3 eye = camera.position();
    const auto& h = solver_.hierarchy();
    const auto& vis = solver_.visibility();
    // The lights of the specular pass, when a virtual object in the scene has a term.
    std::unique_ptr<SpecularLights> specular;
    for (size_t i = 0; i < objectSpecular_.size() && i < scene.objects.size() && !specular; ++i)
        if (objectSpecular_[i]) specular = std::make_unique<SpecularLights>(scene, radiance_);
    parallelFor(static_cast<size_t>(o.height), 1, [&](size_t row) {
        const int by = static_cast<int>(row);
        for (int bx = 0; bx < o.width; ++bx) {
            const int x = o.x0 + bx, y = o.y0 + by;
            double realShare = 0;
            Rgb added;
            // A pixel of a removed object: replaced whole, its real samples by the fill.
            const bool filled = !gone.empty() && gone.inMask(x, y);
            const size_t g =
                filled ? static_cast<size_t>((y - gone.y0) * gone.width + x - gone.x0) : 0;
            for (int s = 0; s < k * k; ++s) {
                const auto [u, v] = samples.at(x, y, s);
                const Vec3 dir = camera.rayDirection(u, v);
                const auto hit = vis.intersect(eye, dir, 0, 1e30, passed);
                bool front = false;
                const double tFace = drawMoved && passed >= 0
                                         ? rayFace(eye, dir, moved.back().corners, &front)
                                         : std::numeric_limits<double>::infinity();
                if (tFace < (hit.polygon >= 0 ? hit.t : std::numeric_limits<double>::infinity())) {
                    // Its back is black, as a virtual lamp's below.
                    if (front) added += radiance_[static_cast<size_t>(moved.back().light)];
                    continue;
                }
                if (hit.polygon < static_cast<int>(realPolygons_) && filled) {
                    const size_t i = g * static_cast<size_t>(k * k) + static_cast<size_t>(s);
                    const int p = gone.polygon[i];
                    if (p < 0) continue;
                    const int light = scene.polygons[static_cast<size_t>(p)].light;
                    if (light >= 0) {
                        added += radiance_[static_cast<size_t>(light)];
                        continue;
                    }
                    if (gone.leaf[i] < 0) continue;
                    const Rgb Hs = gone.direct[i] + removedIndirect(gone, g, i);
                    for (int c = 0; c < 3; ++c)
                        added[c] +=
                            static_cast<double>(gone.reflectance[3 * g + static_cast<size_t>(c)]) *
                            Hs[c];
                    continue;
                }
                if (hit.polygon < static_cast<int>(realPolygons_)) {
                    realShare += 1;  // the photo's sample, as the ratio display shows
                    continue;
                }
                const auto& poly = scene.polygons[hit.polygon];
                if (glm::dot(poly.normal, dir) >= 0) continue;  // back: black
                if (poly.light >= 0) {
                    added += radiance_[poly.light];
                    continue;
                }
                const Vec3 point = eye + hit.t * dir;
                // ../shared/seeds/000, §6: the specular radiance on top of the diffuse.
                const uint64_t sample =
                    (static_cast<uint64_t>(y) * static_cast<uint64_t>(camera.width) +
                     static_cast<uint64_t>(x)) *
                        static_cast<uint64_t>(k * k) +
                    static_cast<uint64_t>(s);
                added += specularAt(specular.get(), hit.polygon, point, dir, sample);
                if (!objectMesh_) continue;
                const int leaf = h.locateLeaf(hit.polygon, point);
                const auto w = objectMesh_->weights(leaf, point);
                const auto& corners = objectMesh_->corners(leaf);
                for (int i = 0; i < h.nodes[leaf].vertexCount; ++i)
                    added += objectRadiance_[corners[i]] * w[i];
            }
            const double n = static_cast<double>(k * k);
            float* a = &o.rgba[(static_cast<size_t>(by) * o.width + bx) * 4];
            for (int c = 0; c < 3; ++c) a[c] = static_cast<float>(added[c] / n);
            a[3] = static_cast<float>(realShare / n);
        }
    });
    times_.display = secondsSince(t0);
    return o;
}

namespace {
// The stream of the moved object's shadow rays (previewOverlay), apart from the others.
constexpr uint64_t kPreviewSeed = 0x7d4a6bull << 28;
constexpr double kPi = std::numbers::pi;
}  // namespace

VirtualOverlay DynamicRelighting::previewOverlay() const {
    const ObjectPreview& q = *objectPreview_;
    const Camera& camera = r_.scene.camera;
    int x0 = camera.width, y0 = camera.height, x1 = -1, y1 = -1;
    growProjectedBox(camera, q.polygons, x0, y0, x1, y1);
    VirtualOverlay o = clippedOverlay(camera, x0, y0, x1, y1);
    if (o.empty()) return o;
    const OverlaySamples samples(r_.items.spp);
    const Vec3 eye = camera.position();
    const auto& scene = solver_.scene();
    const auto& vis = solver_.visibility();
    const size_t L = scene.lights.size();
    parallelFor(static_cast<size_t>(o.height), 1, [&](size_t row) {
        std::vector<double> G(L);
        const int by = static_cast<int>(row);
        for (int bx = 0; bx < o.width; ++bx) {
            const int x = o.x0 + bx, y = o.y0 + by;
            double realShare = 0;
            Rgb added, shade;
            int shaded = -1;  // the face whose radiance `shade` holds for this pixel
            for (int s = 0; s < samples.count(); ++s) {
                const auto [u, v] = samples.at(x, y, s);
                const Vec3 dir = camera.rayDirection(u, v);
                const auto hit = q.vis->intersect(eye, dir);
                // Not the object, or the scene (or another part) in front of it: the image
                // as it is there.
                if (hit.polygon < 0 || vis.occluded(eye, dir, 0, hit.t)) {
                    realShare += 1;
                    continue;
                }
                const size_t f = static_cast<size_t>(hit.polygon);
                const radiosity::Polygon& face = q.polygons[f];
                if (glm::dot(face.normal, dir) >= 0) continue;  // back: black, as overlay()
                if (shaded != hit.polygon) {
                    // One point per pixel and face: the direct light from kPreviewRays rays
                    // per lamp face, the indirect as the face gathered it before the drag.
                    const radiosity::ReceiverPoint at{eye + hit.t * dir, face.normal, -1};
                    const uint64_t seed =
                        kPreviewSeed ^
                        ((static_cast<uint64_t>(y) * 4099u + static_cast<uint64_t>(x)) * 64u + f);
                    quickPointGeometry(scene, vis, /*sameScene=*/true, at, kPreviewRays, seed,
                                       G.data());
                    Rgb H = q.indirect[f];
                    for (size_t l = 0; l < L && l < radiance_.size(); ++l)
                        H += radiance_[l] * (kPi * G[l]);
                    shade = q.rho[f] * H * (1.0 / kPi);
                    shaded = hit.polygon;
                }
                added += shade;
            }
            const double n = static_cast<double>(samples.count());
            float* a = &o.rgba[(static_cast<size_t>(by) * static_cast<size_t>(o.width) +
                                static_cast<size_t>(bx)) *
                               4];
            for (int c = 0; c < 3; ++c) a[c] = static_cast<float>(added[c] / n);
            a[3] = static_cast<float>(realShare / n);
        }
    });
    return o;
}

}  // namespace relight
