// Emitter: the one model of a light source (as Mitsuba's Emitter): what every layer asks of
// a light, whatever its type. The format's four types (docs/scene-format.md, "lights"):
//   quad         emitting polygons of one radiance L (the scene's emitting faces);
//   sun          parallel light from a disc at infinity: direction towards it, angular
//                diameter, irradiance at normal incidence;
//   point        an isotropic point lamp: position, intensity I (irradiance I cos / d^2);
//   environment  the sky, L(w) = sum_k sh9[k] Y_k(w) (radiosity/sh9.h), occluded by the scene.
//
// Each answers
//   irradiance(x, n)  the direct irradiance at point x with unit normal n, shadows included
//                     (Embree rays through radiosity/visibility.h), in radiosity units: a
//                     white Lambertian surface there has radiosity B = irradiance (scene.h);
//   unitGlossy(x, n, lobe)  the same irradiance weighed per direction of arrival by a lobe
//                     f(w): integral of f(w) dE(w) V(w), for a reflection that is not
//                     Lambertian (the specular pass: relight/dynamic/specular.h);
//   power()           what it emits (radiosity units x m^2), for the solver's scale and to
//                     tell whether it is on;
//   apply(edit)       the edit's fields (docs/scene-format.md, "Edit"): scale; radiance,
//                     irradiance, intensity or sh9 set; direction (sun), position (point),
//                     rotate (environment). A field the type does not have is refused,
//                     naming the light and the field.
// The type-specific code lives in the implementations (emitter.cpp), never in a switch
// in the layers that use them.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "radiosity/detail/rng.h"
#include "radiosity/rgb.h"
#include "radiosity/sh9.h"
#include "radiosity/vec.h"
#include "radiosity/visibility.h"

namespace radiosity {

/// One light's edit (docs/scene-format.md, "Edit"): each field that is set applies, in the
/// order scale last (a scale multiplies the strength the other fields leave).
struct EmitterEdit {
    std::optional<double> scale;
    std::optional<Rgb> strength;    ///< radiance (quad), irradiance (sun), intensity (point)
    std::optional<Sh9Rgb> sh9;      ///< environment
    std::optional<Vec3> direction;  ///< sun: towards it (any non-zero length)
    std::optional<Vec3> position;   ///< point lamp (metres)
    struct Rotation {
        Vec3 axis;
        double degrees = 0;
    };
    std::optional<Rotation> rotate;  ///< environment
};

/// One field of a light as the format writes it (docs/scene-format.md, "lights" and "Edit"):
/// its key, a path of JSON keys joined by '.' ("rotate.axis"), and its numbers.
struct EmitterField {
    enum class Shape {
        number,  ///< one number ("angle", "scale", "rotate.degrees")
        list,    ///< [x, y, z] or [r, g, b] ("direction", "irradiance")
        rows     ///< rows of 3 ("sh9": 9 rows; "vertices")
    };
    std::string key;
    std::vector<double> values;
    Shape shape = Shape::list;
};

/// Where a light's irradiance is asked for: a point on a surface.
struct ReceiverPoint {
    Vec3 x;            ///< metres
    Vec3 n;            ///< unit front normal
    int polygon = -1;  ///< Scene::polygons index x lies on (never its own blocker), or -1
};

/// The most components a light has (a sky's 9 coefficients).
inline constexpr int kMaxEmitterComponents = 9;

/// A light seen from a point as one point, one direction or one planar face, whose shadows
/// a few shadow maps hold (the viewer's frames of a light being moved,
/// viewer/gpu_moved_light.h). Its unit irradiance at a point x of normal n, unoccluded, is
///   a point at `at`:           max(0, n.v) / |v|^3,  v = at - x   (cos / d^2)
///   a direction `at` (unit):   max(0, n.at)                        (cos)
///   a face of `corners`:       pi F(x -> face)   (Lambert's contour integral, one-sided)
/// as unitUnoccluded() gives it. A face's visibility is estimated as the mean over
/// facePoints(), the centres of its 2 x 2 cells (a penumbra in five steps).
struct ShadowSource {
    enum class Kind { point, direction, face };
    Kind kind = Kind::point;
    /// The point (metres), the unit direction towards the light, or a face's centroid.
    Vec3 at{0, 0, 0};
    /// A face: its 3 or 4 corners, counter-clockwise seen from the side it lights.
    std::vector<Vec3> corners;
    static constexpr int kFacePoints = 4;
    /// A face's points its shadows are cast from: the centres of the 2 x 2 cells of its
    /// parameterisation (the quad lamp's stratified sampling, radiosity::makeQuadLamp).
    std::array<Vec3, kFacePoints> facePoints() const;
};

class Emitter {
  public:
    explicit Emitter(std::string name) : name_(std::move(name)) {}
    virtual ~Emitter() = default;

