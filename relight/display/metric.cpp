#include "relight/display/metric.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace relight {

Score scoreImage(const Image& R, const Image& T, const Image& P, const std::vector<uint8_t>& maskT,
                 const std::vector<uint8_t>& maskP, Image* errorMap) {
    const int w = T.width, h = T.height;
    const size_t n = static_cast<size_t>(w) * h;
    if (R.width != w || R.height != h || P.width != w || P.height != h || maskT.size() != n ||
        maskP.size() != n)
        throw std::invalid_argument("scoreImage: images and masks must have the same size");
    double sq = 0, sumT = 0, sqC = 0, sumTC = 0;
    Score s;
    std::vector<double> blockRms(static_cast<size_t>(w / 4) * (h / 4), -1.0);
    for (int by = 0; by < h / 4; ++by) {
        for (int bx = 0; bx < w / 4; ++bx) {
            double r[3] = {0, 0, 0}, t[3] = {0, 0, 0}, p[3] = {0, 0, 0};
            bool keep = true;
            for (int y = by * 4; y < by * 4 + 4 && keep; ++y) {
                for (int x = bx * 4; x < bx * 4 + 4; ++x) {
                    const size_t i = static_cast<size_t>(y) * w + x;
                    if (maskT[i] != 255 || maskP[i] != 255) {
                        keep = false;
                        break;
                    }
                    for (int c = 0; c < 3; ++c) {
                        r[c] += static_cast<double>(R.at(x, y)[c]) / 16;
                        t[c] += static_cast<double>(T.at(x, y)[c]) / 16;
                        p[c] += static_cast<double>(P.at(x, y)[c]) / 16;
                    }
                }
            }
            if (!keep) continue;
            ++s.blocks;
            double diffTP = 0, meanT = 0, blockSq = 0;
            for (int c = 0; c < 3; ++c) {
                blockSq += (r[c] - t[c]) * (r[c] - t[c]);
                diffTP += std::abs(t[c] - p[c]) / 3;
                meanT += t[c] / 3;
            }
            sq += blockSq;
            blockRms[static_cast<size_t>(by) * (w / 4) + bx] = std::sqrt(blockSq / 3);
            sumT += 3 * meanT;
            if (diffTP > 0.1 * meanT) {
                ++s.changedBlocks;
                sqC += blockSq;
                sumTC += 3 * meanT;
            }
        }
    }
    // Guards: no kept block, or a black truth, leave the score at 0 / undefined.
    if (s.blocks > 0 && sumT > 0) {
        const double m = 3.0 * s.blocks;
        s.relRmse = std::sqrt(sq / m) / (sumT / m);
    }
    if (errorMap) {
        *errorMap = Image(w / 4, h / 4);
        const double meanT = s.blocks > 0 ? sumT / (3.0 * s.blocks) : 0;
        for (int by = 0; by < h / 4; ++by)
            for (int bx = 0; bx < w / 4; ++bx) {
                const double e = blockRms[static_cast<size_t>(by) * (w / 4) + bx];
                float* px = errorMap->at(bx, by);
                if (e < 0 || !(meanT > 0)) {
                    px[0] = px[1] = 0;
                    px[2] = 0.05f;
                } else {
                    px[0] = px[1] = px[2] = static_cast<float>(e / meanT);
                }
            }
    }
    if (s.changedBlocks > 0 && sumTC > 0) {
        const double m = 3.0 * s.changedBlocks;
        s.changedRelRmse = std::sqrt(sqC / m) / (sumTC / m);
        s.hasChanged = true;
    }
    return s;
}

double relativeRmsDifference(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size())
        throw std::invalid_argument("relativeRmsDifference: images of different sizes");
    double se = 0, sum = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        const double d = static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i]);
        se += d * d;
        sum += static_cast<double>(b.rgb[i]);
    }
    const double n = static_cast<double>(std::max<size_t>(a.rgb.size(), 1));
    return sum > 0 ? std::sqrt(se / n) / (sum / n) : 0;
}

}  // namespace relight
