#include "relight/dynamic/object_removal.h"
#include "relight/dynamic/overlay_samples.h"
#include "relight/dynamic/rectified_fill.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "radiosity/direct_light.h"
#include "radiosity/final_gather.h"
#include "radiosity/parallel.h"
#include "relight/pipeline/pixel_light.h"
#include "relight/pipeline/texture_fill.h"

namespace relight {

using radiosity::Rgb;
using radiosity::Vec3;

namespace {

constexpr double kPi = std::numbers::pi;
// Seeds of the shadow rays of the region's samples, apart from the scene's and the objects'.
constexpr uint64_t kRegionSeed = 0x4e30e5ull << 28;
/// Sources whose photo irradiance is below this fraction of their surface's median are
/// left out of the texture sample: in a shadow, T / H is the photo's noise over a small,
/// less certain H (the 1999 paper's confidence, §4.2). Half: the Cornell box with its blocks
/// taken out showed a ghost of a penumbra copied from 10 % (bench/RESULTS.md, 2026-11-26).
constexpr double kDarkSource = 0.5;
/// The texture sample: the photo's pixels within this many pixels of the mask's box, or
/// its own size if larger (a wide hole needs a wide sample).
constexpr int kSampleMargin = 48;

/// The photo's irradiance at pixel px: the per-pixel display's denominator, or, without
/// per-pixel light, the vertex irradiance interpolated with the display map's weights.
Rgb photoIrradiance(const PreparedImage& P, size_t px) {
    if (!P.pixelDirect.empty())
        return photoIrradianceAt(P.display, px, P.pixelDirect, P.vertexIndirect, P.photoRadiance);
    const DisplayMap& map = P.display;
    const int k0 = map.start[px], k1 = map.start[px + 1];
    double wsum = 0;
    for (int k = k0; k < k1; ++k) wsum += static_cast<double>(map.weight[static_cast<size_t>(k)]);
    Rgb H;
    if (!(wsum > 0)) return H;
    for (int k = k0; k < k1; ++k)
        H += P.lighting.irradiance(map.vertex[static_cast<size_t>(k)], P.photoRadiance) *
             (static_cast<double>(map.weight[static_cast<size_t>(k)]) / wsum);
    return H;
}

/// Max filter of radius g over a w x h mask, separable (rows, then columns).
std::vector<char> dilate(const std::vector<char>& m, int w, int h, int g) {
    std::vector<char> rows(m.size(), 0), out(m.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!m[static_cast<size_t>(y * w + x)]) continue;
            for (int d = std::max(0, x - g); d <= std::min(w - 1, x + g); ++d)
                rows[static_cast<size_t>(y * w + d)] = 1;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!rows[static_cast<size_t>(y * w + x)]) continue;
            for (int d = std::max(0, y - g); d <= std::min(h - 1, y + g); ++d)
                out[static_cast<size_t>(d * w + x)] = 1;
        }
    return out;
}

