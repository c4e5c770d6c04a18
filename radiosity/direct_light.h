// DirectLight: the light that reaches a point straight from each light source, evaluated
// per point rather than per element (Loscos et al. 1999, §5: "per-pixel direct light").
//
// For a point x on polygon p (front normal n) and a light l with emitting polygons q,
//     G_l(x) = sum_q F(x -> q) V(x, q)
// where F is the exact point-to-polygon form factor (Lambert's contour integral,
// form_factor.h) and V in [0, 1] the fraction of stratified shadow rays from x to q that
// arrive. The direct irradiance is then H_direct(x) = sum_l E_l G_l(x), E_l = pi L_l: G is
// geometry only, so a change of a light's colour or strength rescales it without a ray.
//
// The hierarchy's links decide where rays are needed (the radiosity solution's own
// visibility work, reused): when every link from q's elements to the element holding x
// (or its ancestors) was decided VISIBLE by an empty shaft, no ray is cast. Elsewhere
// `minRays` rays are cast; when they disagree (penumbra) up to `maxRays` in all.
//
// A light that is not faces (sun, point lamp, sky: Light::emitter, radiosity/emitter.h)
// gives G = H_unit / pi, its unit-strength irradiance with shadows from maxRays rays of its
// own (the emitter's sampling: the sun's disc, the sky's hemisphere), so that H = pi L G
// holds for every light.
//
// The links' verdict for a leaf and a light polygon is read once per leaf and kept (a leaf
// holds many points: the pixels' samples, its vertices), so a DirectLight must not outlive a
// change of the solver's links; each batch of points makes its own.
//
// Units: G is dimensionless (a form factor); x in metres. Deterministic: the rays of a
// point come from a generator seeded by the caller, so results do not depend on the
// order of evaluation or the thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "radiosity/defaults.h"
#include "radiosity/emitter.h"
#include "radiosity/solver.h"

namespace radiosity {

struct DirectLightOptions {
    int minRays = kDefaultMinRays;  ///< shadow rays per light polygon at first, 1..256
    int maxRays = kDefaultMaxRays;  ///< in penumbra, >= minRays, <= 256
};

class DirectLight {
  public:
    explicit DirectLight(const HierarchicalSolver& solver, DirectLightOptions options = {});

    /// G_l(x) for every light l of the scene (G.size() == scene.lights.size()), lights that
    /// are off included. `seed` selects the shadow rays. When `unoccluded` is given it gets
    /// sum_q F(x -> q) without visibility (the light a point would get with no blocker:
    /// Loscos et al. 2000, Eq. (8) per point).
    /// With firstLight > 0 only lights firstLight.. are evaluated (G of the others is left
    /// as it is): the virtual lights added after the scene's.
    void geometry(int polygon, const Vec3& x, uint64_t seed, double* G,
                  double* unoccluded = nullptr, int firstLight = 0) const;

    /// The direct irradiance at x, sum_l E_l G_l(x) over every light (radiosity units).
    Rgb irradiance(int polygon, const Vec3& x, uint64_t seed) const;

    int lightCount() const { return static_cast<int>(solver_.scene().lights.size()); }
    uint64_t raysCast() const { return rays_; }

  private:
    /// True when every link from an element of light polygon q to the chain of nodes above
    /// `leaf` was decided by an empty shaft (and there is at least one). Kept per leaf and
    /// light polygon (shaftMemo_) after the first call.
    bool shaftClear(int leaf, int q) const;
    bool shaftClearByLinks(int leaf, int q) const;
    /// G of the components of the emitter light l starts (radiosity/emitter.h) at x, from
    /// maxRays rays; returns how many lights it filled.
    size_t emitterGeometry(size_t l, int polygon, const Vec3& x, uint64_t base, double* G,
                           double* unoccluded) const;
    const HierarchicalSolver& solver_;
    DirectLightOptions options_;
    mutable std::atomic<uint64_t> rays_{0};
    // Per polygon: its index among the light polygons, or -1; per node and light polygon:
    // 0 not yet known, 1 clear, 2 not (empty above kMaxShaftMemo entries: no memo).
    std::vector<int> lightSlot_;
    int lightPolygons_ = 0;
    std::unique_ptr<std::atomic<uint8_t>[]> shaftMemo_;
};

}  // namespace radiosity
