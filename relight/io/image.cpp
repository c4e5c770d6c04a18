#include "relight/io/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "relight/errors.h"
#include "relight/io/atomic_write.h"
#include "relight/io/input_file.h"

namespace relight {

double srgbEncode(double x) {
    x = std::clamp(x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double y) {
    y = std::clamp(y, 0.0, 1.0);
    return y <= 0.04045 ? y / 12.92 : std::pow((y + 0.055) / 1.055, 2.4);
}

Image readImage(const std::filesystem::path& path, bool srgb) {
    requireRegularFile(path, "file", "an image file");
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw InputError(path.string() + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    const int w = spec.width, h = spec.height, nc = spec.nchannels;
    if (w <= 0 || h <= 0 || nc <= 0) throw InputError(path.string() + ": empty image");
    std::vector<float> pixels(static_cast<size_t>(w) * h * nc);
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, pixels.data())) {
        throw InputError(path.string() + ": cannot read pixels: " + in->geterror());
    }
    in->close();
    Image img(w, h);
    for (size_t i = 0; i < static_cast<size_t>(w) * h; ++i) {
        for (int c = 0; c < 3; ++c) {
            float v = pixels[i * nc + std::min(c, nc < 3 ? 0 : c)];
            if (srgb) v = static_cast<float>(srgbDecode(v));
            img.rgb[i * 3 + c] = v;
        }
    }
    return img;
}

std::vector<uint8_t> readMask(const std::filesystem::path& path, int& width, int& height) {
    requireRegularFile(path, "file", "an image file");
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw InputError(path.string() + ": cannot read mask: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    width = spec.width;
    height = spec.height;
    std::vector<uint8_t> all(static_cast<size_t>(width) * height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, all.data()))
        throw InputError(path.string() + ": cannot read mask pixels: " + in->geterror());
    std::vector<uint8_t> mask(static_cast<size_t>(width) * height);
    for (size_t i = 0; i < mask.size(); ++i) mask[i] = all[i * spec.nchannels];
    return mask;
}

void writeImage(const std::filesystem::path& path, const Image& image, double exposureStops) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    const bool isFloat =
        ext == ".exr" || ext == ".hdr" || ext == ".pfm" || ext == ".tif" || ext == ".tiff";
    const double scale = std::exp2(exposureStops);
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw std::runtime_error(path.string() + ": no image writer for '" + ext + "'");
    writeAtomic(path, "cannot write image", [&](const std::filesystem::path& tmp) -> std::string {
        bool ok = false;
        if (isFloat) {
            OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
            if (ext == ".exr") spec.attribute("compression", "zip");
            std::vector<float> px(image.rgb);
            for (float& v : px) v = static_cast<float>(static_cast<double>(v) * scale);
            ok = out->open(tmp.string(), spec) &&
                 out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close();
        } else {
            OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
            std::vector<uint8_t> px(image.rgb.size());
            for (size_t i = 0; i < px.size(); ++i) {
                const double v =
                    std::isfinite(image.rgb[i]) ? static_cast<double>(image.rgb[i]) * scale : 0.0;
                px[i] = static_cast<uint8_t>(std::lround(255.0 * srgbEncode(v)));
            }
            ok = out->open(tmp.string(), spec) &&
                 out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close();
        }
        if (ok) return {};
        const std::string why = out->geterror();
        return why.empty() ? "the image writer failed" : why;
    });
}

}  // namespace relight
