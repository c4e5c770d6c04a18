// The final gather of many points at once, with the far field shared per receiving element.
//
// finalGatherWeights() walks, for one point x, every link on the chain above the leaf that
// holds x. A large element (a wall that cannot be split below the minimum area) can hold
// thousands of links, one per small source cluster or triangle it sees, and the display
// puts up to 4^4 vertices inside one leaf: on a real stair hall (262 k triangles) that was
// thousands of links per vertex, 75 % of the preparation's vertex lighting (165 s) and
// most of its 11.5 GB in the kept terms (bench/RESULTS.md, 2026-11-26).
//
// The links that a receiving element r holds from a source s far from it vary smoothly over
// r: with d the distance between their centres and R_r, R_s their bounding radii, a link is
// "far" when d > kFar (R_r + R_s). Its transfer to a point x of r, F(x) V(x), is then a
// smooth function of x over r, and it is gathered once per corner of r instead of once per
// point: at each corner c (moved a hair inside r) the same per-point gather as
// finalGatherWeights() (point form factor, visibility rays from the corner on PARTIAL
// links) over r's far links only; a point x of r takes the affine function through the
// corners' gathers (least squares on a quad, barycentric on a triangle; exact for a
// transfer that is affine over r). With 1/d^2 the dominant variation, the part an affine
// function misses is of order 3 (R_r / d)^2 at a corner, at most 3/16 of that link's small
// share for kFar = 4 and a point source, a quarter of it after the fit (error spread over
// the element, not concentrated at a corner); the near links, whose transfer bends over r
// (a floor meeting the wall, a lamp shade next to it), stay per point.
//
// This is Willmott, Heckbert & Garland 1999's sharing of a face cluster's gather between
// the triangles it shows, on the element hierarchy: the cost is (links x corners) per
// element plus (near links + elements on the chain) per point, not (links above x) per
// point. Cluster receivers (not planar) keep every link per point. A link near its
// receiving element but far from the leaf that holds the point (a large wall's link to a
// small source beside it) is gathered at the leaf's corners, when the leaf holds more
// than twice as many points as it has corners.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "radiosity/final_gather.h"
#include "radiosity/light_response.h"
#include "radiosity/progress.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"

namespace radiosity {

/// A point to gather at: x on `polygon` (polygon < 0: no gather, e.g. a light's own face);
/// `seed` selects its rays.
struct GatherPoint {
    int polygon = -1;
    Vec3 x{0, 0, 0};
    uint64_t seed = 0;
};

/// Lists of items (an item: a point or a corner) stored in blocks of consecutive items,
/// each block allocated at its exact size once its items are gathered. A flat array built
/// from one growing vector per item held the terms twice, with the vectors' slack, at its
/// peak: 1 GB of the stair hall's 2.4 GB (bench/RESULTS.md, 2026-11-28, sixteenth session).
template <class T>
struct BlockedLists {
    struct Range {
        uint32_t block = 0, begin = 0, count = 0;
    };
    std::vector<std::vector<T>> blocks;
    std::vector<Range> items;

    size_t size() const { return items.size(); }
    std::span<const T> operator[](size_t i) const {
        const Range& r = items[i];
        return {blocks[r.block].data() + r.begin, r.count};
    }
    /// The entries of every item.
    size_t entries() const {
        size_t n = 0;
        for (const auto& b : blocks) n += b.size();
        return n;
    }
    /// Fills block b with items [from, to) in order: `fill(i, out)` appends item i's entries
    /// to out. Blocks are filled independently (in parallel), each exactly its size.
    template <class Fill>
    void fillBlock(size_t b, size_t from, size_t to, Fill&& fill) {
        std::vector<T> out;
        for (size_t i = from; i != to; ++i) {
            const size_t begin = out.size();
            fill(i, out);
            items[i] = {static_cast<uint32_t>(b), static_cast<uint32_t>(begin),
                        static_cast<uint32_t>(out.size() - begin)};
        }
        out.shrink_to_fit();
        blocks[b] = std::move(out);
    }
};

/// The gather terms of many points (links and subdivision fixed): the indirect irradiance
/// at point i is
///   H_i = sum over point terms t of w_t R(node_t)
///       + sum over sample references (s, a) of a * sum over sample terms t of s: w_t R(node_t)
/// with R(node) the radiosity that node reflects (B - E on an emitter).
struct SharedGather {
    struct SampleRef {
        int sample;
        float weight;  ///< affine weight of the sample (a corner of an element) at the point
    };
    BlockedLists<GatherWeight> sampleTerms;  ///< per sample (an element's corner)
    BlockedLists<GatherWeight> pointTerms;   ///< per point: its near terms
    BlockedLists<SampleRef> refs;            ///< per point: its sample references
    uint64_t rays = 0;                       ///< visibility rays cast
    size_t sharedLinks = 0;  ///< links gathered per corner (counted once per element)
    size_t nearLinks = 0;    ///< links gathered per point (counted once per element)
    /// Of those, the links gathered at the corners of a leaf below their receiver instead,
    /// counted once per leaf (a leaf with many points: sharedFinalGather)
    size_t leafSharedLinks = 0;
    /// Corners and points gathered after `raysUntil` had passed: their PARTIAL links kept
    /// their own V (the link's mean over its receiver) instead of rays from the point.
    size_t withoutRays = 0;

    size_t points() const { return pointTerms.size(); }
    size_t samples() const { return sampleTerms.size(); }
    size_t terms() const { return sampleTerms.entries() + pointTerms.entries() + refs.entries(); }
    bool empty() const { return pointTerms.size() == 0; }
    /// out[i * lights + l] += indirect irradiance at point i per unit radiance of light l
    /// (responses built on the same solver and links).
    void addResponses(const LightResponses& responses, Rgb* out) const;
    /// out[i] += indirect irradiance at point i with the solver's radiosities now.
    void addIndirect(const HierarchicalSolver& solver, Rgb* out) const;
};

/// Far links: a link whose source's centre is more than kFar times the sum of the two
/// bounding radii from its receiving element's centre.
inline constexpr double kSharedGatherFar = 4.0;

/// The terms of every point's final gather, far links shared per element (see above). In
/// parallel, deterministic (each point's rays from its seed, each corner's from its node).
/// `progress` hears how far it is every ProgressMeter::kEverySeconds. A corner or point
/// begun after `raysUntil` (a time budget's share, radiosity/stopwatch.h) casts no rays:
/// its PARTIAL links keep their V, as links of F(x) below kPointVisibilityF always do; the
/// rays are nine tenths of a gather's time (bench/RESULTS.md, 2026-11-27, sixth session).
SharedGather sharedFinalGather(const HierarchicalSolver& solver,
                               std::span<const GatherPoint> points, int partialRays = 4,
                               const ProgressFn& progress = {},
                               Clock::time_point raysUntil = Clock::time_point::max());

}  // namespace radiosity
