// Image: linear float RGB images, read and written with OpenImageIO only.
//
// Writing is atomic: the image goes to a temporary file beside the target, which is then
// renamed over it, so a failed write never leaves a half-written or corrupted file.
// EXR (and other float formats) store linear values. PNG/JPEG/8-bit TIFF store the linear
// values through the sRGB transfer function, clipped to [0, 1], after an optional
// exposure scale of 2^stops.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "radiosity/rgb.h"

namespace relight {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;  ///< 3 floats per pixel, row-major from the top-left, linear

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * h * 3, 0.0f) {}
    float* at(int x, int y) { return &rgb[(static_cast<size_t>(y) * width + x) * 3]; }
    const float* at(int x, int y) const { return &rgb[(static_cast<size_t>(y) * width + x) * 3]; }
};

/// sRGB transfer function (IEC 61966-2-1): linear in [0, 1] -> encoded in [0, 1].
double srgbEncode(double linear);
/// Its inverse: encoded in [0, 1] -> linear.
double srgbDecode(double encoded);

/// Reads an image as linear RGB (grey images are replicated, alpha dropped). `srgb`
/// decodes the values with the sRGB transfer function. Throws relight::InputError naming
/// the file when it is missing or unreadable.
Image readImage(const std::filesystem::path& path, bool srgb = false);

/// Reads an 8-bit mask (first channel), values 0..255.
std::vector<uint8_t> readMask(const std::filesystem::path& path, int& width, int& height);

/// Writes atomically (relight/io/atomic_write.h); the format follows the extension (.exr,
/// .png, ...). Throws OutputError naming the file when it cannot be written, and
/// std::runtime_error for an extension no image writer knows.
void writeImage(const std::filesystem::path& path, const Image& image, double exposureStops = 0);

}  // namespace relight
