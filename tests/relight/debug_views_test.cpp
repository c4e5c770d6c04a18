// The debug views of the relighting pipeline (relight/display/debug_views.h) on the room.
#include "relight/display/debug_views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "relight/display/ratio_display.h"
#include "relight/io/edit_file.h"
#include "relight/relighting.h"
#include "room_fixture.h"
#include "temp_dir.h"

using namespace relight;
using radiosity::Rgb;
namespace fs = std::filesystem;

namespace {

using test::coarseOptions;
const Relighting& room() {
    return test::coarseRoom();
}

std::vector<Rgb> backOff() {
    const EditFile e = loadEdit(RELIGHT_DATA_DIR "/room/edits/back_off.json", room().scene);
    return editRadiance(room().scene, e, room().prepared.photoRadiance);
}

/// The views of the unedited lights, and of back_off, computed once.
const DebugViews& photoViews() {
    static const DebugViews v = computeDebugViews(room(), room().prepared.photoRadiance);
    return v;
}
const DebugViews& backOffViews() {
    static const DebugViews v = computeDebugViews(room(), backOff());
    return v;
}

Rgb at(const Image& img, int x, int y) {
    const float* p = img.at(x, y);
    return {p[0], p[1], p[2]};
}

/// Pixels fully on reflecting surfaces: no sample sees nothing or a lamp's face.
bool allSurface(const DisplayMap& m, int px) {
    return m.unshaded[px] == 0 && m.emitterStart[px] == m.emitterStart[px + 1];
}

/// The 8-bit code of a linear value in a PNG written by writeImage (sRGB, clipped).
int code(double linear) {
    return static_cast<int>(std::lround(255.0 * srgbEncode(std::clamp(linear, 0.0, 1.0))));
}

}  // namespace

TEST(DebugViews, WritesEveryListedFileAtThePhotosSize) {
    relight::test::TempDir dir("relight_debug_views");
    const fs::path out = dir.path() / "a" / "b";  // missing parents are created
    const auto files = writeDebugViews(room(), backOff(), out);
    const std::vector<std::string> expected = {
        "B.exr",       "B.png",           "D.exr",    "D.png",        "T_orig.png", "T_inter.png",
        "T_final.png", "reflectance.png", "mesh.png", "frontier.png", "index.json"};
    EXPECT_EQ(files, expected);
    for (const auto& f : files) {
        ASSERT_TRUE(fs::is_regular_file(out / f)) << f;
        if (f == "index.json") continue;
        const Image img = readImage(out / f);
        EXPECT_EQ(img.width, 320) << f;
        EXPECT_EQ(img.height, 240) << f;
    }
    // No temporary file is left behind.
    for (const auto& e : fs::directory_iterator(out))
        EXPECT_EQ(e.path().filename().string().rfind(".tmp-", 0), std::string::npos) << e.path();
    // The index lists what was written, with the PNG scale of B and D.
    nlohmann::json index;
    std::ifstream(out / "index.json") >> index;
    std::vector<std::string> listed;
    for (const auto& v : index["views"]) listed.push_back(v["file"]);
    EXPECT_EQ(listed, std::vector<std::string>(files.begin(), files.end() - 1));
    // Prepared without per-pixel light: only the per-pixel photo irradiance is skipped, and
    // the edit's mesh (none given).
    ASSERT_EQ(index["skipped"].size(), 2u);
    EXPECT_EQ(index["skipped"][0]["file"], "H_photo.exr");
    EXPECT_EQ(index["skipped"][1]["file"], "mesh_edit.png");
    EXPECT_DOUBLE_EQ(index["views"][1]["scale"].get<double>(), backOffViews().bdScale);
    EXPECT_EQ(index["lights"]["C"], nlohmann::json({0.0, 0.0, 0.0}));
    // The EXR holds the view's floats as computed.
    const Image B = readImage(out / "B.exr");
    EXPECT_EQ(B.rgb, backOffViews().B.rgb);
}

TEST(DebugViews, TOrigIsThePhotosPngEncoding) {
    relight::test::TempDir dir("relight_debug_views");
    writeDebugViews(room(), backOff(), dir.path());
    writeImage(dir.path() / "photo.png", room().prepared.photo);
    const Image views = readImage(dir.path() / "T_orig.png"),
                photo = readImage(dir.path() / "photo.png");
    EXPECT_EQ(views.rgb, photo.rgb);
}

