#include "radiosity/reference_solver.h"

#include <cmath>
#include <cstdio>

#include "radiosity/parallel.h"
#include "radiosity/stopwatch.h"

namespace radiosity {

ReferenceSolver::ReferenceSolver(const Scene& scene, ReferenceOptions options)
    : scene_(scene), options_(std::move(options)), h_(scene_) {
    vis_ = std::make_unique<Visibility>(scene_);
    TransferOptions t;
    t.quadratureOrder = options_.quadratureOrder;
    t.minRays = t.maxRays = std::max(1, options_.rays);
    transfer_ = std::make_unique<TransferEvaluator>(h_, *vis_, t);
    // Uniform mesh: split every element until its area is at most maxArea. The guard on
    // maxArea keeps a zero or negative setting from subdividing forever.
    const double maxArea = std::max(options_.maxArea, 1e-12 * (1.0 + scene_.totalArea()));
    for (size_t p = 0; p < scene_.polygons.size(); ++p) {
        std::vector<int> stack{h_.polygonRoot[p]};
        while (!stack.empty()) {
            const int e = stack.back();
            stack.pop_back();
            if (h_.nodes[e].area > maxArea) {
                h_.subdivide(e);
                for (int k = 0; k < 4; ++k) stack.push_back(h_.nodes[e].firstChild + k);
            } else {
                leaves_.push_back(e);
            }
        }
    }
}

ReferenceSolver::~ReferenceSolver() = default;

uint64_t ReferenceSolver::rays() const {
    return transfer_->counters.rays.load();
}

void ReferenceSolver::solve() {
    const int n = static_cast<int>(leaves_.size());
    if (options_.progress) {
        options_.progress("reference: " + std::to_string(n) + " elements, " +
                          std::to_string(static_cast<long long>(n) * n) + " pairs");
    }
    const auto t0 = Clock::now();
    // K_ij = F_ij V_ij, one row per receiver; rows of non-reflecting elements stay empty.
    std::vector<float> K(static_cast<size_t>(n) * n, 0.0f);
    parallelFor(static_cast<size_t>(n), 8, [&](size_t row) {
        const int i = static_cast<int>(row);
        const int r = leaves_[i];
        if (h_.nodes[r].rho.maxComponent() <= 0) return;
        for (int j = 0; j < n; ++j) {
            const int s = leaves_[j];
            if (i == j || !transfer_->facing(r, s)) continue;
            Link link;
            link.receiver = r;
            link.source = s;
            link.F = transfer_->formFactor(r, s);
            if (!(link.F > 0)) continue;
            transfer_->visibility(link);
            K[static_cast<size_t>(i) * n + j] =
                static_cast<float>(link.F * static_cast<double>(link.V));
        }
    });
    timeFF_ = secondsSince(t0);

    // Gauss-Seidel, all channels at once.
    std::vector<Rgb> B(n);
    for (int i = 0; i < n; ++i) B[i] = h_.nodes[leaves_[i]].E;
    sweeps_ = 0;
    for (; sweeps_ < options_.maxSweeps; ++sweeps_) {
        double maxChange = 0, maxB = 0;
        for (int i = 0; i < n; ++i) {
            const Node& e = h_.nodes[leaves_[i]];
            Rgb H;
            const float* row = &K[static_cast<size_t>(i) * n];
            for (int j = 0; j < n; ++j)
                if (row[j] != 0.0f) H += B[j] * static_cast<double>(row[j]);
            const Rgb next = e.E + e.rho * H;
            for (int c = 0; c < 3; ++c)
                maxChange = std::max(maxChange, std::abs(next[c] - B[i][c]));
            maxB = std::max(maxB, next.maxComponent());
            B[i] = next;
        }
        if (maxChange <= options_.tolerance * maxB) {
            ++sweeps_;
            break;
        }
    }
    for (int i = 0; i < n; ++i) h_.nodes[leaves_[i]].B = B[i];
    h_.pullAverages(Hierarchy::kRoot);
}

Rgb ReferenceSolver::radiosityAt(int polygon, const Vec3& x) const {
    return h_.nodes[h_.locateLeaf(polygon, x)].B;
}

Rgb elementMean(const Node& e, const std::function<Rgb(int polygon, const Vec3& x)>& B) {
    Rgb sum;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            sum += B(e.polygon, pointOnElement(e, (i + 0.5) / 4, (j + 0.5) / 4));
    return sum * (1.0 / 16);
}

double relativeRmsError(const ReferenceSolver& ref,
                        const std::function<Rgb(int polygon, const Vec3& x)>& B) {
    const Hierarchy& h = ref.hierarchy();
    double sumSq = 0, sumRef = 0, sumArea = 0;
    for (int id : ref.leaves()) {
        const Node& e = h.nodes[id];
        if (e.rho.maxComponent() <= 0) continue;
        const Rgb d = elementMean(e, B) - e.B;
        sumSq += e.area * (d.r * d.r + d.g * d.g + d.b * d.b);
        sumRef += e.area * (e.B.r + e.B.g + e.B.b);
        sumArea += e.area;
    }
    if (!(sumArea > 0) || !(sumRef > 0)) return 0.0;  // nothing lit to compare
    return std::sqrt(sumSq / (3 * sumArea)) / (sumRef / (3 * sumArea));
}

}  // namespace radiosity