/// The region's indirect light per box pixel and real light: side^2 rays per sample, the
/// photo's gather of a vertex over a pixel's samples, at the pixels of a lattice of step
/// 2 `block`, then averaged over the lattice pixels within 2 `block` that see the same
/// surface (indirect light varies slowly along a surface: 4 to 9 pixels' worth of rays
/// bring the noise to a half or a third of one pixel's, for a quarter of the rays).
void gatherRegionIndirect(RemovedRegion& region, const Relighting& r,
                          const std::vector<int>& nowSurface, int bw, int bh, int block) {
    const auto& solver = *r.solver;
    const size_t L = static_cast<size_t>(std::max(0, r.responses->lights()));
    const size_t kk = static_cast<size_t>(region.k * region.k);
    const size_t boxPixels = static_cast<size_t>(bw) * static_cast<size_t>(bh);
    const int side = std::max(2, r.gatherSide / region.k);
    // The responses are the photo's solution's; the solver's own, solved again with the
    // objects out, holds the light they blocked from the surfaces around (their shadows
    // gone): the same rays read it too, and the ratio of the two corrects the responses.
    const auto& lights = solver.scene().lights;
    std::vector<Rgb> own(boxPixels * L, Rgb{}), now(boxPixels, Rgb{}), then(boxPixels, Rgb{});
    std::vector<int> count(boxPixels, 0);
    // The lattice grows with `block`: the rays per area of the scene stay those of a
    // 320 x 240 photo.
    const int step = 2 * std::max(1, block);
    radiosity::parallelForChunks(boxPixels, 4, [&](size_t first, size_t last) {
        std::vector<Rgb> H(L);
        for (size_t b = first; b != last; ++b) {
            const int x = region.x0 + static_cast<int>(b % static_cast<size_t>(bw));
            const int y = region.y0 + static_cast<int>(b / static_cast<size_t>(bw));
            if (x % step != 0 || y % step != 0) continue;
            for (size_t s = 0; s < kk; ++s) {
                const size_t i = b * kk + s;
                if (region.leaf[i] < 0) continue;
                const uint64_t seed = kRegionSeed ^ (i * 0x9E3779B9ull);
                radiosity::rayGatherResponses(solver, *r.responses, region.polygon[i],
                                              region.point[i], H.data(), side, seed);
                for (size_t l = 0; l < L; ++l) {
                    own[b * L + l] += H[l];
                    if (l < lights.size()) then[b] += lights[l].radiance * H[l];
                }
                now[b] += radiosity::rayGatherIndirect(solver, region.polygon[i], region.point[i],
                                                       side, seed);
                ++count[b];
            }
        }
    });
    const int R = 2 * std::max(1, block);
    region.lights = static_cast<int>(L);
    region.indirect.assign(boxPixels * L, Rgb{});
    region.gathered.assign(boxPixels, 0);
    radiosity::parallelFor(static_cast<size_t>(bh), 1, [&](size_t row) {
        const int y = static_cast<int>(row);
        for (int x = 0; x < bw; ++x) {
            const size_t b = static_cast<size_t>(y * bw + x);
            int n = 0;
            Rgb sumNow, sumThen;
            for (int dy = std::max(0, y - R); dy <= std::min(bh - 1, y + R); ++dy)
                for (int dx = std::max(0, x - R); dx <= std::min(bw - 1, x + R); ++dx) {
                    const size_t c = static_cast<size_t>(dy * bw + dx);
                    if (count[c] == 0 || nowSurface[c] != nowSurface[b]) continue;
                    for (size_t l = 0; l < L; ++l) region.indirect[b * L + l] += own[c * L + l];
                    sumNow += now[c];
                    sumThen += then[c];
                    n += count[c];
                }
            if (n == 0) continue;
            region.gathered[b] = 1;
            // The correction of the amount of light, grey: the colour stays the responses'
            // (a per-channel ratio turned the cropped room's corner grey, where the solver's
            // reflectances of walls the photo does not show are the objects' means).
            // Guarded where the responses read no light.
            const double lThen = sumThen.luminance(), lNow = sumNow.luminance();
            const Rgb f = Rgb::gray(lThen > 1e-12 && lNow > 0 ? lNow / lThen : 1.0);
            for (size_t l = 0; l < L; ++l)
                region.indirect[b * L + l] = region.indirect[b * L + l] * f * (1.0 / n);
        }
    });
}

/// The rectified fill's reflectance per box pixel: the sum over the pixel's samples that a
/// plane filled (3 per pixel) and how many there were.
struct PlaneFill {
    std::vector<float> sum;
    std::vector<int> count;
};

