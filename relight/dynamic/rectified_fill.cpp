#include "relight/dynamic/rectified_fill.h"

#include <opencv2/core.hpp>
#include <opencv2/photo.hpp>

#include <algorithm>
#include <cmath>

#include "relight/dynamic/plane_homography.h"

namespace relight {

using radiosity::Vec3;

namespace {

/// Texels per side of a plane's grid, at most: a hole filling most of a 12 MP photo at its
/// pixel footprint (the grid's memory, 16 bytes a texel, stays below 256 MiB).
constexpr int kMaxGridSide = 4096;
/// Normals within this cosine (about 1 degree) are one plane's.
constexpr double kSameNormal = 0.9998;

/// A plane of one surface and its 2D frame; the grid of texels over it.
struct PlaneGrid {
    int surface = -1;
    Vec3 normal{0, 0, 1}, origin{0, 0, 0}, u{1, 0, 0}, v{0, 1, 0};
    double offset = 0;                          ///< normal . x on the plane
    double texel = 0;                           ///< metres per texel
    int a0 = 0, b0 = 0, width = 0, height = 0;  ///< the grid: texels [a0, a0 + width) ...
    std::vector<int> members;                   ///< indices of its hidden points
    /// The grid's continuous texel coordinates (texel centres at +0.5) to the photo's pixels,
    /// and back: the plane's homography (plane_homography.h) after the texel scale.
    cv::Matx33d toImage = cv::Matx33d::eye(), fromImage = cv::Matx33d::eye();

