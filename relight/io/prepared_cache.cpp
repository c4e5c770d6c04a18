// The prepared-state cache (prepared_cache.h): preparation key, binary file, checks.
//
// One serialize() per struct lists its fields in file order and serves both directions:
// the Writer takes const fields, the Reader fills them. Adding a field is one line there
// (and a bump of kPreparedFormatVersion); the test PreparedCache.LayoutGuard fails when a
// struct gains a field that serialize() (or hashOptions(), for RelightOptions) does not
// list yet.
#include "relight/io/prepared_cache.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <climits>
#include <cmath>
#include <concepts>
#include <cstring>
#include <fstream>
#include <limits>
#include <type_traits>

#include "relight/errors.h"
#include "relight/io/atomic_write.h"

namespace relight {

namespace fs = std::filesystem;
using radiosity::Rgb;

// The file is little-endian with IEEE 754 floats, written and read by copying memory.
static_assert(std::endian::native == std::endian::little,
              "prepared_cache.cpp copies memory: add byte swapping for a big-endian host");
static_assert(std::numeric_limits<float>::is_iec559 && std::numeric_limits<double>::is_iec559);
static_assert(sizeof(int) == 4 && sizeof(float) == 4 && sizeof(double) == 8);
static_assert(std::is_trivially_copyable_v<Rgb> && sizeof(Rgb) == 3 * sizeof(double));

namespace {

constexpr std::array<char, 8> kMagic = {'R', 'L', 'P', 'R', 'E', 'P', '\r', '\n'};
constexpr size_t kHeaderSize = 8 + 4 + 4 + 8 + 8;  // magic, version, reserved, key, payload
constexpr size_t kTrailerSize = 8;                 // checksum

// ---- FNV-1a 64 --------------------------------------------------------------------------

struct Fnv1a {
    uint64_t h = 14695981039346656037ull;
    void bytes(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) {
            h ^= p[i];
            h *= 1099511628211ull;
        }
    }
    void u64(uint64_t v) { bytes(&v, sizeof v); }
    void i64(int64_t v) { bytes(&v, sizeof v); }
    void f64(double v) { bytes(&v, sizeof v); }
    void text(const std::string& s) {
        u64(s.size());
        bytes(s.data(), s.size());
    }
};

/// A file's bytes, its size first; a file that cannot be read hashes as missing (distinct
/// from any content), and preparing it then reports the problem.
void hashFile(Fnv1a& h, const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        h.u64(std::numeric_limits<uint64_t>::max());
        return;
    }
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    h.text(bytes);
}

/// Every option that changes the prepared state, in one place: add new ones here (and
/// bump kPreparationEngineVersion if an old default changes). Progress callbacks do not.
void hashOptions(Fnv1a& h, const ShadowRefinementOptions& o) {
    h.f64(o.colourThreshold);
    h.f64(o.visibilityThreshold);
    h.f64(o.minShare);
    h.i64(o.minSamples);
    h.i64(o.maxSplits);
}

void hashOptions(Fnv1a& h, const ShadowRemovalOptions& o) {
    h.f64(o.colourThreshold);
    h.f64(o.umbraThreshold);
    h.f64(o.minShare);
    h.i64(o.minSamples);
}

void hashOptions(Fnv1a& h, const RelightOptions& o) {
    h.f64(o.epsilon);
    h.f64(o.darkFloor);
    // Only when on: the caches prepared before the option existed keep their keys.
    if (o.perLightOracle > 0) h.f64(o.perLightOracle);
    if (o.narrowSources) h.text("narrow-sources");
    // The budget in force, not the option: a default that comes from the machine's memory
    // gives the same state on machines of the same memory only.
    h.i64(static_cast<int64_t>(o.maxLinks));
    h.i64(static_cast<int64_t>(o.maxMemory > 0 ? o.maxMemory : radiosity::defaultMemoryBudget()));
    h.f64(o.timeBudget);
    h.i64(o.spp);
    h.i64(o.sampleBudget);
    h.i64(o.minRays);
    h.i64(o.maxRays);
    h.i64(o.reflectanceRounds);
    h.i64(o.leafReflectance ? 1 : 0);
    h.i64(o.leafReflectanceSamples);
    h.i64(o.shadowRefinement ? 1 : 0);
    hashOptions(h, o.refinement);
    h.i64(o.shadowRemoval ? 1 : 0);
    h.i64(o.importance ? 1 : 0);
    hashOptions(h, o.removal);
    h.f64(o.displayPiecePixels);
    h.i64(o.pixelLight ? 1 : 0);
    h.i64(o.mergePhotos ? 1 : 0);
    h.i64(o.indirectRays);
    h.i64(o.indirectRayBudget);
    h.i64(o.pixelGatherCut ? 1 : 0);
}

