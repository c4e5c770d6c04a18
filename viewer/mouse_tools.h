// The mouse on the photo: the panel's tools (viewer/app.cpp) as a state machine that takes
// one Pointer a frame. The window builds the Pointer from GLFW's input; a test builds it by
// hand, so that the drags (the sun turned, a point lamp moved, an object grabbed and let go)
// run through the same code without a window's events (tests/viewer).
//
// What a tool does to the session it does through a ToolHost: at once in the frame
// (act(): a quick frame, a pick), or on the window's worker thread (inBackground(): an
// insertion, a drag's end that solves again). The window's host is App's; a test's may run
// both at once or on a BackgroundWork.
#pragma once

#include <functional>
#include <string>

#include "viewer/session.h"

namespace relight::viewer {

/// What a click on the image does: pick and drag an object, add a light, a box, a point lamp,
/// take a real object out, place a real lamp, turn the sun (drag), move a point lamp or a
/// virtual quad lamp (drag).
enum class Tool { select, light, box, remove, lamp, point, sun, movePoint };

/// Where the photo is drawn in the window (window coordinates, y down): the area left of
/// the panel, at the photo's aspect, centred.
struct PhotoRect {
    double x = 0, y = 0, w = 1, h = 1;
    bool contains(double mx, double my) const {
        return mx >= x && mx < x + w && my >= y && my < y + h;
    }
    /// Pixel coordinates in the photo (OpenCV: 0 is the centre of the first pixel).
    void toPixel(double mx, double my, int photoW, int photoH, double& u, double& v) const {
        u = (mx - x) / w * photoW - 0.5;
        v = (my - y) / h * photoH - 0.5;
    }
};

/// Where the pointer is this frame and whether its left button is down.
struct Pointer {
    double x = 0, y = 0;   ///< window coordinates
    bool down = false;     ///< the left button
    bool onPhoto = false;  ///< over the photo, not over the panel
};

/// What the tools ask of the window.
struct ToolHost {
    /// Runs f now, in the frame; false (its error shown) when it threw.
    std::function<bool(const char* what, const std::function<void()>& f)> act;
    /// Runs `work` on the worker thread; until it ends the worker alone touches the session.
    /// `work` captures by value what it uses.
    std::function<void(std::string what, std::function<void()> work)> inBackground;
    /// Whether work runs in the background (then nothing more of the session this frame).
    std::function<bool()> busy;
};

class MouseTools {
  public:
    MouseTools(Session& session, ToolHost host) : session_(session), host_(std::move(host)) {}

    /// One frame's pointer over the photo drawn at `r`.
    void handle(const PhotoRect& r, const Pointer& p);

    Tool tool = Tool::select;
    /// The sun Tool::sun turns; the point lamp or virtual quad lamp Tool::movePoint moves.
    std::string sun, point;
    int movingLamp = -1;            ///< the real lamp the next click moves, or -1
    float newLampSize[2] = {0, 0};  ///< metres; 0: the size of the scene's lamps
    std::string status;             ///< what the last click could not do, for the panel

  private:
    /// The pointer in photo pixels, and whether the button went down this frame.
    struct Press {
        double u = 0, v = 0;
        bool pressed = false;
    };
    /// Tool::sun: a drag on the image turns the sun. In the per-pixel displays the sun
    /// follows the drag, a quick frame each time the pointer moves (Session::setQuickMoves),
    /// exact once it rests; in the ratio display the drag is applied when the button is let
    /// go (each turn is solved again, as a saved "direction" is: a second or more on a large
    /// scene), on the worker thread.
    void sunTool(const PhotoRect& r, const Pointer& p, const Press& q);
    /// Tool::movePoint: the point lamp or virtual quad lamp goes onto the surface where the
    /// button is let go (a drag; a click is a drag of no length; Session::moveLightTo).
    void pointTool(const Pointer& p, const Press& q);
    /// The other tools: a click adds, removes, places or grabs; a drag moves the grabbed object.
    void click(const Pointer& p, const Press& q);

    Session& session_;
    ToolHost host_;
    bool wasDown_ = false;
    double lastX_ = -1, lastY_ = -1;
    double dragU_ = 0, dragV_ = 0;  ///< the sun tool's drag so far (photo pixels)
    bool sunDrag_ = false;
    bool pointDrag_ = false;  ///< Tool::movePoint: the button is down
};

}  // namespace relight::viewer