/// The mask's samples that see a surface, rebuilt per plane (rectified_fill.h); the box is
/// boxWidth pixels wide from (region.x0, region.y0).
template <class SurfaceOf>
PlaneFill fillHiddenPlanes(const RemovedRegion& region, int boxWidth, const Camera& camera,
                           const radiosity::Scene& scene, const PhotoWindow& photo,
                           const std::vector<char>& mask, const std::vector<int>& nowSurface,
                           SurfaceOf surfaceOf, const RectifiedFillOptions& options) {
    const size_t kk = static_cast<size_t>(region.k * region.k);
    const OverlaySamples samples(region.k * region.k);
    std::vector<HiddenPoint> hidden;
    std::vector<size_t> hiddenPixel;
    for (size_t b = 0; b < mask.size(); ++b) {
        if (!mask[b] || nowSurface[b] < 0) continue;
        for (size_t s = 0; s < kk; ++s) {
            const size_t i = b * kk + s;
            const int sf = surfaceOf(region.polygon[i]);
            if (region.leaf[i] < 0 || sf < 0) continue;
            // The sample's position in the photo (OverlaySamples, as it was cast).
            const auto [u, v] =
                samples.at(region.x0 + static_cast<int>(b) % boxWidth,
                           region.y0 + static_cast<int>(b) / boxWidth, static_cast<int>(s));
            hidden.push_back({region.point[i], region.polygon[i], sf, u, v});
            hiddenPixel.push_back(b);
        }
    }
    const RectifiedFillResult rect = fillRectified(camera, scene, photo, hidden, options);
    PlaneFill out{std::vector<float>(3 * mask.size(), 0.0f), std::vector<int>(mask.size(), 0)};
    for (size_t i = 0; i < hidden.size(); ++i) {
        if (!rect.filled[i]) continue;
        const size_t b = hiddenPixel[i];
        for (size_t c = 0; c < 3; ++c) out.sum[3 * b + c] += rect.value[3 * i + c];
        ++out.count[b];
    }
    return out;
}

/// The ring around the mask (object_removal.h): box pixels outside it that show in the photo
/// real surfaces only, with a gather at their points, join the mask with the reflectance
/// the display gives them, T / H_photo: only their light is measured again. It starts at the
/// mask's edge: a band the display kept between them showed as an outline (buildRemovedRegion).
template <class SurfaceOf>
void lightRing(RemovedRegion& region, const Relighting& r, const std::vector<char>& mask,
               const std::vector<int>& nowSurface, SurfaceOf surfaceOf) {
    const PreparedImage& P = r.prepared;
    const ItemBuffer& items = r.items;
    if (region.gathered.empty() || P.pixelDirect.empty()) return;
    const int W = items.width;
    for (int by = 0; by < region.height; ++by)
        for (int bx = 0; bx < region.width; ++bx) {
            const size_t b = static_cast<size_t>(by * region.width + bx);
            if (mask[b] || nowSurface[b] < 0 || !region.gathered[b]) continue;
            const int x = region.x0 + bx, y = region.y0 + by;
            const size_t px =
                static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x);
            if (!shownPerPixel(P.display, px)) continue;
            bool real = true;
            for (int s = 0; s < items.spp && real; ++s)
                real =
                    surfaceOf(items.polygon[static_cast<size_t>(items.sampleIndex(x, y, s))]) >= 0;
            if (!real) continue;
            const Rgb Hp = photoIrradiance(P, px);
            if (!(Hp.minComponent() > 0)) continue;  // unlit in the photo: the display's
            const float* t = P.photo.rgb.data() + px * 3;
            for (size_t c = 0; c < 3; ++c)
                region.reflectance[3 * b + c] =
                    static_cast<float>(static_cast<double>(t[c]) / Hp[static_cast<int>(c)]);
            region.mask[b] = 1;
            ++region.ring;
        }
}

}  // namespace

int defaultMaskGrowth(int width, int height) {
    const double diagonal = std::hypot(static_cast<double>(width), static_cast<double>(height));
    return std::max(1, static_cast<int>(std::lround(diagonal / 400.0)));
}

