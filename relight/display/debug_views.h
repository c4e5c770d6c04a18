// Debug views: the intermediate images of the relighting pipeline, at the photo's size,
// as the paper shows them (Loscos, Drettakis & Robert 2000, Fig. 10, 11, 14, 17, 18).
//
// Per-vertex quantities (B, D, the texture factors) are interpolated to the pixels with
// the display map (relight/display/ratio_display.h), i.e. with exactly the weights the relit image
// uses; per-leaf quantities (reflectance, shadow class, the element grid) are read from
// the leaf each item-buffer sample falls in (locateSample, as the display map does).
//
//   B            the radiosity of the edit's lighting as the camera sees it, B / pi =
//                rho H / pi: radiance in the photo's units (the photo shows rho H / pi,
//                relight/pipeline/reflectance.h), so it compares with the photo directly; rho the
//                pixel's leaf reflectance after shadow removal, H the vertex irradiance
//                (vertexIrradiance). Fig. 18(b).
//   D            the display correction factor in the same units, rho D / pi with the same
//                rho, so that B / D is the display ratio of Eq. (3). Fig. 17(a), 18(a).
//   T_orig       the photo. Fig. 18(c).
//   T_inter      T_orig k_inter (Eq. (13)): shadows lifted with the reference reflectance.
//   T_final      T_orig k_final: the texture after the umbra correction (Eq. (16)). Fig. 18(e).
//   reflectance  the leaf reflectance rho (linear, no scale).
//   H_photo      with per-pixel light only: the photo's irradiance per pixel as the
//                per-pixel display divides by it (pipeline/pixel_light.h,
//                photoIrradianceAt), in the photo's units; pi T / H_photo is the pixel's
//                reflectance (Loscos et al. 1999, Eq. (2)).
//   mesh         the leaf elements' edges over the dimmed photo. Fig. 10, 11.
//   frontier     occluded leaves (blue) and frontier leaves (green, the paper's colour)
//                over the dimmed photo. Fig. 14(a).
// What pixels without a reflecting surface show (samples that see nothing or a lamp's
// emitting face): B, D and reflectance are black there (no radiosity solution), and where
// a pixel is partly surface they show the mean over its surface part; the textures keep
// the photo there (k = 1, as the relit image keeps it), the overlays show the dimmed photo.
//
// With shadow removal off, T_inter, T_final and frontier do not exist and are skipped.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "radiosity/rgb.h"
#include "relight/io/image.h"
#include "relight/relighting.h"

namespace relight {

struct DebugViews {
    Image B, D;                   ///< linear, photo units (EXR as is, PNG times bdScale)
    Image Torig, Tinter, Tfinal;  ///< linear; Tinter and Tfinal empty without shadow removal
    Image reflectance;            ///< linear, dimensionless
    Image Hphoto;                 ///< linear, photo units; empty without per-pixel light
    Image mesh, frontier;         ///< linear overlays; frontier empty without shadow removal
    /// Per pixel rho / (pi sum_v w_v), 0 without surface: B = bFactor * sum_v w_v H(v) with
    /// the display map's weights, so that a display can draw B for any vertex irradiance.
    Image bFactor;
    /// PNG scale of B and D, the same for both so that their brightness compares: the
    /// 99th percentile of D's luminance over the pixels with a surface maps to 1. D is the
    /// photo's lighting, so the scale is the same for every edit of a prepared scene.
    double bdScale = 1;
};

/// The views for the lights' radiances `radianceNow` (one per light, photo units).
DebugViews computeDebugViews(const Relighting& r, std::span<const radiosity::Rgb> radianceNow);

/// Creates `dir` (and its parents) when missing. Throws OutputError naming it when it cannot
/// be created or is not a folder.
void createDebugViewsFolder(const std::filesystem::path& dir);

/// Computes the views and writes them into `dir` (created if missing): B.exr, B.png, D.exr,
/// D.png, T_orig.png, T_inter.png, T_final.png, reflectance.png, H_photo.exr, mesh.png,
/// frontier.png, mesh_edit.png (`editMesh`, editMeshView(), when given), then index.json listing
/// each file, what it shows and its scale, and the views skipped and why. Every file is written
/// atomically (temporary name, then renamed) and index.json last, so an index lists only complete
/// files. Returns the file names written, index.json last. Throws as createDebugViewsFolder, and
/// OutputError naming the file when one cannot be written.
std::vector<std::string> writeDebugViews(const Relighting& r,
                                         std::span<const radiosity::Rgb> radianceNow,
                                         const std::filesystem::path& dir,
                                         const Image* editMesh = nullptr);

/// The leaf elements' edges over the dimmed photo as the solver's hierarchy stands now (an
/// edit's virtual parts inserted), those of the leaves with ids from `preparedNodes` on
/// (split by the edit: Loscos et al. 2000, Fig. 24(a)) in cyan. writeDebugViews() writes it
/// as mesh_edit.png.
Image editMeshView(const Relighting& r, size_t preparedNodes);

}  // namespace relight
