// The prepared-state cache (relight/io/prepared_cache.h): round trip, stale and corrupt files,
// the preparation key, failed writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "relight/io/edit_file.h"
#include "relight/io/prepared_cache.h"
#include "relight/relighting.h"
#include "room_fixture.h"
#include "temp_dir.h"

using namespace relight;
using radiosity::Rgb;
namespace fs = std::filesystem;

namespace {

RelightOptions cheapOptions() {
    return test::coarseOptions();
}
const Relighting& room() {
    return test::coarseRoom();
}

uint64_t roomKey() {
    static const uint64_t key = preparationKey(room().scene, cheapOptions());
    return key;
}

std::string readBytes(const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& f, const std::string& bytes) {
    std::ofstream out(f, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// A valid cache of the room, as bytes (written once).
const std::string& roomCacheBytes() {
    static const std::string bytes = [] {
        relight::test::TempDir dir("relight_cache_test");
        writePreparedCache(dir.path() / "prepared.bin", room().prepared, roomKey());
        return readBytes(dir.path() / "prepared.bin");
    }();
    return bytes;
}

/// readPreparedCache of `bytes` with the room's key: the reason it was rejected, or
/// "accepted".
std::string rejection(const std::string& bytes, uint64_t key = roomKey()) {
    relight::test::TempDir dir("relight_cache_test");
    const fs::path f = dir.path() / "prepared.bin";
    writeBytes(f, bytes);
    std::string why;
    const auto p = readPreparedCache(f, key, &why);
    if (p) return "accepted";
    EXPECT_FALSE(why.empty());
    return why;
}

/// A copy of the room's files (not truth/) in `dir`.
void copyRoom(const fs::path& dir) {
    const fs::path src = RELIGHT_DATA_DIR "/room";
    for (const char* f : {"scene.json", "room.obj", "photo.exr", "photo.mask.png"})
        fs::copy_file(src / f, dir / f, fs::copy_options::overwrite_existing);
}

bool sameBits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size() &&
           std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

uint64_t fnv1a(const char* p, size_t n) {
    uint64_t h = 14695981039346656037ull;
    for (size_t i = 0; i < n; ++i) {
        h ^= static_cast<unsigned char>(p[i]);
        h *= 1099511628211ull;
    }
    return h;
}

/// Re-seals `bytes` after editing its payload: a new checksum, so that only the reader's
/// own checks stand between the edit and the renderer.
void reseal(std::string& bytes) {
    constexpr size_t header = 32;
    const size_t payload = bytes.size() - header - 8;
    const uint64_t sum = fnv1a(bytes.data() + header, payload);
    std::memcpy(bytes.data() + header + payload, &sum, sizeof sum);
}

}  // namespace

TEST(PreparedCache, RoundTripRendersBitIdentically) {
    const Relighting& r = room();
    relight::test::TempDir dir("relight_cache_test");
    const fs::path f = dir.path() / "sub" / "prepared.bin";  // parent folder created
    writePreparedCache(f, r.prepared, roomKey());
    std::string why;
    const auto p = readPreparedCache(f, roomKey(), &why);
    ASSERT_TRUE(p) << why;
    EXPECT_EQ(checkPrepared(*p), "");
    EXPECT_EQ(p->leaves, r.prepared.leaves);
    EXPECT_EQ(p->links, r.prepared.links);
    EXPECT_EQ(p->vertexCount(), r.prepared.vertexCount());
    EXPECT_EQ(p->lighting.rays, r.prepared.lighting.rays);
    EXPECT_EQ(p->times.solve, r.prepared.times.solve);
    EXPECT_EQ(p->photoRadiance, r.prepared.photoRadiance);
    EXPECT_TRUE(sameBits(renderEdit(*p, p->photoRadiance),
                         renderEdit(r.prepared, r.prepared.photoRadiance)));
    const EditFile e = loadEdit(RELIGHT_DATA_DIR "/room/edits/left_off_right_double.json", r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    EXPECT_TRUE(sameBits(renderEdit(*p, radiance), renderEdit(r.prepared, radiance)));
    // Written again (a newer preparation), the old file is replaced whole.
    writePreparedCache(f, r.prepared, roomKey() + 1);
    EXPECT_TRUE(readPreparedCache(f, roomKey() + 1, nullptr));
    // No temporary file left beside it.
    int files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(f.parent_path())) ++files;
    EXPECT_EQ(files, 1);
}

TEST(PreparedCache, MissingFileIsRejectedWithAReason) {
    relight::test::TempDir dir("relight_cache_test");
    std::string why;
    EXPECT_FALSE(readPreparedCache(dir.path() / "none.bin", 1, &why));
    EXPECT_NE(why.find("no cache"), std::string::npos) << why;
    EXPECT_FALSE(readPreparedCache(dir.path(), 1, &why));  // a folder, not a file
    EXPECT_FALSE(why.empty());
}

TEST(PreparedCache, OtherKeyIsStale) {
    EXPECT_EQ(rejection(roomCacheBytes()), "accepted");
    // Another option: another key.
    RelightOptions o = cheapOptions();
    o.spp = 8;
    const uint64_t other = preparationKey(room().scene, o);
    ASSERT_NE(other, roomKey());
    const std::string why = rejection(roomCacheBytes(), other);
    EXPECT_NE(why.find("stale"), std::string::npos) << why;
}

TEST(PreparedCache, ChangedSceneJsonMakesTheCacheStale) {
    relight::test::TempDir dir("relight_cache_test");
    copyRoom(dir.path());
    const SceneFile before = loadScene(dir.path());
    const uint64_t key = preparationKey(before, cheapOptions());
    const fs::path cache = defaultCachePath(dir.path());
    EXPECT_EQ(cache, dir.path() / ".relight" / "prepared.bin");
    writePreparedCache(cache, room().prepared, key);
    ASSERT_TRUE(readPreparedCache(cache, key, nullptr));
    // One byte of scene.json: a wall's reflectance 0.7 -> 0.8.
    std::string json = readBytes(dir.path() / "scene.json");
    const size_t at = json.find("0.7");
    ASSERT_NE(at, std::string::npos);
    json[at + 2] = '8';
    writeBytes(dir.path() / "scene.json", json);
    const uint64_t changed = preparationKey(loadScene(dir.path()), cheapOptions());
    EXPECT_NE(changed, key);
    std::string why;
    EXPECT_FALSE(readPreparedCache(cache, changed, &why));
    EXPECT_NE(why.find("stale"), std::string::npos) << why;
}

TEST(PreparedCache, CorruptFilesAreRejectedWithoutCrashing) {
    const std::string& good = roomCacheBytes();
    ASSERT_GT(good.size(), 1000u);
    // Empty, and truncated at many lengths: inside the magic, the header, the payload,
    // the checksum.
    EXPECT_NE(rejection("").find("empty"), std::string::npos);
    for (size_t n : {size_t{1}, size_t{7}, size_t{8}, size_t{12}, size_t{20}, size_t{31},
                     size_t{32}, size_t{33}, size_t{40}, size_t{100}, good.size() / 3,
                     good.size() / 2, good.size() - 9, good.size() - 8, good.size() - 1}) {
        const std::string why = rejection(good.substr(0, n));
        EXPECT_NE(why, "accepted") << n;
        if (n >= 32) {
            EXPECT_NE(why.find("truncated"), std::string::npos) << n << ": " << why;
        }
    }
    // One more byte at the end.
    EXPECT_NE(rejection(good + '\0'), "accepted");
    // A flipped byte anywhere in the payload or the checksum.
    for (size_t at : {size_t{32}, size_t{40}, good.size() / 2, good.size() - 9, good.size() - 1}) {
        std::string bad = good;
        bad[at] = static_cast<char>(bad[at] ^ 0x10);
        const std::string why = rejection(bad);
        EXPECT_NE(why.find("checksum"), std::string::npos) << at << ": " << why;
    }
    // Wrong magic.
    std::string bad = good;
    bad[0] = 'X';
    EXPECT_NE(rejection(bad).find("magic"), std::string::npos);
    EXPECT_NE(rejection("not a cache at all, just text\n").find("magic"), std::string::npos);
    // Another format version.
    bad = good;
    const uint32_t version = kPreparedFormatVersion + 1;
    std::memcpy(bad.data() + 8, &version, sizeof version);
    EXPECT_NE(rejection(bad).find("version"), std::string::npos);
    // A payload size in the header that does not match the file, or overflows.
    for (uint64_t payload : {uint64_t{0}, uint64_t{1} << 40, ~uint64_t{0}, ~uint64_t{0} - 20}) {
        bad = good;
        std::memcpy(bad.data() + 24, &payload, sizeof payload);
        EXPECT_NE(rejection(bad), "accepted") << payload;
    }
}

TEST(PreparedCache, AbsurdLengthsAreRejectedBeforeAllocating) {
    // A length field that says 2^62 elements, with a valid checksum: only the length check
    // against the bytes left stands between it and a huge allocation (ASan would abort).
    // Payload: photo width (4), height (4), then the count of its values (8).
    for (uint64_t count : {uint64_t{1} << 62, ~uint64_t{0}, uint64_t{1} << 30}) {
        std::string bad = roomCacheBytes();
        std::memcpy(bad.data() + 32 + 8, &count, sizeof count);
        reseal(bad);
        const std::string why = rejection(bad);
        EXPECT_NE(why.find("corrupt"), std::string::npos) << why;
    }
    // A negative photo width.
    std::string bad = roomCacheBytes();
    const int32_t width = -320;
    std::memcpy(bad.data() + 32, &width, sizeof width);
    reseal(bad);
    EXPECT_NE(rejection(bad).find("corrupt"), std::string::npos);
}

TEST(PreparedCache, ResealedRandomDamageNeverCrashes) {
    // Random 4-byte damage with a valid checksum: the reader either rejects the file or
    // returns a state that renders within bounds (ASan/UBSan builds check the latter).
    std::mt19937 rng(12345);
    const std::string& good = roomCacheBytes();
    const int32_t values[] = {-1, 0, 1, 7, 1 << 20, INT32_MAX, INT32_MIN};
    int rejected = 0;
    for (int i = 0; i < 40; ++i) {
        std::string bad = good;
        const size_t at = 32 + rng() % (good.size() - 32 - 8 - 4);
        const int32_t v = values[rng() % std::size(values)];
        std::memcpy(bad.data() + at, &v, sizeof v);
        reseal(bad);
        relight::test::TempDir dir("relight_cache_test");
        writeBytes(dir.path() / "p.bin", bad);
        std::string why;
        const auto p = readPreparedCache(dir.path() / "p.bin", roomKey(), &why);
        if (!p) {
            EXPECT_FALSE(why.empty());
            ++rejected;
            continue;
        }
        const Image out = renderEdit(*p, p->photoRadiance);
        EXPECT_EQ(out.width, p->photo.width);
    }
    EXPECT_GT(rejected, 0);
}

TEST(PreparedCache, InconsistentSizesAreRejected) {
    // Each written through the ordinary writer (valid checksum): the reader's checks of
    // how the sizes fit together must catch them.
    const PreparedImage& good = room().prepared;
    ASSERT_EQ(checkPrepared(good), "");
    auto rejected = [&](const PreparedImage& p, const std::string& expected) {
        relight::test::TempDir dir("relight_cache_test");
        writePreparedCache(dir.path() / "p.bin", p, 7);
        std::string why;
        EXPECT_FALSE(readPreparedCache(dir.path() / "p.bin", 7, &why)) << expected;
        EXPECT_NE(why.find(expected), std::string::npos) << why;
    };
    PreparedImage p = good;
    p.display.start.pop_back();
    rejected(p, "display.start");
    p = good;
    p.display.vertex[p.display.vertex.size() / 2] = static_cast<int>(good.vertexCount());
    rejected(p, "display.vertex");
    p = good;
    p.display.vertex[0] = -1;
    rejected(p, "display.vertex");
    p = good;
    p.display.start[5] = p.display.start[6] + 1;
    rejected(p, "display.start");
    p = good;
    p.display.emitterLight.assign(p.display.emitterLight.size(), 99);
    if (!p.display.emitterLight.empty()) rejected(p, "emitterLight");
    p = good;
    p.lighting.response.pop_back();
    rejected(p, "lighting.response");
    p = good;
    p.lighting.lights += 1;
    rejected(p, "lights");
    p = good;
    p.D.pop_back();
    rejected(p, "");
    p = good;
    p.textureFactor.clear();
    rejected(p, "textureFactor");
    p = good;
    p.photo = Image(good.photo.width - 1, good.photo.height);
    rejected(p, "photo");
}

TEST(PreparedCache, KeyFollowsTheInputsAndOptions) {
    relight::test::TempDir dir("relight_cache_test");
    copyRoom(dir.path());
    const RelightOptions o = cheapOptions();
    const uint64_t key = preparationKey(loadScene(dir.path()), o);
    // Two loads of the same scene, and a progress callback: the same key.
    RelightOptions withProgress = o;
    withProgress.progress = [](const std::string&) {};
    EXPECT_EQ(preparationKey(loadScene(dir.path()), withProgress), key);
    // Files the preparation does not read (truth/, albedo.exr) do not count.
    fs::create_directories(dir.path() / "truth");
    dir.write("truth/identity.exr", "anything");
    dir.write("albedo.exr", "anything");
    EXPECT_EQ(preparationKey(loadScene(dir.path()), o), key);
    // Each option that changes the result does.
    RelightOptions e = o;
    e.epsilon = 2e-3;
    EXPECT_NE(preparationKey(loadScene(dir.path()), e), key);
    for (int RelightOptions::*field :
         {&RelightOptions::spp, &RelightOptions::minRays, &RelightOptions::maxRays,
          &RelightOptions::reflectanceRounds}) {
        RelightOptions changed = o;
        changed.*field += 1;
        EXPECT_NE(preparationKey(loadScene(dir.path()), changed), key);
    }
    RelightOptions noRefinement = o;
    noRefinement.shadowRefinement = !o.shadowRefinement;
    EXPECT_NE(preparationKey(loadScene(dir.path()), noRefinement), key);
    for (double ShadowRefinementOptions::*field :
         {&ShadowRefinementOptions::colourThreshold, &ShadowRefinementOptions::visibilityThreshold,
          &ShadowRefinementOptions::minShare}) {
        RelightOptions changed = o;
        changed.refinement.*field *= 1.5;
        EXPECT_NE(preparationKey(loadScene(dir.path()), changed), key);
    }
    for (int ShadowRefinementOptions::*field :
         {&ShadowRefinementOptions::minSamples, &ShadowRefinementOptions::maxSplits}) {
        RelightOptions changed = o;
        changed.refinement.*field += 1;
        EXPECT_NE(preparationKey(loadScene(dir.path()), changed), key);
    }
    RelightOptions noRemoval = o;
    noRemoval.shadowRemoval = !o.shadowRemoval;
    EXPECT_NE(preparationKey(loadScene(dir.path()), noRemoval), key);
    for (bool RelightOptions::*flag : {&RelightOptions::pixelLight, &RelightOptions::mergePhotos,
                                       &RelightOptions::narrowSources}) {
        RelightOptions changed = o;
        changed.*flag = !(o.*flag);
        EXPECT_NE(preparationKey(loadScene(dir.path()), changed), key);
    }
    for (double ShadowRemovalOptions::*field :
         {&ShadowRemovalOptions::colourThreshold, &ShadowRemovalOptions::umbraThreshold,
          &ShadowRemovalOptions::minShare}) {
        RelightOptions changed = o;
        changed.removal.*field *= 1.5;
        EXPECT_NE(preparationKey(loadScene(dir.path()), changed), key);
    }
    {
        RelightOptions changed = o;
        changed.removal.minSamples += 1;
        EXPECT_NE(preparationKey(loadScene(dir.path()), changed), key);
    }
    // The photo's bytes: one pixel changed.
    Image photo = readImage(dir.path() / "photo.exr");
    photo.at(10, 10)[0] += 0.25f;
    writeImage(dir.path() / "photo.exr", photo);
    const uint64_t photoChanged = preparationKey(loadScene(dir.path()), o);
    EXPECT_NE(photoChanged, key);
    // The OBJ file's bytes.
    {
        std::ofstream obj(dir.path() / "room.obj", std::ios::app);
        obj << "# a comment\n";
    }
    const uint64_t objChanged = preparationKey(loadScene(dir.path()), o);
    EXPECT_NE(objChanged, photoChanged);
    EXPECT_NE(objChanged, key);
}

TEST(PreparedCache, FailedWriteIsAClearErrorAndLeavesNoTemporaryFile) {
    const PreparedImage& p = room().prepared;
    relight::test::TempDir dir("relight_cache_test");
    dir.write("blocker", "a file where a folder should be");
    // The parent folder cannot be created: a file stands in its way.
    const fs::path f = dir.path() / "blocker" / "sub" / "prepared.bin";
    try {
        writePreparedCache(f, p, 1);
        ADD_FAILURE() << "no error";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("cannot create the folder"), std::string::npos)
            << e.what();
    }
    // The target is a folder: the temporary file is written, the rename fails.
    fs::create_directories(dir.path() / "cache.bin" / "inside");
    try {
        writePreparedCache(dir.path() / "cache.bin", p, 1);
        ADD_FAILURE() << "no error";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find((dir.path() / "cache.bin").string()),
                  std::string::npos)
            << e.what();
    }
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir.path()))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"blocker", "cache.bin"}));
}

