// Polygons cut where other surfaces meet them (Baum, Mann, Smith & Winget 1991, "Making
// radiosity usable: automatic preprocessing and meshing techniques for the generation of
// accurate radiosity solutions", §3: light and shadow leaks).
//
// A wall that stands on a floor slab which runs on beneath it, or a slab that runs through a
// wall, is one polygon on both sides of the other surface. Every element of the hierarchy
// over it then straddles the line of contact: lit on one side, it radiates on the other, and
// a closed space's light leaks into the room next to it (or a room's shadow under a wall
// into the open). Measured on the stair hall of `../shared/data/staircase` (bench/RESULTS.md,
// 2026-11-28): a lamp alone in the closed space above the entrance's lower ceiling lights the
// hall, in a forward solve, at 8.5 times the truth's level; this rule (412 of its 393 k
// polygons cut, 0.1 s) takes 43 % of that away. Cut by hand along the wall's plane and the
// slab's, the leak was gone. The slab ends on one face of a thick wall whose top has no face,
// and the wall's other face, which runs up past the slab, touches nothing along that line:
// no contact for the rule to find.
//
// The rule (Baum et al.'s, restricted to what a mesh gives): where edges of other polygons,
// not parallel to polygon A, lie in A's plane along one line and together cover A's chord
// on that line from boundary to boundary, A is cut along it (A is convex: its pieces stay
// convex; later lines cut only the pieces they cross). A wall standing across a slab divides
// it; a box standing on a floor does not span the floor, and cutting the floor along its
// foot's lines would turn it into long strips for a leak under the box nobody sees (those
// strips cost the bundled room's virtual box 0.035 -> 0.073 in its changed pixels). Only
// edges of at least minEdge and polygons of at least minArea take part: a contact shorter
// than that shades too little to matter, and the cuts stay few. Pieces are triangles or
// quads, in the polygon's plane, with its object and reflectance: nothing but the meshing
// changes.
#pragma once

#include <vector>

#include "radiosity/scene.h"

namespace radiosity {

struct ContactSplitOptions {
    /// Edges shorter than this share of the scene's bounding-box diagonal cut nothing.
    double minEdge = 0.007;
    /// Polygons smaller than this share of the diagonal squared are not cut.
    double minArea = 2.5e-5;
    /// A polygon is cut into at most this many pieces (the lines beyond are not applied).
    int maxPieces = 512;
};

struct ContactSplitReport {
    int polygonsCut = 0;    ///< polygons split
    int lines = 0;          ///< contact lines applied, summed over those polygons
    int piecesAdded = 0;    ///< polygons appended (a cut polygon keeps its index for a piece)
    int piecesLimited = 0;  ///< polygons that reached ContactSplitOptions::maxPieces
};

/// Cuts polygons [0, count) of `polygons` along their contact lines (above). A cut polygon's
/// first piece takes its index, the others are appended at the end, so that indices held
/// elsewhere stay valid. Emitting faces (light >= 0) are neither cut nor cut along.
ContactSplitReport splitAtContacts(std::vector<Polygon>& polygons, size_t count,
                                   const ContactSplitOptions& options = {});

}  // namespace radiosity
