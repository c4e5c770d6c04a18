#include "relight/io/undistort.h"

#include <OpenImageIO/imageio.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "relight/errors.h"
#include "relight/io/atomic_write.h"
#include "relight/io/image.h"
#include "relight/io/input_file.h"

namespace relight {

namespace fs = std::filesystem;
using colmap::Lens;

namespace {

/// The undistorted (x, y) of the old photo's pixel (u, v); throws when Newton's method finds
/// none (the distortion folds back before this pixel).
void undistortPixel(const Lens& lens, double u, double v, double& x, double& y,
                    const std::string& where) {
    if (!lens.undistort((u - lens.cx) / lens.fx, (v - lens.cy) / lens.fy, x, y))
        throw InputError(where + ": the lens distortion folds back inside the photo (at pixel " +
                         std::to_string(static_cast<int>(u)) + ", " +
                         std::to_string(static_cast<int>(v)) +
                         "): no pinhole photo can be made from it");
}

}  // namespace

Lens undistortedLens(const Lens& lens, const std::string& where) {
    const double right = lens.width - 1, bottom = lens.height - 1;
    if (!(lens.cx > 0 && lens.cx < right && lens.cy > 0 && lens.cy < bottom))
        throw InputError(where + ": the principal point lies outside the photo");
    // The largest rectangle (in undistorted x, y) about the principal point inside the old
    // photo's outermost pixel centres, bounded by the innermost point of each edge.
    double xMin = -1e300, xMax = 1e300, yMin = -1e300, yMax = 1e300;
    const int steps = std::max(lens.width, lens.height);
    for (int i = 0; i <= steps; ++i) {
        const double u = right * i / steps, v = bottom * i / steps;
        double x = 0, y = 0;
        undistortPixel(lens, 0, v, x, y, where);
        xMin = std::max(xMin, x);
        undistortPixel(lens, right, v, x, y, where);
        xMax = std::min(xMax, x);
        undistortPixel(lens, u, 0, x, y, where);
        yMin = std::max(yMin, y);
        undistortPixel(lens, u, bottom, x, y, where);
        yMax = std::min(yMax, y);
    }
    if (!(xMin < 0 && xMax > 0 && yMin < 0 && yMax > 0))
        throw InputError(where + ": the undistorted photo does not surround its principal point");
    // The pinhole photo's outermost pixel centres at focal lengths s fx, s fy fall inside
    // that rectangle for the smallest s that meets all four edges.
    const double s = std::max({(-lens.cx / lens.fx) / xMin, ((right - lens.cx) / lens.fx) / xMax,
                               (-lens.cy / lens.fy) / yMin, ((bottom - lens.cy) / lens.fy) / yMax});
    Lens pinhole = lens;
    pinhole.k1 = pinhole.k2 = pinhole.p1 = pinhole.p2 = 0;
    pinhole.fx = lens.fx * s;
    pinhole.fy = lens.fy * s;
    return pinhole;
}

namespace {

/// `photo` read at (u, v) (pixel centres at integers, inside [0, w - 1] x [0, h - 1]) by
/// bilinear interpolation, into `dst`.
void sampleBilinear(const PixelGrid& photo, double u, double v, float* dst) {
    const size_t nc = static_cast<size_t>(photo.channels);
    // The cell's top-left corner, one short of the last row and column so that a point on
    // the far edge reads it with weight 1.
    const int u0 = std::min(static_cast<int>(u), std::max(photo.width - 2, 0));
    const int v0 = std::min(static_cast<int>(v), std::max(photo.height - 2, 0));
    const int u1 = std::min(u0 + 1, photo.width - 1), v1 = std::min(v0 + 1, photo.height - 1);
    const double a = u - u0, b = v - v0;
    auto at = [&](int x, int y) {
        return &photo.values[(static_cast<size_t>(y) * photo.width + x) * nc];
    };
    const float *p00 = at(u0, v0), *p10 = at(u1, v0), *p01 = at(u0, v1), *p11 = at(u1, v1);
    for (size_t c = 0; c < nc; ++c) {
        const double top = (1 - a) * double{p00[c]} + a * double{p10[c]};
        const double bottom = (1 - a) * double{p01[c]} + a * double{p11[c]};
        dst[c] = static_cast<float>((1 - b) * top + b * bottom);
    }
}

}  // namespace

PixelGrid undistortPixels(const PixelGrid& photo, const Lens& lens, const Lens& pinhole) {
    PixelGrid out;
    out.width = pinhole.width;
    out.height = pinhole.height;
    out.channels = photo.channels;
    const size_t nc = static_cast<size_t>(photo.channels);
    out.values.assign(static_cast<size_t>(out.width) * out.height * nc, 0.0f);
    const double uMax = photo.width - 1, vMax = photo.height - 1;
    tbb::parallel_for(0, out.height, [&](int row) {
        for (int col = 0; col < out.width; ++col) {
            double xd = 0, yd = 0;
            lens.distort((col - pinhole.cx) / pinhole.fx, (row - pinhole.cy) / pinhole.fy, xd, yd);
            // The fitted pinhole lands inside; clamping only catches the last rounding.
            const double u = std::clamp(lens.fx * xd + lens.cx, 0.0, uMax);
            const double v = std::clamp(lens.fy * yd + lens.cy, 0.0, vMax);
            sampleBilinear(photo, u, v,
                           &out.values[(static_cast<size_t>(row) * out.width + col) * nc]);
        }
    });
    return out;
}

namespace {

/// The photo's colour channels (RGB, or one grey channel; alpha dropped) as floats.
PixelGrid readPixels(const fs::path& path, bool srgb, bool& eightBit) {
    requireRegularFile(path, "photo", "a photo");
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw InputError(path.string() + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    PixelGrid g;
    g.width = spec.width;
    g.height = spec.height;
    g.channels = spec.nchannels >= 3 ? 3 : 1;
    eightBit = spec.format.size() == 1;
    g.values.resize(static_cast<size_t>(g.width) * g.height * g.channels);
    if (!in->read_image(0, 0, 0, g.channels, OIIO::TypeDesc::FLOAT, g.values.data()))
        throw InputError(path.string() + ": cannot read pixels: " + in->geterror());
    if (srgb)
        for (float& value : g.values) value = static_cast<float>(srgbDecode(value));
    return g;
}

}  // namespace

void undistortPhoto(const fs::path& photo, bool srgb, const Lens& lens, const Lens& pinhole,
                    const fs::path& output) {
    bool eightBit = false;
    const PixelGrid in = readPixels(photo, srgb, eightBit);
    if (in.width != lens.width || in.height != lens.height)
        throw InputError(photo.string() + ": photo is " + std::to_string(in.width) + "x" +
                         std::to_string(in.height) + " but its camera is " +
                         std::to_string(lens.width) + "x" + std::to_string(lens.height));
    const PixelGrid out = undistortPixels(in, lens, pinhole);
    // Half floats hold an 8-bit photo's every level (11 significant bits); floats the rest.
    const OIIO::TypeDesc type = eightBit ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
    writeAtomic(output, "cannot write image", [&](const fs::path& tmp) -> std::string {
        auto writer = OIIO::ImageOutput::create(tmp.string());
        if (!writer) return "no image writer: " + OIIO::geterror();
        OIIO::ImageSpec spec(out.width, out.height, out.channels, type);
        spec.attribute("compression", "zip");
        if (writer->open(tmp.string(), spec) &&
            writer->write_image(OIIO::TypeDesc::FLOAT, out.values.data()) && writer->close())
            return {};
        const std::string why = writer->geterror();
        return why.empty() ? "the image writer failed" : why;
    });
}

}  // namespace relight
