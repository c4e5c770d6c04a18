// Polygons buried inside closed solids: faces no light can reach and no eye can see.
//
// A model built of overlapping boxes (walls that run into each other at the corners, a slab
// on which the walls stand, a shelf pushed into a cabinet's side) has faces inside other
// solids: once splitAtContacts (radiosity/contact_split.h) has cut the slab along the
// walls' feet, the pieces under the walls, and the walls' own feet and ends where they touch,
// lie wholly inside solid matter. Surfaces are one-sided (scene.h): such a face, whose front
// sees only the backs of the solid around it, receives nothing and sends nothing. It is not
// harmless, though. The solution's clusters hold it with the faces it is grouped with, so a
// cluster's average takes its area as if it were lit and lit back (measured on
// bench/scenes/window_room: a forward solve with such faces gives 0.95-0.97 of the truth's
// level at epsilon 1e-5, without them 0.98-1.00; bench/RESULTS.md, fourteenth session).
//
// The rule: a face is buried when every ray from a set of points on it, into the half-spaces
// in front of and behind it, first meets the back of a face (it is inside a solid on both
// sides). A thin sheet modelled as two faces back to back and two solids that touch look
// alike where a ray meets them (a back face and a front face at one distance): the ray passes
// through the pair and its fate is decided beyond. A ray that escapes, meets a front face, a
// light's face or a face of another object that an edit may remove (the face's own object
// leaves with it), or passes through more than maxPairs pairs, sees out: the face is kept. A
// face the photo's camera sees is kept whatever its rays meet (a camera that stands inside a
// wall looks out through it).
#pragma once

#include <optional>
#include <vector>

#include "radiosity/scene.h"
#include "radiosity/visibility.h"

namespace radiosity {

struct BuriedOptions {
    /// Rays per point and side, cosine-distributed over the hemisphere.
    int raysPerPoint = 4;
    /// Pairs of coincident faces (a sheet, two solids touching) a ray may pass through.
    int maxPairs = 8;
};

/// What may not count as solid matter about a face, and what must see it.
struct BuriedContext {
    /// Per object (Scene::objects): true when an edit may take it away ("removable").
    std::vector<bool> mayVanish;
    /// The photo's camera centre, if any.
    std::optional<Vec3> eye;
};

/// Indices, ascending, of the polygons in [0, count) of vis's scene that are buried (above).
/// Emitting faces are never buried.
std::vector<int> findBuriedPolygons(const Scene& scene, size_t count, const Visibility& vis,
                                    const BuriedContext& context,
                                    const BuriedOptions& options = {});

/// Removes `buried` (ascending indices below every light's faces) from scene.polygons and
/// renumbers the lights' faces. Returns the area removed.
double removeBuriedPolygons(Scene& scene, const std::vector<int>& buried);

}  // namespace radiosity
