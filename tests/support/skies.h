// Skies shared by the tests and bench/ (header only): one definition of each, so that a
// bench's figures and a test's assertions are about the same sky.
#pragma once

#include "radiosity/sh9.h"

namespace radiosity::test {

/// A clear sky, z up: bright overhead and towards +x (the format's tools' example), in the
/// format's SH9 basis (radiosity/sh9.h).
inline Sh9Rgb clearSky() {
    Sh9Rgb L;
    L.c = {Rgb{1.00, 1.10, 1.35}, Rgb{0.05, 0.06, 0.08}, Rgb{0.55, 0.60, 0.80},
           Rgb{0.20, 0.18, 0.12}, Rgb{0.02, 0.02, 0.02}, Rgb{0.03, 0.03, 0.04},
           Rgb{0.10, 0.12, 0.18}, Rgb{0.10, 0.09, 0.05}, Rgb{0.04, 0.04, 0.03}};
    return L;
}

}  // namespace radiosity::test
