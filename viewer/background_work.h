// Session work that takes longer than a frame, run on a worker thread so that the window
// keeps drawing: the exact image when a slider or a drag rests (1.3 s for a point lamp moved
// in the room at 320x240, 10.6 s at 1280x960), a light or a box inserted (2.4 s), an object
// let go, the panel's slow actions (a virtual lamp's strength, *bring back*: App::later in
// viewer/app.cpp). bench/RESULTS.md, 2026-11-28 (eleventh session), measured these as
// frames that blocked the window; the ratio-map paper's point (../shared/seeds/000) is that
// nothing the user does should wait on the radiosity.
//
// While the work runs, nothing else may touch the session: the window shows the last image
// it drew and a panel that says what is being done and for how long, and takes no input
// (viewer/app.cpp). The work's end is seen by the window's next frame (finish()), which then
// draws its result; an exception it threw is rethrown there, once.
#pragma once

#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <string>
#include <thread>

namespace relight::viewer {

class BackgroundWork {
  public:
    BackgroundWork() = default;
    BackgroundWork(const BackgroundWork&) = delete;
    BackgroundWork& operator=(const BackgroundWork&) = delete;
    /// Waits for the work to end (its exception, if any, is dropped).
    ~BackgroundWork();

    /// Whether work was started and finish() has not yet seen its end.
    bool busy() const { return worker_.joinable(); }
    /// Starts `work` on the worker thread, described by `what` ("settling: ..."). Throws
    /// std::logic_error while busy().
    void start(std::string what, std::function<void()> work);
    /// If the work has ended: joins it, rethrows what it threw, and returns true. False
    /// while it runs, or when nothing was started.
    bool finish();
    /// Waits for the work to end, then finish()es it.
    void wait();

    const std::string& what() const { return what_; }
    /// Seconds since start().
    double seconds() const;

  private:
    /// Joins the worker, then rethrows what the work threw (finish() and wait()).
    void joinAndRethrow();

    std::thread worker_;
    std::atomic<bool> done_{false};
    std::exception_ptr error_;
    std::string what_;
    std::chrono::steady_clock::time_point started_{};
};

}  // namespace relight::viewer
