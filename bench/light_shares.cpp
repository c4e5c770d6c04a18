// Where the per-pixel display's light comes from, light by light, against the path-traced
// truth: for each light edit of a prepared scene, the irradiance the per-pixel display
// multiplies the photo by (relight/pipeline/pixel_light.h: the direct light measured per
// pixel, and the indirect part interpolated from the leaf vertices), summed over the pixels
// it draws, beside the truth's irradiance at the same pixels, pi T_truth / albedo (the
// truth's albedo.exr: a bench may read it, the engine never does).
//
// A light edit is right when the edit's irradiance over the photo's is right, pixel by
// pixel; with lamps switched off, what is left must be each remaining lamp's share. A share
// that the model under-counts (an indirect part too small) shows as model/truth < 1 for the
// edit that keeps that lamp alone, and the others' light too bright once it is off.
//
//   ./build/bench/light_shares <scene_dir> <prepared cache> [--out DIR] [--box X0 Y0 X1 Y1]
//       [edit ...]
// (default: every edit of the scene whose truth exists and that changes lights only). The
// cache is read whatever binary made it (its key is taken from its own header). With --out,
// per edit: the per-pixel display's render (EDIT.exr, to score with `relight eval`) and
// EDIT_shares.png: the render, the truth, and model/truth of the edit's irradiance per pixel
// (grey 1, red up to 2 and more, blue down to 1/2 and less), side by side; and on the
// terminal the error by scale (blockError) and the 16 px regions that hold most of it. --box: the
// sums over those pixels only (x in [X0, X1), y in [Y0, Y1)).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/io/prepared_cache.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/pixel_light.h"
#include "relight/prepared.h"
#include "relight/relighting.h"

namespace fs = std::filesystem;
using radiosity::Rgb;
using namespace relight;