    const std::string& name() const { return name_; }
    /// "quad", "sun", "point" or "environment": the format's word, for messages and reports.
    virtual const char* type() const = 0;

    /// Direct irradiance at `p`, visibility included, radiosity units, from about `rays`
    /// shadow rays (at least 1) drawn from `rng`.
    virtual Rgb irradiance(const Visibility& vis, const ReceiverPoint& p, int rays,
                           Rng& rng) const = 0;
    /// The same without blockers (the light a point would get with nothing in the way).
    virtual Rgb unoccludedIrradiance(const ReceiverPoint& p) const = 0;

    /// The light as a sum of components of fixed shape, each scaled by an RGB strength,
    /// so that a change of strengths is a weighted sum of what each component gives
    /// (superposition: the solver's per-light responses, the per-pixel light): one for a
    /// quad (its radiance), a sun (its irradiance) and a point lamp (its intensity); nine
    /// for a sky (its coefficients: sh9[k] scales the basis function Y_k).
    virtual int components() const { return 1; }
    /// Each component's strength, components() of them (a sky's may be negative).
    virtual std::vector<Rgb> strengths() const = 0;
    /// Sets them (throws std::invalid_argument on a count or value out of range).
    virtual void setStrengths(std::span<const Rgb> s) = 0;
    /// The irradiance each component gives at unit strength, out[c] for c < components(),
    /// visibility included (rays, rng as irradiance()): irradiance() is sum_c s_c out[c].
    /// A sky's is the point's transfer vector (Sloan, Kautz & Snyder 2002; sky_transfer.h).
    virtual void unitIrradiance(const Visibility& vis, const ReceiverPoint& p, int rays, Rng& rng,
                                double* out) const = 0;
    /// The same without blockers.
    virtual void unitUnoccluded(const ReceiverPoint& p, double* out) const = 0;
    /// The light as one point, direction or face (ShadowSource), for a light of one
    /// component: a point lamp, a sun (its disc's centre; hard shadows, as unitIrradiance()
    /// casts them from one ray), a quad lamp of one face (its soft shadows from a few
    /// points). Empty for the others (a lamp of several faces, a sky).
    virtual std::optional<ShadowSource> shadowSource() const { return std::nullopt; }
    /// A weight per direction of arrival: w is the unit direction from the point towards
    /// the light. A BRDF lobe (the specular pass, relight/dynamic/specular.h).
    using Lobe = std::function<double(const Vec3& w)>;
    /// The irradiance each component gives at unit strength, weighed per direction of
    /// arrival by `lobe`: out[c] = integral of lobe(w) dE_c(w) V(w) over the directions w
    /// that reach the light (cos included, shadows by Embree rays as unitIrradiance). With
    /// lobe = 1 it is unitIrradiance in expectation; with lobe = a BRDF it is the radiance
    /// reflected towards the eye per unit strength. Sampled where the light has extent: a
    /// quad by `rays` points per face, uniform by area (its irradiance form factor is exact,
    /// this is not); a sun's disc and a sky's hemisphere as unitIrradiance draws them.
    virtual void unitGlossy(const Visibility& vis, const ReceiverPoint& p, const Lobe& lobe,
                            int rays, Rng& rng, double* out) const = 0;

