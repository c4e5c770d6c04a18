// parallelFor: a loop over independent indices on TBB's threads, for the solver's and the
// relighting's per-node, per-link and per-vertex loops. Each index must write only its own
// results: then nothing depends on which thread ran it or in what order, and results are
// the same with any thread count. Sums across indices are no such loop: they keep their
// fixed order where they are (the gather sums each receiver's links in list order).
// Users link TBB themselves (radiosity and relight_lib do).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>

namespace radiosity {

/// Calls f(i) for every i in [0, n), in chunks that TBB does not split below `grain`
/// indices (the cost of one index decides it: a few for a link's rays, thousands for
/// clearing a node).
template <class F>
void parallelFor(size_t n, size_t grain, F&& f) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                      [&f](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i) f(i);
                      });
}

/// Calls f(begin, end) for chunks [begin, end) covering [0, n), split as parallelFor's:
/// for loops that set up scratch space (a vector per light, say) once per chunk rather
/// than once per index.
template <class F>
void parallelForChunks(size_t n, size_t grain, F&& f) {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, n, grain),
        [&f](const tbb::blocked_range<size_t>& range) { f(range.begin(), range.end()); });
}

}  // namespace radiosity
