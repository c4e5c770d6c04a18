// A small log-log line plot written with OpenImageIO (render_line, render_box,
// render_text), for the benchmarks' PNG figures. Text needs a TrueType font (DejaVu
// on Debian); without one the plot is drawn without labels.
#pragma once

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace bench {

struct Colour {
    float r, g, b;
};

struct Series {
    std::string label;
    Colour colour;
    std::vector<std::pair<double, double>> points;  ///< (x, y), both > 0
};

inline bool plotLogLog(const std::string& path, const std::vector<Series>& series,
                       const std::string& xLabel, const std::string& yLabel) {
    const int W = 900, H = 600, left = 90, right = 30, top = 30, bottom = 70;
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto& s : series)
        for (auto [x, y] : s.points)
            if (x > 0 && y > 0) {
                x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y),
                y1 = std::max(y1, y);
            }
    if (!(x0 < x1) || !(y0 < y1)) return false;
    // Whole decades around the data.
    x0 = std::pow(10, std::floor(std::log10(x0))), x1 = std::pow(10, std::ceil(std::log10(x1)));
    y0 = std::pow(10, std::floor(std::log10(y0))), y1 = std::pow(10, std::ceil(std::log10(y1)));
    OIIO::ImageBuf img(OIIO::ImageSpec(W, H, 3, OIIO::TypeDesc::UINT8));
    const float white[3] = {1, 1, 1}, grey[3] = {0.85f, 0.85f, 0.85f}, black[3] = {0, 0, 0};
    OIIO::ImageBufAlgo::fill(img, white);
    auto px = [&](double x) {
        return left + static_cast<int>((std::log10(x) - std::log10(x0)) /
                                       (std::log10(x1) - std::log10(x0)) * (W - left - right));
    };
    auto py = [&](double y) {
        return H - bottom -
               static_cast<int>((std::log10(y) - std::log10(y0)) /
                                (std::log10(y1) - std::log10(y0)) * (H - top - bottom));
    };
    const std::string font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    const bool text = std::filesystem::exists(font);
    for (double d = x0; d <= x1 * 1.0001; d *= 10) {
        OIIO::ImageBufAlgo::render_line(img, px(d), top, px(d), H - bottom, grey);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", d);
        if (text)
            OIIO::ImageBufAlgo::render_text(img, px(d) - 10, H - bottom + 20, buf, 14, font, black);
    }
    for (double d = y0; d <= y1 * 1.0001; d *= 10) {
        OIIO::ImageBufAlgo::render_line(img, left, py(d), W - right, py(d), grey);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", d);
        if (text) OIIO::ImageBufAlgo::render_text(img, 10, py(d) + 5, buf, 14, font, black);
    }
    OIIO::ImageBufAlgo::render_box(img, left, top, W - right, H - bottom, black);
    if (text) {
        OIIO::ImageBufAlgo::render_text(img, W / 2 - 80, H - 20, xLabel, 16, font, black);
        OIIO::ImageBufAlgo::render_text(img, 10, 20, yLabel, 16, font, black);
    }
    int legendY = top + 25;
    for (const auto& s : series) {
        const float c[3] = {s.colour.r, s.colour.g, s.colour.b};
        std::vector<std::pair<double, double>> pts = s.points;
        std::sort(pts.begin(), pts.end());
        for (size_t i = 0; i < pts.size(); ++i) {
            if (!(pts[i].first > 0 && pts[i].second > 0)) continue;
            const int x = px(pts[i].first), y = py(pts[i].second);
            OIIO::ImageBufAlgo::render_box(img, x - 3, y - 3, x + 3, y + 3, c, true);
            if (i > 0 && pts[i - 1].first > 0 && pts[i - 1].second > 0)
                OIIO::ImageBufAlgo::render_line(img, px(pts[i - 1].first), py(pts[i - 1].second), x,
                                                y, c);
        }
        OIIO::ImageBufAlgo::render_box(img, W - right - 330, legendY - 8, W - right - 318,
                                       legendY + 4, c, true);
        if (text)
            OIIO::ImageBufAlgo::render_text(img, W - right - 310, legendY + 4, s.label, 14, font,
                                            black);
        legendY += 22;
    }
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    return img.write(path);
}

}  // namespace bench
