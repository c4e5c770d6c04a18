// The interactive window: the photo area at the photo's aspect, the panel (Dear ImGui) with
// the lights, the virtual parts, the display settings and saving, and the mouse tools
// (Loscos, Drettakis & Robert 2000, Fig. 8: the user switches lamps, adds lights and moves
// objects and sees the relit photo at once).
#pragma once

#include <string>

#include "viewer/frame.h"
#include "viewer/gl_window.h"

namespace relight::viewer {

struct AppOptions {
    std::string saveFile = "viewer-edit.json";  ///< where "Save edit" writes by default
    /// When set: the whole window (panel included) is written here after a few frames, once
    /// the image is exact (no work in the background, nothing left to settle), and the
    /// viewer exits (documentation, and a test that the interface runs).
    std::string windowShot;
};

/// Runs the window until it is closed. Returns the process exit code.
int runApp(GlWindow& window, Session& session, FrameRenderer& frame, const AppOptions& options);

}  // namespace relight::viewer
