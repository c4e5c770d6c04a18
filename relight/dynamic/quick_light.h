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
#pragma once

#include <vector>

#include "radiosity/emitter.h"
#include "radiosity/scene.h"
#include "radiosity/visibility.h"
#include "relight/pipeline/item_buffer.h"

namespace relight {

/// Per pixel and component of `light`, [pixel * components + c], its unit irradiance
/// (pi G per unit strength, as DynamicRelighting::pixelDirect stores it) at one camera
/// sample of the pixel, from one shadow ray of `vis` (virtual parts included); 0 where no
/// sample sees a reflecting surface (nothing, a lamp's face).
std::vector<float> quickPixelLight(const ItemBuffer& items, const radiosity::Scene& scene,
                                   const radiosity::Visibility& vis,
                                   const radiosity::Emitter& light);

}  // namespace relight