    /// Emitted power, radiosity units x m^2. A light at infinity emits without bound; its
    /// power is what crosses the bounding sphere of `sceneBounds` (radius R): the sun
    /// E pi R^2, the sky pi R^2 times the mean irradiance over the sphere's directions.
    virtual Rgb power(const Bounds3& sceneBounds) const = 0;
    /// Whether it gives any light (its strength is not zero).
    virtual bool on() const = 0;

    /// Applies `edit`; throws std::invalid_argument naming the light and the field when
    /// the type lacks it or the value is out of range.
    virtual void apply(const EmitterEdit& edit) = 0;
    virtual std::unique_ptr<Emitter> clone() const = 0;

    /// The format's key of EmitterEdit::strength for this type: "radiance" (quad),
    /// "irradiance" (sun), "intensity" (point); "sh9" for a sky (EmitterEdit::sh9).
    virtual const char* strengthKey() const = 0;
    /// The light as scene.json's "lights" and an edit's "add_lights" say it, after "name"
    /// and "type": what the light reader (relight/io/light_reader.h) reads back to this light.
    virtual std::vector<EmitterField> fields() const = 0;
    /// The edit that takes `original` (this light as it was loaded: the same type) to this
    /// light's state: its strengths always (an absolute state, whatever `original`'s were),
    /// its place (a sun's direction, a lamp's position) only where it differs, since an
    /// edit that moves a light re-solves it as a virtual light (LightEdit::moves). Throws
    /// std::invalid_argument when `original` is another type.
    virtual EmitterEdit editFrom(const Emitter& original) const = 0;

  protected:
    [[noreturn]] void refuse(const char* field) const;

  private:
    std::string name_;
};

/// A sun of `irradiance` (radiosity units: irradiance on a surface facing it) in
/// `direction` (towards the sun, non-zero), a disc of angular diameter `angleDegrees`
/// (0: a point, hard shadows; < 180). Its disc is sampled by stratified directions
/// (soft shadows). Throws std::invalid_argument for a bad direction, angle or irradiance.
std::unique_ptr<Emitter> makeSun(std::string name, const Vec3& direction, double angleDegrees,
                                 const Rgb& irradiance);
/// An isotropic point lamp of `intensity` (irradiance I cos / d^2) at `position`.
std::unique_ptr<Emitter> makePointLamp(std::string name, const Vec3& position,
                                       const Rgb& intensity);
/// A sky of radiance L(w) = sum_k sh9[k] Y_k(w), occluded by the scene: its irradiance is
/// pi times the mean of L V over cosine-distributed directions (stratified).
std::unique_ptr<Emitter> makeEnvironment(std::string name, const Sh9Rgb& sh9);
/// A quad lamp: emitting polygons (corners counter-clockwise seen from the front) of one
/// radiance; its irradiance is pi L sum_q F(x -> q) V_q (exact form factor, Lambert's
/// contour integral; V_q the fraction of rays to points of q that arrive). `polygons`:
/// the Scene::polygons indices of the faces (they do not block their own light), or empty.
std::unique_ptr<Emitter> makeQuadLamp(std::string name, std::vector<std::vector<Vec3>> faces,
                                      std::vector<int> polygons, const Rgb& radiance);

/// `e` as an edit of `light` says it (docs/scene-format.md, "Edit"): "scale", the strength
/// under light.strengthKey(), "sh9", "direction", "position", "rotate.axis" and
/// "rotate.degrees", for the fields that are set, in that order.
std::vector<EmitterField> editFields(const Emitter& light, const EmitterEdit& e);
/// The field `key` of light.fields(), or null when the light has none.
std::optional<EmitterField> findField(const Emitter& light, const std::string& key);

/// The sum of every emitter's irradiance at `p` (one rng per emitter, seeded from `seed`
/// and its index, so that the answer does not depend on the others).
Rgb totalIrradiance(const std::vector<std::unique_ptr<Emitter>>& emitters, const Visibility& vis,
                    const ReceiverPoint& p, int rays, uint64_t seed);

}  // namespace radiosity
