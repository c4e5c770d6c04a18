// Undistorting a photo taken through a COLMAP lens (SIMPLE_RADIAL, RADIAL, OPENCV) into the
// photo a pinhole camera of the same size would have taken, for the scene format, whose
// photos are undistorted.
//
// The pinhole camera keeps the principal point and the aspect of the focal lengths, and its
// focal lengths are scaled so that every pixel of the new photo sees a point inside the old
// one (COLMAP's image_undistorter with no blank pixels): a black border would read as black
// walls. Barrel distortion (k1 < 0) gives a shorter focal length (a wider view, which keeps
// the middles of the photo's edges and cuts the corners it stretches outwards), pincushion
// (k1 > 0) a longer one (the middles of the edges, drawn inwards, are cut).
//
// Each pixel of the new photo is resampled backwards: its ray's point (x, y) is distorted
// (Lens::distort), projected into the old photo, and read there by bilinear interpolation.
// The fit of the focal length inverts the distortion (Lens::undistort) along the old
// photo's border.
#pragma once

#include <filesystem>
#include <vector>

#include "relight/io/colmap_camera.h"

namespace relight {

/// The pinhole lens (no distortion) of the undistorted photo of `lens` (see above). Throws
/// InputError naming `where` when the distortion folds back inside the photo (no pinhole
/// photo can be made from it).
colmap::Lens undistortedLens(const colmap::Lens& lens, const std::string& where);

/// A photo's pixels as floats, every channel, row-major from the top-left.
struct PixelGrid {
    int width = 0, height = 0, channels = 0;
    std::vector<float> values;
};

/// The photo `pinhole` sees, resampled from `photo` taken through `lens` (bilinear; a
/// point that falls beyond the photo's outermost pixel centres reads the nearest edge
/// pixel). `photo` must have lens.width x lens.height pixels.
PixelGrid undistortPixels(const PixelGrid& photo, const colmap::Lens& lens,
                          const colmap::Lens& pinhole);

/// Reads `photo` (any format OpenImageIO reads; sRGB-encoded 8- and 16-bit files decoded
/// when `srgb`), undistorts it and writes the linear result to `output` (EXR, half floats
/// for an 8-bit photo, floats otherwise) atomically. Throws InputError naming `photo`,
/// OutputError naming `output`.
void undistortPhoto(const std::filesystem::path& photo, bool srgb, const colmap::Lens& lens,
                    const colmap::Lens& pinhole, const std::filesystem::path& output);

}  // namespace relight
