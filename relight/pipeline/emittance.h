// Emittance estimation for the lights whose scene.json radiance is "estimate"
// (docs/scene-format.md, "lights").
//
// Two ways, tried in this order for each such light:
//
// 1. From the photo's view of the light ("photo"). The spec defines a light's radiance as
//    "the value a pixel reads where it sees the emitting face, so a photo can calibrate
//    it". Where the first photo sees the light's emitting face on at least
//    EmittanceOptions::minPixels clean pixels, the radiance is their per-channel median.
//    Clean: every item-buffer sample of the pixel lies on one of the light's emitting
//    polygons, the value is finite, and it is not clipped (an sRGB photo clips at 1; a
//    linear photo, EXR/HDR/PFM, is taken to be unclipped). Pixels whose four neighbours are
//    clean too ("interior" pixels) are preferred when there are at least minPixels of them.
//    Why the median and the interior: a pixel whose samples all hit the face may still be
//    partly covered by its dark surroundings between the samples (the photo integrates the
//    whole pixel; with k x k samples up to 1/(2k) of it per edge), and a real lamp shows
//    glare at its rim and hot spots; the median of a majority of interior pixels reads the
//    face itself, where a mean would be pulled down (or up) by that minority.
//
// 2. Otherwise, from the power balance of Fournier et al. (1993), Eq. (1)-(2) of Loscos,
//    Drettakis & Robert 2000 ("ambient"). As printed, Eq. (2) reads
//        sum_i E_i A_i = (1 - rho^) B^_A sum_j A_j                           (2)
//    with E_i the exitance of light i (radiosity units: E = pi L for a Lambertian emitter of
//    radiance L), A_i its area, rho^ the user's average reflectance (scene.json
//    "average_reflectance"; kDefaultAverageReflectance with a warning when absent), B^_A
//    the mean radiosity of the surfaces in the photo and sum_j A_j the area of the
//    reflecting surfaces (emitting faces excluded).
//    We use it with a factor 1 / rho^:
//        sum_i E_i A_i = (1 - rho^) / rho^ B^_A sum_j A_j.                    (2')
//    Why: (2) comes from the ambient term of progressive radiosity (Cohen et al. 1988, the
//    paper's [CCWG88]), Ambient = sum E A / ((1 - rho^) sum A). That term is the light
//    *arriving* at an average surface; a surface shows rho_i Ambient, so the mean radiosity
//    a photo shows is B^_A = rho^ Ambient, which is also what Eq. (1) assumes (rho_i =
//    rho^ B^_i / B^_A: one common irradiance B^_A / rho^). (2') is then also the exact power
//    balance of a closed room whose surfaces all have reflectance rho^ (emitted = absorbed =
//    sum (1 - rho^) H_j A_j, B_j = rho^ H_j). On data/room (closed, rho^ = 0.6, red emitted
//    power 4.19 in photo units x m^2) the printed (2) gives 2.67, (2') gives 4.45.
//    Units: the photo reads radiance L = B / pi on a Lambertian surface, and a light's
//    radiance in scene.json is in the same photo units with E = pi L_e, so the factor pi
//    cancels and in photo units
//        sum_i L_e,i A_i = (1 - rho^) / rho^ L^_A sum_j A_j,
//    with L^_A the area-weighted mean photo value over the reflecting surfaces the photo
//    sees (each polygon's mean over its clean pixels, relight/pipeline/leaf_texture.h's
//    usablePixels, weighted by the polygon's area; the paper takes the plain image mean,
//    which over-weights what is near the camera); surfaces the photo does not see are
//    assumed to have that mean. The power of the lights whose radiance is known (given in
//    scene.json and on in the photo, or estimated by way 1) is subtracted; the rest is
//    split over the remaining lights with one common radiance (the paper's simplification:
//    "we consider that all the sources have the same intensity"),
//        L_e = (balance power - known power) / sum of their areas,   per channel,
//    clamped to >= 0 with a warning where the known lights already exceed the balance.
//    This is a rough estimate: it assumes a closed room, one grey rho^ (the colour of the
//    surfaces ends up in the light's colour) and one common irradiance; an open scene
//    (light escaping) gives too little. With lights of known power the rest is a small
//    difference of large numbers: on data/room, with A, C and D read from the photo, B
//    (outside the frame) gets (15.0, 3.0, 0) for a true (12, 11.5, 10.2); all four from
//    (2') get (12.4, 9.0, 6.0) for a mean of (11.6, 11.1, 10.4). Way 1 reads the photo's
//    own value where it applies.
//
// A light that says "estimate" but is off in the first photo (not in lights_on) leaves no
// trace in it: an InputError names scene.json and the key lights[i].radiance (so does a
// scene without photos).
#pragma once

#include <string>
#include <vector>

#include "radiosity/rgb.h"
#include "radiosity/scene.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/item_buffer.h"

