// Test helper: the room of data/ prepared with coarse settings, shared by the test files.
#pragma once

#include "relight/relighting.h"

namespace relight::test {

/// Coarse settings keep the tests fast; what they check holds at any setting.
inline RelightOptions coarseOptions() {
    RelightOptions o;
    o.epsilon = 1e-3;
    o.spp = 4;
    o.reflectanceRounds = 3;
    return o;
}

/// The room prepared once per test program with coarseOptions().
inline const Relighting& coarseRoom() {
    static const auto r = prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), coarseOptions());
    return *r;
}

}  // namespace relight::test
