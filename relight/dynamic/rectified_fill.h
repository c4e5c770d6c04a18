// The reflectance of the surfaces a removed object hid, synthesised in each surface's own
// plane (issue 34; Loscos et al. 1999, §4.4 and §5.3, whose texture generation takes a sample
// of the same surface). In the photo a wall seen at a grazing angle shrinks its pattern with
// distance and bends it at a corner; next to an object standing against it, the pixels
// around the hole are mostly the object's own sides and shadow. So the fill does not work on
// the photo's pixels but on a rectified image of each plane:
//  1. the hidden points (camera rays cast through the model without the object) are grouped
//     by plane: one surface (pipeline/reflectance.h, surfaceOf) and one supporting plane;
//  2. each plane gets a 2D frame (u, v orthonormal in it) and a grid of texels whose size is
//     the photo's pixel footprint at the hidden points (median depth / focal length);
//  3. a texel is a source when its centre projects onto a photo pixel that the caller marks
//     as a sample of that same surface (its item-buffer samples all on it, away from the
//     removed object, lit enough) and whose polygon lies in the plane: the photo shows that
//     very point of the plane. Its value is the pixel's reflectance T / H_photo;
//  4. the texels the hidden points need (and a band around them bridging the guard band the
//     caller keeps free of sources) are synthesised from the plane's sources only:
//     non-parametric sampling (pipeline/texture_fill.h, Efros & Leung with coherent
//     candidates), or, as the baseline to compare with, OpenCV's cv::inpaint (Telea);
//  5. each hidden point reads its plane's texture bilinearly where the plane's homography
//     (relight/dynamic/plane_homography.h) takes its pixel position back into the plane, so
//     the corner lines stay straight.
// Steps 3 and 5 go through one matrix per plane, H = K [R u | R v | R o + t] composed with
// the grid's texel scale (a cv::Matx33d): texel centre to pixel for the sampling (the photo
// warped into the plane, nearest pixel), and H^-1 from each hidden sample's pixel position
// to its texel coordinates (the texture warped into the photo, bilinear).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "radiosity/scene.h"
#include "radiosity/vec.h"
#include "relight/pipeline/camera.h"
#include "relight/pipeline/texture_fill.h"

namespace relight {

/// How the rectified texture of a plane is synthesised.
enum class SurfaceSynthesis : uint8_t {
    exemplar,  ///< non-parametric sampling (pipeline/texture_fill.h)
    inpaint,   ///< OpenCV's cv::inpaint (Telea 2004): diffusion, the baseline
};

/// The photo's pixels around the hole: a window of the photo.
struct PhotoWindow {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    std::span<const float> value;    ///< 3 per pixel: T / H_photo where a source
    std::span<const int> surface;    ///< per pixel: the surface of a source, else -1
    std::span<const int> polygon;    ///< per pixel: a polygon it shows (a source's)
    std::span<const FillRole> role;  ///< per pixel: source or not
};

/// A hidden point: where a camera ray met the model without the removed objects.
struct HiddenPoint {
    radiosity::Vec3 point;
    int polygon = -1;     ///< the scene polygon it lies on
    int surface = -1;     ///< its surface
    double x = 0, y = 0;  ///< the photo position its camera ray went through (pixels)
};

struct RectifiedFillOptions {
    SurfaceSynthesis synthesis = SurfaceSynthesis::exemplar;
    int block = 1;   ///< texture_fill's block (defaultFillBlock of the photo)
    int bridge = 8;  ///< texels synthesised around the needed ones (the guard band's width)
    /// Texels of sample around the hidden points' extent, at least (or that extent).
    int margin = 48;
    double planeTolerance = 1e-4;  ///< metres off a plane still on it
};

struct RectifiedFillResult {
    std::vector<float> value;     ///< 3 per hidden point: its reflectance
    std::vector<uint8_t> filled;  ///< per hidden point: 1 when the plane had sources
    int planes = 0;               ///< planes synthesised
};

RectifiedFillResult fillRectified(const Camera& camera, const radiosity::Scene& scene,
                                  const PhotoWindow& photo, std::span<const HiddenPoint> points,
                                  const RectifiedFillOptions& options = {});

}  // namespace relight
