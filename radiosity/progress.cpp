#include "radiosity/progress.h"

#include <cstdio>
#include <utility>

namespace radiosity {

ProgressMeter::ProgressMeter(ProgressFn report, std::string what, size_t total, double every)
    : report_(std::move(report)),
      what_(std::move(what)),
      total_(total),
      every_(every),
      next_(every) {}

void ProgressMeter::add(size_t count) {
    const size_t done = done_.fetch_add(count, std::memory_order_relaxed) + count;
    if (!report_) return;
    const double now = secondsSince(start_);
    double next = next_.load(std::memory_order_relaxed);
    if (now < next || !next_.compare_exchange_strong(next, now + every_)) return;
    // total_ may be 0 (nothing to do): no division by it.
    const double percent = total_ > 0 ? 100.0 * static_cast<double>(done) / total_ : 100.0;
    char msg[256];
    std::snprintf(msg, sizeof msg, "  %s: %.0f %% (%zu of %zu), %.0f s", what_.c_str(), percent,
                  done, total_, now);
    const std::lock_guard<std::mutex> lock(mutex_);
    report_(msg);
}

}  // namespace radiosity