TEST(DebugViews, TFinalTimesBOverDGivesBackThePhoto) {
    // The unedited display is T_orig (k B/D) interpolated from the vertices, and k B/D = 1
    // at every vertex (relighting_test: UneditedLightsReproduceThePhoto). The views
    // interpolate k, B and D separately; the product of the interpolations equals the
    // interpolated product where k (hence B/D = 1/k) is the same at all the pixel's
    // vertices, and differs by their covariance elsewhere (shadow boundaries, where both
    // change). Read back from the files (T_final through its 8-bit PNG, B and D from EXR):
    // within one 8-bit code (quantization) wherever k varies by less than 1 % over the
    // pixel's vertices, and for at least 95 % of all surface values (about 9 % of them are
    // on such boundaries, and less than half of those are off by more than a code).
    // T_final values the PNG clips at 1 are left out.
    relight::test::TempDir dir("relight_debug_views");
    writeDebugViews(room(), room().prepared.photoRadiance, dir.path());
    const Image T = readImage(dir.path() / "T_final.png", /*srgb=*/true),
                B = readImage(dir.path() / "B.exr"), D = readImage(dir.path() / "D.exr");
    const Image& photo = room().prepared.photo;
    const DisplayMap& m = room().prepared.display;
    const auto& k = room().removal.kFinal;
    int checked = 0, within1 = 0, flat = 0;
    for (int y = 0; y < photo.height; ++y)
        for (int x = 0; x < photo.width; ++x) {
            const int px = y * photo.width + x;
            if (!allSurface(m, px)) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = D.at(x, y)[c], t = T.at(x, y)[c];
                if (!(d > 0) || t >= 1) continue;
                const double shown = t * static_cast<double>(B.at(x, y)[c]) / d;
                const int err = std::abs(code(shown) - code(photo.at(x, y)[c]));
                ++checked;
                within1 += err <= 1;
                double lo = k[m.vertex[m.start[px]]][c], hi = lo;
                for (int i = m.start[px]; i < m.start[px + 1]; ++i) {
                    lo = std::min(lo, k[m.vertex[i]][c]);
                    hi = std::max(hi, k[m.vertex[i]][c]);
                }
                if (hi > 1.01 * lo) continue;
                ++flat;
                EXPECT_LE(err, 1) << x << ", " << y << " channel " << c;
            }
        }
    EXPECT_GT(checked, 200000);  // of 320 x 240 x 3 = 230400
    EXPECT_GT(flat, 0.8 * checked);
    EXPECT_GE(within1, 0.95 * checked);
}

TEST(DebugViews, SwitchingLightsOffNeverBrightensB) {
    // back_off only lowers radiances: every vertex irradiance is a sum of non-negative
    // responses times the radiances (superposition), and rho is the same, so B can only
    // fall (float rounding aside: 1e-6 relative). D is the photo's and does not change.
    const DebugViews &before = photoViews(), &after = backOffViews();
    ASSERT_EQ(before.B.rgb.size(), after.B.rgb.size());
    double sumBefore = 0, sumAfter = 0;
    for (size_t i = 0; i < before.B.rgb.size(); ++i) {
        const double b = before.B.rgb[i], a = after.B.rgb[i];
        ASSERT_GE(a, 0.0) << i;
        ASSERT_LE(a, b * (1 + 1e-6)) << i;
        sumBefore += b;
        sumAfter += a;
    }
    // Two of the four lamps off: a clear fall overall, not just rounding.
    EXPECT_LT(sumAfter, 0.9 * sumBefore);
    EXPECT_EQ(before.D.rgb, after.D.rgb);
    EXPECT_EQ(before.bdScale, after.bdScale);
}

TEST(DebugViews, FrontierAndOccludedLeavesAreTinted) {
    // Loscos et al. 2000, Fig. 14(a). A pixel whose samples all lie on frontier leaves is
    // frontier green, all on occluded leaves occluded blue; one with neither is the dimmed
    // photo.
    const Relighting& r = room();
    ASSERT_GT(r.removal.frontier, 0);
    const Image& f = photoViews().frontier;
    const auto& h = r.solver->hierarchy();
    int frontier = 0, occluded = 0, plain = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            int nf = 0, no = 0;
            for (int s = 0; s < r.items.spp; ++s) {
                const SampleHit hit =
                    locateSample(r.items, h, r.solver->scene(), r.items.sampleIndex(x, y, s));
                if (!hit.surface()) continue;
                nf += r.removal.leafClass[hit.leaf] == LeafShadowClass::frontier;
                no += r.removal.leafClass[hit.leaf] == LeafShadowClass::occluded;
            }
            const Rgb c = at(f, x, y);
            if (nf == r.items.spp) {
                ++frontier;
                EXPECT_GT(c.g, 2 * std::max(c.r, c.b));
            } else if (no == r.items.spp) {
                ++occluded;
                EXPECT_GT(c.b, 2 * std::max(c.r, c.g));
            } else if (nf == 0 && no == 0) {
                ++plain;
                const Rgb p = at(r.prepared.photo, x, y);
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.4 * p[k], 1e-6 * (1 + p[k]));
            }
        }
    EXPECT_GT(frontier, 100);
    EXPECT_GT(occluded, 100);
    EXPECT_GT(plain, f.width * f.height / 4);
}

