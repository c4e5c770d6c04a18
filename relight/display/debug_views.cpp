#include "relight/display/debug_views.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>
#include <string>
#include <system_error>

#include "radiosity/parallel.h"
#include "relight/display/ratio_display.h"
#include "relight/errors.h"
#include "relight/io/json_file.h"
#include "relight/pipeline/pixel_light.h"

namespace relight {

using radiosity::parallelFor;
using radiosity::Rgb;
namespace fs = std::filesystem;

namespace {

/// A display-map weight sum below this is a pixel without reflecting surface (the weights
/// are floats: a real share of a surface is at least 1/spp of the pixel).
constexpr double kMinSurface = 1e-6;
/// The photo under the overlays (mesh, frontier), dimmed so that the marks stand out.
constexpr double kDim = 0.4;

Rgb pixel(const Image& img, int px) {
    const float* p = &img.rgb[static_cast<size_t>(px) * 3];
    return {p[0], p[1], p[2]};
}

void setPixel(Image& img, int px, const Rgb& c) {
    float* p = &img.rgb[static_cast<size_t>(px) * 3];
    for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(c[k]);
}

/// What a pixel's item-buffer samples fall in (per-leaf quantities).
struct PixelLeaves {
    Rgb rho;              ///< sum of the leaf reflectances of its surface samples
    int surface = 0;      ///< samples on a leaf
    int occluded = 0;     ///< samples on an occluded leaf (shadow removal's class)
    int frontier = 0;     ///< samples on a frontier leaf
    int first = -1;       ///< id of sample 0 (the top-left one): see sampleId
    bool mixed = false;   ///< its samples have different ids: a leaf edge crosses the pixel
    bool anyNew = false;  ///< a sample lies in a leaf whose id is at least scanLeaves' firstNew
};

/// Leaf, or -1 for nothing, or -2 - light for a light's emitting face: an edge is where
/// this changes (the elements' edges and the polygons' outlines).
int sampleId(const SampleHit& hit) {
    return hit.surface() ? hit.leaf : (hit.light >= 0 ? -2 - hit.light : -1);
}

PixelLeaves scanPixel(const Relighting& r, int x, int y, size_t firstNew) {
    const ItemBuffer& items = r.items;
    const auto& h = r.solver->hierarchy();
    PixelLeaves p;
    for (int s = 0; s < items.spp; ++s) {
        const SampleHit hit = locateSample(items, h, r.solver->scene(), items.sampleIndex(x, y, s));
        const int id = sampleId(hit);
        if (s == 0) p.first = id;
        if (id != p.first) p.mixed = true;
        if (!hit.surface()) continue;
        p.anyNew = p.anyNew || static_cast<size_t>(hit.leaf) >= firstNew;
        ++p.surface;
        p.rho += h.nodes[hit.leaf].rho;
        // Shadow removal was off, or the leaf is newer than its classes.
        if (static_cast<size_t>(hit.leaf) >= r.removal.leafClass.size()) continue;
        const LeafShadowClass c = r.removal.leafClass[hit.leaf];
        if (c == LeafShadowClass::occluded) ++p.occluded;
        if (c == LeafShadowClass::frontier) ++p.frontier;
    }
    return p;
}

std::vector<PixelLeaves> scanLeaves(const Relighting& r, size_t firstNew) {
    const int w = r.items.width;
    std::vector<PixelLeaves> out(static_cast<size_t>(w) * r.items.height);
    parallelFor(static_cast<size_t>(r.items.height), 1, [&](size_t y) {
        for (int x = 0; x < w; ++x) out[y * w + x] = scanPixel(r, x, static_cast<int>(y), firstNew);
    });
    return out;
}

/// The leaf elements' edges over the dimmed photo: pixels whose samples, or whose first
/// sample and its right or lower neighbour's, lie in different leaves. Yellow, or cyan where
/// one of the two leaves has an id from `firstNew` on (split by an edit).
Image meshOverPhoto(const Relighting& r, const std::vector<PixelLeaves>& leaves, size_t firstNew) {
    const Rgb edge{1.0, 0.85, 0.0}, newEdge{0.0, 0.9, 1.0};
    const int w = r.items.width, hgt = r.items.height;
    const auto isNew = [&](int id) { return id >= 0 && static_cast<size_t>(id) >= firstNew; };
    Image out(w, hgt);
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            const int px = y * w + x;
            const PixelLeaves& p = leaves[px];
            const int right = x + 1 < w ? leaves[px + 1].first : p.first;
            const int below = y + 1 < hgt ? leaves[px + w].first : p.first;
            const bool onEdge = p.mixed || right != p.first || below != p.first;
            const bool fresh = isNew(p.first) || (right != p.first && isNew(right)) ||
                               (below != p.first && isNew(below)) || (p.mixed && p.anyNew);
            setPixel(out, px,
                     onEdge ? (fresh ? newEdge : edge) : pixel(r.prepared.photo, px) * kDim);
        }
    return out;
}

/// sum_k w_k values[v_k] over the pixel's display-map entries (Gouraud, the weights the
/// relit image uses); `weight` gets sum_k w_k, the pixel's share of reflecting surface.
Rgb interpolate(const DisplayMap& m, int px, std::span<const Rgb> values, double& weight) {
    Rgb sum;
    weight = 0;
    for (int k = m.start[px]; k < m.start[px + 1]; ++k) {
        sum += values[m.vertex[k]] * static_cast<double>(m.weight[k]);
        weight += static_cast<double>(m.weight[k]);
    }
    return sum;
}

/// The photo times the texture factor k interpolated over the surface, 1 elsewhere.
Image texture(const PreparedImage& P, std::span<const Rgb> k) {
    Image out(P.photo.width, P.photo.height);
    const int pixels = P.photo.width * P.photo.height;
    for (int px = 0; px < pixels; ++px) {
        double w = 0;
        const Rgb sum = interpolate(P.display, px, k, w);
        const Rgb factor = sum + Rgb::gray(std::max(0.0, 1.0 - w));
        setPixel(out, px, pixel(P.photo, px) * factor);
    }
    return out;
}

/// 1 / the 99th percentile of the luminance of `img` over `pixels`; 1 when that is not
/// positive (an all-black view needs no scale).
double robustScale(const Image& img, const std::vector<int>& pixels) {
    std::vector<double> lum;
    lum.reserve(pixels.size());
    for (int px : pixels) lum.push_back(pixel(img, px).luminance());
    if (lum.empty()) return 1;
    const auto nth = lum.begin() + static_cast<std::ptrdiff_t>(0.99 * (lum.size() - 1));
    std::nth_element(lum.begin(), nth, lum.end());
    return *nth > 0 && std::isfinite(*nth) ? 1.0 / *nth : 1.0;
}

}  // namespace