namespace {

uint64_t storedKey(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    char header[24] = {};
    in.read(header, sizeof header);
    uint64_t key = 0;
    std::memcpy(&key, header + 16, sizeof key);
    return key;
}

/// Per light, the model's direct and indirect irradiance at pixel px (photo units, for
/// radiance `L`), as renderPixelLight sums them.
void modelLight(const PreparedImage& P, size_t px, std::span<const Rgb> L, Rgb& direct,
                Rgb& indirect) {
    const auto& map = P.display;
    const size_t nl = L.size();
    const int k0 = map.start[px], k1 = map.start[px + 1];
    double wsum = 0;
    for (int k = k0; k < k1; ++k) wsum += static_cast<double>(map.weight[static_cast<size_t>(k)]);
    direct = indirect = Rgb{};
    if (!(wsum > 0)) return;
    for (size_t l = 0; l < nl; ++l) {
        Rgb ind;
        for (int k = k0; k < k1; ++k)
            ind +=
                P.vertexIndirect[static_cast<size_t>(map.vertex[static_cast<size_t>(k)]) * nl + l] *
                (static_cast<double>(map.weight[static_cast<size_t>(k)]) / wsum);
        direct += L[l] * static_cast<double>(P.pixelDirect[px * nl + l]);
        indirect += L[l] * ind;
    }
}

/// sqrt(mean (a - b)^2) / mean(b) over blocks of s x s pixels and channels (no masks): the
/// error at a scale; at large s the photo's and the truth's noise average out and what is
/// left is the error of the light's distribution.
/// Blocks with a pixel that `keep` marks 0 (the spec's masks: lamps' faces) are left out.
double blockError(const Image& a, const Image& b, const std::vector<uint8_t>& keep, int s) {
    double se = 0, sb = 0;
    int n = 0;
    for (int by = 0; by + s <= a.height; by += s)
        for (int bx = 0; bx + s <= a.width; bx += s) {
            bool kept = true;
            for (int y = by; y < by + s; ++y)
                for (int x = bx; x < bx + s; ++x)
                    kept = kept && keep[static_cast<size_t>(y) * a.width + x] != 0;
            if (!kept) continue;
            for (int c = 0; c < 3; ++c) {
                double ma = 0, mb = 0;
                for (int y = by; y < by + s; ++y)
                    for (int x = bx; x < bx + s; ++x) {
                        ma += static_cast<double>(a.at(x, y)[c]);
                        mb += static_cast<double>(b.at(x, y)[c]);
                    }
                se += (ma - mb) * (ma - mb) / (s * s * s * s);
                sb += mb / (s * s);
                ++n;
            }
        }
    return sb > 0 ? std::sqrt(se / n) / (sb / n) : 0.0;
}

/// Where the metric's squared error is: the 4 px blocks' (kept as in blockError) summed
/// per region of 16 x 16 px; prints the `top` regions with their share of the whole and the
/// ratio of the render to the photo beside that of the truth to the truth's identity.
void worstRegions(const Image& img, const Image& truth, const Image& photo, const Image& identity,
                  const std::vector<uint8_t>& keep, int top) {
    constexpr int kBlock = 4, kRegion = 16;
    struct Region {
        double err = 0, r = 0, t = 0, p = 0, i = 0;
        int x = 0, y = 0;
    };
    const int rw = img.width / kRegion, rh = img.height / kRegion;
    std::vector<Region> regions(static_cast<size_t>(rw) * rh);
    double total = 0;
    for (int by = 0; by + kBlock <= rh * kRegion; by += kBlock)
        for (int bx = 0; bx + kBlock <= rw * kRegion; bx += kBlock) {
            bool kept = true;
            for (int y = by; y < by + kBlock; ++y)
                for (int x = bx; x < bx + kBlock; ++x)
                    kept = kept && keep[static_cast<size_t>(y) * img.width + x] != 0;
            if (!kept) continue;
            Region& g = regions[static_cast<size_t>(by / kRegion) * rw + bx / kRegion];
            g.x = bx / kRegion * kRegion;
            g.y = by / kRegion * kRegion;
            for (int c = 0; c < 3; ++c) {
                double m[4] = {0, 0, 0, 0};
                for (int y = by; y < by + kBlock; ++y)
                    for (int x = bx; x < bx + kBlock; ++x) {
                        m[0] += static_cast<double>(img.at(x, y)[c]);
                        m[1] += static_cast<double>(truth.at(x, y)[c]);
                        m[2] += static_cast<double>(photo.at(x, y)[c]);
                        m[3] += static_cast<double>(identity.at(x, y)[c]);
                    }
                const double e = (m[0] - m[1]) * (m[0] - m[1]);
                g.err += e;
                total += e;
                g.r += m[0];
                g.t += m[1];
                g.p += m[2];
                g.i += m[3];
            }
        }
    std::sort(regions.begin(), regions.end(),
              [](const Region& a, const Region& b) { return a.err > b.err; });
    for (int k = 0; k < top && k < static_cast<int>(regions.size()); ++k) {
        const Region& g = regions[static_cast<size_t>(k)];
        std::printf(
            "    16 px region at (%d, %d): %.0f %% of the squared error; render/photo "
            "%.3f, truth/identity %.3f\n",
            g.x, g.y, total > 0 ? 100 * g.err / total : 0.0, g.p > 0 ? g.r / g.p : 0.0,
            g.i > 0 ? g.t / g.i : 0.0);
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s <scene_dir> <prepared cache> [edit ...]\n", argv[0]);
        return 2;
    }
    const fs::path dir = argv[1], cache = argv[2];
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf("\n");
    std::string why;
    auto prepared = readPreparedCache(cache, storedKey(cache), &why);
    if (!prepared || prepared->pixelDirect.empty()) {
        std::fprintf(stderr, "%s: %s\n", cache.c_str(),
                     prepared ? "no per-pixel light in it" : why.c_str());
        return 1;
    }
    const PreparedImage& P = *prepared;
    const SceneFile sf = loadScene(dir);
    const Image albedo = readImage(dir / "truth" / "albedo.exr");
    std::vector<std::string> edits;
    fs::path out;
    int box[4] = {0, 0, 1 << 30, 1 << 30};  // x0 y0 x1 y1: the sums over these pixels only
    for (int i = 3; i < argc; ++i) {
        if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (std::strcmp(argv[i], "--box") == 0 && i + 4 < argc)
            for (int k = 0; k < 4; ++k) box[k] = std::atoi(argv[++i]);
        else
            edits.emplace_back(argv[i]);
    }
    if (!out.empty()) fs::create_directories(out);
    if (edits.empty())
        for (const auto& e : fs::directory_iterator(dir / "edits"))
            if (fs::exists(dir / "truth" / (e.path().stem().string() + ".exr")))
                edits.push_back(e.path().stem().string());
    std::sort(edits.begin(), edits.end());
    const Image identity = readImage(dir / "truth" / "identity.exr");
    const size_t pixels = static_cast<size_t>(P.display.width) * P.display.height;
    std::printf("pixels drawn per pixel, luminance summed over them (irradiance, photo units)\n");
    std::printf("%-24s %10s %10s %10s %10s %8s %8s\n", "edit", "direct", "indirect", "model",
                "truth", "ind/dir", "mod/tru");
    for (const auto& name : edits) {
        const EditFile edit = loadEdit(dir / "edits" / (name + ".json"), sf);
        if (!edit.addLights.empty() || !edit.addObjects.empty() || !edit.removeObjects.empty())
            continue;  // light edits only
        const auto radiance = editRadiance(sf, edit, P.photoRadiance);
        const Image truth = readImage(dir / "truth" / (name + ".exr"));
        const int W = P.display.width;
        Image side(3 * W, P.display.height);
        double dsum = 0, isum = 0, tsum = 0;
        for (size_t px = 0; px < pixels; ++px) {
            if (!shownPerPixel(P.display, px)) continue;
            const int x = static_cast<int>(px % static_cast<size_t>(P.display.width));
            const int y = static_cast<int>(px / static_cast<size_t>(P.display.width));
            if (x < box[0] || y < box[1] || x >= box[2] || y >= box[3]) continue;
            const float* a = albedo.rgb.data() + 3 * px;
            const float* t = truth.rgb.data() + 3 * px;
            Rgb rho{a[0], a[1], a[2]}, T{t[0], t[1], t[2]};
            if (rho.minComponent() < 0.05) continue;  // guard: irradiance from a dark albedo
            Rgb d, in;
            modelLight(P, px, radiance, d, in);
            Rgb H;
            for (int c = 0; c < 3; ++c) H[c] = std::numbers::pi * T[c] / rho[c];
            const double q = (d + in).luminance() / std::max(H.luminance(), 1e-9);
            const double u = std::clamp(std::log2(std::max(q, 1e-9)), -1.0, 1.0);
            float* o = side.at(2 * W + static_cast<int>(px % W), static_cast<int>(px / W));
            o[0] = static_cast<float>(0.5 + 0.5 * std::max(u, 0.0) - 0.25 * std::max(-u, 0.0));
            o[1] = static_cast<float>(0.5 - 0.25 * std::abs(u));
            o[2] = static_cast<float>(0.5 + 0.5 * std::max(-u, 0.0) - 0.25 * std::max(u, 0.0));
            for (int c = 0; c < 3; ++c) o[c] = o[c] * o[c];  // linear, written through sRGB
            dsum += d.luminance();
            isum += in.luminance();
            tsum += H.luminance();
        }
        if (!out.empty()) {
            const Image img = renderEdit(P, radiance, DisplayMode::pixel);
            writeImage(out / (name + ".exr"), img);
            int mw = 0, mh = 0;
            std::vector<uint8_t> keep = readMask(dir / "truth" / (name + ".mask.png"), mw, mh);
            const std::vector<uint8_t> photoMask = readMask(dir / "photo.mask.png", mw, mh);
            for (size_t i = 0; i < keep.size() && i < photoMask.size(); ++i)
                keep[i] = keep[i] == 255 && photoMask[i] == 255;
            // The error by scale. Noise that is independent from block to block halves
            // its RMS from 4 to 8 px blocks, an error of the light's distribution does not
            // (to first order): e4^2 = n^2 + s^2, e8^2 = n^2 / 4 + s^2.
            const double e4 = blockError(img, truth, keep, 4), e8 = blockError(img, truth, keep, 8);
            const double n2 = std::max(0.0, (e4 * e4 - e8 * e8) * 4.0 / 3.0);
            // The photo's own noise as this render carries it: the render against the
            // same ratio applied to the truth's identity (an independent rendering of the
            // photo), over sqrt 2 (two renderings' noise in that difference).
            Image carried = img;
            for (size_t i = 0; i < carried.rgb.size(); ++i) {
                const double p = static_cast<double>(P.photo.rgb[i]);
                carried.rgb[i] = p > 0
                                     ? static_cast<float>(static_cast<double>(img.rgb[i]) *
                                                          static_cast<double>(identity.rgb[i]) / p)
                                     : 0.0f;
            }
            std::printf(
                "  %s: render against truth at blocks of 4 / 8 / 16 / 40 px: %.4f %.4f "
                "%.4f %.4f; noise %.3f, distribution %.3f; the photo's noise carried "
                "%.3f\n",
                name.c_str(), e4, e8, blockError(img, truth, keep, 16),
                blockError(img, truth, keep, 40), std::sqrt(n2),
                std::sqrt(std::max(0.0, e4 * e4 - n2)),
                blockError(img, carried, keep, 4) / std::sqrt(2.0));
            worstRegions(img, truth, P.photo, identity, keep, 4);
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < W; ++x)
                    for (int c = 0; c < 3; ++c) {
                        side.at(x, y)[c] = img.at(x, y)[c];
                        side.at(W + x, y)[c] = truth.at(x, y)[c];
                    }
            // The render and the truth at the exposure that shows the edit's own level.
            double mean = 0;
            for (const float v : truth.rgb) mean += static_cast<double>(v);
            mean /= static_cast<double>(truth.rgb.size());
            const double k = mean > 0 ? 0.18 / mean : 1.0;
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < 2 * W; ++x)
                    for (int c = 0; c < 3; ++c) side.at(x, y)[c] *= static_cast<float>(k);
            writeImage(out / (name + "_shares.png"), side);
        }
        const double model = dsum + isum;
        std::printf("%-24s %10.4g %10.4g %10.4g %10.4g %8.3f %8.3f\n", name.c_str(), dsum, isum,
                    model, tsum, dsum > 0 ? isum / dsum : 0.0, tsum > 0 ? model / tsum : 0.0);
    }
    return 0;
}
