// DirectionalIrradiance: the irradiance a cluster gathers, kept by direction so that each
// surface inside the cluster receives it according to its own orientation.
//
// A cluster that receives light through a link stands for surfaces facing every way.
// Handing the same scalar irradiance to all of them (Sillion's isotropic receiver) lights
// surfaces that face away from the source: light leaks round corners and through the backs
// of walls. A single vector irradiance (Arvo 1994) fixes that for sources in front of a
// surface, but sources on opposite sides cancel (a table top would lose the ceiling's
// light to the floor's). So a cluster bins what it gathers by the six directions +-e_a of
// its principal frame (the eigenvectors of its normals' second moment, hierarchy.h):
//     bin(+a) += H max(0, w_a),   bin(-a) += H max(0, -w_a)      (w in that frame)
// for irradiance H arriving from unit direction w. A surface of unit normal n takes
//     sum_a  |n_a| bin(sign(n_a) a)  =  sum_links H sum_a [n_a w_a > 0] n_a w_a.
// That is exact, H max(0, n.w), whenever n is along a principal axis (a face cluster's
// surfaces, a box's faces), zero for a source behind the surface, and never more than H
// (Cauchy-Schwarz), the irradiance of a surface facing the source squarely. Where the sum
// over a leaf's links could still exceed what it can physically gather, the solver's
// energy bound (solver.h) scales it.
#pragma once

#include <array>
#include <cmath>

#include "radiosity/rgb.h"
#include "radiosity/vec.h"

namespace radiosity {

struct DirectionalIrradiance {
    /// bin[2a] gathers along +e_a, bin[2a + 1] along -e_a (radiosity units).
    std::array<Rgb, 6> bin{};

    /// Adds irradiance H (perpendicular to the direction of arrival) from unit direction w,
    /// given in the cluster's frame.
    void add(const Rgb& H, const Vec3& w) {
        for (int a = 0; a < 3; ++a) {
            if (w[a] > 0)
                bin[2 * a] += H * w[a];
            else if (w[a] < 0)
                bin[2 * a + 1] += H * (-w[a]);
        }
    }
    DirectionalIrradiance& operator+=(const DirectionalIrradiance& o) {
        for (int i = 0; i < 6; ++i) bin[i] += o.bin[i];
        return *this;
    }
    /// Irradiance on a surface of unit normal n, given in the cluster's frame.
    Rgb onto(const Vec3& n) const {
        Rgb H;
        for (int a = 0; a < 3; ++a) {
            if (n[a] > 0)
                H += bin[2 * a] * n[a];
            else if (n[a] < 0)
                H += bin[2 * a + 1] * (-n[a]);
        }
        return H;
    }
    bool isZero() const {
        for (const Rgb& b : bin)
            if (!(b == Rgb{})) return false;
        return true;
    }
};

}  // namespace radiosity