TEST(DebugViews, MeshMarksPixelsWhereLeavesChange) {
    // Fig. 10, 11: an edge pixel is one whose samples lie in different leaves (or next to
    // one where its neighbour's do); a pixel that is not marked has all its samples in one
    // leaf. The leaves are larger than a pixel on most surfaces, so edges are lines, not a
    // fill.
    const Relighting& r = room();
    const Image& mesh = photoViews().mesh;
    const auto& h = r.solver->hierarchy();
    int marked = 0;
    for (int y = 0; y < mesh.height; ++y)
        for (int x = 0; x < mesh.width; ++x) {
            std::set<int> ids;
            for (int s = 0; s < r.items.spp; ++s) {
                const SampleHit hit =
                    locateSample(r.items, h, r.solver->scene(), r.items.sampleIndex(x, y, s));
                ids.insert(hit.surface() ? hit.leaf : -2 - hit.light);
            }
            const bool isEdge = at(mesh, x, y) == Rgb{1.0f, 0.85f, 0.0f};
            marked += isEdge;
            if (ids.size() > 1) {
                EXPECT_TRUE(isEdge) << x << ", " << y;
            }
            if (!isEdge) {
                EXPECT_EQ(ids.size(), 1u) << x << ", " << y;
            }
        }
    EXPECT_GT(marked, mesh.width * mesh.height / 20);
    EXPECT_LT(marked, mesh.width * mesh.height * 3 / 5);
}

TEST(DebugViews, ReflectanceIsTheLeafReflectance) {
    // A pixel whose samples all lie in one leaf shows that leaf's rho; pixels that see no
    // reflecting surface are black.
    const Relighting& r = room();
    const Image& rho = photoViews().reflectance;
    const auto& h = r.solver->hierarchy();
    int checked = 0;
    for (int y = 0; y < rho.height; ++y)
        for (int x = 0; x < rho.width; ++x) {
            std::set<int> leaves;
            bool surface = false;
            for (int s = 0; s < r.items.spp; ++s) {
                const SampleHit hit =
                    locateSample(r.items, h, r.solver->scene(), r.items.sampleIndex(x, y, s));
                if (hit.surface()) surface = true;
                leaves.insert(hit.leaf);
            }
            const Rgb c = at(rho, x, y);
            if (!surface) {
                EXPECT_EQ(c, Rgb{});
            } else if (leaves.size() == 1) {
                const Rgb want = h.nodes[*leaves.begin()].rho;
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], want[k], 1e-6);
                ++checked;
            }
        }
    EXPECT_GT(checked, rho.width * rho.height / 2);
}

TEST(DebugViews, WithoutShadowRemovalTheTextureViewsAreSkipped) {
    RelightOptions o = coarseOptions();
    o.spp = 1;
    o.reflectanceRounds = 1;
    o.shadowRefinement = false;
    o.shadowRemoval = false;
    const auto r = prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), o);
    relight::test::TempDir dir("relight_debug_views");
    const auto files = writeDebugViews(*r, r->prepared.photoRadiance, dir.path());
    for (const char* f : {"T_inter.png", "T_final.png", "frontier.png"}) {
        EXPECT_EQ(std::find(files.begin(), files.end(), f), files.end()) << f;
        EXPECT_FALSE(fs::exists(dir.path() / f)) << f;
    }
    EXPECT_TRUE(fs::exists(dir.path() / "B.png"));
    nlohmann::json index;
    std::ifstream(dir.path() / "index.json") >> index;
    EXPECT_FALSE(index["shadow_removal"].get<bool>());
    ASSERT_EQ(index["skipped"].size(), 5u);  // T_inter, T_final, H_photo, frontier, mesh_edit
    EXPECT_EQ(index["skipped"][3]["file"], "frontier.png");
    EXPECT_NE(index["skipped"][0]["why"].get<std::string>().find("shadow removal was off"),
              std::string::npos);
}

TEST(DebugViews, AFolderThatCannotBeMadeIsAnErrorNamingIt) {
    relight::test::TempDir dir("relight_debug_views");
    const fs::path blocker = dir.write("blocker", "a file where a folder should be");
    for (const fs::path& bad : {blocker, blocker / "views"}) {
        try {
            writeDebugViews(room(), backOff(), bad);
            ADD_FAILURE() << "no error for " << bad;
        } catch (const OutputError& e) {
            EXPECT_NE(std::string(e.what()).find(bad.string() + ": cannot create"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(DebugViews, ARadiancePerLightIsRequired) {
    const std::vector<Rgb> tooFew(room().prepared.photoRadiance.size() - 1);
    EXPECT_THROW(computeDebugViews(room(), tooFew), std::invalid_argument);
}
