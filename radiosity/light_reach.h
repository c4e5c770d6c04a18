// Light reach: how much of a light's emission meets the front of a reflecting surface.
//
// A lamp placed below the floor, facing away from the room or shut inside an object emits
// into nothing or into the backs of the geometry. The solver takes such a light as given:
// its power is absorbed or lost and the solution is darker, silently. Casting a few rays
// from its emitting faces over their front hemispheres tells it apart from a lamp that
// lights the room, cheaply (256 rays per light, against the solver's millions).
#pragma once

#include "radiosity/scene.h"
#include "radiosity/visibility.h"

namespace radiosity {

struct LightReach {
    int rays = 0;  ///< cast from the light's faces, cosine-distributed over their fronts
    int hits = 0;  ///< of them, those whose first hit is the front of a reflecting polygon
    /// The share of the light's emission that meets the front of a reflecting polygon:
    /// per face hits / rays, weighted by the faces' areas (a Lambertian face emits in
    /// proportion to its area, along the cosine).
    double fraction = 0;
};

/// The reach of scene.lights[light], from about `rays` rays (at least 16 per face),
/// stratified over each face and its hemisphere and seeded by the light's index (the same
/// answer every run). Its own faces and the other emitting faces, which reflect nothing,
/// do not count as hits. Throws std::out_of_range for a light index the scene lacks.
LightReach lightReach(const Scene& scene, const Visibility& vis, int light, int rays = 256);

}  // namespace radiosity