TEST(PreparedCache, LayoutGuard) {
    // A field added to one of these structs must be written to the cache (a serialize() in
    // relight/io/prepared_cache.cpp, and kPreparedFormatVersion bumped) or, for an option that
    // changes the result, hashed into the preparation key (hashOptions() there); then
    // update the size here. (Sizes for libstdc++ on 64-bit targets.)
#if defined(__GLIBCXX__) && defined(__LP64__)
    EXPECT_EQ(sizeof(Image), 32u) << "Image changed: update serialize(Image)";
    // DisplayMap's leaf runs (rowRuns, runs, runWeight) are derived: packDisplayMap() after
    // reading, not written.
    EXPECT_EQ(sizeof(DisplayMap), 248u) << "DisplayMap changed: update serialize(DisplayMap)";
    EXPECT_EQ(sizeof(VertexLighting), 40u)
        << "VertexLighting changed: update serialize(VertexLighting)";
    EXPECT_EQ(sizeof(PrepareTimes), 64u) << "PrepareTimes changed: update serialize(PrepareTimes)";
    // PreparedImage::photoPixels (its per-pixel indirect parts and the pool's guide
    // included) and pixelTable are derived: derivePhotoPixels() after reading, not written.
    EXPECT_EQ(sizeof(PreparedImage), 944u)
        << "PreparedImage changed: update serialize(PreparedImage)";
    // ShadowRefinementOptions::until is the deadline prepareRelighting sets from
    // RelightOptions::timeBudget (hashed): not hashed itself, as it is a time point.
    EXPECT_EQ(sizeof(ShadowRefinementOptions), 72u)
        << "ShadowRefinementOptions changed: hash the new option in hashOptions()";
    // ShadowRemovalOptions::progress (3ea5a5b) only hears the steps: not hashed, as
    // RelightOptions::progress is not.
    EXPECT_EQ(sizeof(ShadowRemovalOptions), 64u)
        << "ShadowRemovalOptions changed: hash the new option in hashOptions()";
    // Its ShadowRefinementOptions' until; pixelGatherCut (hashed) in padding; perLightOracle
    // is hashed when on (0, the default, keeps the caches' keys); so is narrowSources.
    // budgetStart is where timeBudget (hashed) counts from: a time point, not hashed.
    // machineMemory decides whether a preparation starts, never what it computes: not hashed.
    EXPECT_EQ(sizeof(RelightOptions), 320u)
        << "RelightOptions changed: hash the new option in hashOptions()";
#else
    GTEST_SKIP() << "sizes known for libstdc++ on 64-bit targets only";
#endif
}
