// COLMAP's binary model: cameras.bin and images.bin (relight/io/colmap_model.h), little-endian
// as COLMAP writes them:
//   cameras.bin: uint64 count; per camera int32 id, int32 model id, uint64 width, uint64
//                height, double params[n(model)]
//   images.bin:  uint64 count; per image int32 id, double qvec[4], double tvec[3], int32
//                camera id, the name ending in '\0', uint64 n, n x (double x, double y,
//                int64 point3D id)
// Binary files have no lines: messages name the record and its byte offset.
#include <bit>
#include <cmath>
#include <fstream>

#include "relight/errors.h"
#include "relight/io/colmap_model.h"
#include "relight/io/input_file.h"

namespace relight::colmap {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little,
              "COLMAP's binary files are little-endian; this reader reads them as they are");

namespace {

/// Reads fixed-size values from a binary file, keeping the offset for messages.
class BinaryReader {
  public:
    explicit BinaryReader(const fs::path& path) : path_(path) {
        requireRegularFile(path, "COLMAP model file", "a COLMAP model file");
        in_.open(path, std::ios::binary);
        if (!in_) throw InputError(path.string() + ": cannot open");
        std::error_code ec;
        size_ = fs::file_size(path, ec);
    }
    template <typename T>
    T read(const std::string& what) {
        T value{};
        if (!in_.read(reinterpret_cast<char*>(&value), sizeof(T)))
            fail(what + ": the file ends at byte " + std::to_string(size_));
        offset_ += sizeof(T);
        return value;
    }
    double readFinite(const std::string& what) {
        const double v = read<double>(what);
        if (!std::isfinite(v)) fail(what + " is not finite");
        return v;
    }
    std::string readName(const std::string& what) {
        std::string name;
        if (!std::getline(in_, name, '\0'))
            fail(what + ": the file ends at byte " + std::to_string(size_));
        offset_ += name.size() + 1;
        return name;
    }
    /// Skips `count` records of `bytes` each, failing when the file is shorter.
    void skip(uint64_t count, uint64_t bytes, const std::string& what) {
        if (count > (size_ - offset_) / bytes)
            fail(what + ": " + std::to_string(count) + " entries of " + std::to_string(bytes) +
                 " bytes do not fit in the file's last " + std::to_string(size_ - offset_) +
                 " bytes");
        in_.seekg(static_cast<std::streamoff>(count * bytes), std::ios::cur);
        offset_ += count * bytes;
    }
    void expectEnd() {
        if (offset_ != size_)
            fail(std::to_string(size_ - offset_) + " bytes after the last record");
    }
    uint64_t offset() const { return offset_; }
    const fs::path& path() const { return path_; }
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(path_.string() + ": " + what);
    }

  private:
    fs::path path_;
    std::ifstream in_;
    uint64_t size_ = 0, offset_ = 0;
};

std::string record(const char* kind, uint64_t k, uint64_t offset) {
    return std::string(kind) + " record " + std::to_string(k) + " (byte " + std::to_string(offset) +
           ")";
}

Camera readCameraRecord(BinaryReader& in, uint64_t k) {
    const std::string where = record("camera", k, in.offset());
    Camera c;
    c.id = in.read<int32_t>(where);
    const int32_t model = in.read<int32_t>(where);
    c.model = modelName(model);
    if (c.model.empty()) in.fail(where + ": unknown camera model id " + std::to_string(model));
    const uint64_t w = in.read<uint64_t>(where), h = in.read<uint64_t>(where);
    if (w == 0 || h == 0 || w > (1u << 30) || h > (1u << 30))
        in.fail(where + ": bad camera size " + std::to_string(w) + "x" + std::to_string(h));
    c.width = static_cast<int64_t>(w);
    c.height = static_cast<int64_t>(h);
    for (int p = 0; p < paramCount(c.model); ++p) c.params.push_back(in.readFinite(where));
    c.where = in.path().string() + ": " + where;
    return c;
}

Image readImageRecord(BinaryReader& in, uint64_t k) {
    const std::string where = record("image", k, in.offset());
    Image im;
    im.id = in.read<int32_t>(where);
    for (double& q : im.qvec) q = in.readFinite(where);
    for (double& t : im.tvec) t = in.readFinite(where);
    im.cameraId = in.read<int32_t>(where);
    im.name = in.readName(where);
    if (im.name.empty()) in.fail(where + ": empty image name");
    const uint64_t points = in.read<uint64_t>(where);
    in.skip(points, 2 * sizeof(double) + sizeof(int64_t), where + ": its 2D points");
    im.where = in.path().string() + ": " + where;
    return im;
}

}  // namespace

Model readBinary(const fs::path& dir) {
    Model m;
    m.camerasFile = dir / "cameras.bin";
    m.imagesFile = dir / "images.bin";
    BinaryReader cams(m.camerasFile);
    const uint64_t numCameras = cams.read<uint64_t>("the camera count");
    // A count beyond the file's records fails at the first record that is not there.
    for (uint64_t k = 0; k < numCameras; ++k) {
        Camera c = readCameraRecord(cams, k);
        if (m.cameras.count(c.id))
            cams.fail(c.where + ": camera " + std::to_string(c.id) + " defined twice");
        m.cameras[c.id] = std::move(c);
    }
    cams.expectEnd();
    BinaryReader ims(m.imagesFile);
    const uint64_t numImages = ims.read<uint64_t>("the image count");
    for (uint64_t k = 0; k < numImages; ++k) m.images.push_back(readImageRecord(ims, k));
    ims.expectEnd();
    return m;
}

}  // namespace relight::colmap
