#include "relight/pipeline/photo_merge.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "radiosity/parallel.h"
#include "relight/pipeline/pixel_light.h"

namespace relight {

using radiosity::Rgb;

PhotoMerge mergePhotos(const DisplayMap& map, std::span<const MergePhoto> photos,
                       std::span<const float> pixelDirect, std::span<const Rgb> indirect,
                       const Rgb& delta) {
    const size_t W = static_cast<size_t>(map.width), Hgt = static_cast<size_t>(map.height);
    const size_t pixels = W * Hgt;
    if (photos.empty()) throw std::invalid_argument("mergePhotos: no photo");
    const size_t L = photos[0].radiance.size();
    if (pixelDirect.size() != pixels * L || (L > 0 && indirect.size() % L != 0))
        throw std::invalid_argument("mergePhotos: " + std::to_string(pixelDirect.size()) +
                                    " direct values for " + std::to_string(pixels) + " pixels x " +
                                    std::to_string(L) + " lights");
    for (const MergePhoto& ph : photos)
        if (!ph.image || ph.image->width != map.width || ph.image->height != map.height ||
            ph.radiance.size() != L)
            throw std::invalid_argument("mergePhotos: a photo of another size or light count");

    std::vector<float> num(pixels * 3, 0.0f), den(pixels, 0.0f), first(pixels, 0.0f);
    std::vector<float> first0(pixels * 3, 0.0f);  // T_0 / (H_0 + delta): the fallback
    std::vector<float> dirLum(pixels);
    std::vector<Rgb> total(pixels);
    // Per pixel of the current photo: its confidence K and reading.
    std::vector<float> conf(pixels), read(pixels * 3);
    PhotoMerge m;
    for (size_t i = 0; i < photos.size(); ++i) {
        const Image& T = *photos[i].image;
        std::fill(conf.begin(), conf.end(), 0.0f);
        radiosity::parallelFor(pixels, 256, [&](size_t px) {
            if (!shownPerPixel(map, px)) {
                dirLum[px] = -1.0f;
                return;
            }
            Rgb direct;
            total[px] =
                photoIrradianceAt(map, px, pixelDirect, indirect, photos[i].radiance, &direct);
            dirLum[px] = static_cast<float>(direct.luminance());
        });
        radiosity::parallelFor(pixels, 256, [&](size_t px) {
            const float d = dirLum[px];
            if (d < 0) return;
            const float* t = T.rgb.data() + px * 3;
            Rgb reading;
            for (int c = 0; c < 3; ++c)
                reading[c] = static_cast<double>(t[c]) / (std::max(total[px][c], 0.0) + delta[c]);
            if (i == 0)
                for (int c = 0; c < 3; ++c) first0[px * 3 + c] = static_cast<float>(reading[c]);
            // Pixel value: a reading from a value that is not finite or negative says nothing.
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(t[c]) || t[c] < 0) return;
            // Shadow boundary: a neighbour's direct light more than kBoundaryContrast apart.
            const size_t x = px % W, y = px / W;
            const size_t nb[4] = {x > 0 ? px - 1 : px, x + 1 < W ? px + 1 : px, y > 0 ? px - W : px,
                                  y + 1 < Hgt ? px + W : px};
            for (size_t q : nb) {
                const float e = dirLum[q];
                if (e < 0) continue;
                if (std::abs(static_cast<double>(d - e)) >
                    kBoundaryContrast * static_cast<double>(std::max(d, e)))
                    return;
            }
            // Light ratio: the photo counts as its lamps' direct light at the pixel, and
            // more where that is most of its light.
            const double tot = total[px].luminance();
            const double K = tot > 0 ? static_cast<double>(d) * (static_cast<double>(d) / tot) : 0;
            if (!(K > 0)) return;
            conf[px] = static_cast<float>(K);
            for (int c = 0; c < 3; ++c) read[px * 3 + c] = static_cast<float>(reading[c]);
        });
        for (size_t px = 0; px < pixels; ++px) {
            if (!(conf[px] > 0)) continue;
            for (int c = 0; c < 3; ++c) num[px * 3 + c] += conf[px] * read[px * 3 + c];
            den[px] += conf[px];
            if (i == 0) first[px] = conf[px];
        }
    }
    m.reflectance.assign(pixels * 3, 0.0f);
    double share = 0;
    for (size_t px = 0; px < pixels; ++px) {
        if (!shownPerPixel(map, px)) continue;
        ++m.pixels;
        if (den[px] > 0) {
            for (int c = 0; c < 3; ++c) m.reflectance[px * 3 + c] = num[px * 3 + c] / den[px];
            share += static_cast<double>(first[px] / den[px]);
        } else {
            // No photo says anything with confidence: the first photo's own reading.
            for (int c = 0; c < 3; ++c) m.reflectance[px * 3 + c] = first0[px * 3 + c];
            share += 1;
        }
    }
    m.firstPhotoShare = m.pixels > 0 ? share / m.pixels : 1.0;
    return m;
}

}  // namespace relight