// ---- the two directions ------------------------------------------------------------------

/// On-disk size of one element of a vector.
template <class T>
constexpr size_t kDiskSize = sizeof(T);
template <>
constexpr size_t kDiskSize<Rgb> = 3 * sizeof(double);

template <class T>
concept Bulk = std::same_as<T, int> || std::same_as<T, float> || std::same_as<T, Rgb>;

class Writer {
  public:
    explicit Writer(std::string& out) : out_(out) {}
    void operator()(const int& v) { put(static_cast<int32_t>(v)); }
    void operator()(const uint64_t& v) { put(v); }
    void operator()(const double& v) { put(v); }
    void operator()(const Rgb& v) {
        put(v.r);
        put(v.g);
        put(v.b);
    }
    template <Bulk T>
    void operator()(const std::vector<T>& v) {
        put(static_cast<uint64_t>(v.size()));
        if (!v.empty())
            out_.append(reinterpret_cast<const char*>(v.data()), v.size() * kDiskSize<T>);
    }

  private:
    template <class T>
    void put(const T& v) {
        out_.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    std::string& out_;
};

/// Reads fields from a byte range; after the first problem it reads nothing more and
/// error() says what it was. Every length is checked against the bytes left before
/// anything is allocated.
class Reader {
  public:
    Reader(const char* data, size_t size) : p_(data), left_(size) {}
    bool ok() const { return error_.empty(); }
    const std::string& error() const { return error_; }
    size_t left() const { return left_; }

    void operator()(int& v) {
        int32_t x = 0;
        if (take(&x, sizeof x)) v = x;
    }
    void operator()(uint64_t& v) { take(&v, sizeof v); }
    void operator()(double& v) { take(&v, sizeof v); }
    void operator()(Rgb& v) {
        take(&v.r, sizeof(double));
        take(&v.g, sizeof(double));
        take(&v.b, sizeof(double));
    }
    template <Bulk T>
    void operator()(std::vector<T>& v) {
        uint64_t n = 0;
        (*this)(n);
        if (!ok()) return;
        if (n > left_ / kDiskSize<T>) {
            fail("an array of " + std::to_string(n) + " elements of " +
                 std::to_string(kDiskSize<T>) + " bytes, but only " + std::to_string(left_) +
                 " bytes are left");
            return;
        }
        v.resize(static_cast<size_t>(n));
        take(v.data(), v.size() * kDiskSize<T>);
    }

  private:
    bool take(void* dst, size_t n) {
        if (!ok()) return false;
        if (n > left_) {
            fail("needs " + std::to_string(n) + " more bytes, only " + std::to_string(left_) +
                 " are left");
            return false;
        }
        if (n > 0) std::memcpy(dst, p_, n);
        p_ += n;
        left_ -= n;
        return true;
    }
    void fail(const std::string& what) {
        if (ok()) error_ = what;
    }
    const char* p_;
    size_t left_;
    std::string error_;
};

// ---- the fields, one function per struct, in file order ----------------------------------

/// T is U or const U: one function for the Writer (const) and the Reader.
template <class T, class U>
concept Is = std::same_as<std::remove_const_t<T>, U>;

template <class A, Is<Image> T>
void serialize(A& a, T& x) {
    a(x.width);
    a(x.height);
    a(x.rgb);
}

template <class A, Is<DisplayMap> T>
void serialize(A& a, T& x) {
    a(x.width);
    a(x.height);
    a(x.start);
    a(x.vertex);
    a(x.weight);
    a(x.unshaded);
    a(x.emitterStart);
    a(x.emitterLight);
    a(x.emitterFraction);
}

template <class A, Is<VertexLighting> T>
void serialize(A& a, T& x) {
    a(x.lights);
    a(x.response);
    a(x.rays);
}

template <class A, Is<PrepareTimes> T>
void serialize(A& a, T& x) {
    a(x.itemBuffer);
    a(x.solve);
    a(x.reflectance);
    a(x.refinement);
    a(x.responses);
    a(x.vertexLighting);
    a(x.shadowRemoval);
    a(x.displayMap);
}

template <class A, Is<PreparedImage> T>
void serialize(A& a, T& x) {
    serialize(a, x.photo);
    serialize(a, x.display);
    serialize(a, x.lighting);
    a(x.D);
    a(x.textureFactor);
    a(x.photoRadiance);
    a(x.confidence);
    a(x.modelReflectance);
    a(x.pixelDirect);
    a(x.vertexIndirect);
    a(x.pixelReflectance);
    a(x.pixelNormal);
    a(x.skyCoefficient);
    a(x.leaves);
    a(x.links);
    a(x.budgetReached);
    a(x.solverBytes);
    a(x.maxLinks);
    a(x.maxMemory);
    serialize(a, x.times);
}

// ---- header ------------------------------------------------------------------------------

template <class T>
void putAt(std::string& s, size_t at, const T& v) {
    std::memcpy(s.data() + at, &v, sizeof v);
}
template <class T>
T getAt(const char* p, size_t at) {
    T v{};
    std::memcpy(&v, p + at, sizeof v);
    return v;
}

uint64_t checksum(const char* data, size_t n) {
    Fnv1a h;
    h.bytes(data, n);
    return h.h;
}

/// Checks that each range array starts at 0, never decreases and ends at `total`.
std::string checkRanges(const std::vector<int>& start, size_t total, const char* name) {
    if (start.front() != 0) return std::string(name) + " does not start at 0";
    for (size_t i = 1; i < start.size(); ++i)
        if (start[i] < start[i - 1])
            return std::string(name) + " decreases at " + std::to_string(i);
    if (static_cast<size_t>(start.back()) != total)
        return std::string(name) + " ends at " + std::to_string(start.back()) + ", not at " +
               std::to_string(total);
    return {};
}

}  // namespace

