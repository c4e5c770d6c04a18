// The prepared state on disk: `relight prepare` writes a PreparedImage (relight/prepared.h)
// once, `relight render` reads it back instead of preparing again.
//
// A cache is trusted only when everything that made it is unchanged: its file carries the
// preparation key of its inputs (preparationKey: scene.json, the OBJ files, the photos, the
// options that change the result, and an engine version), and it is rebuilt when the key
// differs (stale), when its format version differs, and when it is corrupt (checksum,
// truncation, inconsistent sizes). Reading never throws and never trusts a length it has
// not checked against the bytes left in the file.
//
// File layout (all integers little-endian, floats IEEE 754):
//   header   8 bytes magic "RLPREP\r\n", uint32 format version, uint32 0 (reserved),
//            uint64 preparation key, uint64 payload size in bytes
//   payload  the PreparedImage's fields in the order its serialize() lists them:
//            int as int32, uint64 as uint64, float as float32, double as float64, Rgb as
//            3 float64, a vector as a uint64 element count and then its elements
//   trailer  uint64 FNV-1a 64 of the payload
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "relight/io/scene_file.h"
#include "relight/prepared.h"
#include "relight/relighting.h"

namespace relight {

/// Version of the file layout. Bump it whenever the layout changes: a field added to,
/// removed from or reordered in any serialize() in prepared_cache.cpp (PreparedImage,
/// Image, DisplayMap, VertexLighting, PrepareTimes), or an encoding changed. Files of
/// another version are rebuilt, never read.
constexpr uint32_t kPreparedFormatVersion = 6;

/// Version of the preparation itself, part of the preparation key. Bump it whenever
/// prepareRelighting() gives a different PreparedImage for the same inputs and options
/// (a new step, a changed algorithm or default): caches made by the old code are then
/// stale. (On Linux the key also hashes the program's own bytes, which catches a forgotten
/// bump; elsewhere this constant is all there is.)
constexpr uint32_t kPreparationEngineVersion = 5;

/// FNV-1a 64 of the preparation's inputs: the two versions above, the bytes of the running
/// program (on Linux: a cache made by another build is stale), the bytes of scene.json,
/// of every OBJ file of its geometry and of every photo (a file that cannot be read counts
/// as missing: preparing then reports it), and the options that change the result (see
/// hashOptions in prepared_cache.cpp; RelightOptions::progress does not). The truth/ folder
/// and other files the preparation does not read are not part of it.
uint64_t preparationKey(const SceneFile& scene, const RelightOptions& options);

/// `<scene_dir>/.relight/prepared.bin`.
std::filesystem::path defaultCachePath(const std::filesystem::path& sceneDir);

/// Writes `p` with `key` atomically: to a temporary file in the same folder, renamed over
/// `file` (a failed write leaves any previous cache as it was, and no temporary file).
/// Creates the parent folders. Throws OutputError naming the file or folder on failure.
void writePreparedCache(const std::filesystem::path& file, const PreparedImage& p, uint64_t key);

/// Reads a cache written with `key`. Returns nullopt, with the reason in *why (when not
/// null), when the file is missing, is not a cache, is of another format version, was made
/// from other inputs (the reason then says "stale"), is truncated or corrupt, or holds
/// sizes that do not fit together. Never throws for a bad file.
std::optional<PreparedImage> readPreparedCache(const std::filesystem::path& file, uint64_t key,
                                               std::string* why);

/// Checks that the sizes of `p` fit together (what renderEdit relies on to stay in bounds).
/// Returns an empty string when they do, else what is wrong.
std::string checkPrepared(const PreparedImage& p);

}  // namespace relight