DebugViews computeDebugViews(const Relighting& r, std::span<const Rgb> radianceNow) {
    const PreparedImage& P = r.prepared;
    if (radianceNow.size() != P.photoRadiance.size())
        throw std::invalid_argument("computeDebugViews: " + std::to_string(radianceNow.size()) +
                                    " radiances for " + std::to_string(P.photoRadiance.size()) +
                                    " lights");
    const DisplayMap& m = P.display;
    const int w = P.photo.width, hgt = P.photo.height, pixels = w * hgt;
    const size_t nodes = r.solver->hierarchy().nodes.size();
    const std::vector<PixelLeaves> leaves = scanLeaves(r, nodes);
    const std::vector<Rgb> H = vertexIrradiance(P, radianceNow);

    DebugViews v;
    v.B = Image(w, hgt);
    v.D = Image(w, hgt);
    v.reflectance = Image(w, hgt);
    v.bFactor = Image(w, hgt);
    std::vector<int> surfacePixels;
    for (int px = 0; px < pixels; ++px) {
        const PixelLeaves& p = leaves[px];
        double weight = 0;
        const Rgb Hsum = interpolate(m, px, H, weight);
        const Rgb Dsum = interpolate(m, px, P.D, weight);
        if (p.surface == 0 || weight < kMinSurface) continue;  // black: no solution here
        const Rgb rho = p.rho * (1.0 / p.surface);
        // B / pi = rho H / pi: radiance in the photo's units (relight/pipeline/reflectance.h).
        const Rgb toRadiance = rho * (1.0 / (std::numbers::pi * weight));
        setPixel(v.B, px, Hsum * toRadiance);
        setPixel(v.bFactor, px, toRadiance);
        setPixel(v.D, px, Dsum * toRadiance);
        setPixel(v.reflectance, px, rho);
        surfacePixels.push_back(px);
    }
    v.bdScale = robustScale(v.D, surfacePixels);
    if (!P.pixelDirect.empty()) {
        v.Hphoto = Image(w, hgt);
        radiosity::parallelFor(static_cast<size_t>(pixels), 1024, [&](size_t px) {
            if (shownPerPixel(m, px))
                setPixel(
                    v.Hphoto, static_cast<int>(px),
                    photoIrradianceAt(m, px, P.pixelDirect, P.vertexIndirect, P.photoRadiance));
        });
    }

    v.Torig = P.photo;
    const bool removal = !r.removal.kInter.empty();
    if (removal) {
        v.Tinter = texture(P, r.removal.kInter);
        v.Tfinal = texture(P, r.removal.kFinal);
    }

    // Loscos et al. 2000, Fig. 10, 11: the leaf elements' edges over the photo.
    v.mesh = meshOverPhoto(r, leaves, nodes);

    // Loscos et al. 2000, Fig. 14(a): the shadow regions and their frontier. The tint is
    // the share of the pixel's samples on such leaves.
    if (removal) {
        const Rgb occludedTint{0.05, 0.15, 1.0}, frontierTint{0.1, 1.0, 0.1};
        const double perSample = 1.0 / r.items.spp;
        v.frontier = Image(w, hgt);
        for (int px = 0; px < pixels; ++px) {
            const PixelLeaves& p = leaves[px];
            const double fo = p.occluded * perSample, ff = p.frontier * perSample;
            setPixel(v.frontier, px,
                     pixel(P.photo, px) * (kDim * (1 - fo - ff)) + occludedTint * fo +
                         frontierTint * ff);
        }
    }
    return v;
}

