// COLMAP's text model: cameras.txt and images.txt (relight/io/colmap_model.h).
#include "relight/io/colmap_model.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "relight/errors.h"
#include "relight/io/input_file.h"

namespace relight::colmap {

namespace fs = std::filesystem;

namespace {

struct ModelInfo {
    const char* name;
    int params;
};

// COLMAP's camera models in the order of their ids (camera_models.h). The importer converts
// the first five; the others are read so that a model holding them can still be used for
// its other images, and are refused by name only when the chosen image needs one.
constexpr ModelInfo kModels[] = {
    {"SIMPLE_PINHOLE", 3},
    {"PINHOLE", 4},
    {"SIMPLE_RADIAL", 4},
    {"RADIAL", 5},
    {"OPENCV", 8},
    {"OPENCV_FISHEYE", 8},
    {"FULL_OPENCV", 12},
    {"FOV", 5},
    {"SIMPLE_RADIAL_FISHEYE", 4},
    {"RADIAL_FISHEYE", 5},
    {"THIN_PRISM_FISHEYE", 12},
    {"RAD_TAN_THIN_PRISM_FISHEYE", 16},
};
constexpr int kModelCount = static_cast<int>(std::size(kModels));

/// A text file's lines with their numbers, skipping nothing: images.txt's 2D points line
/// may be empty, so blank lines matter there.
class LineReader {
  public:
    explicit LineReader(const fs::path& path) : path_(path), in_(path) {
        requireRegularFile(path, "COLMAP model file", "a COLMAP model file");
        if (!in_) throw InputError(path.string() + ": cannot open");
    }
    bool next(std::string& line) {
        if (!std::getline(in_, line)) return false;
        ++number_;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        return true;
    }
    /// The next line that is neither blank nor a comment.
    bool nextData(std::string& line) {
        while (next(line)) {
            const auto first = line.find_first_not_of(" \t");
            if (first != std::string::npos && line[first] != '#') return true;
        }
        return false;
    }
    std::string where() const { return path_.string() + ":" + std::to_string(number_); }
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(where() + ": " + what);
    }

  private:
    fs::path path_;
    std::ifstream in_;
    int number_ = 0;
};

/// Reads one whitespace-separated field of `fields` as T, failing with the line's place.
/// Numbers are read with strtod, which takes "nan" and "inf", so that those are named as
/// such.
template <typename T>
T field(std::istringstream& fields, const LineReader& lines, const char* what) {
    std::string text;
    if (!(fields >> text)) lines.fail(std::string("missing ") + what);
    T value{};
    if constexpr (std::is_floating_point_v<T>) {
        char* end = nullptr;
        value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0')
            lines.fail(std::string("bad ") + what + " \"" + text + "\"");
        if (!std::isfinite(value)) lines.fail(std::string(what) + " is not finite");
    } else {
        std::istringstream one(text);
        if (!(one >> value) || !one.eof())
            lines.fail(std::string("bad ") + what + " \"" + text + "\"");
    }
    return value;
}

Camera readCameraLine(const std::string& line, const LineReader& lines) {
    std::istringstream fields(line);
    Camera c;
    c.id = field<int64_t>(fields, lines, "CAMERA_ID");
    c.model = field<std::string>(fields, lines, "MODEL");
    c.width = field<int64_t>(fields, lines, "WIDTH");
    c.height = field<int64_t>(fields, lines, "HEIGHT");
    // The binary reader's bound too: a size beyond 2^30 pixels is a damaged line.
    if (c.width <= 0 || c.height <= 0 || c.width > (1 << 30) || c.height > (1 << 30))
        lines.fail("bad camera size " + std::to_string(c.width) + "x" + std::to_string(c.height));
    const int n = paramCount(c.model);
    if (n < 0) lines.fail("unknown camera model \"" + c.model + "\"");
    for (int k = 0; k < n; ++k) c.params.push_back(field<double>(fields, lines, "PARAMS"));
    std::string extra;
    if (fields >> extra)
        lines.fail(c.model + " has " + std::to_string(n) + " parameters, the line has more");
    c.where = lines.where();
    return c;
}

Image readImageLine(const std::string& line, const LineReader& lines) {
    std::istringstream fields(line);
    Image im;
    im.id = field<int64_t>(fields, lines, "IMAGE_ID");
    for (double& q : im.qvec) q = field<double>(fields, lines, "QVEC");
    for (double& t : im.tvec) t = field<double>(fields, lines, "TVEC");
    im.cameraId = field<int64_t>(fields, lines, "CAMERA_ID");
    // The rest of the line is the name; COLMAP writes it last.
    std::getline(fields >> std::ws, im.name);
    while (!im.name.empty() && (im.name.back() == ' ' || im.name.back() == '\t'))
        im.name.pop_back();
    if (im.name.empty()) lines.fail("missing NAME");
    im.where = lines.where();
    return im;
}

}  // namespace