    bool holds(const radiosity::Polygon& p, int s, double tol) const {
        if (s != surface || glm::dot(p.normal, normal) < kSameNormal) return false;
        for (int i = 0; i < p.vertexCount; ++i)
            if (std::abs(glm::dot(normal, p.v[static_cast<size_t>(i)]) - offset) > tol)
                return false;
        return true;
    }
    /// Continuous texel coordinates of the plane's point seen at pixel (x, y) (texel
    /// centres at +0.5): H^-1. False when the pixel's ray runs parallel to the plane or meets
    /// it behind the camera (the homogeneous w of the back-mapped point, whose sign is the
    /// depth's only for points in front: checked again forwards).
    bool coords(double x, double y, double& a, double& b) const {
        const cv::Vec3d p = fromImage * cv::Vec3d(x, y, 1.0);
        if (!(std::abs(p[2]) > 1e-300)) return false;
        a = p[0] / p[2];
        b = p[1] / p[2];
        double xb = 0, yb = 0;
        return applyHomography(toImage, a, b, xb, yb);
    }
    /// Sets the homographies once the grid is placed.
    void setHomography(const Camera& camera) {
        // Texel coordinates (a, b) to metres in the frame: (a0 + a) texel, (b0 + b) texel.
        const cv::Matx33d S(texel, 0, a0 * texel, 0, texel, b0 * texel, 0, 0, 1);
        toImage = planeToImage(camera, PlaneFrame{origin, u, v}) * S;
        fromImage = toImage.inv();
    }
    size_t size() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
};

/// Step 1: the hidden points grouped by surface and plane.
std::vector<PlaneGrid> groupByPlane(const radiosity::Scene& scene,
                                    std::span<const HiddenPoint> points, double tol) {
    std::vector<PlaneGrid> planes;
    for (size_t i = 0; i < points.size(); ++i) {
        const HiddenPoint& h = points[i];
        if (h.polygon < 0 || h.surface < 0) continue;
        const radiosity::Polygon& poly = scene.polygons[static_cast<size_t>(h.polygon)];
        auto found = std::find_if(planes.begin(), planes.end(), [&](const PlaneGrid& g) {
            return g.holds(poly, h.surface, tol);
        });
        if (found == planes.end()) {
            PlaneGrid g;
            g.surface = h.surface;
            g.normal = poly.normal;
            g.offset = glm::dot(poly.normal, poly.v[0]);
            g.origin = h.point - (glm::dot(g.normal, h.point) - g.offset) * g.normal;
            // u along the world axis least aligned with the normal, made orthogonal to it.
            const Vec3 n = glm::abs(g.normal);
            const Vec3 axis = n.x <= n.y && n.x <= n.z ? Vec3{1, 0, 0}
                              : n.y <= n.z             ? Vec3{0, 1, 0}
                                                       : Vec3{0, 0, 1};
            g.u = glm::normalize(axis - glm::dot(axis, g.normal) * g.normal);
            g.v = glm::cross(g.normal, g.u);
            planes.push_back(g);
            found = planes.end() - 1;
        }
        found->members.push_back(static_cast<int>(i));
    }
    return planes;
}

/// Step 2: the texel size (the pixel footprint at the median depth of the plane's hidden
/// points) and the grid over their extent, grown by the margin.
void placeGrid(PlaneGrid& g, const Camera& camera, std::span<const HiddenPoint> points,
               int margin) {
    std::vector<double> depth;
    double amin = 1e300, bmin = 1e300, amax = -1e300, bmax = -1e300;
    for (int m : g.members) {
        const Vec3& x = points[static_cast<size_t>(m)].point;
        double pu = 0, pv = 0, d = 0;
        if (camera.project(x, pu, pv, d) && d > 0) depth.push_back(d);
        amin = std::min(amin, glm::dot(x - g.origin, g.u));
        amax = std::max(amax, glm::dot(x - g.origin, g.u));
        bmin = std::min(bmin, glm::dot(x - g.origin, g.v));
        bmax = std::max(bmax, glm::dot(x - g.origin, g.v));
    }
    std::nth_element(depth.begin(), depth.begin() + static_cast<std::ptrdiff_t>(depth.size() / 2),
                     depth.end());
    const double focal = std::max(1e-9, std::max(camera.fx, camera.fy));
    const double median = depth.empty() ? 1.0 : depth[depth.size() / 2];
    g.texel = std::max(1e-9, median / focal);
    const double ext = std::max(amax - amin, bmax - bmin) / g.texel;
    const double grow = std::max(static_cast<double>(margin), ext);
    const double lo = -static_cast<double>(kMaxGridSide) / 2;
    const double a0 = std::floor(amin / g.texel - grow), b0 = std::floor(bmin / g.texel - grow);
    const double a1 = std::ceil(amax / g.texel + grow), b1 = std::ceil(bmax / g.texel + grow);
    const double centreA = 0.5 * (amin + amax) / g.texel, centreB = 0.5 * (bmin + bmax) / g.texel;
    g.a0 = static_cast<int>(std::max(a0, centreA + lo));
    g.b0 = static_cast<int>(std::max(b0, centreB + lo));
    g.width = static_cast<int>(std::min(a1, centreA - lo)) - g.a0 + 1;
    g.height = static_cast<int>(std::min(b1, centreB - lo)) - g.b0 + 1;
    g.setHomography(camera);
}

/// Max filter of radius r over a w x h mask (separable).
std::vector<char> grow(const std::vector<char>& m, int w, int h, int r) {
    std::vector<char> rows(m.size(), 0), out(m.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (m[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)])
                for (int d = std::max(0, x - r); d <= std::min(w - 1, x + r); ++d)
                    rows[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(d)] =
                        1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (rows[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)])
                for (int d = std::max(0, y - r); d <= std::min(h - 1, y + r); ++d)
                    out[static_cast<size_t>(d) * static_cast<size_t>(w) + static_cast<size_t>(x)] =
                        1;
    return out;
}

/// The plane's texture image: steps 3 and 4's roles and the sources' values.
struct PlaneTexture {
    std::vector<float> value;
    std::vector<FillRole> role;
};

/// Step 3 and the roles of step 4.
PlaneTexture sampleGrid(const PlaneGrid& g, const radiosity::Scene& scene, const PhotoWindow& photo,
                        std::span<const HiddenPoint> points, const RectifiedFillOptions& options) {
    PlaneTexture t;
    const size_t n = g.size();
    t.value.assign(3 * n, 0.0f);
    t.role.assign(n, FillRole::none);
    for (int j = 0; j < g.height; ++j)
        for (int i = 0; i < g.width; ++i) {
            // The texel centre's pixel through the plane's homography: the photo warped
            // into the plane, nearest pixel.
            double pu = 0, pv = 0;
            if (!applyHomography(g.toImage, i + 0.5, j + 0.5, pu, pv)) continue;
            const long x = std::lround(pu) - photo.x0, y = std::lround(pv) - photo.y0;
            if (x < 0 || y < 0 || x >= photo.width || y >= photo.height) continue;
            const size_t w =
                static_cast<size_t>(y) * static_cast<size_t>(photo.width) + static_cast<size_t>(x);
            if (photo.role[w] != FillRole::source || photo.surface[w] != g.surface) continue;
            const int p = photo.polygon[w];
            if (p < 0 ||
                !g.holds(scene.polygons[static_cast<size_t>(p)], g.surface, options.planeTolerance))
                continue;
            const size_t k =
                static_cast<size_t>(j) * static_cast<size_t>(g.width) + static_cast<size_t>(i);
            t.role[k] = FillRole::source;
            for (size_t c = 0; c < 3; ++c) t.value[3 * k + c] = photo.value[3 * w + c];
        }
    // The texels the hidden points read (bilinear: the four around each), and a band around
    // them: every texel there that is not a source is synthesised.
    std::vector<char> needed(n, 0);
    for (int m : g.members) {
        double a = 0, b = 0;
        const HiddenPoint& h = points[static_cast<size_t>(m)];
        if (!g.coords(h.x, h.y, a, b)) continue;
        const int i0 = static_cast<int>(std::floor(a - 0.5)),
                  j0 = static_cast<int>(std::floor(b - 0.5));
        for (int j = j0; j <= j0 + 1; ++j)
            for (int i = i0; i <= i0 + 1; ++i)
                if (i >= 0 && j >= 0 && i < g.width && j < g.height)
                    needed[static_cast<size_t>(j) * static_cast<size_t>(g.width) +
                           static_cast<size_t>(i)] = 1;
    }
    const std::vector<char> band = grow(needed, g.width, g.height, std::max(0, options.bridge));
    for (size_t k = 0; k < n; ++k)
        if (band[k] && t.role[k] != FillRole::source) t.role[k] = FillRole::fill;
    return t;
}

/// Step 4 with OpenCV's inpainting (Telea), channel by channel: everything that is not a
/// source is unknown to it. Returns the texels filled (all, when any source exists).
std::vector<uint8_t> inpaintGrid(const PlaneGrid& g, PlaneTexture& t) {
    const int rows = g.height, cols = g.width;
    cv::Mat unknown(rows, cols, CV_8UC1);
    bool any = false;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < cols; ++i) {
            const size_t k =
                static_cast<size_t>(j) * static_cast<size_t>(cols) + static_cast<size_t>(i);
            const bool source = t.role[k] == FillRole::source;
            any = any || source;
            unknown.at<uint8_t>(j, i) = source ? 0 : 255;
        }
    std::vector<uint8_t> unfilled(g.size(), any ? 0 : 1);
    if (!any) return unfilled;
    // 16-bit channels: Debian's OpenCV 4.6 inpaints 8- and 16-bit single channels reliably
    // (its float path gave values far outside the sources'); 60000 steps over the sources'
    // range keep 5 significant digits.
    float top = 0;
    for (size_t k = 0; k < g.size(); ++k)
        if (t.role[k] == FillRole::source)
            for (size_t c = 0; c < 3; ++c) top = std::max(top, t.value[3 * k + c]);
    const double scale = top > 0 ? 60000.0 / static_cast<double>(top) : 1.0;
    for (int c = 0; c < 3; ++c) {
        cv::Mat channel(rows, cols, CV_16UC1), out;
        for (int j = 0; j < rows; ++j)
            for (int i = 0; i < cols; ++i) {
                const size_t k =
                    static_cast<size_t>(j) * static_cast<size_t>(cols) + static_cast<size_t>(i);
                const double v = static_cast<double>(t.value[3 * k + static_cast<size_t>(c)]);
                channel.at<uint16_t>(j, i) = static_cast<uint16_t>(
                    t.role[k] == FillRole::source ? std::clamp(std::lround(v * scale), 0L, 65535L)
                                                  : 0L);
            }
        cv::inpaint(channel, unknown, out, 3.0, cv::INPAINT_TELEA);
        for (int j = 0; j < rows; ++j)
            for (int i = 0; i < cols; ++i) {
                const size_t k =
                    static_cast<size_t>(j) * static_cast<size_t>(cols) + static_cast<size_t>(i);
                if (t.role[k] == FillRole::fill)
                    t.value[3 * k + static_cast<size_t>(c)] =
                        static_cast<float>(static_cast<double>(out.at<uint16_t>(j, i)) / scale);
            }
    }
    return unfilled;
}

