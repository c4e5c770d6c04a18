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
#pragma once

#include <vector>

#include "radiosity/direct_light.h"
#include "radiosity/solver.h"
#include "relight/image.h"
#include "relight/item_buffer.h"

namespace relight {

struct LightingBuffer {
    int lights = 0;
    std::vector<float> G;            ///< G[sample * lights + l], dimensionless
    std::vector<int> gatherPoint;    ///< per sample: its gather point, -1 when it sees nothing
    std::vector<int> gatherPolygon;  ///< per gather point
    std::vector<radiosity::Vec3> gatherPosition;  ///< per gather point (metres)
    std::vector<radiosity::Rgb> indirect;         ///< per gather point (radiosity units), or empty
    uint64_t rays = 0;                            ///< shadow rays cast for G

    const float* direct(int sample) const {
        return G.data() + static_cast<size_t>(sample) * lights;
    }
};

/// Evaluates G for every sample that sees a reflecting polygon (0 elsewhere) and places
/// the gather points; the indirect light stays empty (zero) until updateIndirect(). Uses
/// the solver's links to skip rays where a shaft is empty, so call it after solve().
LightingBuffer computeLightingBuffer(const ItemBuffer& items,
                                     const radiosity::HierarchicalSolver& solver,
                                     radiosity::DirectLightOptions options = {});

/// Re-gathers the indirect light of every gather point from the solver's current solution.
void updateIndirect(LightingBuffer& buffer, const radiosity::HierarchicalSolver& solver);

/// Irradiance H at sample `idx` (radiosity units): direct light with the solver's
/// current light emittances, plus the indirect light of the sample's gather point.
radiosity::Rgb sampleIrradiance(const LightingBuffer& buffer, const radiosity::Scene& scene,
                                int idx);

/// Radiance image of the solution, (E + rho H) / pi per sample averaged over each pixel
/// (an emitting face shows its radiance; a sample that sees nothing is black).
Image renderRadiosity(const ItemBuffer& items, const LightingBuffer& buffer,
                      const radiosity::Scene& scene);

}  // namespace relight
