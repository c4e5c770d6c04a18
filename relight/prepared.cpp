#include "relight/prepared.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "radiosity/parallel.h"
#include "relight/display/wen_display.h"
#include "relight/pipeline/pixel_light.h"
#include "relight/relighting.h"

namespace relight {

using radiosity::Rgb;

std::vector<Rgb> vertexIrradiance(const PreparedImage& p, std::span<const Rgb> radiance) {
    const int n = static_cast<int>(p.lighting.vertexCount());
    std::vector<Rgb> B(static_cast<size_t>(n));
    for (int v = 0; v < n; ++v) B[v] = p.lighting.irradiance(v, radiance);
    return B;
}

std::vector<Rgb> vertexRatio(const PreparedImage& p, std::span<const Rgb> H) {
    auto ratio = displayRatio(H, p.D);
    if (p.textureFactor.size() == ratio.size())
        for (size_t v = 0; v < ratio.size(); ++v)
            for (int c = 0; c < 3; ++c) ratio[v][c] *= p.textureFactor[v][c];
    return ratio;
}

const char* displayModeName(DisplayMode mode) {
    return mode == DisplayMode::ratio        ? "ratio"
           : mode == DisplayMode::confidence ? "confidence"
           : mode == DisplayMode::ratioMap   ? "ratio-map"
           : mode == DisplayMode::wen        ? "wen"
                                             : "pixel";
}

bool drawsPerPixel(DisplayMode mode) {
    return mode == DisplayMode::pixel || mode == DisplayMode::ratioMap || mode == DisplayMode::wen;
}

DisplayMode parseDisplayMode(const std::string& name) {
    if (name == "ratio") return DisplayMode::ratio;
    if (name == "confidence") return DisplayMode::confidence;
    if (name == "pixel") return DisplayMode::pixel;
    if (name == "ratio-map") return DisplayMode::ratioMap;
    if (name == "wen") return DisplayMode::wen;
    throw std::invalid_argument("unknown display \"" + name +
                                "\" (ratio, confidence, pixel, ratio-map or wen)");
}

SplitIrradiance splitIrradiance(const PreparedImage& p, std::span<const Rgb> radiance) {
    // A lamp that was off in the photo (radiance 0 in every channel) brings fresh light.
    std::vector<Rgb> kept(radiance.begin(), radiance.end()), fresh(radiance.size());
    for (size_t l = 0; l < radiance.size() && l < p.photoRadiance.size(); ++l)
        if (!(p.photoRadiance[l].maxComponent() > 0)) std::swap(kept[l], fresh[l]);
    SplitIrradiance H;
    H.kept = vertexIrradiance(p, kept);
    H.fresh = vertexIrradiance(p, fresh);
    return H;
}

VertexDisplay vertexDisplay(const PreparedImage& p, const SplitIrradiance& H, DisplayMode mode) {
    const size_t n = H.kept.size();
    if (H.fresh.size() != n)
        throw std::invalid_argument("vertexDisplay: kept and fresh irradiance differ in size");
    // The per-pixel display is not a value per vertex (renderEdit draws it): no silent
    // fallback to the ratio display for a caller that asks for it (virtual parts).
    if (drawsPerPixel(mode))
        throw std::invalid_argument("vertexDisplay: the per-pixel display has no vertex values");
    VertexDisplay d;
    const bool fresh =
        std::any_of(H.fresh.begin(), H.fresh.end(), [](const Rgb& b) { return !(b == Rgb{}); });
    const bool confident = mode == DisplayMode::confidence && fresh && p.confidence.size() == n &&
                           p.modelReflectance.size() == n;
    std::vector<Rgb> B(n);
    if (!confident) {
        for (size_t v = 0; v < n; ++v) B[v] = H.kept[v] + H.fresh[v];
        d.ratio = vertexRatio(p, B);
        return d;
    }
    d.added.resize(n);
    for (size_t v = 0; v < n; ++v) {
        const double K = p.confidence[v];
        B[v] = H.kept[v] + H.fresh[v] * K;
        d.added[v] = p.modelReflectance[v] * H.fresh[v] * ((1 - K) / std::numbers::pi);
    }
    d.ratio = vertexRatio(p, B);
    return d;
}

Image renderEdit(const PreparedImage& p, std::span<const Rgb> radiance, DisplayMode mode) {
    Image out;
    renderEdit(p, radiance, out, mode);
    return out;
}

void renderPixelEditReference(const PreparedImage& p, std::span<const Rgb> radiance, Image& out) {
    if (p.pixelDirect.empty())
        throw std::invalid_argument(
            "renderEdit: the per-pixel display needs a preparation with per-pixel light");
    // One gather of the lights, as before the split. The per-pixel display keeps this image
    // where a pixel sees a lamp's face or nothing.
    const auto ratio = vertexRatio(p, vertexIrradiance(p, radiance));
    renderRatio(p.display, p.photo, ratio, radiance, p.photoRadiance, out, {},
                /*leafRuns=*/false);
    renderPixelLight(p.display, p.photo, p.pixelDirect, p.vertexIndirect, radiance, p.photoRadiance,
                     ratioFloor(p.D), out, {}, p.pixelReflectance, &p.photoPixels);
}

void renderRatioMap(const PreparedImage& p, std::span<const Rgb> radiance, Image& out) {
    if (p.pixelDirect.empty())
        throw std::invalid_argument(
            "renderEdit: the ratio-map display needs a preparation with per-pixel light");
    renderRatio(p.display, p.photo, vertexRatio(p, vertexIrradiance(p, radiance)), radiance,
                p.photoRadiance, out, {}, /*leafRuns=*/false);
    // ../shared/seeds/000, Eq. (3): L_r = L_o I_r / I_o, I the direct irradiance of the lights
    // (the sun with its shadows, point lamps, the sky through what the pixel sees); the
    // indirect part is left out, as the paper's ratio of two direct irradiances does.
    const std::vector<Rgb> noIndirect(p.vertexIndirect.size());
    renderPixelLight(p.display, p.photo, p.pixelDirect, noIndirect, radiance, p.photoRadiance,
                     ratioFloor(p.D), out);
}

namespace {

/// The ratio display at the pixels the per-pixel display does not draw (lamps' faces,
/// samples that see nothing), from the display ratio k B / D of the vertices they read
/// alone: renderRatio()'s value there, without the edit's irradiance at every vertex.
void renderRatioPixels(const PreparedImage& p, std::span<const Rgb> radiance, Image& out) {
    const PixelLightTable& t = p.pixelTable;
    // Indexed by vertex id as ratioPixel() reads it; only the pixels' vertices are written.
    // Kept from frame to frame (per thread): no allocation per edit.
    thread_local std::vector<std::array<float, 4>> ratio;
    if (ratio.size() < p.vertexCount()) ratio.resize(p.vertexCount());
    const bool textured = p.textureFactor.size() == p.vertexCount();
    for (const int v : t.ratioVertices) {
        const Rgb B = p.lighting.irradiance(v, radiance);
        const size_t i = static_cast<size_t>(v);
        for (int c = 0; c < 3; ++c) {
            double r = guardedRatio(B[c], p.D[i][c], t.delta[c]);  // as vertexRatio()
            if (textured) r *= p.textureFactor[i][c];
            ratio[i][static_cast<size_t>(c)] = static_cast<float>(r);
        }
    }
    const std::array<float, 4>* r = ratio.data();
    radiosity::parallelFor(t.ratioPixels.size(), 256, [&](size_t k) {
        ratioPixel(p.display, p.photo, static_cast<size_t>(t.ratioPixels[k]), r, nullptr, radiance,
                   p.photoRadiance, out);
    });
}

}  // namespace

void renderEdit(const PreparedImage& p, std::span<const Rgb> radiance, Image& out,
                DisplayMode mode) {
    if (mode == DisplayMode::pixel && !p.pixelTable.empty() && p.pixelReflectance.empty() &&
        radiance.size() == p.pixelTable.lights) {
        // The table's path (pixel_light_table.h): the per-pixel display's pixels, then the
        // ratio display at the others.
        renderPixelLightFast(p.pixelTable, p.display, p.photo, radiance, p.photoRadiance, out,
                             &p.photoPixels);
        renderRatioPixels(p, radiance, out);
        return;
    }
    if (mode == DisplayMode::pixel) {
        renderPixelEditReference(p, radiance, out);
        return;
    }
    if (mode == DisplayMode::ratioMap) {
        renderRatioMap(p, radiance, out);
        return;
    }
    if (mode == DisplayMode::wen) {
        renderWen(p, radiance, out);
        return;
    }
    if (mode == DisplayMode::ratio) {
        renderRatio(p.display, p.photo, vertexRatio(p, vertexIrradiance(p, radiance)), radiance,
                    p.photoRadiance, out);
        return;
    }
    const VertexDisplay d = vertexDisplay(p, splitIrradiance(p, radiance), mode);
    renderRatio(p.display, p.photo, d.ratio, radiance, p.photoRadiance, out, d.added);
}

void derivePhotoPixels(PreparedImage& p) {
    p.photoPixels = {};
    p.pixelTable = {};
    if (p.pixelDirect.empty()) return;
    p.photoPixels = photoPixels(p.display, p.photo, p.pixelDirect, p.vertexIndirect,
                                p.photoRadiance, ratioFloor(p.D));
    p.pixelTable = pixelLightTable(p.display, p.photo, p.pixelDirect, p.vertexIndirect,
                                   p.photoRadiance, ratioFloor(p.D), &p.photoPixels);
}

std::string stepTimes(const PrepareTimes& t) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "item buffer %.3f, solve %.3f, reflectance %.3f, refinement %.3f, responses "
                  "%.3f, vertex lighting %.3f, shadow removal %.3f, display map %.3f",
                  t.itemBuffer, t.solve, t.reflectance, t.refinement, t.responses, t.vertexLighting,
                  t.shadowRemoval, t.displayMap);
    return text;
}

