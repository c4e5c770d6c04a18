#include "relight/pipeline/texture_fill.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace relight {

namespace {

/// splitmix64: a small, well-mixed generator, seeded per pixel (reproducible fill).
struct SplitMix {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    int below(int n) { return static_cast<int>(next() % static_cast<uint64_t>(n)); }
};

/// Half-width of the window the local random candidates are drawn from, pixels.
constexpr int kLocalWindow = 24;

/// The fill, pixel by pixel (the header's algorithm); `origin` gets the source each fill
/// pixel copied (-1: none).
TextureFillResult fillPixels(const TextureFillInput& in, const TextureFillOptions& options,
                             std::vector<int>& origin) {
    const int W = in.width, H = in.height;
    const size_t n = static_cast<size_t>(W) * static_cast<size_t>(H);
    TextureFillResult out;
    out.value.assign(in.value.begin(), in.value.end());
    out.unfilled.assign(n, 0);
    const int r = std::max(1, options.radius);
    const auto isSource = [&](int x, int y, int region) {
        if (x < 0 || y < 0 || x >= W || y >= H) return false;
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x);
        return in.role[i] == FillRole::source && in.region[i] == region;
    };

    // The sources of each region.
    std::unordered_map<int, std::vector<int>> sources;
    for (size_t i = 0; i < n; ++i)
        if (in.role[i] == FillRole::source) sources[in.region[i]].push_back(static_cast<int>(i));