RemovedRegion buildRemovedRegion(const Relighting& r, const std::vector<int>& removed,
                                 size_t realNodes, int grow, SurfaceSynthesis synthesis) {
    RemovedRegion region;
    const ItemBuffer& items = r.items;
    const PreparedImage& P = r.prepared;
    const auto& solver = *r.solver;
    const auto& scene = solver.scene();
    const auto& h = solver.hierarchy();
    const auto& vis = solver.visibility();
    const int W = items.width, H = items.height;
    const size_t realPolygons = r.surface.size();
    std::vector<char> isRemoved(scene.polygons.size(), 0);
    for (size_t p = 0; p < realPolygons; ++p)
        isRemoved[p] =
            std::find(removed.begin(), removed.end(), scene.polygons[p].object) != removed.end();
    const auto surfaceOf = [&](int p) {
        return p >= 0 && static_cast<size_t>(p) < realPolygons && !isRemoved[p] &&
                       scene.polygons[static_cast<size_t>(p)].light < 0
                   ? r.surface[static_cast<size_t>(p)]
                   : -1;
    };

    // 1. The pixels the objects covered in the photo, and their box grown.
    std::vector<char> core(static_cast<size_t>(W) * static_cast<size_t>(H), 0);
    int cx0 = W, cy0 = H, cx1 = -1, cy1 = -1;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int s = 0; s < items.spp; ++s) {
                const int p = items.polygon[static_cast<size_t>(items.sampleIndex(x, y, s))];
                if (p < 0 || static_cast<size_t>(p) >= realPolygons || !isRemoved[p]) continue;
                core[static_cast<size_t>(y * W + x)] = 1;
                cx0 = std::min(cx0, x);
                cy0 = std::min(cy0, y);
                cx1 = std::max(cx1, x);
                cy1 = std::max(cy1, y);
                break;
            }
    if (cx1 < 0) return region;
    // The box holds the ring around the objects (the header): half their extent, or `grow`.
    const int around = std::max(grow, (std::max(cx1 - cx0, cy1 - cy0) + 1) / 2);
    const int bx0 = std::max(0, cx0 - around), by0 = std::max(0, cy0 - around);
    const int bw = std::min(W - 1, cx1 + around) - bx0 + 1,
              bh = std::min(H - 1, cy1 + around) - by0 + 1;
    const size_t boxPixels = static_cast<size_t>(bw) * static_cast<size_t>(bh);

    // 2. The camera's samples in the box again, the objects hidden; virtual parts in front
    //    are passed through (the overlay draws them over the fill at each frame).
    const OverlaySamples samples(items.spp);
    const int k = samples.k;
    const size_t kk = static_cast<size_t>(samples.count());
    region.k = k;
    region.polygon.assign(boxPixels * kk, -1);
    region.leaf.assign(boxPixels * kk, -1);
    region.point.assign(boxPixels * kk, Vec3{0, 0, 0});
    region.direct.assign(boxPixels * kk, Rgb{});
    const Camera& camera = r.scene.camera;
    const Vec3 eye = camera.position();
    const double diag = glm::length(h.nodes[0].bounds.diagonal());
    std::vector<int> nowSurface(boxPixels, -1);
    radiosity::parallelFor(static_cast<size_t>(bh), 1, [&](size_t row) {
        std::unordered_map<int, int> votes;
        for (int bx = 0; bx < bw; ++bx) {
            const int x = bx0 + bx, y = by0 + static_cast<int>(row);
            const size_t b = row * static_cast<size_t>(bw) + static_cast<size_t>(bx);
            votes.clear();
            for (size_t s = 0; s < kk; ++s) {
                const auto [u, v] = samples.at(x, y, static_cast<int>(s));
                const Vec3 dir = camera.rayDirection(u, v);
                double tMin = 0;
                radiosity::Visibility::Hit hit;
                for (int pass = 0; pass < 8; ++pass) {
                    hit = vis.intersect(eye, dir, tMin);
                    if (hit.polygon < 0 || static_cast<size_t>(hit.polygon) < realPolygons) break;
                    tMin = hit.t + 1e-6 * diag;  // a virtual part: what lies behind it
                }
                if (hit.polygon < 0 || static_cast<size_t>(hit.polygon) >= realPolygons) continue;
                const size_t i = b * kk + s;
                const Vec3 point = eye + hit.t * dir;
                region.polygon[i] = hit.polygon;
                region.point[i] = point;
                if (scene.polygons[static_cast<size_t>(hit.polygon)].light >= 0) continue;
                if (glm::dot(scene.polygons[static_cast<size_t>(hit.polygon)].normal, dir) >= 0) {
                    region.polygon[i] = -1;  // a back face: black, as the display shows it
                    continue;
                }
                int leaf = h.locateLeaf(hit.polygon, point);
                while (leaf >= 0 && static_cast<size_t>(leaf) >= realNodes)
                    leaf = h.nodes[leaf].parent;
                region.leaf[i] = leaf;
                ++votes[surfaceOf(hit.polygon)];
            }
            int best = -1, most = 0;
            for (const auto& [s, n] : votes)
                if (n > most || (n == most && s < best)) {
                    best = s;
                    most = n;
                }
            nowSurface[b] = best;
        }
    });

    // The indirect light at the revealed points, per real light (the header's `indirect`).
    region.x0 = bx0;
    region.y0 = by0;
    if (r.responses && r.gatherSide > 0)
        gatherRegionIndirect(region, r, nowSurface, bw, bh, defaultFillBlock(W, H));

    // The mask: the covered pixels, and the ring around them on the surfaces they revealed.
    std::vector<char> boxCore(boxPixels, 0);
    std::vector<int> revealed;
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            const size_t b = static_cast<size_t>(by * bw + bx);
            boxCore[b] = core[static_cast<size_t>((by0 + by) * W + bx0 + bx)];
            if (boxCore[b] && nowSurface[b] >= 0) revealed.push_back(nowSurface[b]);
        }
    std::sort(revealed.begin(), revealed.end());
    revealed.erase(std::unique(revealed.begin(), revealed.end()), revealed.end());
    const std::vector<char> grown = dilate(boxCore, bw, bh, grow);
    std::vector<char> mask(boxPixels, 0);
    for (size_t b = 0; b < boxPixels; ++b)
        mask[b] = boxCore[b] ||
                  (grown[b] && std::binary_search(revealed.begin(), revealed.end(), nowSurface[b]));

    // 3. The reflectance image around the mask, and the fill.
    const int margin = std::max({kSampleMargin, bw, bh});
    const int wx0 = std::max(0, bx0 - margin), wy0 = std::max(0, by0 - margin);
    const int ww = std::min(W - 1, bx0 + bw - 1 + margin) - wx0 + 1;
    const int wh = std::min(H - 1, by0 + bh - 1 + margin) - wy0 + 1;
    const size_t windowPixels = static_cast<size_t>(ww) * static_cast<size_t>(wh);
    std::vector<float> value(3 * windowPixels, 0.0f);
    std::vector<int> regionId(windowPixels, -1), shownPolygon(windowPixels, -1);
    std::vector<FillRole> role(windowPixels, FillRole::none);
    std::vector<double> light(windowPixels, 0.0);
    const auto inBoxMask = [&](int x, int y) {
        return x >= bx0 && y >= by0 && x < bx0 + bw && y < by0 + bh &&
               (mask[static_cast<size_t>((y - by0) * bw + x - bx0)] ||
                boxCore[static_cast<size_t>((y - by0) * bw + x - bx0)]);
    };
    // No sample from the band around the object as wide again as the mask's growth: the
    // photo's pixels there may still hold some of its colour (the camera's pixel filter, a
    // calibration off by a pixel), and the onion peel copies its nearest sources most.
    std::vector<char> windowCore(windowPixels, 0);
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx)
            if (boxCore[static_cast<size_t>(by * bw + bx)])
                windowCore[static_cast<size_t>(by0 + by - wy0) * static_cast<size_t>(ww) +
                           static_cast<size_t>(bx0 + bx - wx0)] = 1;
    const std::vector<char> guard = dilate(windowCore, ww, wh, 2 * grow + 1);
    radiosity::parallelFor(static_cast<size_t>(wh), 4, [&](size_t row) {
        for (int wx = 0; wx < ww; ++wx) {
            const int x = wx0 + wx, y = wy0 + static_cast<int>(row);
            const size_t w = row * static_cast<size_t>(ww) + static_cast<size_t>(wx);
            if (inBoxMask(x, y)) {
                const size_t b = static_cast<size_t>((y - by0) * bw + x - bx0);
                if (mask[b] && nowSurface[b] >= 0) {
                    role[w] = FillRole::fill;
                    regionId[w] = nowSurface[b];
                }
                continue;
            }
            const size_t px =
                static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x);
            if (guard[w] || !shownPerPixel(P.display, px)) continue;
            int s0 = -2;
            bool one = true;
            for (int s = 0; s < items.spp && one; ++s) {
                const int p = items.polygon[static_cast<size_t>(items.sampleIndex(x, y, s))];
                const int sf = surfaceOf(p);
                one = sf >= 0 && (s0 == -2 || sf == s0);
                s0 = sf;
                if (s == 0) shownPolygon[w] = p;
            }
            if (!one) continue;
            const Rgb Hp = photoIrradiance(P, px);
            if (!(Hp.minComponent() > 0)) continue;
            const float* t = P.photo.rgb.data() + px * 3;
            for (int c = 0; c < 3; ++c)
                value[3 * w + static_cast<size_t>(c)] =
                    static_cast<float>(static_cast<double>(t[c]) / Hp[c]);
            light[w] = Hp.luminance();
            role[w] = FillRole::source;
            regionId[w] = s0;
        }
    });
    // Dark sources out, against their surface's median light.
    std::unordered_map<int, std::vector<double>> lights;
    for (size_t w = 0; w < windowPixels; ++w)
        if (role[w] == FillRole::source) lights[regionId[w]].push_back(light[w]);
    std::unordered_map<int, double> median;
    for (auto& [s, l] : lights) {
        std::nth_element(l.begin(), l.begin() + static_cast<std::ptrdiff_t>(l.size() / 2), l.end());
        median[s] = l[l.size() / 2];
    }
    for (size_t w = 0; w < windowPixels; ++w)
        if (role[w] == FillRole::source && light[w] < kDarkSource * median[regionId[w]])
            role[w] = FillRole::none;
    TextureFillOptions fillOptions;
    fillOptions.block = defaultFillBlock(W, H);
    // Each hidden plane rebuilt from its own visible part, rectified (rectified_fill.h); the
    // photo-space fill below only for the pixels it leaves (a plane the photo shows nowhere).
    const PhotoWindow photoWindow{wx0, wy0, ww, wh, value, regionId, shownPolygon, role};
    RectifiedFillOptions rectOptions;
    rectOptions.synthesis = synthesis;
    rectOptions.block = fillOptions.block;
    rectOptions.bridge = 2 * (2 * grow + 1) + 2;  // the guard band, twice for a grazing plane
    rectOptions.margin = std::max({kSampleMargin, bw, bh});
    rectOptions.planeTolerance = 1e-5 * diag;
    const PlaneFill planes = fillHiddenPlanes(region, bw, camera, scene, photoWindow, mask,
                                              nowSurface, surfaceOf, rectOptions);
    const std::vector<float>& rectSum = planes.sum;
    const std::vector<int>& rectCount = planes.count;
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx)
            if (rectCount[static_cast<size_t>(by * bw + bx)] > 0)
                role[static_cast<size_t>(by0 + by - wy0) * static_cast<size_t>(ww) +
                     static_cast<size_t>(bx0 + bx - wx0)] = FillRole::none;
    const TextureFillResult fill = fillTexture({ww, wh, value, regionId, role}, fillOptions);

    // The region: the box, the fill's reflectance; the leaf's model where the photo shows
    // none of the surface.
    region.x0 = bx0;
    region.y0 = by0;
    region.width = bw;
    region.height = bh;
    region.mask = mask;
    region.covered = boxCore;
    region.reflectance.assign(3 * boxPixels, 0.0f);
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            const size_t b = static_cast<size_t>(by * bw + bx);
            if (!mask[b] || nowSurface[b] < 0) continue;
            const size_t w = static_cast<size_t>(by0 + by - wy0) * static_cast<size_t>(ww) +
                             static_cast<size_t>(bx0 + bx - wx0);
            if (const int n = rectCount[b]; n > 0) {
                for (size_t c = 0; c < 3; ++c)
                    region.reflectance[3 * b + c] = rectSum[3 * b + c] / static_cast<float>(n);
                ++region.filled;
                continue;
            }
            if (!fill.unfilled[w] && role[w] == FillRole::fill) {
                for (int c = 0; c < 3; ++c)
                    region.reflectance[3 * b + static_cast<size_t>(c)] =
                        fill.value[3 * w + static_cast<size_t>(c)];
                ++region.filled;
                continue;
            }
            for (size_t s = 0; s < kk; ++s) {
                const int leaf = region.leaf[b * kk + s];
                if (leaf < 0) continue;
                for (int c = 0; c < 3; ++c)
                    region.reflectance[3 * b + static_cast<size_t>(c)] =
                        static_cast<float>(h.nodes[static_cast<size_t>(leaf)].rho[c] / kPi);
                break;
            }
            ++region.modelled;
        }
    // The ring reaches the covered pixels' edge, the guard band included: the band's photo is
    // shown relit either way (T times a light), and the display's light there, interpolated
    // from vertex changes through links that ran to the object's faces, read 1.2-1.3 times
    // the truth's in the first 3 pixels beside the room's and the furnished room's objects:
    // a light outline (bench/RESULTS.md, 2026-11-27, fifth session). Only the fill's samples
    // keep out of the guard band (above), as the onion peel would copy its colour inward.
    lightRing(region, r, mask, nowSurface, surfaceOf);
    return region;
}

