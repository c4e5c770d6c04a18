// Rgb: a linear RGB triple (radiosity, emittance, reflectance or irradiance).
//
// Units are those of the quantity it holds; the solver states them where it stores one.
// Kept a separate type from Vec3 so that a colour is never mixed up with a point.
#pragma once

#include <algorithm>
#include <cmath>

namespace radiosity {

struct Rgb {
    double r = 0, g = 0, b = 0;

    constexpr Rgb() = default;
    constexpr Rgb(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
    static constexpr Rgb gray(double v) { return {v, v, v}; }

    constexpr double operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    constexpr double& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }

    constexpr Rgb& operator+=(const Rgb& o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    constexpr Rgb& operator-=(const Rgb& o) {
        r -= o.r;
        g -= o.g;
        b -= o.b;
        return *this;
    }
    constexpr Rgb& operator*=(double s) {
        r *= s;
        g *= s;
        b *= s;
        return *this;
    }
    friend constexpr Rgb operator+(Rgb a, const Rgb& o) { return a += o; }
    friend constexpr Rgb operator-(Rgb a, const Rgb& o) { return a -= o; }
    friend constexpr Rgb operator*(Rgb a, double s) { return a *= s; }
    friend constexpr Rgb operator*(double s, Rgb a) { return a *= s; }
    /// Component-wise product (reflectance times irradiance).
    friend constexpr Rgb operator*(const Rgb& a, const Rgb& o) {
        return {a.r * o.r, a.g * o.g, a.b * o.b};
    }
    friend constexpr bool operator==(const Rgb&, const Rgb&) = default;

    constexpr double maxComponent() const { return std::max(r, std::max(g, b)); }
    constexpr double minComponent() const { return std::min(r, std::min(g, b)); }
    constexpr double average() const { return (r + g + b) / 3.0; }
    /// Rec. 709 luminance of linear RGB.
    constexpr double luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
    bool isFinite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

}  // namespace radiosity
