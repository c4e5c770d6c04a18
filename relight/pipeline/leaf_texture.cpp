#include "relight/pipeline/leaf_texture.h"

#include <algorithm>
#include <cmath>

namespace relight {

using radiosity::Rgb;

std::vector<uint8_t> usablePixels(const ItemBuffer& items, const radiosity::Scene& scene,
                                  const Image& photo, int stride) {
    stride = std::max(stride, 1);
    const int w = items.width, hgt = items.height;
    std::vector<uint8_t> usable(static_cast<size_t>(w) * hgt, 0),
        nearEmitter(static_cast<size_t>(w) * hgt, 0);
    // A lamp is tens of times brighter than what it lights: a sliver of its face in a
    // pixel, or its glare one pixel away, ruins that pixel as a sample of the surface.
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < items.spp; ++s) {
                const int p = items.polygon[items.sampleIndex(x, y, s)];
                if (p >= 0 && scene.polygons[p].light >= 0)
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const int xx = x + dx, yy = y + dy;
                            if (xx >= 0 && yy >= 0 && xx < w && yy < hgt)
                                nearEmitter[static_cast<size_t>(yy) * w + xx] = 1;
                        }
            }
    for (int y = 0; y < hgt; y += stride) {
        for (int x = 0; x < w; x += stride) {
            const float* px = photo.at(x, y);
            if (!std::isfinite(px[0]) || !std::isfinite(px[1]) || !std::isfinite(px[2])) continue;
            if (nearEmitter[static_cast<size_t>(y) * w + x]) continue;
            const int p0 = items.polygon[items.sampleIndex(x, y, 0)];
            bool pure = p0 >= 0;
            for (int s = 1; s < items.spp && pure; ++s)
                pure = items.polygon[items.sampleIndex(x, y, s)] == p0;
            usable[static_cast<size_t>(y) * w + x] = pure ? 1 : 0;
        }
    }
    return usable;
}

LeafTexture::LeafTexture(const radiosity::Hierarchy& h, const radiosity::Scene& scene,
                         const ItemBuffer& items, const Image& photo,
                         const std::vector<uint8_t>& usable)
    : h_(h), items_(items), photo_(photo) {
    samples_.resize(h.nodes.size());
    for (int y = 0; y < items.height; ++y)
        for (int x = 0; x < items.width; ++x) {
            if (!usable[static_cast<size_t>(y) * items.width + x]) continue;
            for (int s = 0; s < items.spp; ++s) {
                const int idx = items.sampleIndex(x, y, s);
                const int p = items.polygon[idx];
                if (scene.polygons[p].light >= 0) continue;  // usable: p >= 0
                samples_[h.locateLeaf(p, items.point[idx])].push_back(idx);
            }
        }
}

void LeafTexture::ensure(int node) {
    if (node >= static_cast<int>(samples_.size())) samples_.resize(h_.nodes.size());
}

void LeafTexture::split(int node) {
    const radiosity::Node& n = h_.nodes[node];
    ensure(n.firstChild + n.childCount - 1);
    for (int idx : samples_[node]) {
        const radiosity::Vec3& x = items_.point[idx];
        int child = n.firstChild;  // fallback: rounding may put a point on no child
        for (int k = 0; k < n.childCount; ++k)
            if (radiosity::elementContains(h_.nodes[n.firstChild + k], x, 1e-9)) {
                child = n.firstChild + k;
                break;
            }
        samples_[child].push_back(idx);
    }
    samples_[node].clear();
}

void LeafTexture::merge(int node) {
    const radiosity::Node& n = h_.nodes[node];
    for (int k = 0; k < n.childCount; ++k) {
        auto& c = samples_[n.firstChild + k];
        samples_[node].insert(samples_[node].end(), c.begin(), c.end());
        c.clear();
    }
}

int LeafTexture::samples(int node) const {
    return node < static_cast<int>(samples_.size()) ? static_cast<int>(samples_[node].size()) : 0;
}

std::span<const int> LeafTexture::sampleIndices(int node) const {
    if (node < 0 || node >= static_cast<int>(samples_.size())) return {};
    return samples_[static_cast<size_t>(node)];
}

Rgb LeafTexture::sampleColour(int idx) const {
    const int px = idx / items_.spp;
    const float* c = photo_.at(px % items_.width, px / items_.width);
    return Rgb{c[0], c[1], c[2]};
}

Rgb LeafTexture::colour(int node) const {
    Rgb sum;
    if (samples(node) == 0) return sum;
    for (int idx : samples_[node]) {
        const int px = idx / items_.spp;
        const float* c = photo_.at(px % items_.width, px / items_.width);
        sum += Rgb{c[0], c[1], c[2]};
    }
    return sum * (1.0 / samples_[node].size());
}

}  // namespace relight