    // Onion-peel order: breadth first from the fill pixels next to a source of their region,
    // through fill pixels of the same region; the rest (no source next to them) after.
    std::vector<char> queued(n, 0);
    std::vector<int> order;
    std::deque<int> queue;
    const auto neighbourSource = [&](int x, int y, int region) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if ((dx || dy) && isSource(x + dx, y + dy, region)) return true;
        return false;
    };
    for (size_t i = 0; i < n; ++i) {
        if (in.role[i] != FillRole::fill) continue;
        const int x = static_cast<int>(i % static_cast<size_t>(W));
        const int y = static_cast<int>(i / static_cast<size_t>(W));
        if (neighbourSource(x, y, in.region[i])) {
            queued[i] = 1;
            queue.push_back(static_cast<int>(i));
        }
    }
    while (!queue.empty()) {
        const int i = queue.front();
        queue.pop_front();
        order.push_back(i);
        const int x = i % W, y = i / W;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= W || ny >= H) continue;
                const size_t j =
                    static_cast<size_t>(ny) * static_cast<size_t>(W) + static_cast<size_t>(nx);
                if (queued[j] || in.role[j] != FillRole::fill ||
                    in.region[j] != in.region[static_cast<size_t>(i)])
                    continue;
                queued[j] = 1;
                queue.push_back(static_cast<int>(j));
            }
    }
    for (size_t i = 0; i < n; ++i)
        if (in.role[i] == FillRole::fill && !queued[i]) order.push_back(static_cast<int>(i));

    // Gaussian weights of the window (Efros & Leung: sigma = window / 6.4, about r / 2).
    const int side = 2 * r + 1;
    std::vector<double> weight(static_cast<size_t>(side * side));
    const double sigma = std::max(0.5, 0.5 * r);
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx)
            weight[static_cast<size_t>((dy + r) * side + dx + r)] =
                std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));

    std::vector<char> known(n, 0);
    origin.assign(n, -1);
    for (size_t i = 0; i < n; ++i) known[i] = in.role[i] == FillRole::source ? 1 : 0;
    std::vector<int> candidates;
    for (int p : order) {
        const size_t pi = static_cast<size_t>(p);
        const int region = in.region[pi];
        const auto found = sources.find(region);
        if (found == sources.end() || found->second.empty()) {
            out.unfilled[pi] = 1;
            ++out.withoutSource;
            continue;
        }
        const std::vector<int>& pool = found->second;
        const int px = p % W, py = p / W;
        SplitMix rng{options.seed ^ (static_cast<uint64_t>(p) * 0x9E3779B97F4A7C15ull)};
        candidates.clear();
        // Coherence: the source next to what each filled neighbour copied.
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                const int nx = px + dx, ny = py + dy;
                if ((!dx && !dy) || nx < 0 || ny < 0 || nx >= W || ny >= H) continue;
                const int o = origin[static_cast<size_t>(ny) * static_cast<size_t>(W) +
                                     static_cast<size_t>(nx)];
                if (o < 0) continue;
                const int cx = o % W - dx, cy = o / W - dy;
                if (isSource(cx, cy, region)) candidates.push_back(cy * W + cx);
            }
        // Random sources: half near the pixel, half anywhere on the surface.
        const int K = std::max(2, options.randomCandidates);
        for (int t = 0, got = 0; t < 3 * K / 2 && got < K / 2; ++t) {
            const int cx = px + rng.below(2 * kLocalWindow + 1) - kLocalWindow;
            const int cy = py + rng.below(2 * kLocalWindow + 1) - kLocalWindow;
            if (!isSource(cx, cy, region)) continue;
            candidates.push_back(cy * W + cx);
            ++got;
        }
        for (int k = 0; k < K / 2; ++k)
            candidates.push_back(
                pool[static_cast<size_t>(rng.below(static_cast<int>(pool.size())))]);

        double best = std::numeric_limits<double>::infinity();
        int bestC = candidates.front();
        for (int c : candidates) {
            const int cx = c % W, cy = c / W;
            double cost = 0, wsum = 0;
            for (int dy = -r; dy <= r; ++dy)
                for (int dx = -r; dx <= r; ++dx) {
                    const int ax = px + dx, ay = py + dy;
                    if (ax < 0 || ay < 0 || ax >= W || ay >= H) continue;
                    const size_t a =
                        static_cast<size_t>(ay) * static_cast<size_t>(W) + static_cast<size_t>(ax);
                    if (!known[a] || in.region[a] != region) continue;
                    if (!isSource(cx + dx, cy + dy, region)) continue;
                    const size_t b = static_cast<size_t>(cy + dy) * static_cast<size_t>(W) +
                                     static_cast<size_t>(cx + dx);
                    const double w = weight[static_cast<size_t>((dy + r) * side + dx + r)];
                    double d2 = 0;
                    for (int ch = 0; ch < 3; ++ch) {
                        const double d = static_cast<double>(out.value[3 * a + ch]) -
                                         static_cast<double>(in.value[3 * b + ch]);
                        d2 += d * d;
                    }
                    cost += w * d2;
                    wsum += w;
                }
            // No overlap: only a last resort.
            const double score = wsum > 0 ? cost / wsum : 1e30;
            if (score < best) {
                best = score;
                bestC = c;
            }
        }
        const size_t b = static_cast<size_t>(bestC);
        for (int ch = 0; ch < 3; ++ch) out.value[3 * pi + ch] = in.value[3 * b + ch];
        origin[pi] = bestC;
        known[pi] = 1;
        ++out.filled;
    }
    return out;
}

}  // namespace

int defaultFillBlock(int width, int height) {
    const double diagonal = std::hypot(static_cast<double>(width), static_cast<double>(height));
    return std::max(1, static_cast<int>(std::lround(diagonal / 800.0)));
}

