// CLI11 validators shared by `relight` and `relight-viewer`.
//
// CLI11's PositiveNumber and Range let NaN through (every comparison with NaN is false):
// --epsilon nan refined nothing, silently. And an unsigned option takes "-5" and wraps it
// to 2^64 - 5 (--max-links -5 was no limit at all). These check the text itself.
#pragma once

#include <CLI/CLI.hpp>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>

namespace relight::cli {

enum class Sign { kAny, kNonNegative, kPositive };

/// A finite number, and at least 0 (kNonNegative) or above 0 (kPositive).
inline CLI::Validator finiteNumber(Sign sign) {
    const char* what = sign == Sign::kPositive      ? "a finite number > 0"
                       : sign == Sign::kNonNegative ? "a finite number >= 0"
                                                    : "a finite number";
    return CLI::Validator(
        [sign, what](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            const bool ok = end != text.c_str() && *end == '\0' && std::isfinite(v) &&
                            (sign == Sign::kAny || (sign == Sign::kPositive ? v > 0 : v >= 0));
            return ok ? std::string() : std::string("must be ") + what + ", got " + text;
        },
        "FINITE");
}

/// A whole number >= 0 written in decimal digits (a count: links, rays).
inline CLI::Validator wholeNumber() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            bool ok = !text.empty() && text.size() <= 18;  // below 2^63: no overflow
            for (const char c : text) ok = ok && std::isdigit(static_cast<unsigned char>(c));
            return ok ? std::string() : "must be a whole number >= 0, got " + text;
        },
        "UINT");
}

}  // namespace relight::cli
