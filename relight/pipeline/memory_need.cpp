#include "relight/pipeline/memory_need.h"

#include <cstdio>
#include <stdexcept>

#include "radiosity/machine_memory.h"

namespace relight {

namespace {

/// The peaks were read as /usr/bin/time's maximum resident size, in KiB: 1024 bytes each.
constexpr double kKiB = 1024;
/// Per face and light: the per-light responses' arrays (relight/prepared.h), measured as the
/// growth of the x4 hall's peak when they are made (1.2e6 KiB for 1.57 M leaves, 3 lights:
/// 0.255 KiB), less the unit emittance those arrays no longer hold (24 bytes a node and
/// light; the x4 hall's peak fell by 182 264 KiB at 3 lights: 38.6 bytes a face and light).
constexpr double kBytesPerFaceLight = 0.255 * kKiB - 38.6;
/// Per face, the rest: node, links, measurements, the vertex lighting, the loaded mesh
/// (2.40 KiB a face at 3 lights, the x16 hall's peak, less the responses).
constexpr double kBytesPerFace = 2.40 * kKiB - 3 * kBytesPerFaceLight;

double gigabytes(double bytes) {
    return bytes / 1e9;
}

}  // namespace

double preparationMemoryNeed(size_t faces, size_t lights) {
    return static_cast<double>(faces) *
           (kBytesPerFace + kBytesPerFaceLight * static_cast<double>(lights));
}

std::string checkPreparationMemory(const radiosity::Scene& scene, const std::string& what,
                                   size_t available) {
    if (available == 0) available = radiosity::usableMemory();
    if (available == 0) return {};  // the system does not say: nothing to compare with
    const double need = preparationMemoryNeed(scene.polygons.size(), scene.lights.size());
    const double have = static_cast<double>(available);
    const double perFace =
        scene.polygons.empty() ? 0.0 : need / static_cast<double>(scene.polygons.size());
    char msg[640];
    if (need > kMemoryRefuseShare * have) {
        std::snprintf(msg, sizeof msg,
                      "%s: %zu faces and %zu lights: preparing them needs about %.1f GB "
                      "(%.1f kB a face, measured on real meshes), more than this machine's "
                      "%.1f GB can give (%.0f %% of it); a mesh of at most %.0f k faces fits in "
                      "%.0f %% of it (decimate it, or prepare it on a machine with more memory)",
                      what.c_str(), scene.polygons.size(), scene.lights.size(), gigabytes(need),
                      perFace / 1e3, gigabytes(have), 100 * kMemoryRefuseShare,
                      perFace > 0 ? kMemoryWarnShare * have / perFace / 1e3 : 0.0,
                      100 * kMemoryWarnShare);
        throw std::runtime_error(msg);
    }
    if (!(need > kMemoryWarnShare * have)) return {};
    std::snprintf(msg, sizeof msg,
                  "warning: %zu faces: the preparation needs about %.1f GB of this machine's "
                  "%.1f GB; other programs may run short",
                  scene.polygons.size(), gigabytes(need), gigabytes(have));
    return msg;
}

}  // namespace relight
