// The specular pass of the ratio-map relighting (../shared/seeds/000, §6 and Fig. 5): the
// relit image is the photo modulated by the diffuse ratio, "and subsequently" a specular
// radiance is added on top. relight adds it to the virtual objects that an edit gives a
// "specular" key (docs/scene-format.md, an engine extension of the edit format).
//
// The lobe is Blinn-Phong, normalised so that ks is the share of the light reflected at the
// lobe's peak direction for any shininess s (the "modified Blinn-Phong" of real-time
// rendering: Akenine-Moller, Haines & Hoffman, Real-Time Rendering 4th ed., Eq. (9.52)):
//   f_s(w) = ks (s + 8) / (8 pi) (n.h)^s,   h = (w + v) / |w + v|
// for the direction w towards the light and v towards the eye, and the radiance the surface
// sends to the eye is
//   L_s = sum_lights integral f_s(w) dE(w) V(w),   (n.w > 0)
// with dE the light's irradiance arriving from w (cos included) and V its visibility: for a
// point lamp of intensity I at distance d, L_s = f_s(w) I cos / d^2, one shadow ray, as its
// direct light. Each light answers through its one model (radiosity/emitter.h, unitGlossy):
// a quad lamp by points of its faces, a sun by its disc, a sky by its hemisphere.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "radiosity/emitter.h"
#include "radiosity/rgb.h"
#include "radiosity/scene.h"
#include "radiosity/visibility.h"
#include "relight/io/edit_file.h"

namespace relight {

using radiosity::Rgb;

/// f_s(w) / ks: (s + 8) / (8 pi) (n.h)^s for w and toEye on the front of n, else 0.
double blinnPhongLobe(const radiosity::Vec3& n, const radiosity::Vec3& toEye, double shininess,
                      const radiosity::Vec3& w);

/// The lights of a solver scene, each through its one model: a light of faces as a quad
/// lamp (radiosity::makeQuadLamp over its polygons), a sun, point lamp or sky as its emitter
/// (its components' strengths). Made once per frame; read from many threads.
class SpecularLights {
  public:
    /// `strength`: one per scene light (a component's strength for an emitter's), as the
    /// edit stands (DynamicRelighting::radiance()).
    SpecularLights(const radiosity::Scene& scene, std::span<const Rgb> strength);

    /// L_s at point p (on polygon p.polygon, front normal p.n) towards the unit direction
    /// `toEye`: about `rays` samples per light with extent, from a generator seeded by
    /// `seed` (the same seed, the same answer).
    Rgb radiance(const Specular& s, const radiosity::Visibility& vis,
                 const radiosity::ReceiverPoint& p, const radiosity::Vec3& toEye, int rays,
                 uint64_t seed) const;

  private:
    struct Entry {
        std::shared_ptr<const radiosity::Emitter> emitter;
        std::vector<Rgb> strengths;  ///< one per component
    };
    std::vector<Entry> lights_;
};

}  // namespace relight
