// Real objects taken out of the solution (Loscos et al. 1999, §4.4 and §5.3): "When
// removing an object ... we delete every link and all corresponding shaft structures of the
// removed object", and the links it blocked see through its place again. The object stays
// in the scene and the hierarchy (node ids do not move, so the display's leaf mesh and the
// insertion stack stay valid); it is hidden from the visibility BVH and its elements
// neither reflect nor send. removeLastObject() restores the snapshot taken here.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"

namespace radiosity {

std::vector<int> HierarchicalSolver::removedObjects() const {
    std::vector<int> out;
    for (const Insertion& rec : inserted_)
        if (rec.removed >= 0) out.push_back(rec.removed);
    return out;
}

void HierarchicalSolver::removeRealObject(int object, DynamicUpdate* reportOut) {
    if (!started_) throw std::logic_error("removeRealObject: solve() first");
    const size_t scenePolygons = this->scenePolygons();
    const int sceneObjects =
        static_cast<int>(inserted_.empty() ? scene_.objects.size() : inserted_.front().objects);
    if (object < 0 || object >= sceneObjects)
        throw std::invalid_argument("removeRealObject: no object " + std::to_string(object) +
                                    " in the scene (it has " + std::to_string(sceneObjects) + ")");
    const std::string& name = scene_.objects[static_cast<size_t>(object)];
    std::vector<int> polygons;
    Bounds3 box;
    for (size_t p = 0; p < scenePolygons; ++p) {
        const Polygon& poly = scene_.polygons[p];
        if (poly.object != object) continue;
        if (poly.light >= 0)
            throw std::invalid_argument("removeRealObject: object \"" + name +
                                        "\" holds a lamp's emitting face");
        polygons.push_back(static_cast<int>(p));
        box.extend(poly.bounds());
    }
    if (polygons.empty())
        throw std::invalid_argument("removeRealObject: object \"" + name + "\" has no polygon");
    if (vis_->hidden(polygons.front()))
        throw std::invalid_argument("removeRealObject: object \"" + name +
                                    "\" is taken out already");

    links_.index();
    DynamicUpdate report;
    Insertion rec = snapshot();
    rec.name = name;
    rec.removed = object;
    rec.hidden = polygons;
    rec.rho.reserve(h_.nodes.size());
    for (const Node& n : h_.nodes) rec.rho.push_back(n.rho);
    if (frozenNodes_ == 0) frozenNodes_ = h_.nodes.size();
    inserted_.push_back(std::move(rec));

    // 1. Out of the BVH; its elements reflect and send nothing; its links go.
    const auto t0 = Clock::now();
    vis_->hidePolygons(polygons);
    std::vector<char> gone(h_.nodes.size(), 0);
    for (size_t n = 0; n < h_.nodes.size(); ++n) {
        Node& e = h_.nodes[n];
        if (e.isCluster() || scene_.polygons[static_cast<size_t>(e.polygon)].object != object)
            continue;
        gone[n] = 1;
        e.rho = Rgb{};
        e.B = e.Bsent = e.H = e.Hd = Rgb{};
    }
    h_.pullAverages(Hierarchy::kRoot);
    std::vector<Link> kept;
    kept.reserve(links_.size());
    for (const Link& l : links_.all()) {
        if (!gone[l.receiver] && !gone[l.source]) kept.push_back(l);
    }
    links_.replace(std::move(kept));
    report.timeLinks += secondsSince(t0);

    // 2. The links its box cut see through it now.
    cutLinks(box, object, report, /*revive=*/false);
    links_.index();

    // 3. What the leaves around it see, measured again where it filled much of their view,
    //    and their energy bound set again. The other leaves keep their gather scales: a
    //    leaf that gathered from the object now gathers, through the links the object cut,
    //    from what lay behind it in the same directions, so its sum of form factors G
    //    stays about what the bound made it.
    const auto t1 = Clock::now();
    const std::vector<int> also =
        remeasureSeenNear(box.centre(), 0.5 * glm::length(box.diagonal()), h_.nodes.size(), object);
    if (!also.empty()) boundGather(h_.nodes.size(), /*balance=*/true, &also);
    refreshEmitterLight(report);
    inserted_.back().shadowLeaves = report.shadowLeaves;
    report.timeLinks += secondsSince(t1);

    // 4. Gather/push-pull from the solution as it was.
    const auto t2 = Clock::now();
    report.sweeps = gatherPushPull();
    report.timeGather += secondsSince(t2);
    if (reportOut) *reportOut = std::move(report);
}

}  // namespace radiosity
