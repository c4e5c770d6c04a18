// Time per daylight edit (issue 31): the sky turned, the sun moved, a point lamp moved, and
// the preparation, on a scene with a sun and a sky (data/courtyard, or a tessellated and
// upscaled copy of it for 1280 x 960).
//
//   ./build/bench/daylight_edit_times [SCENE_DIR] [--repeats N]   (default data/courtyard, 20)
//
// - sky turned: editRadiance() of a 120-degree turn about z, then renderEdit() with the
//   per-pixel display (the default of `relight render`): the sky is 9 lights, so this is a
//   weighted sum of precomputed per-light images. Median over N runs.
// - sun moved: the sun off where it was and a virtual sun where it went (movedLights(),
//   DynamicRelighting::addLight, render): median over 3 runs, with the FrameTimes breakdown.
// - point lamp moved: a virtual point lamp (the night_lamp edit's) at a new place: the
//   dynamic state set up, the lamp inserted, rendered; median of 3.
// Prints the preparation's steps (PreparedImage::times).
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "radiosity/emitter.h"
#include "radiosity/stopwatch.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/relighting.h"

using namespace relight;
using bench::quantile;
using radiosity::Clock;
using radiosity::secondsSince;

namespace {

EditFile editOf(const SceneFile& sf, const std::string& text) {
    std::istringstream in(text);
    return parseEdit(in, sf.dir / "bench_edit.json", sf);
}

void printFrame(const char* what, double total, const FrameTimes& t) {
    std::printf(
        "%-18s %8.3f s  (shafts %.3f, visibility %.3f, links %.3f, radiosity %.3f, vertices "
        "%.3f, display %.3f)\n",
        what, total, t.shafts, t.visibility, t.links, t.radiosity, t.vertices, t.display);
}

}  // namespace

int main(int argc, char** argv) {
    std::string dir = "data/courtyard";
    int repeats = 20;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc)
            repeats = std::max(1, std::atoi(argv[++i]));
        else
            dir = argv[i];
    }
    std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each figure as soon as it is measured
    std::printf("command: ./build/bench/daylight_edit_times %s --repeats %d\n", dir.c_str(),
                repeats);
    RelightOptions o;
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    o.pixelLight = true;                                // relight render's default display
    auto t0 = Clock::now();
    auto r = prepareRelighting(loadScene(dir), o);
    const double prepare = secondsSince(t0);
    const PreparedImage& P = r->prepared;
    std::printf("%dx%d photo\n", P.photo.width, P.photo.height);
    const auto& T = P.times;
    std::printf(
        "preparation        %8.3f s  (item buffer %.3f, solve %.3f, reflectance %.3f, "
        "refinement %.3f, responses %.3f, vertex lighting %.3f, shadow removal %.3f, display "
        "map %.3f)\n",
        prepare, T.itemBuffer, T.solve, T.reflectance, T.refinement, T.responses, T.vertexLighting,
        T.shadowRemoval, T.displayMap);

    // The sky turned: a weighted sum of the per-light images.
    const EditFile turn = editOf(
        r->scene,
        R"({"format": "relight-edit/1", "lights": {"sky": {"rotate": {"axis": [0, 0, 1], "degrees": 120}}}})");
    Image out;
    std::vector<double> sky;
    for (int i = 0; i < repeats; ++i) {
        t0 = Clock::now();
        const auto radiance = editRadiance(r->scene, turn, P.photoRadiance);
        renderEdit(P, radiance, out, DisplayMode::pixel);
        sky.push_back(secondsSince(t0));
    }
    std::printf("sky turned         %8.4f s  (median of %d; 90th percentile %.4f s)\n",
                quantile(sky, 0.5), repeats, quantile(sky, 0.9));

    // The sun moved: off where it was, a virtual sun where it went.
    const EditFile sunMoved = editOf(
        r->scene,
        R"({"format": "relight-edit/1", "lights": {"sun": {"direction": [0.453154, -0.784886, 0.422618]}}})");
    std::vector<double> sun;
    FrameTimes sunTimes;
    for (int i = 0; i < 3; ++i) {
        t0 = Clock::now();
        const auto radiance = editRadiance(r->scene, sunMoved, P.photoRadiance);
        DynamicRelighting dyn(*r, radiance);
        for (const VirtualLight& l : movedLights(r->scene, sunMoved)) dyn.addLight(l);
        out = dyn.render(DisplayMode::pixel);
        sun.push_back(secondsSince(t0));
        sunTimes = dyn.times();
    }
    printFrame("sun moved", quantile(sun, 0.5), sunTimes);

    // A point lamp moved: the edit with the lamp at its new place (a virtual point lamp,
    // as night_lamp's), as `relight render` or a drag in the viewer makes it: the dynamic
    // state set up, the lamp inserted, the image rendered. (DynamicRelighting::removeLast
    // undoes objects only, so the move is a fresh insertion at the new place.)
    std::vector<double> lamp;
    FrameTimes lampTimes;
    const std::vector<radiosity::Vec3> places = {{0.8, 3.6, 2.8}, {-0.8, 2.6, 2.2}};
    const radiosity::Rgb I{6.0, 5.2, 4.0};
    const EditFile none = editOf(r->scene, R"({"format": "relight-edit/1"})");
    for (int i = 0; i < 3; ++i) {
        t0 = Clock::now();
        const auto radiance = editRadiance(r->scene, none, P.photoRadiance);
        DynamicRelighting dyn(*r, radiance);
        dyn.addLight({"P1", {}, {}, radiosity::makePointLamp("P1", places[i % 2], I)});
        out = dyn.render(DisplayMode::pixel);
        lamp.push_back(secondsSince(t0));
        lampTimes = dyn.times();
    }
    printFrame("point lamp moved", quantile(lamp, 0.5), lampTimes);
    return 0;
}