int paramCount(const std::string& model) {
    const int id = modelId(model);
    return id < 0 ? -1 : kModels[id].params;
}

int modelId(const std::string& model) {
    for (int i = 0; i < kModelCount; ++i)
        if (model == kModels[i].name) return i;
    return -1;
}

std::string modelName(int id) {
    return id >= 0 && id < kModelCount ? kModels[id].name : "";
}

const Image& Model::image(const std::string& name) const {
    for (const Image& im : images)
        if (im.name == name) return im;
    std::string some;
    for (size_t i = 0; i < images.size() && i < 5; ++i)
        some += (i ? ", " : "") + ("\"" + images[i].name + "\"");
    if (images.size() > 5) some += ", ...";
    throw InputError(imagesFile.string() + ": no image named \"" + name + "\" (it has " +
                     std::to_string(images.size()) + (images.size() == 1 ? " image" : " images") +
                     (images.empty() ? "" : ": " + some) + ")");
}

const Camera& Model::cameraOf(const Image& image) const {
    const auto it = cameras.find(image.cameraId);
    if (it == cameras.end())
        throw InputError(image.where + ": image \"" + image.name + "\" uses camera " +
                         std::to_string(image.cameraId) + ", which " + camerasFile.string() +
                         " does not define");
    return it->second;
}

Model readText(const fs::path& dir) {
    Model m;
    m.camerasFile = dir / "cameras.txt";
    m.imagesFile = dir / "images.txt";
    LineReader cams(m.camerasFile);
    std::string line;
    while (cams.nextData(line)) {
        Camera c = readCameraLine(line, cams);
        if (m.cameras.count(c.id))
            cams.fail("camera " + std::to_string(c.id) + " defined twice (first at " +
                      m.cameras[c.id].where + ")");
        m.cameras[c.id] = std::move(c);
    }
    LineReader ims(m.imagesFile);
    // Two lines an image: its pose, then its 2D points (possibly empty, not read).
    while (ims.nextData(line)) {
        m.images.push_back(readImageLine(line, ims));
        std::string points;
        ims.next(points);
    }
    return m;
}

Model readModel(const fs::path& dir) {
    std::error_code ec;
    auto has = [&](const fs::path& d, const char* a, const char* b) {
        return fs::is_regular_file(d / a, ec) && fs::is_regular_file(d / b, ec);
    };
    if (!fs::is_directory(dir, ec))
        throw InputError(dir.string() + ": COLMAP model folder not found");
    if (has(dir, "cameras.bin", "images.bin")) return readBinary(dir);
    if (has(dir, "cameras.txt", "images.txt")) return readText(dir);
    std::string hint;
    if (has(dir / "0", "cameras.bin", "images.bin") || has(dir / "0", "cameras.txt", "images.txt"))
        hint = "; its subfolder " + (dir / "0").string() + " holds one";
    throw InputError(dir.string() +
                     ": no COLMAP model (cameras.txt and images.txt, or cameras.bin and "
                     "images.bin)" +
                     hint);
}

}  // namespace relight::colmap
