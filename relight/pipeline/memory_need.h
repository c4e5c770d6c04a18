// What a preparation needs of the machine's memory, known once the scene is loaded and
// before the long work starts. A mesh too large for the machine then ends at once with a
// message that says what it needs and what there is, rather than minutes later by the
// system's out-of-memory killer (the stair hall cut into 6.3 M faces peaked at 15.8 GB).
//
// The need is linear in the input (bench/RESULTS.md, 2026-11-29 (twentieth session)):
// the solver's unit is still the input face (issue 30), so every face is a leaf with its
// node, links, measurements and per-light responses. Per face, measured on the stair hall
// subdivided x4 (1.57 M faces, 3.75e6 KiB peak) and x16 (6.29 M faces, 15.10e6 KiB), 3
// lights: 2.4 KiB, of which the per-light responses are about 0.22 KiB per light.
#pragma once

#include <cstddef>
#include <string>

#include "radiosity/scene.h"

namespace relight {

/// Bytes a preparation of `faces` input faces lit by `lights` lights (scene lights: a sky is
/// 9) is expected to peak at.
double preparationMemoryNeed(size_t faces, size_t lights);

/// Throws std::runtime_error, naming `what` (the scene's folder), the faces and the bytes
/// needed and available, when the preparation's need exceeds kMemoryRefuseShare of
/// `available` bytes (0: the memory this process may count on, radiosity::usableMemory()). Returns
/// a warning line when it exceeds kMemoryWarnShare of them, else an empty string.
std::string checkPreparationMemory(const radiosity::Scene& scene, const std::string& what,
                                   size_t available = 0);

/// The shares of the memory above which the preparation warns, and is refused: the system,
/// the window and the other programs hold the rest (a 16 GB machine has about 14 GB for it).
inline constexpr double kMemoryWarnShare = 0.6;
inline constexpr double kMemoryRefuseShare = 0.9;

}  // namespace relight
