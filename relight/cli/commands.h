// The `relight` command's subcommands, one file each; main.cpp parses the arguments.
// Each returns the process exit code and throws InputError for bad input.
#pragma once

#include <string>

namespace relight::cli {

/// `relight solve`: clustered hierarchical radiosity of a scene.
struct SolveArgs {
    std::string scene;
    double epsilon = 1e-3;
    double minArea = 0;
    int minRays = 4, maxRays = 16;
    int spp = 16;
    int reflectanceRounds = 12;
    bool photoReflectance = true;
    std::string report, output;
    double exposure = 0;
};

int runSolve(const SolveArgs& a);

/// `relight eval`: scores an image against a scene's ground truth (spec metric).
int runEval(const std::string& sceneDir, const std::string& edit, const std::string& image,
            const std::string& errorMapFile);

/// `relight render`: the relit photo for an edit.
struct RenderArgs {
    std::string scene, edit, output, report;
    double epsilon = 1e-4;
    int spp = 16;
    double exposure = 0;
};
int runRender(const RenderArgs& a);

}  // namespace relight::cli
