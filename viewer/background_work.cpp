#include "viewer/background_work.h"

#include <stdexcept>
#include <utility>

namespace relight::viewer {

BackgroundWork::~BackgroundWork() {
    if (worker_.joinable()) worker_.join();
}

void BackgroundWork::start(std::string what, std::function<void()> work) {
    if (busy()) throw std::logic_error("BackgroundWork::start while \"" + what_ + "\" runs");
    what_ = std::move(what);
    error_ = nullptr;
    done_.store(false, std::memory_order_relaxed);
    started_ = std::chrono::steady_clock::now();
    worker_ = std::thread([this, work = std::move(work)] {
        try {
            work();
        } catch (...) {
            error_ = std::current_exception();  // read by finish() after the join
        }
        done_.store(true, std::memory_order_release);
    });
}

bool BackgroundWork::finish() {
    if (!worker_.joinable() || !done_.load(std::memory_order_acquire)) return false;
    joinAndRethrow();
    return true;
}

void BackgroundWork::wait() {
    if (worker_.joinable()) joinAndRethrow();
}

void BackgroundWork::joinAndRethrow() {
    worker_.join();
    // Cleared first: the error is rethrown once, and a later start() begins without it.
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

double BackgroundWork::seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

}  // namespace relight::viewer