/// Step 5: each hidden point of the plane reads its texture bilinearly, from the texels
/// that hold a value (sources and synthesised texels).
void readBack(const PlaneGrid& g, const PlaneTexture& t, const std::vector<uint8_t>& unfilled,
              std::span<const HiddenPoint> points, RectifiedFillResult& out) {
    const auto holds = [&](int i, int j) {
        if (i < 0 || j < 0 || i >= g.width || j >= g.height) return false;
        const size_t k =
            static_cast<size_t>(j) * static_cast<size_t>(g.width) + static_cast<size_t>(i);
        return t.role[k] == FillRole::source || (t.role[k] == FillRole::fill && !unfilled[k]);
    };
    for (int m : g.members) {
        double a = 0, b = 0;
        const HiddenPoint& h = points[static_cast<size_t>(m)];
        if (!g.coords(h.x, h.y, a, b)) continue;  // left to the caller
        const double fa = a - 0.5, fb = b - 0.5;
        const int i0 = static_cast<int>(std::floor(fa)), j0 = static_cast<int>(std::floor(fb));
        const double wa = fa - i0, wb = fb - j0;
        double sum[3] = {0, 0, 0}, wsum = 0;
        for (int dj = 0; dj <= 1; ++dj)
            for (int di = 0; di <= 1; ++di) {
                if (!holds(i0 + di, j0 + dj)) continue;
                const double w = (di ? wa : 1 - wa) * (dj ? wb : 1 - wb);
                const size_t k = static_cast<size_t>(j0 + dj) * static_cast<size_t>(g.width) +
                                 static_cast<size_t>(i0 + di);
                for (size_t c = 0; c < 3; ++c)
                    sum[c] += w * static_cast<double>(t.value[3 * k + c]);
                wsum += w;
            }
        if (!(wsum > 1e-9)) continue;  // no texel with a value around it: left to the caller
        const size_t o = static_cast<size_t>(m);
        for (size_t c = 0; c < 3; ++c) out.value[3 * o + c] = static_cast<float>(sum[c] / wsum);
        out.filled[o] = 1;
    }
}

}  // namespace

