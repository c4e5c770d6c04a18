#include "relight/io/atomic_write.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <system_error>

#include "relight/errors.h"

namespace relight {

namespace fs = std::filesystem;

namespace {

/// A number no other writer picks.
std::string uniqueSuffix() {
    static std::random_device rd;
    std::mt19937_64 g((static_cast<uint64_t>(rd()) << 32) ^ rd());
    return std::to_string(g());
}

void removeQuietly(const fs::path& file) {
    std::error_code ignored;
    fs::remove(file, ignored);
}

}  // namespace

void writeAtomic(const fs::path& path, const std::string& what, const WriteTemporary& write,
                 bool uniqueTemporary) {
    std::string name = ".tmp-" + path.filename().string();
    if (uniqueTemporary) {
        name += '-';
        name += uniqueSuffix();
    }
    const fs::path tmp = path.parent_path() / name;
    std::string why;
    try {
        why = write(tmp);
    } catch (...) {
        removeQuietly(tmp);
        throw;
    }
    if (why.empty()) {
        std::error_code ec;
        fs::rename(tmp, path, ec);
        if (!ec) return;
        why = ec.message();
    }
    removeQuietly(tmp);
    throw OutputError(path.string() + ": " + what + ": " + why);
}

void writeBytesAtomic(const fs::path& path, const std::string& what, std::string_view bytes,
                      bool uniqueTemporary) {
    writeAtomic(
        path, what,
        [&](const fs::path& tmp) -> std::string {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            if (!out) return "cannot create " + tmp.string() + ": " + std::strerror(errno);
            out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
            out.close();  // a write that fails on flushing (disk full) fails here, not silently
            if (!out) return "writing " + tmp.string() + " failed (disk full?)";
            return {};
        },
        uniqueTemporary);
}

void writeTextAtomic(const fs::path& path, const std::string& text) {
    writeBytesAtomic(path, "cannot write", text);
}

}  // namespace relight
