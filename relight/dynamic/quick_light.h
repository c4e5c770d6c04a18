// The direct light of a moved sun or point lamp per pixel, quickly: for the frames while the
// user drags it (the viewer's sun tool and sliders; DynamicRelighting::previewEmitter).
//
// The exact per-pixel light (DynamicRelighting::pixelDirect, pipeline/pixel_light.h) is the
// mean over a pixel's camera samples (16 at 320 x 240) of the light's unit irradiance, each
// from the light's own sampling with maxRays shadow rays (a sun's disc: 16 directions):
// 256 rays a pixel, 20 M at 320 x 240, about a second on 2 cores (bench/RESULTS.md,
// 2026-11-27 seventh session). Here one sample per pixel (the middle one of its strata, else
// the first that sees a reflecting surface) and one ray: the same quantity
// (radiosity::Emitter::unitIrradiance, whatever the light's type), 256 times fewer rays.
// Inside a lit or shadowed region it is the exact value up to the normal's and the disc's
// spread over the pixel; at a shadow's edge it is 0 or 1 where the exact value is a
// fraction (a hard, pixel-sized edge).
//
// The same for an object moved (DynamicRelighting::previewLastObject, a box dragged): the
// share of every light that the object lets through at one camera sample per pixel
// (quickTransmission), traced against the object alone in its own Embree scene, at the
// pixels whose shadow rays can meet it (a cone test against its bounding sphere) only.
#pragma once

#include <span>
#include <vector>

#include "radiosity/emitter.h"
#include "radiosity/scene.h"
#include "radiosity/visibility.h"
#include "relight/pipeline/camera.h"
#include "relight/pipeline/item_buffer.h"

namespace relight {

/// Per pixel and component of `light`, [pixel * components + c], its unit irradiance
/// (pi G per unit strength, as DynamicRelighting::pixelDirect stores it) at one camera
/// sample of the pixel, from one shadow ray of `vis` (virtual parts included); 0 where no
/// sample sees a reflecting surface (nothing, a lamp's face).
std::vector<float> quickPixelLight(const ItemBuffer& items, const radiosity::Scene& scene,
                                   const radiosity::Visibility& vis,
                                   const radiosity::Emitter& light);

/// Per pixel, the receiver quickPixelLight() lights: the point and the front normal of the
/// camera sample it takes, [pixel * 6 + 0..2] and [pixel * 6 + 3..5] (metres; unit), the
/// normal 0 where no sample sees a reflecting surface (its light is 0 there). What a
/// display that measures the light itself (the viewer's GPU frames) reads.
std::vector<float> quickReceivers(const ItemBuffer& items, const radiosity::Scene& scene);

/// Where the ray x = o + t d (t > 0) meets the planar convex face `corners` (3 or 4,
/// counter-clockwise seen from its front): t, or +infinity where it passes beside it, or
/// parallel to it. `front` gets whether the ray meets its front. For a lamp's face shown
/// where it is moved (the quick frames' overlay; the viewer's GPU frames do the same).
double rayFace(const radiosity::Vec3& o, const radiosity::Vec3& d,
               std::span<const radiosity::Vec3> corners, bool* front = nullptr);

/// How much of pixel (x, y) a lamp's face shown moved covers: the shares of its k x k camera
/// samples (OverlaySamples' grid) whose rays meet the face `corners` nearer than `shows`
/// metres (the distance to what the pixel's centre shows), and of those that meet its front.
/// The viewer's GPU frames draw the face this way (viewer/gpu_moved_light.h).
struct FaceCover {
    double all = 0, front = 0;
};
FaceCover faceCoverage(const Camera& camera, int k, int x, int y, double shows,
                       std::span<const radiosity::Vec3> corners);

/// A sphere that bounds a moved object (its polygons' corners), to tell the points whose
/// light it may block.
struct BoundingSphere {
    radiosity::Vec3 centre{0, 0, 0};
    double radius = 0;
};
BoundingSphere boundingSphere(std::span<const radiosity::Polygon> polygons);

/// G_l at `at` for every light l of `scene` (DirectLight::geometry's quantity: pi G is the
/// light's unit irradiance; a quad light's faces by Lambert's contour integral times the
/// share of `rays` stratified shadow rays that arrive, a sun, point lamp or sky through its
/// own sampling, radiosity::Emitter::unitIrradiance), its shadows traced in `vis`, never
/// the links' verdicts (they hold for the solver's geometry, not for an object moved
/// outside it). `sameScene`: `vis` holds `scene`'s polygons (the receiver's and the lamps'
/// faces are then ignored as blockers); false for an occluder's own scene (quickTransmission's).
/// `unoccluded` (optional): the same without blockers. `near` (optional): a quad's face
/// whose rays from `at` cannot meet that sphere is taken as unblocked without a ray.
void quickPointGeometry(const radiosity::Scene& scene, const radiosity::Visibility& vis,
                        bool sameScene, const radiosity::ReceiverPoint& at, int rays, uint64_t seed,
                        double* G, double* unoccluded = nullptr,
                        const BoundingSphere* near = nullptr);

/// Per pixel and light of `scene`, [pixel * lights + l]: the share of light l's unit
/// irradiance at one camera sample of the pixel (quickPixelLight's) that the polygons of
/// `occluder` (their own scene: a moved object) let through, from quickPointGeometry with
/// `rays` rays; 1 where they block nothing, where no ray can meet `near`, or where the
/// light sends nothing there.
std::vector<float> quickTransmission(const ItemBuffer& items, const radiosity::Scene& scene,
                                     const radiosity::Visibility& occluder,
                                     const BoundingSphere& near, int rays);

}  // namespace relight