namespace relight {

/// rho^ when scene.json has no "average_reflectance" (the same grey loadScene gives
/// surfaces without a reflectance).
inline constexpr double kDefaultAverageReflectance = 0.5;

struct EmittanceOptions {
    /// Clean pixels on a light's emitting face needed to read its radiance from the photo:
    /// fewer are too easily all rim pixels (a 2 x 2 patch is all rim), and the median of
    /// fewer than 4 values is no longer robust to one outlier.
    int minPixels = 4;
};

struct LightEmittance {
    enum class Method {
        given,    ///< scene.json gives the radiance: nothing estimated
        photo,    ///< median of the photo's pixels on the emitting face (way 1)
        ambient,  ///< Eq. (2'), the power balance (way 2)
    };
    std::string name;
    Method method = Method::given;
    radiosity::Rgb radiance;  ///< photo units; the photo's state for `given` (0 when off)
    int pixels = 0;           ///< clean pixels on the emitting face (photo: those used)
};

/// What estimateEmittance() did, per light and for Eq. (2').
struct EmittanceReport {
    std::vector<LightEmittance> lights;  ///< one per scene light, scene order
    // Eq. (2'), filled when a light used it:
    bool ambientUsed = false;
    double averageReflectance = 0;       ///< rho^ used
    radiosity::Rgb meanSurfaceRadiance;  ///< L^_A, photo units
    double reflectingArea = 0;           ///< sum_j A_j, m^2
    double seenArea = 0;                 ///< area of the polygons L^_A was taken over, m^2
    radiosity::Rgb knownPower;           ///< sum L A of the known lights (photo units x m^2)
    std::vector<std::string> warnings;   ///< defaulted rho^, negative power clamped, ...

    bool anyEstimated() const;
    /// One line per estimated light, e.g. `light "A": 13.0 11.2 9.0 from 96 photo pixels`.
    std::vector<std::string> summary() const;
};

/// Throws InputError (naming scene.json and lights[i].radiance) for a light that says
/// "estimate" but is off in the first photo, or when the scene has no photo.
void checkEstimableLights(const SceneFile& sf);

/// L_e of Eq. (2') in photo units, per channel:
///     ((1 - rho) / rho L_A areaReflecting - knownPower) / areaEstimated,
/// rho in (0, 1). A channel that comes out negative is set to 0 and flagged in `negative`.
radiosity::Rgb ambientRadiance(const radiosity::Rgb& meanSurfaceRadiance, double rho,
                               double areaReflecting, const radiosity::Rgb& knownPower,
                               double areaEstimated, bool* negative = nullptr);

/// Estimates every "estimate" light of `sf` from `photo` (the first photo, linear) and
/// `items`, the item buffer of `scene` (sf.scene, or the solver's copy of it: same polygon
/// indices). Lights given in scene.json are reported as `given` with their photo state.
/// Throws InputError as checkEstimableLights(), and when Eq. (2') is needed but the photo
/// shows no reflecting surface on a clean pixel or average_reflectance is 0 (black
/// surfaces show nothing of the lights' power).
EmittanceReport estimateEmittance(const SceneFile& sf, const radiosity::Scene& scene,
                                  const ItemBuffer& items, const Image& photo,
                                  const EmittanceOptions& options = {});

// ---- The two ways on their own -----------------------------------------------------------

/// Per pixel of an item buffer, the light whose emitting face covers all the pixel's samples
/// (-1: none, or a pixel partly on something else).
struct LightFaceMap {
    int width = 0, height = 0;
    std::vector<int> light;  ///< row-major
    int at(int x, int y) const { return light[static_cast<size_t>(y) * width + x]; }
};
LightFaceMap lightFaceMap(const ItemBuffer& items, const radiosity::Scene& scene);

/// Way 1 for light `light`: the per-channel median of its clean face pixels in `photo`
/// (finite, and below the clip of an sRGB photo when `srgb`), of the interior ones (all four
/// neighbours clean too) when there are at least `minPixels` of them.
struct FaceReading {
    radiosity::Rgb radiance;  ///< the median, photo units (when used > 0)
    int covered = 0;          ///< pixels on the face
    int clean = 0;            ///< of those, clean
    int used = 0;             ///< pixels the median is taken over; 0: fewer than minPixels
};
FaceReading readLightFromPhoto(const LightFaceMap& faces, const Image& photo, bool srgb, int light,
                               int minPixels);

/// Way 2's reading of the photo: L^_A, the area-weighted mean over the reflecting polygons
/// the photo sees of each one's mean over its clean pixels (usablePixels), and the areas.
struct SurfaceRadiance {
    radiosity::Rgb mean;        ///< L^_A, photo units (0 when the photo sees none)
    double reflectingArea = 0;  ///< sum_j A_j over the reflecting polygons, m^2
    double seenArea = 0;        ///< of which the photo sees, m^2
};
SurfaceRadiance measureSurfaceRadiance(const ItemBuffer& items, const radiosity::Scene& scene,
                                       const Image& photo);

}  // namespace relight
