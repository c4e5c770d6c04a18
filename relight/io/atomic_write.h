// Writing a file atomically, for every file relight writes (images, the prepared-state
// cache, reports, edits, debug views): the bytes go to a temporary file beside the target,
// which is then renamed over it. A reader sees the old file or the new one, never part of
// one, and a failed write leaves the old file as it was and no temporary file behind.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace relight {

/// Writes the temporary file it is given; returns an empty string when that worked, else
/// why not (what is left of the file is removed).
using WriteTemporary = std::function<std::string(const std::filesystem::path& temporary)>;

/// Writes `path` atomically (see above) with `write`. The temporary file is
/// `.tmp-<file name>` in the same folder (the rename is atomic within one file system; the
/// extension stays last, as OpenImageIO picks the format from it); with `uniqueTemporary`
/// a random `-<number>` follows, so that two processes writing the same file (two
/// `relight prepare` of one scene) do not share one temporary file. The folder must exist.
/// On failure throws OutputError "<path>: <what>: <why>".
void writeAtomic(const std::filesystem::path& path, const std::string& what,
                 const WriteTemporary& write, bool uniqueTemporary = false);

/// writeAtomic() of `bytes` as they are.
void writeBytesAtomic(const std::filesystem::path& path, const std::string& what,
                      std::string_view bytes, bool uniqueTemporary = false);

/// writeBytesAtomic() of `text`; fails with "<path>: cannot write: <why>".
void writeTextAtomic(const std::filesystem::path& path, const std::string& text);

}  // namespace relight