Image editMeshView(const Relighting& r, size_t preparedNodes) {
    return meshOverPhoto(r, scanLeaves(r, preparedNodes), preparedNodes);
}

void createDebugViewsFolder(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw OutputError(dir.string() + ": cannot create the debug-views folder" +
                          (ec ? ": " + ec.message() : ": a file of that name is in the way"));
}

std::vector<std::string> writeDebugViews(const Relighting& r, std::span<const Rgb> radianceNow,
                                         const fs::path& dir, const Image* editMesh) {
    createDebugViewsFolder(dir);
    const DebugViews v = computeDebugViews(r, radianceNow);

    std::vector<std::string> files;
    nlohmann::json views = nlohmann::json::array(), skipped = nlohmann::json::array();
    // `scale`: the linear factor applied before writing (PNG: then the sRGB transfer,
    // clipped to [0, 1]); EXR files hold the values as computed.
    auto put = [&](const std::string& name, const Image& img, double scale,
                   const std::string& shows) {
        writeImage(dir / name, img, std::log2(scale));
        files.push_back(name);
        views.push_back({{"file", name}, {"shows", shows}, {"scale", scale}});
    };
    const std::string bShows =
        "radiosity of the edit's lighting as the camera sees it, B / pi = rho H / pi (the "
        "photo's radiance units; Loscos et al. 2000, Fig. 18(b)); black without reflecting "
        "surface";
    const std::string dShows =
        "display correction factor in the same units, rho D / pi (Fig. 17(a), 18(a)); black "
        "without reflecting surface";
    put("B.exr", v.B, 1, bShows);
    put("B.png", v.B, v.bdScale, bShows + "; scale: 99th percentile of D's luminance -> 1");
    put("D.exr", v.D, 1, dShows);
    put("D.png", v.D, v.bdScale, dShows + "; scale: 99th percentile of D's luminance -> 1");
    put("T_orig.png", v.Torig, 1, "the photo T_orig (Fig. 18(c))");
    const std::string why = "shadow removal was off: no T_inter, T_final or shadow classes";
    const std::string overDimmedPhoto =
        " over the photo at " + std::to_string(std::lround(100 * kDim)) + " %";
    if (v.Tinter.width > 0) {
        put("T_inter.png", v.Tinter, 1,
            "T_orig k_inter: shadows lifted with the reference reflectance (Eq. (13)); the "
            "photo where there is no reflecting surface");
        put("T_final.png", v.Tfinal, 1,
            "T_orig k_final: the final texture after the umbra correction (Eq. (16), "
            "Fig. 18(e)); the photo where there is no reflecting surface");
    } else {
        skipped.push_back({{"file", "T_inter.png"}, {"why", why}});
        skipped.push_back({{"file", "T_final.png"}, {"why", why}});
    }
    put("reflectance.png", v.reflectance, 1,
        "leaf reflectance rho, after shadow removal when it ran (linear; black without "
        "reflecting surface)");
    if (v.Hphoto.width > 0)
        put("H_photo.exr", v.Hphoto, 1,
            "the photo's irradiance per pixel as the per-pixel display divides by it (direct "
            "light per pixel plus the interpolated indirect light, photo units); pi T / H_photo "
            "is the pixel's reflectance (Loscos et al. 1999, Eq. (2)); black where the "
            "per-pixel display does not draw");
    else
        skipped.push_back({{"file", "H_photo.exr"}, {"why", "prepared without per-pixel light"}});
    put("mesh.png", v.mesh, 1,
        "leaf element edges (yellow)" + overDimmedPhoto +
            " (Fig. 10, 11): pixels whose samples, or whose first sample and its right or "
            "lower neighbour's, lie in different leaves");
    if (v.frontier.width > 0)
        put("frontier.png", v.frontier, 1,
            "occluded leaves (blue) and frontier leaves (green)" + overDimmedPhoto +
                " (Fig. 14(a)), tinted by the share of each pixel's samples on them");
    else
        skipped.push_back({{"file", "frontier.png"}, {"why", why}});
    if (editMesh && editMesh->width > 0)
        put("mesh_edit.png", *editMesh, 1,
            "the leaves as the edit's insertions left them (Loscos et al. 2000, Fig. 24(a)): "
            "edges of the prepared leaves yellow, of the leaves split for the edit (under "
            "its new shadows) cyan" +
                overDimmedPhoto +
                "; the photo's surfaces only (the camera's samples of the "
                "preparation: a virtual object does not hide them)");
    else
        skipped.push_back({{"file", "mesh_edit.png"}, {"why", "the edit inserts nothing"}});

    nlohmann::json lights = nlohmann::json::object();
    const auto& ls = r.scene.scene.lights;
    for (size_t l = 0; l < ls.size() && l < radianceNow.size(); ++l)
        lights[ls[l].name] = {radianceNow[l].r, radianceNow[l].g, radianceNow[l].b};
    const nlohmann::json index = {{"format", "relight-debug-views/1"},
                                  {"width", r.prepared.photo.width},
                                  {"height", r.prepared.photo.height},
                                  {"shadow_removal", !r.removal.kInter.empty()},
                                  {"lights", lights},
                                  {"views", views},
                                  {"skipped", skipped}};
    writeJsonAtomic(dir / "index.json", index);
    files.push_back("index.json");
    return files;
}

}  // namespace relight