std::vector<std::string> phaseBudgetLines(int budgetReached, double seconds) {
    struct Phase {
        int bit;
        double ends;
        const char* fallback;
    };
    const Phase phases[] = {
        {PreparedImage::kShadowRefinementBudget, RelightOptions::kShadowRefinementEnds,
         "shadow-boundary refinement stopped (its own share at most), leaves left unexamined"},
        {PreparedImage::kGatherBudget, RelightOptions::kVertexGatherEnds,
         "the vertices' final gather kept the partly occluded links' mean visibility"},
        {PreparedImage::kLeafReflectanceBudget, RelightOptions::kVertexGatherEnds,
         "the leaves' reflectance from their texture skipped (the polygons' kept)"},
        {PreparedImage::kPixelGatherBudget, RelightOptions::kPixelGatherEnds,
         "fewer indirect rays per vertex for the per-pixel display"},
        {PreparedImage::kShadowRemovalBudget, RelightOptions::kShadowRemovalEnds,
         "real-shadow removal skipped (D = the photo's lighting)"},
    };
    std::vector<std::string> out;
    if (budgetReached & PreparedImage::kBudgetOverrun)
        out.emplace_back(
            "the preparation ended past its budget: the work that no fallback removes "
            "(the hierarchy, the lamps' links to every face, the responses) grows with "
            "the mesh; a larger --time-budget, or fewer faces, ends within it");
    for (const Phase& ph : phases) {
        if (!(budgetReached & ph.bit)) continue;
        char line[240];
        std::snprintf(line, sizeof line, "share spent (ends at %.0f %% of %g s): %s", 100 * ph.ends,
                      seconds, ph.fallback);
        out.push_back(line);
    }
    return out;
}

}  // namespace relight
