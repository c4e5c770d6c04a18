// Writing a COLMAP model in its text and binary forms (relight/io/colmap_model.h), as COLMAP
// writes them, so that a scene's camera can be handed to COLMAP's tools and read back.
#include <cstring>
#include <sstream>

#include "relight/io/atomic_write.h"
#include "relight/io/colmap_model.h"

namespace relight::colmap {

namespace fs = std::filesystem;

namespace {

template <typename T>
void put(std::string& bytes, T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes.append(raw, sizeof(T));
}

}  // namespace

void writeText(const fs::path& dir, const Model& model) {
    std::ostringstream cams;
    // 17 significant digits: every double reads back as the same double.
    cams.precision(17);
    cams << "# Camera list with one line of data per camera:\n"
         << "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
         << "# Number of cameras: " << model.cameras.size() << "\n";
    for (const auto& [id, c] : model.cameras) {
        cams << id << " " << c.model << " " << c.width << " " << c.height;
        for (const double p : c.params) cams << " " << p;
        cams << "\n";
    }
    writeTextAtomic(dir / "cameras.txt", cams.str());

    std::ostringstream ims;
    ims.precision(17);
    ims << "# Image list with two lines of data per image:\n"
        << "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
        << "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
        << "# Number of images: " << model.images.size() << "\n";
    for (const Image& im : model.images) {
        ims << im.id;
        for (const double q : im.qvec) ims << " " << q;
        for (const double t : im.tvec) ims << " " << t;
        ims << " " << im.cameraId << " " << im.name << "\n\n";
    }
    writeTextAtomic(dir / "images.txt", ims.str());
}

void writeBinary(const fs::path& dir, const Model& model) {
    std::string cams;
    put<uint64_t>(cams, model.cameras.size());
    for (const auto& [id, c] : model.cameras) {
        put<int32_t>(cams, static_cast<int32_t>(id));
        put<int32_t>(cams, modelId(c.model));
        put<uint64_t>(cams, static_cast<uint64_t>(c.width));
        put<uint64_t>(cams, static_cast<uint64_t>(c.height));
        for (const double p : c.params) put<double>(cams, p);
    }
    writeBytesAtomic(dir / "cameras.bin", "cannot write", cams);

    std::string ims;
    put<uint64_t>(ims, model.images.size());
    for (const Image& im : model.images) {
        put<int32_t>(ims, static_cast<int32_t>(im.id));
        for (const double q : im.qvec) put<double>(ims, q);
        for (const double t : im.tvec) put<double>(ims, t);
        put<int32_t>(ims, static_cast<int32_t>(im.cameraId));
        ims.append(im.name.c_str(), im.name.size() + 1);
        put<uint64_t>(ims, 0);  // no 2D points
    }
    writeBytesAtomic(dir / "images.bin", "cannot write", ims);
}

}  // namespace relight::colmap