TextureFillResult fillTexture(const TextureFillInput& in, const TextureFillOptions& options) {
    const int W = in.width, H = in.height;
    const size_t n = W > 0 && H > 0 ? static_cast<size_t>(W) * static_cast<size_t>(H) : 0;
    if (in.value.size() != 3 * n || in.region.size() != n || in.role.size() != n)
        throw std::invalid_argument("fillTexture: " + std::to_string(in.value.size()) +
                                    " values, " + std::to_string(in.region.size()) +
                                    " regions and " + std::to_string(in.role.size()) +
                                    " roles for " + std::to_string(n) + " pixels");
    std::vector<int> origin;
    const int s = std::max(1, options.block);
    if (s == 1) return fillPixels(in, options, origin);

    // Blocks of s x s pixels: a source block is s^2 sources of one region (its value their
    // mean), a fill block any block with a fill pixel (its region their majority's).
    const int CW = (W + s - 1) / s, CH = (H + s - 1) / s;
    const size_t cn = static_cast<size_t>(CW) * static_cast<size_t>(CH);
    std::vector<float> cvalue(3 * cn, 0.0f);
    std::vector<int> cregion(cn, -1);
    std::vector<FillRole> crole(cn, FillRole::none);
    std::unordered_map<int, int> votes;
    for (int cy = 0; cy < CH; ++cy)
        for (int cx = 0; cx < CW; ++cx) {
            const size_t c =
                static_cast<size_t>(cy) * static_cast<size_t>(CW) + static_cast<size_t>(cx);
            votes.clear();
            int sources = 0, pixels = 0, sourceRegion = -1;
            bool oneRegion = true;
            double sum[3] = {0, 0, 0};
            for (int y = cy * s; y < std::min(H, cy * s + s); ++y)
                for (int x = cx * s; x < std::min(W, cx * s + s); ++x) {
                    const size_t i =
                        static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x);
                    ++pixels;
                    if (in.role[i] == FillRole::fill) ++votes[in.region[i]];
                    if (in.role[i] != FillRole::source) continue;
                    if (sources > 0 && in.region[i] != sourceRegion) oneRegion = false;
                    sourceRegion = in.region[i];
                    ++sources;
                    for (int ch = 0; ch < 3; ++ch)
                        sum[ch] += static_cast<double>(in.value[3 * i + ch]);
                }
            if (!votes.empty()) {
                int most = 0;
                for (const auto& [region, count] : votes)
                    if (count > most || (count == most && region < cregion[c])) {
                        most = count;
                        cregion[c] = region;
                    }
                crole[c] = FillRole::fill;
            } else if (sources == s * s && pixels == s * s && oneRegion) {
                crole[c] = FillRole::source;
                cregion[c] = sourceRegion;
                for (int ch = 0; ch < 3; ++ch)
                    cvalue[3 * c + static_cast<size_t>(ch)] = static_cast<float>(sum[ch] / sources);
            }
        }
    const TextureFillResult coarse = fillPixels({CW, CH, cvalue, cregion, crole}, options, origin);

    // Each fill pixel copies the pixel at its place in the block its block copied.
    TextureFillResult out;
    out.value.assign(in.value.begin(), in.value.end());
    out.unfilled.assign(n, 0);
    for (size_t i = 0; i < n; ++i) {
        if (in.role[i] != FillRole::fill) continue;
        const int x = static_cast<int>(i % static_cast<size_t>(W));
        const int y = static_cast<int>(i / static_cast<size_t>(W));
        const size_t c =
            static_cast<size_t>(y / s) * static_cast<size_t>(CW) + static_cast<size_t>(x / s);
        const int o = origin[c];
        if (o < 0) {
            out.unfilled[i] = 1;
            ++out.withoutSource;
            continue;
        }
        const int sx = (o % CW) * s + x % s, sy = (o / CW) * s + y % s;
        const size_t j = static_cast<size_t>(sy) * static_cast<size_t>(W) + static_cast<size_t>(sx);
        const bool exact =
            sx < W && sy < H && in.role[j] == FillRole::source && in.region[j] == in.region[i];
        for (int ch = 0; ch < 3; ++ch)
            out.value[3 * i + static_cast<size_t>(ch)] =
                exact ? in.value[3 * j + static_cast<size_t>(ch)]
                      : coarse.value[3 * static_cast<size_t>(o) + static_cast<size_t>(ch)];
        ++out.filled;
    }
    return out;
}

}  // namespace relight
