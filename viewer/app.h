// The interactive window: the photo area at the photo's aspect, the panel (Dear ImGui) with
// the lights, the virtual parts, the display settings and saving, and the mouse tools
// (Loscos, Drettakis & Robert 2000, Fig. 8: the user switches lamps, adds lights and moves
// objects and sees the relit photo at once).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "viewer/frame.h"
#include "viewer/gl_window.h"

namespace relight::viewer {

/// An action the window runs as it runs the panel's slow ones: on its worker thread, the
/// window drawing meanwhile (viewer/main.cpp's --do actions when the window is open).
struct ScriptedAction {
    std::string what;                   ///< what the panel and the terminal call it
    std::function<void(Session&)> run;  ///< the work: takes the session, captures by value
};

struct AppOptions {
    std::string saveFile = "viewer-edit.json";  ///< where "Save edit" writes by default
    /// When set: the whole window (panel included) is written here after a few frames, once
    /// the image is exact (no work in the background, nothing left to settle), and the
    /// viewer exits (documentation, and a test that the interface runs).
    std::string windowShot;
    /// Run in order, one at a time, before anything else; the window shot waits for them.
    std::vector<ScriptedAction> actions;
};

/// Runs the window until it is closed. Returns the process exit code.
int runApp(GlWindow& window, Session& session, FrameRenderer& frame, const AppOptions& options);

}  // namespace relight::viewer
