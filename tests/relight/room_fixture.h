// Test helper: the room of data/ prepared with coarse settings, shared by the test files.
#pragma once

#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "relight/display/metric.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/image.h"
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

/// The room prepared once per test program with coarseOptions() and the direct light per
/// pixel (RelightOptions::pixelLight), as render's default display needs.
inline const Relighting& coarsePixelRoom() {
    static const auto r = [] {
        RelightOptions o = coarseOptions();
        o.pixelLight = true;
        return prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), o);
    }();
    return *r;
}

/// The spec's score (relight/display/metric.h) of `image`, relit for the edit `edit` of the
/// scene in `dir`, against its path-traced truth, with the truth's and the photo's masks.
inline Score scoreAgainstTruth(const std::string& dir, const std::string& edit, const Image& image,
                               const Image& photo) {
    int w = image.width, h = image.height;
    return scoreImage(image, readImage(dir + "/truth/" + edit + ".exr"), photo,
                      readMask(dir + "/truth/" + edit + ".mask.png", w, h),
                      readMask(dir + "/photo.mask.png", w, h));
}

/// The scene in `dir` prepared with `o`, and its edit `edit` (real objects taken out, then
/// virtual parts inserted, as relight render does)
/// rendered in each display of `modes`, in that order.
struct EditRenders {
    std::unique_ptr<Relighting> relighting;
    std::vector<Image> images;
};
inline EditRenders renderEditIn(const std::string& dir, const std::string& edit,
                                const RelightOptions& o, std::initializer_list<DisplayMode> modes) {
    EditRenders out;
    out.relighting = prepareRelighting(loadScene(dir), o);
    Relighting& r = *out.relighting;
    const EditFile e = loadEdit(dir + "/edits/" + edit + ".json", r.scene);
    DynamicRelighting dyn(r, editRadiance(r.scene, e, r.prepared.photoRadiance));
    for (const auto& name : e.removeObjects) dyn.removeObject(name);
    for (const auto& l : movedLights(r.scene, e)) dyn.addLight(l);
    for (const auto& l : e.addLights) dyn.addLight(l);
    for (const auto& obj : e.addObjects) dyn.addObject(obj);
    for (const DisplayMode mode : modes) out.images.push_back(dyn.render(mode));
    return out;
}

/// A display map of W x H surface pixels built by hand, pixel i on vertex i alone (weight 1):
/// for the per-pixel display's and the photo merge's arithmetic, without a scene.
inline DisplayMap surfaceGrid(int W, int H) {
    DisplayMap m;
    m.width = W;
    m.height = H;
    const int n = W * H;
    for (int i = 0; i <= n; ++i) {
        m.start.push_back(i);
        m.emitterStart.push_back(0);
    }
    for (int i = 0; i < n; ++i) {
        m.vertex.push_back(i);
        m.weight.push_back(1.0f);
        m.unshaded.push_back(0.0f);
    }
    return m;
}

}  // namespace relight::test
