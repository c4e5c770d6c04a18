// The bundled room-multi scene (data/room-multi): the room with six more lamps, each off in
// the first photo and alone on in one of six further photos (Loscos et al. 1999's radiance
// images). Its edits load, and turning on a lamp that was off in the photo (lamp_M3_on)
// matches the path-traced truth.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "relight/display/metric.h"
#include "relight/io/edit_file.h"
#include "relight/io/scene_file.h"
#include "relight/prepared.h"
#include "relight/relighting.h"
#include "room_fixture.h"

using namespace relight;
namespace fs = std::filesystem;

namespace {
const std::string kMulti = RELIGHT_DATA_DIR "/room-multi";
}  // namespace

TEST(RoomMulti, SevenPhotosTenLampsAndEveryEditLoads) {
    const SceneFile sf = loadScene(kMulti);
    ASSERT_EQ(sf.photos.size(), 7u);
    EXPECT_EQ(sf.scene.lights.size(), 10u);
    // The first photo has the ceiling lamps A-D on; photo i + 1 has lamp M(i + 1) alone.
    EXPECT_EQ(sf.photos[0].lightsOn.size(), 4u);
    for (size_t i = 1; i < sf.photos.size(); ++i) {
        ASSERT_EQ(sf.photos[i].lightsOn.size(), 1u) << i;
        std::string lamp = "M";  // not "M" + to_string: GCC 12 warns wrongly (-Wrestrict)
        lamp += std::to_string(i);
        EXPECT_EQ(sf.photos[i].lightsOn[0], lamp);
    }
    int edits = 0;
    for (const auto& entry : fs::directory_iterator(kMulti + "/edits")) {
        SCOPED_TRACE(entry.path().string());
        const EditFile e = loadEdit(entry.path(), sf);
        EXPECT_TRUE(e.file == entry.path());
        ++edits;
    }
    EXPECT_EQ(edits, 10);
}

TEST(RoomMulti, ALampOffInThePhotoTurnedOnMatchesTheTruth) {
    // lamp_M3_on: A-D as in the photo plus M3 (low on the right wall, under the table) at
    // radiance 30. The photo holds none of M3's light: the ratio display multiplies the
    // photo by (B_ABCD + B_M3) / D. The bound for an edit is 0.05 (0.15 where it
    // changes the image); measured 0.0212 at the default settings, 0.03 at the tests'
    // coarse ones. Both displays are held to the bound.
    const auto r = prepareRelighting(loadScene(kMulti), test::coarseOptions());
    const EditFile e = loadEdit(kMulti + "/edits/lamp_M3_on.json", r->scene);
    const auto radiance = editRadiance(r->scene, e, r->prepared.photoRadiance);
    for (const DisplayMode mode : {DisplayMode::ratio, DisplayMode::confidence}) {
        const Score s = test::scoreAgainstTruth(
            kMulti, "lamp_M3_on", renderEdit(r->prepared, radiance, mode), r->prepared.photo);
        std::printf("lamp_M3_on, %s display: rel_rmse %.4f, changed %.4f\n", displayModeName(mode),
                    s.relRmse, s.changedRelRmse);
        EXPECT_LE(s.relRmse, 0.05) << displayModeName(mode);
        EXPECT_LE(s.changedRelRmse, 0.15) << displayModeName(mode);
    }
}