void measureRegionDirect(RemovedRegion& region, const Relighting& r, std::span<const Rgb> radiance,
                         const std::vector<char>* changedLeaves) {
    if (region.empty()) return;
    const auto& solver = *r.solver;
    const auto& scene = solver.scene();
    const size_t L = scene.lights.size();
    const radiosity::DirectLight direct(solver, r.directOptions);
    const size_t kk = static_cast<size_t>(region.k * region.k);
    radiosity::parallelForChunks(region.mask.size(), 16, [&](size_t first, size_t last) {
        std::vector<double> G(L);
        for (size_t b = first; b != last; ++b) {
            if (!region.mask[b]) continue;
            for (size_t s = 0; s < kk; ++s) {
                const size_t i = b * kk + s;
                const int leaf = region.leaf[i];
                if (leaf < 0) continue;
                if (changedLeaves && !(static_cast<size_t>(leaf) < changedLeaves->size() &&
                                       (*changedLeaves)[static_cast<size_t>(leaf)]))
                    continue;
                direct.geometry(region.polygon[i], region.point[i], kRegionSeed + i, G.data());
                Rgb d;
                for (size_t l = 0; l < L && l < radiance.size(); ++l)
                    d += radiance[l] * (kPi * G[l]);
                region.direct[i] = d;
            }
        }
    });
}

}  // namespace relight