uint64_t preparationKey(const SceneFile& scene, const RelightOptions& options) {
    Fnv1a h;
    h.text("relight-prepared");
    h.u64(kPreparedFormatVersion);
    h.u64(kPreparationEngineVersion);
    // The running program itself: a cache made by another build of the engine is stale
    // even where kPreparationEngineVersion was not bumped (a rebuild prepares once more).
    h.text("program");
#if defined(__linux__)
    static const uint64_t program = [] {
        Fnv1a p;
        hashFile(p, "/proc/self/exe");
        return p.h;
    }();
    h.u64(program);
#endif
    h.text("scene.json");
    hashFile(h, scene.dir / "scene.json");
    h.text("geometry");
    h.u64(scene.geometryFiles.size());
    for (const fs::path& f : scene.geometryFiles) hashFile(h, f);
    h.text("photos");
    h.u64(scene.photos.size());
    for (const PhotoSpec& ph : scene.photos) hashFile(h, ph.file);
    h.text("options");
    hashOptions(h, options);
    return h.h;
}

fs::path defaultCachePath(const fs::path& sceneDir) {
    return sceneDir / ".relight" / "prepared.bin";
}

std::string checkPrepared(const PreparedImage& p) {
    const auto n = [](size_t v) { return std::to_string(v); };
    const Image& photo = p.photo;
    if (photo.width <= 0 || photo.height <= 0)
        return "photo size " + std::to_string(photo.width) + "x" + std::to_string(photo.height);
    const uint64_t pixels =
        static_cast<uint64_t>(photo.width) * static_cast<uint64_t>(photo.height);
    if (pixels >= static_cast<uint64_t>(INT_MAX / 3)) return "photo of " + n(pixels) + " pixels";
    if (photo.rgb.size() != pixels * 3)
        return "photo has " + n(photo.rgb.size()) + " values, not " + n(pixels * 3);
    const DisplayMap& m = p.display;
    if (m.width != photo.width || m.height != photo.height)
        return "display map is " + std::to_string(m.width) + "x" + std::to_string(m.height) +
               ", the photo " + std::to_string(photo.width) + "x" + std::to_string(photo.height);
    if (m.start.size() != pixels + 1) return "display.start has " + n(m.start.size()) + " entries";
    if (m.emitterStart.size() != pixels + 1)
        return "display.emitterStart has " + n(m.emitterStart.size()) + " entries";
    if (m.unshaded.size() != pixels)
        return "display.unshaded has " + n(m.unshaded.size()) + " entries";
    if (m.weight.size() != m.vertex.size())
        return "display has " + n(m.vertex.size()) + " vertices but " + n(m.weight.size()) +
               " weights";
    if (m.emitterFraction.size() != m.emitterLight.size())
        return "display has " + n(m.emitterLight.size()) + " emitter lights but " +
               n(m.emitterFraction.size()) + " fractions";
    if (m.vertex.size() > static_cast<size_t>(INT_MAX) ||
        m.emitterLight.size() > static_cast<size_t>(INT_MAX))
        return "display map too large";
    if (auto e = checkRanges(m.start, m.vertex.size(), "display.start"); !e.empty()) return e;
    if (auto e = checkRanges(m.emitterStart, m.emitterLight.size(), "display.emitterStart");
        !e.empty())
        return e;
    const size_t vertices = p.D.size();
    if (vertices > static_cast<size_t>(INT_MAX)) return "too many vertices";
    for (size_t k = 0; k < m.vertex.size(); ++k)
        if (m.vertex[k] < 0 || static_cast<size_t>(m.vertex[k]) >= vertices)
            return "display.vertex[" + n(k) + "] = " + std::to_string(m.vertex[k]) +
                   " is not one of the " + n(vertices) + " vertices";
    const size_t lights = p.photoRadiance.size();
    for (size_t k = 0; k < m.emitterLight.size(); ++k)
        if (m.emitterLight[k] < 0 || static_cast<size_t>(m.emitterLight[k]) >= lights)
            return "display.emitterLight[" + n(k) + "] = " + std::to_string(m.emitterLight[k]) +
                   " is not one of the " + n(lights) + " lights";
    const VertexLighting& l = p.lighting;
    if (l.lights < 0 || static_cast<size_t>(l.lights) != lights)
        return "lighting for " + std::to_string(l.lights) + " lights, the photo has " + n(lights);
    if (l.lights > 0 ? (l.response.size() % lights != 0 || l.response.size() / lights != vertices)
                     : (vertices != 0 || !l.response.empty()))
        return "lighting.response has " + n(l.response.size()) + " entries, not " + n(vertices) +
               " vertices x " + n(lights) + " lights";
    if (p.textureFactor.size() != vertices)
        return "textureFactor has " + n(p.textureFactor.size()) + " entries, not " + n(vertices);
    if (p.confidence.size() != vertices)
        return "confidence has " + n(p.confidence.size()) + " entries, not " + n(vertices);
    for (size_t v = 0; v < vertices; ++v)
        if (!(p.confidence[v] >= 0 && p.confidence[v] <= 1))
            return "confidence[" + n(v) + "] is not in [0, 1]";
    if (!p.pixelDirect.empty() && p.pixelDirect.size() != pixels * lights)
        return "pixelDirect has " + n(p.pixelDirect.size()) + " entries, not " + n(pixels) +
               " pixels x " + n(lights) + " lights";
    if (p.vertexIndirect.size() != (p.pixelDirect.empty() ? 0 : vertices * lights))
        return "vertexIndirect has " + n(p.vertexIndirect.size()) + " entries";
    if (!p.pixelReflectance.empty() &&
        (p.pixelDirect.empty() || p.pixelReflectance.size() != pixels * 3))
        return "pixelReflectance has " + n(p.pixelReflectance.size()) + " entries, not " +
               n(pixels) + " pixels x 3";
    for (const float f : p.pixelReflectance)
        if (!std::isfinite(f)) return "pixelReflectance holds a value that is not finite";
    if (p.pixelNormal.size() != (p.pixelDirect.empty() ? 0 : pixels * 3))
        return "pixelNormal has " + n(p.pixelNormal.size()) + " entries, not " + n(pixels) +
               " pixels x 3";
    for (const float f : p.pixelNormal)
        if (!(std::abs(f) <= 1.0f + 1e-5f)) return "pixelNormal holds a value outside [-1, 1]";
    if (p.skyCoefficient.size() != (p.pixelDirect.empty() ? 0 : lights))
        return "skyCoefficient has " + n(p.skyCoefficient.size()) + " entries, not " + n(lights);
    for (const int k : p.skyCoefficient)
        if (k < -1 || k >= radiosity::kSh9Count)
            return "skyCoefficient holds " + std::to_string(k) + ", not -1 or 0-8";
    if (p.modelReflectance.size() != vertices)
        return "modelReflectance has " + n(p.modelReflectance.size()) + " entries, not " +
               n(vertices);
    if (p.leaves < 0 || p.links < 0) return "negative counts";
    // Bits 0-1: the refinement's budget (bit 1, the time budget, only with bit 0); bit 2:
    // the reflectance rounds' share; bits 3-6: the later phases' shares (prepared.h).
    if (p.budgetReached < 0 || p.budgetReached > 127 || (p.budgetReached & 3) == 2)
        return "budget flag not in 0-127 or bit 1 without bit 0";
    return {};
}