RectifiedFillResult fillRectified(const Camera& camera, const radiosity::Scene& scene,
                                  const PhotoWindow& photo, std::span<const HiddenPoint> points,
                                  const RectifiedFillOptions& options) {
    RectifiedFillResult out;
    out.value.assign(3 * points.size(), 0.0f);
    out.filled.assign(points.size(), 0);
    std::vector<PlaneGrid> planes = groupByPlane(scene, points, options.planeTolerance);
    for (PlaneGrid& g : planes) {
        placeGrid(g, camera, points, options.margin);
        if (g.width <= 0 || g.height <= 0) continue;
        PlaneTexture t = sampleGrid(g, scene, photo, points, options);
        std::vector<uint8_t> unfilled;
        if (options.synthesis == SurfaceSynthesis::inpaint) {
            unfilled = inpaintGrid(g, t);
        } else {
            TextureFillOptions fo;
            fo.block = std::max(1, options.block);
            const std::vector<int> region(g.size(), 0);
            TextureFillResult f = fillTexture({g.width, g.height, t.value, region, t.role}, fo);
            t.value = std::move(f.value);
            unfilled = std::move(f.unfilled);
        }
        readBack(g, t, unfilled, points, out);
        ++out.planes;
    }
    return out;
}

}  // namespace relight
