// SeenInterval: what a leaf's rays allow a measured fraction of its hemisphere to be
// (solver.h, "Energy bound"). A leaf's `seen` is measured by 64-256 rays with a standard
// error of 2-3 %; a value within 2 standard errors of the measurement's target cannot be
// told from the truth and is kept, one outside it is moved to the nearer end. Used by the
// row bound (rowScale, groupRowScales) and by the balance's column pass.
#pragma once

#include <algorithm>

namespace radiosity {

struct SeenInterval {
    double lo, hi;
    /// target +- 2 standard errors, within [0, cap] (hi >= lo also when cap < lo).
    SeenInterval(double target, double standardError, double cap)
        : lo(std::max(0.0, target - 2 * standardError)),
          hi(std::max(lo, std::min(cap, target + 2 * standardError))) {}
    double clamp(double v) const { return std::clamp(v, lo, hi); }
    bool holds(double v) const { return v >= lo && v <= hi; }
};

}  // namespace radiosity
