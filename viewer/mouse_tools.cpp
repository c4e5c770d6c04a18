#include "viewer/mouse_tools.h"

namespace relight::viewer {

void MouseTools::handle(const PhotoRect& r, const Pointer& p) {
    const PreparedImage& prepared = session_.prepared();
    Press q;
    r.toPixel(p.x, p.y, prepared.photo.width, prepared.photo.height, q.u, q.v);
    q.pressed = p.down && !wasDown_;
    if (tool == Tool::sun)
        sunTool(r, p, q);
    else if (tool == Tool::movePoint)
        pointTool(p, q);
    else
        click(p, q);
    wasDown_ = p.down;
    lastX_ = p.x;
    lastY_ = p.y;
}

void MouseTools::sunTool(const PhotoRect& r, const Pointer& p, const Press& q) {
    const PreparedImage& prepared = session_.prepared();
    if (q.pressed && p.onPhoto) {
        sunDrag_ = true;
        dragU_ = dragV_ = 0;
    }
    if (p.down && sunDrag_) {
        dragU_ += (p.x - lastX_) / r.w * prepared.photo.width;
        dragV_ += (p.y - lastY_) / r.h * prepared.photo.height;
    }
    const bool follow = session_.quickMoves() && p.down && sunDrag_;
    if (follow && (dragU_ != 0 || dragV_ != 0))
        host_.act("turning the sun", [&] { session_.dragSun(sun, dragU_, dragV_); });
    else if (!p.down && sunDrag_)  // let go: solved (or, followed, made exact) on the worker
        host_.inBackground("turning the sun", [this, name = sun, du = dragU_, dv = dragV_] {
            session_.dragSun(name, du, dv);
        });
    if (follow || !p.down) dragU_ = dragV_ = 0;
    sunDrag_ = sunDrag_ && p.down;
}

void MouseTools::pointTool(const Pointer& p, const Press& q) {
    if (q.pressed && p.onPhoto) pointDrag_ = true;
    // In the per-pixel displays the lamp follows the pointer (quick frames, as the sun's);
    // else it goes where the button is let go, solved on the worker.
    const bool follow =
        session_.quickMoves() && p.down && pointDrag_ && (p.x != lastX_ || p.y != lastY_);
    if (!follow && (p.down || !pointDrag_)) return;
    pointDrag_ = p.down;
    const Pick pick = session_.pick(q.u, q.v, point);  // one ray, through the lamp's own face
    if (!pick.hit) return;
    if (follow)
        host_.act("moving the lamp", [&] { session_.moveLightTo(point, pick); });
    else
        host_.inBackground("moving the lamp",
                           [this, name = point, pick] { session_.moveLightTo(name, pick); });
}

void MouseTools::click(const Pointer& p, const Press& q) {
    if (q.pressed && p.onPhoto) {
        const Pick pick = session_.pick(q.u, q.v);
        const int last = static_cast<int>(session_.objects().size()) - 1;
        if (!pick.hit)
            status = "nothing there to click on";
        else if (tool == Tool::light)
            host_.inBackground("adding a light", [this, pick] { session_.addLightAt(pick); });
        else if (tool == Tool::box)
            host_.inBackground("adding a box", [this, pick] { session_.addBoxAt(pick); });
        else if (tool == Tool::point)
            // The tool and the lamp it moves are set by the worker: the panel and the mouse,
            // which read them, wait for it.
            host_.inBackground("adding a point lamp", [this, pick] {
                point = session_.addPointLampAt(pick);
                tool = Tool::movePoint;  // a click then moves it (a drag's end)
            });
        else if (tool == Tool::lamp && movingLamp >= 0)
            host_.act("moving the lamp", [&] {
                session_.moveLampTo(movingLamp, pick);
                movingLamp = -1;
            });
        else if (tool == Tool::lamp)
            host_.act("placing a lamp",
                      [&] { session_.placeLampAt(pick, newLampSize[0], newLampSize[1]); });
        else if (tool == Tool::remove && pick.realObject.empty())
            status = "no removable object there (scene.json marks which are)";
        else if (tool == Tool::remove)
            host_.inBackground("removing the object",
                               [this, name = pick.realObject] { session_.removeRealObject(name); });
        else if (pick.object >= 0 && pick.object == last)
            host_.act("picking the object", [&] { session_.beginDrag(pick.object, pick); });
        else if (pick.object >= 0)  // made the last part first: the parts inserted again
            host_.inBackground("picking the object",
                               [this, pick] { session_.beginDrag(pick.object, pick); });
    }
    // Nothing more of the session this frame once work was started in the background.
    if (!host_.busy() && p.down && session_.dragging() >= 0 && (p.x != lastX_ || p.y != lastY_))
        host_.act("moving the object", [&] { session_.dragTo(q.u, q.v); });
    if (!host_.busy() && !p.down && session_.dragging() >= 0)
        host_.inBackground("letting the object go", [this] { session_.endDrag(); });
}

}  // namespace relight::viewer
