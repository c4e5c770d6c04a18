// Sh9: order-2 real spherical harmonics (9 coefficients), for light arriving from infinitely
// far away: the `environment` light of docs/scene-format.md (the sky), its irradiance, its
// rotation (the edit's `rotate`) and its projection.
//
// The basis is Ramamoorthi & Hanrahan 2001's (no Condon-Shortley phase), in the format's
// order, for a unit direction w = (x, y, z) pointing from the scene to the sky:
//   k  0    1      2      3      4       5       6             7       8
//      Y00  Y1-1   Y10    Y11    Y2-2    Y2-1    Y20           Y21     Y22
//      c0   c1 y   c1 z   c1 x   c2 xy   c2 yz   c20(3z^2-1)   c2 xz   c22(x^2-y^2)
// with c0 = 1/(2 sqrt(pi)), c1 = sqrt(3/(4 pi)), c2 = sqrt(15/pi)/2, c20 = sqrt(5/pi)/4,
// c22 = sqrt(15/pi)/4: the format prints them to 6 digits (0.282095, 0.488603, 1.092548,
// 0.315392, 0.546274); the exact values keep the basis orthonormal to rounding, 5e-7
// relative from the printed ones.
//
// API
//   sh9Basis(w)                    Y_k(w), the 9 basis functions at a unit direction
//   sh9Eval(L, w)                  L(w) = sum_k L_k Y_k(w), RGB
//   sh9CosineTransfer(n)           A_l Y_k(n): the unoccluded transfer vector of a normal
//   sh9Irradiance(L, n)            E(n) = sum_k A_l L_k Y_k(n)  (R&H 2001, Eq. 7)
//   sh9IrradianceMatrix(L)         the 4x4 matrix M of R&H 2001, Eq. 12: E(n) = n^T M n
//   sh9Project(f, n)               L_k = integral of f(w) Y_k(w) dw (R&H 2001, Eq. 10)
//   rotationAboutAxis(axis, deg)   the 3x3 rotation of the edit's `rotate`
//   sh9Rotation(R), sh9Rotate(...) the coefficients of L'(w) = L(R^T w), band by band
#pragma once

#include <array>
#include <functional>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "radiosity/rgb.h"
#include "radiosity/vec.h"

namespace radiosity {

inline constexpr int kSh9Count = 9;

/// Nine numbers in the format's order (L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22):
/// the basis at a direction, a transfer vector, or one channel of a sky.
using Sh9 = std::array<double, kSh9Count>;

/// An RGB function on the sphere (the format's `sh9`): L(w) = sum_k c[k] Y_k(w).
struct Sh9Rgb {
    std::array<Rgb, kSh9Count> c{};

    /// One channel (0 r, 1 g, 2 b) as nine numbers.
    Sh9 channel(int ch) const;
    void setChannel(int ch, const Sh9& v);
};

/// The band l (0, 1 or 2) of coefficient k.
constexpr int sh9Band(int k) {
    return k == 0 ? 0 : (k < 4 ? 1 : 2);
}

/// A_l: the clamped cosine max(0, n.w) convolved with band l (R&H 2001, Eqs. 8-9):
/// A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4.
double sh9CosineLobe(int band);

/// Y_k(w) for a unit direction w. The polynomials are evaluated as written: a direction
/// that is not unit gives the polynomials' values there, not those of w / |w|.
Sh9 sh9Basis(const Vec3& w);

/// sum_k a_k b_k.
double sh9Dot(const Sh9& a, const Sh9& b);
/// sum_k t_k L_k, per channel: a transfer vector applied to a sky (Sloan et al. 2002).
Rgb sh9Dot(const Sh9& t, const Sh9Rgb& L);

/// L(w) = sum_k L_k Y_k(w): the radiance arriving from direction w (unit).
Rgb sh9Eval(const Sh9Rgb& L, const Vec3& w);

/// A_l Y_k(n): the coefficients of the clamped cosine max(0, n.w) about a unit normal n,
/// i.e. the transfer vector of a point that nothing occludes (R&H 2001, Eq. 7).
Sh9 sh9CosineTransfer(const Vec3& n);

/// E(n) = sum_k A_l L_k Y_k(n) = integral of L(w) max(0, n.w) dw, exact for a sky of
/// order 2 (R&H 2001, Eq. 7; Wen et al. 2003, Eq. 15). n unit.
Rgb sh9Irradiance(const Sh9Rgb& L, const Vec3& n);

/// R&H 2001, Eq. 12: the symmetric 4x4 matrix M of one channel L, with which
/// E(n) = (n, 1)^T M (n, 1) (Eq. 11). glm's matrices are column-major: M[col][row].
glm::dmat4 sh9IrradianceMatrix(const Sh9& L);
/// (n, 1)^T M (n, 1), R&H 2001, Eq. 11.
double sh9IrradianceQuadratic(const glm::dmat4& M, const Vec3& n);

/// L_k = integral over the sphere of f(w) Y_k(w) dw (R&H 2001, Eq. 10), by a product rule:
/// Gauss-Legendre in z = cos(theta) with `zNodes` nodes times 2 zNodes equal steps in phi.
/// Exact (to rounding) for any f that is a polynomial of degree <= 2 zNodes - 3 in
/// (x, y, z), a band-limited sky among them from zNodes = 3 on. Throws
/// std::invalid_argument for zNodes < 1.
Sh9 sh9Project(const std::function<double(const Vec3&)>& f, int zNodes);
Sh9Rgb sh9ProjectRgb(const std::function<Rgb(const Vec3&)>& f, int zNodes);

/// The rotation by `degrees` about `axis` (right-hand rule; Rodrigues' formula), as the
/// edit's `"rotate": {"axis", "degrees"}`. The axis need not be unit length. Throws
/// std::invalid_argument when the axis is not finite or shorter than 1e-12 (it has no
/// direction), or the angle is not finite.
glm::dmat3 rotationAboutAxis(const Vec3& axis, double degrees);

/// The matrices that turn each band's coefficients for a rotation R (orthonormal,
/// det +1): the coefficients of L'(w) = L(R^T w) are band1 * (L1-1, L10, L11) and
/// band2 * (L2-2 ... L22); band 0 does not change. m[i][j]: row i, column j.
struct Sh9Rotation {
    std::array<std::array<double, 3>, 3> band1{};
    std::array<std::array<double, 5>, 5> band2{};
};

/// The band matrices of R, in closed form (see sh9.cpp). R is not checked: a matrix that
/// is not a rotation gives the coefficients of L(R^T w) only where R^T keeps unit vectors
/// unit.
Sh9Rotation sh9Rotation(const glm::dmat3& R);

Sh9 sh9Rotate(const Sh9Rotation& rot, const Sh9& L);
Sh9Rgb sh9Rotate(const Sh9Rotation& rot, const Sh9Rgb& L);

/// The edit `"rotate": {"axis": axis, "degrees": degrees}` of an environment:
/// L'(w) = L(R^T w) with R = rotationAboutAxis(axis, degrees). Throws as that does.
Sh9Rgb sh9RotateAboutAxis(const Sh9Rgb& L, const Vec3& axis, double degrees);

}  // namespace radiosity
