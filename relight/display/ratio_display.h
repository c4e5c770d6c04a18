// The ratio display of Loscos, Drettakis & Robert 2000 (Eq. (3), §4.5, §5.3): each pixel
// of the photo texture T is modulated by B/D, the ratio of the current radiosity to the
// display correction factor, both known at the leaf vertices and interpolated across the
// leaves (Gouraud), as the paper's glColor per vertex does.
//
// DisplayMap holds, per pixel, what the display needs from the item buffer: for each leaf
// vertex that shades one of its samples, the sum over those samples of the sample's
// interpolation weight (divided by the samples per pixel); the fraction of samples that see
// each light's emitting face; the fraction that see no reflecting surface (kept as in the
// photo). A light edit then costs one multiply-add per (pixel, vertex) pair.
#pragma once

#include <algorithm>
#include <array>
#include <span>
#include <vector>

#include "radiosity/leaf_mesh.h"
#include "radiosity/scene.h"
#include "relight/io/image.h"
#include "relight/pipeline/item_buffer.h"

namespace relight {

struct DisplayMap {
    /// A run of pixels of one row that share their vertices (up to 4, in the same order, no
    /// emitting face and no unshaded sample): the pixels inside one leaf element. A run
    /// whose vertex[0] is -1 holds pixels read from the general arrays below.
    struct Run {
        int x0 = 0, length = 0;
        std::array<int, 4> vertex{-1, -1, -1, -1};  ///< padded with vertex[0]
    };
    int width = 0, height = 0;
    std::vector<int> start;         ///< per pixel, + 1 at the end: its range of vertex/weight
    std::vector<int> vertex;        ///< leaf vertex ids
    std::vector<float> weight;      ///< interpolation weight x fraction of the pixel
    std::vector<float> unshaded;    ///< per pixel: fraction of samples kept as in the photo
    std::vector<int> emitterStart;  ///< per pixel, + 1: its range of emitterLight/Fraction
    std::vector<int> emitterLight;  ///< light whose emitting face a sample sees
    std::vector<float> emitterFraction;
    // Derived from the arrays above by packDisplayMap(), for renderRatio(): not cached, and
    // empty in a map built by hand (renderRatio then reads the general arrays only).
    std::vector<int> rowRuns;      ///< per row, + 1: its range of runs
    std::vector<Run> runs;         ///< each row's pixels, left to right, in runs
    std::vector<float> runWeight;  ///< per pixel of a leaf run: weights of vertex[1..3]
};

/// The photo per pixel as the per-pixel display's pooled reflectance reads it
/// (relight/pipeline/pixel_light.h, photoPixels): derived from the prepared state, not
/// cached.
struct PhotoPixels {
    std::vector<float> rho;    ///< 3 per pixel: T / (H_photo + delta)
    std::vector<float> light;  ///< per pixel: luminance of H_photo + delta; 0: not drawn
    /// 3 per pixel: the per-channel median of rho over the drawn pixels of its 3 x 3
    /// neighbourhood: the pixel's reference in the pool's "same reflectance" test
    /// (pixel_light.h, pooledReflectance), steadier than a dim pixel's own noisy rho;
    /// empty: rho is used.
    std::vector<float> guide;
    /// Per pixel drawn per pixel and light of the photo: the indirect part of h_l(p), the
    /// vertices' interpolated (RGB, [(pixel * lights + l) * 3 + c]), so that a light edit
    /// reads one value a light instead of interpolating it over the pixel's vertices. Empty
    /// above kMaxPixelTransfers values (a very large photo with many lights).
    std::vector<float> indirect;
};

/// At most this many floats of PhotoPixels::indirect (256 MiB).
inline constexpr size_t kMaxPixelTransfers = size_t{1} << 26;

/// Fills rowRuns, runs and runWeight from the general arrays. Call it again after changing
/// those. A pixel of a leaf run then costs 12 bytes instead of about 56 (its start, its
/// emitter range, its unshaded fraction, 4 vertex ids and 4 weights) and its display ratio
/// is r = r_0 + sum_i w_i (r_i - r_0) over the run's vertices (the interpolation
/// sum_i w_i r_i, as the weights sum to 1: w_0 is not read). This is what makes the edit
/// of a 12 MP photo memory-bound at about 48 bytes a pixel (photo, map, image).
void packDisplayMap(DisplayMap& map);

/// What one sample of the item buffer shows, as the display reads it: nothing (kept as in
/// the photo), the emitting face of light `light`, or a point on the leaf element `leaf`.
struct SampleHit {
    int leaf = -1;   ///< leaf element (node id), or -1
    int light = -1;  ///< light whose emitting face the sample sees, or -1
    bool surface() const { return leaf >= 0; }
};
/// Locates sample `index` (ItemBuffer::sampleIndex) in the hierarchy's leaves.
SampleHit locateSample(const ItemBuffer& items, const radiosity::Hierarchy& h,
                       const radiosity::Scene& scene, int index);

/// Builds the map from the item buffer and the leaf mesh (locates each sample's leaf), in
/// bands of rows in parallel (the same map with any number of threads), and packs it.
DisplayMap buildDisplayMap(const ItemBuffer& items, const radiosity::LeafMesh& mesh,
                           const radiosity::Scene& scene);

/// Weighs each pixel's vertices by what they show in the photo, so that the display divides
/// sums, not averages ratios. A pixel's photo value T is the sum of what its samples show,
/// and a sample shows about rho B_photo (its reflectance times the photo's light). The new
/// pixel is then T sum_s rho_s B_s / sum_s rho_s B_photo,s, which with r = B / B_photo per
/// vertex is sum_k u_k r_k with u_k proportional to w_k rho_k B_photo,k. The plain average
/// sum_k w_k r_k is wrong where a pixel straddles a lit and a dark surface (a silhouette, a
/// shadow's edge): T, almost all from the lit side, would be multiplied by the dark side's
/// large ratio as well (an edge of the Cornell box's short block lit from the side showed
/// 2x the truth's mean). Inside one surface this interpolates B and B_photo apart rather
/// than their ratio. `photoRadiance` per vertex: the luminance of rho B_photo (any positive
/// scale). A pixel keeps its total weight (the share of its samples on surfaces), and its
/// plain weights where every vertex it touches shows nothing in the photo. Repacks the map.
/// The unedited display, r = 1 at every vertex, stays the photo.
void weighByPhotoRadiance(DisplayMap& map, std::span<const double> photoRadiance);

/// Where the photo contradicts the model about a lamp: a pixel the item buffer puts (partly)
/// on light e's emitting face, with e on in the photo, but whose photo value is below half
/// of what those samples would show (sum_e f_e L_e(photo), brightest channel). The lamp is
/// then not where the model has it (calibration error): painting its face there would put
/// a lamp-shaped patch beside the real one, even in the unedited display. Those samples are
/// kept as in the photo instead (moved to `unshaded`). The half is the midpoint between a
/// pixel that shows the face (>= f L: the face plus a surface) and one that shows none of
/// it (a surface, far darker than a lamp). Returns the number of pixels changed.
int trustPhotoAtEmitters(DisplayMap& map, const Image& photo,
                         std::span<const radiosity::Rgb> radianceInPhoto);

/// Per-vertex display ratio r = B/D, channel by channel, guarded where D vanishes (umbra,
/// surfaces no light reaches): r = (B + delta) / (D + delta) with delta = kRatioFloor
/// times the mean of D over the vertices (per channel). Where D >> delta this is B/D to
/// within delta/D; where both vanish it is 1 (nothing changes: the photo is kept); where
/// only D vanishes it is bounded by B/delta instead of infinite. Dimensionless.
constexpr double kRatioFloor = 1e-4;
/// delta above: kRatioFloor times the mean of D over the vertices, per channel (a tiny
/// positive number where every D is 0, a scene without light). Shadow removal closes its
/// texture factor with the same floor, so that the unedited display is exact.
radiosity::Rgb ratioFloor(std::span<const radiosity::Rgb> D);
/// One channel of the guarded ratio (B + delta) / (D + delta), negative B and D as 0.
inline double guardedRatio(double B, double D, double delta) {
    return (std::max(B, 0.0) + delta) / (std::max(D, 0.0) + delta);
}
std::vector<radiosity::Rgb> displayRatio(std::span<const radiosity::Rgb> B,
                                         std::span<const radiosity::Rgb> D);

/// One pixel of renderRatio() from the general arrays (any mix of vertices, emitting faces
/// and unshaded samples), `ratio` and `added` (null: none) per vertex as floats (RGB and
/// padding): what renderRatio() does at the pixels outside the leaf runs, and what the
/// per-pixel display's fast path (pipeline/pixel_light_table.h) does at the pixels it does
/// not draw.
void ratioPixel(const DisplayMap& map, const Image& photo, size_t px,
                const std::array<float, 4>* ratio, const std::array<float, 4>* added,
                std::span<const radiosity::Rgb> radianceNow,
                std::span<const radiosity::Rgb> radianceInPhoto, Image& out);

/// The relit image: per pixel
///   out = max(0, T_rest * rbar + sum_e f_e L_e(now)),   T_rest = T - sum_e f_e L_e(photo)
/// where rbar is the mean display ratio over the pixel's non-emitter samples (ratio 1 for
/// the unshaded ones) and f_e the fraction of samples that see light e's emitting face:
/// a light's face shows its current radiance (spec), the rest of the pixel is the photo
/// modulated by B/D.
Image renderRatio(const DisplayMap& map, const Image& photo, std::span<const radiosity::Rgb> ratio,
                  std::span<const radiosity::Rgb> radianceNow,
                  std::span<const radiosity::Rgb> radianceInPhoto);
/// The same into `out` (resized when its size is not the map's): a display that renders
/// edit after edit reuses its image, which saves allocating and clearing it each time
/// (at 12 MP that is 144 MB). Rows run in parallel (TBB); each pixel is computed alone, in
/// float, so the image is the same with any number of threads.
/// `added` (empty, or one per vertex): a radiance added to the modulated photo, interpolated
/// with the same weights, signed (the confidence display's model term, relight/prepared.h):
///   out = max(0, T_rest * rbar + abar + sum_e f_e L_e(now)).
/// `leafRuns` false leaves the pixels of the packed map's leaf runs as they are: the
/// per-pixel display draws every one of them (shownPerPixel) and needs the ratio display
/// only at the others (lamps' faces, the sky, edges).
void renderRatio(const DisplayMap& map, const Image& photo, std::span<const radiosity::Rgb> ratio,
                 std::span<const radiosity::Rgb> radianceNow,
                 std::span<const radiosity::Rgb> radianceInPhoto, Image& out,
                 std::span<const radiosity::Rgb> added = {}, bool leafRuns = true);

}  // namespace relight