void writePreparedCache(const fs::path& file, const PreparedImage& p, uint64_t key) {
    std::string bytes(kHeaderSize, '\0');
    Writer w(bytes);
    serialize(w, p);
    const uint64_t payload = bytes.size() - kHeaderSize;
    std::memcpy(bytes.data(), kMagic.data(), kMagic.size());
    putAt(bytes, 8, kPreparedFormatVersion);
    putAt(bytes, 12, uint32_t{0});
    putAt(bytes, 16, key);
    putAt(bytes, 24, payload);
    const uint64_t sum = checksum(bytes.data() + kHeaderSize, payload);
    bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);

    const fs::path dir = file.parent_path();
    std::error_code ec;
    if (!dir.empty()) {
        fs::create_directories(dir, ec);
        if (ec)
            throw OutputError(file.string() +
                              ": cannot write the cache: cannot create the folder " + dir.string() +
                              ": " + ec.message());
    }
    // Readers see the old cache or the new one, never part of one; two preparations of one
    // scene at once each write their own temporary file.
    writeBytesAtomic(file, "cannot write the cache", bytes, /*uniqueTemporary=*/true);
}

std::optional<PreparedImage> readPreparedCache(const fs::path& file, uint64_t key,
                                               std::string* why) {
    auto reject = [&](std::string r) -> std::optional<PreparedImage> {
        if (why) *why = std::move(r);
        return std::nullopt;
    };
    try {
        std::error_code ec;
        if (!fs::exists(file, ec)) return reject("no cache at " + file.string());
        if (!fs::is_regular_file(file, ec))
            return reject("cache unreadable: " + file.string() + " is not a file");
        std::ifstream in(file, std::ios::binary);
        if (!in) return reject("cache unreadable: " + std::string(std::strerror(errno)));
        in.seekg(0, std::ios::end);
        const std::streamoff end = in.tellg();
        in.seekg(0, std::ios::beg);
        if (end < 0 || !in) return reject("cache unreadable: cannot get its size");
        const auto size = static_cast<uint64_t>(end);
        if (size == 0) return reject("cache corrupt: empty file");
        std::array<char, kHeaderSize> header{};
        const size_t got = static_cast<size_t>(std::min<uint64_t>(size, kHeaderSize));
        in.read(header.data(), static_cast<std::streamsize>(got));
        if (!in) return reject("cache unreadable: reading its header failed");
        if (got < kMagic.size() || std::memcmp(header.data(), kMagic.data(), kMagic.size()) != 0)
            return reject("cache corrupt: not a relight prepared-state file (wrong magic)");
        if (got < kHeaderSize)
            return reject("cache truncated: " + std::to_string(size) + " bytes, shorter than its " +
                          std::to_string(kHeaderSize) + "-byte header");
        const auto version = getAt<uint32_t>(header.data(), 8);
        if (version != kPreparedFormatVersion)
            return reject("cache of format version " + std::to_string(version) +
                          ", this build reads version " + std::to_string(kPreparedFormatVersion));
        if (getAt<uint64_t>(header.data(), 16) != key)
            return reject("cache stale: inputs changed (scene files, options or program)");
        const auto payload = getAt<uint64_t>(header.data(), 24);
        const uint64_t rest = size - kHeaderSize;  // payload and trailer
        if (payload > std::numeric_limits<uint64_t>::max() - kHeaderSize - kTrailerSize)
            return reject("cache corrupt: its header gives an impossible size");
        const uint64_t expected = kHeaderSize + payload + kTrailerSize;
        if (size < expected)
            return reject("cache truncated: " + std::to_string(size) + " bytes, its header says " +
                          std::to_string(expected));
        if (size > expected)
            return reject("cache corrupt: " + std::to_string(size) + " bytes, its header says " +
                          std::to_string(expected));
        std::string body(static_cast<size_t>(rest), '\0');
        in.read(body.data(), static_cast<std::streamsize>(rest));
        if (!in) return reject("cache unreadable: reading it failed");
        const auto stored = getAt<uint64_t>(body.data(), static_cast<size_t>(payload));
        if (checksum(body.data(), static_cast<size_t>(payload)) != stored)
            return reject("cache corrupt: checksum mismatch");
        PreparedImage p;
        Reader r(body.data(), static_cast<size_t>(payload));
        serialize(r, p);
        if (!r.ok()) return reject("cache corrupt: " + r.error());
        if (r.left() != 0)
            return reject("cache corrupt: " + std::to_string(r.left()) +
                          " bytes after the last field");
        if (std::string e = checkPrepared(p); !e.empty())
            return reject("cache corrupt: inconsistent sizes: " + e);
        packDisplayMap(p.display);  // derived, not stored
        derivePhotoPixels(p);
        return p;
    } catch (const std::exception& e) {
        // bad_alloc and friends: a cache that cannot be read is rebuilt, not fatal.
        return reject(std::string("cache unreadable: ") + e.what());
    }
}

}  // namespace relight
