// Face clusters: connected, nearly planar groups of input polygons, built bottom-up by
// greedy contraction of the face adjacency graph (Garland, Willmott & Heckbert 2001,
// "Hierarchical face clustering on polygonal surfaces"; used for radiosity by Willmott,
// Heckbert & Garland 1999, "Face cluster radiosity").
//
// Why: a reconstructed or modelled room cuts one curved surface (a sofa, a chandelier's
// arm, a jittered wall) into thousands of small triangles. Grouped by position alone (a
// median-split BVH), a cluster holds triangles of many orientations, so the solver must open
// it, down to the triangles, to light it right. Grouped by the surface they lie on, the
// clusters near the bottom are nearly planar: a link can stop there, and the solution's cost
// follows the lighting rather than the input.
//
// The rule. Every polygon starts as a cluster. Two clusters are adjacent when they share a
// mesh edge (corners equal to the last bit; polygons of different objects, and a lamp's
// emitting faces, are never adjacent). The adjacent pair of least cost is merged, and so on,
// each merge making a node of a binary tree, until no pair may merge. The cost of merging
// into a cluster of area A, vector area a, normal moment M (hierarchy.h), mean normal
// n = a / |a|, perimeter P:
//     E_dir   = sum_i A_i (1 - n_i . n)^2 / A = (A - 2 |a| + n^T M n) / A   (orientation)
//     E_fit   = n^T C n / A, C the covariance of the cluster's points (area-weighted
//               corners): the mean squared distance to the plane through their centre,
//               relative to the area (planarity, dimensionless like E_dir)
//     E_shape = P^2 / (4 pi A) - 1   (irregularity; 0 for a disc)
//     cost    = E_dir + E_fit + shapeWeight E_shape.
// A merge is refused when the merged cluster's normal cone (a conservative bound from its
// two parts' cones) would be wider than maxConeAngle, or its parts face opposite ways: above
// that the clusters are no longer a surface, and the spatial hierarchy takes over.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "radiosity/scene.h"

namespace radiosity {

struct FaceClusterOptions {
    /// Widest normal cone of a face cluster (radians): 30 degrees, within which one normal
    /// stands for every face's cosine to within cos(30) = 0.87 at the worst and far better
    /// on average (the cone bounds the worst face).
    double maxConeAngle = 0.5235987755982988;
    /// Weight of the irregularity term: small, so that orientation and planarity decide
    /// and shape only breaks ties between equally flat merges (Garland et al. weigh it
    /// likewise below the fit terms).
    double shapeWeight = 0.05;
    /// The merges' heap drops its stale candidates all at once when they outnumber the live
    /// ones and it holds more than this many (buildFaceClusters). It changes the time, never
    /// the merges; tests set 0 (drop as often as that) and SIZE_MAX (never) to compare.
    size_t dropStaleAbove = 4096;
};

/// The merge forest over n polygons. Tree node t < n is polygon t; node n + k is the k-th
/// merge, whose two children are merges[k] (tree nodes made earlier). `roots` lists the
/// nodes that no merge took (each polygon lies under exactly one root), in increasing order.
struct FaceClusterForest {
    int polygons = 0;
    std::vector<std::array<int, 2>> merges;
    std::vector<int> roots;

    bool isPolygon(int t) const { return t < polygons; }
    /// The polygons under tree node t, left subtree first (a contiguous run of a cluster).
    void polygonsUnder(int t, std::vector<int>& out) const;
};

/// Builds the face clusters of `polygons` (O(n log n) in the number of polygons).
FaceClusterForest buildFaceClusters(std::span<const Polygon> polygons,
                                    const FaceClusterOptions& options = {});

}  // namespace radiosity
