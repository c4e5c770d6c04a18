// LightingBuffer: the irradiance of every sample of an item buffer, kept in two parts so
// that an edit recomputes only what it changes.
//
//   H(x) = sum_l E_l G_l(x) + H_indirect(x)
//
// - Direct light per sample (Loscos et al. 1999, §5, "per-pixel direct light"): G_l(x) of
//   radiosity/direct_light.h for each light l, lights that are off included. E_l is the
//   light's current emittance, so a change of its colour or strength costs no ray.
// - Indirect light by final gather (radiosity/final_gather.h) through the hierarchy's
//   links. It varies slowly, so it is gathered once per pixel and polygon, at the mean of
//   the pixel's samples on that polygon (a "gather point"), not once per sample.
//   updateIndirect() re-gathers after the radiosity solution changes.
// With a pixel stride above 1 (SamplingPlan in relight/pipeline/item_buffer.h) the buffer holds the
// samples of the pixels whose x and y are multiples of the stride only: the reflectance
// estimate needs sums over each polygon's samples, which an even sub-grid gives as well
// at a fraction of the shadow rays.
#pragma once

#include <cstdint>
#include <vector>

#include "radiosity/direct_light.h"
#include "radiosity/progress.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "relight/io/image.h"
#include "relight/pipeline/item_buffer.h"

namespace relight {

struct LightingBuffer {
    int lights = 0;
    int stride = 1;                  ///< pixel stride (1: every pixel)
    int width = 0, spp = 1;          ///< the item buffer's width and samples per pixel
    int gridWidth = 0;               ///< pixels per row of the sub-grid, ceil(width / stride)
    std::vector<float> G;            ///< G[slot * lights + l], dimensionless
    std::vector<int> gatherPoint;    ///< per slot: its gather point, -1 when it sees nothing
    std::vector<int> gatherPolygon;  ///< per gather point
    std::vector<radiosity::Vec3> gatherPosition;  ///< per gather point (metres)
    std::vector<radiosity::Rgb> indirect;         ///< per gather point (radiosity units), or empty
    uint64_t rays = 0;                            ///< shadow rays cast for G

    /// Where item-buffer sample `sample` is kept: the sample itself with stride 1, else its
    /// place on the sub-grid (-1 for a sample of a pixel off the sub-grid).
    int64_t slot(int sample) const {
        if (stride == 1) return sample;
        const int pixel = sample / spp, x = pixel % width, y = pixel / width;
        if (x % stride != 0 || y % stride != 0) return -1;
        return (static_cast<int64_t>(y / stride) * gridWidth + x / stride) * spp + sample % spp;
    }
    /// G of item-buffer sample `sample`, a pixel of the sub-grid.
    const float* direct(int sample) const { return G.data() + slot(sample) * lights; }
    int gatherPointOf(int sample) const { return gatherPoint[static_cast<size_t>(slot(sample))]; }
};

/// Evaluates G for every sample that sees a reflecting polygon (0 elsewhere) and places
/// the gather points; the indirect light stays empty (zero) until updateIndirect(). Uses
/// the solver's links to skip rays where a shaft is empty, so call it after solve().
/// `stride` > 1: the pixels of the sub-grid only (above).
LightingBuffer computeLightingBuffer(const ItemBuffer& items,
                                     const radiosity::HierarchicalSolver& solver,
                                     radiosity::DirectLightOptions options = {}, int stride = 1);

/// The finest pixel stride (finest, 2 finest, 4 finest, ... up to probeStride) whose
/// lighting is predicted to take at most `secondsLeft`, from the `probeSeconds` that a
/// sub-grid of `probeStride` took: rays follow the pixels, so stride s costs
/// probeSeconds (probeStride / s)^2. probeStride when none finer fits (also when
/// secondsLeft <= 0 or is NaN).
int finestStrideWithin(double probeSeconds, int probeStride, int finest, double secondsLeft);

/// Re-gathers the indirect light of every gather point from the solver's current solution
/// (the final gather, far links shared per element); `progress` hears how far it is. Points
/// begun after `raysUntil` (a time budget's share) cast no visibility rays: their partly
/// occluded links keep their mean visibility (radiosity::sharedFinalGather).
void updateIndirect(LightingBuffer& buffer, const radiosity::HierarchicalSolver& solver,
                    const radiosity::ProgressFn& progress = {},
                    radiosity::Clock::time_point raysUntil = radiosity::Clock::time_point::max());

/// Gather points whose terms updateIndirect() holds at once.
inline constexpr size_t kIndirectChunk = 8192;

/// Irradiance H at sample `idx` (radiosity units): direct light with the solver's
/// current light emittances, plus the indirect light of the sample's gather point. The
/// sample must be on the buffer's sub-grid.
radiosity::Rgb sampleIrradiance(const LightingBuffer& buffer, const radiosity::Scene& scene,
                                int idx);

/// Radiance image of the solution, (E + rho H) / pi per sample averaged over each pixel
/// (an emitting face shows its radiance; a sample that sees nothing is black). Needs a
/// buffer of stride 1 (throws std::invalid_argument otherwise).
Image renderRadiosity(const ItemBuffer& items, const LightingBuffer& buffer,
                      const radiosity::Scene& scene);

}  // namespace relight
