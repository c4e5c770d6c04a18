// Stress rooms: see stress_room.h for what a room holds and why.
#include "tests/support/stress_room.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

namespace stress {

namespace {

/// splitmix64 (Steele, Lea & Flood 2014). A copy of radiosity::Rng's step, kept here so
/// that a seed's room stays the same room even if the solver's generator changes.
class Random {
  public:
    explicit Random(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1): the top 53 bits, exact in a double.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    /// Uniform integer in [c.lo, c.hi] (the modulo bias is below 1e-17 for these ranges).
    int count(Count c) {
        return c.lo + static_cast<int>(next() % static_cast<uint64_t>(c.hi - c.lo + 1));
    }
    bool chance(double p) { return uniform() < p; }

  private:
    uint64_t state_;
};

/// Distinct streams for the options and the room of one seed (the same seed would
/// otherwise give both the same numbers).
constexpr uint64_t kOptionsStream = 0x6F7074696F6E7321ull;

/// Two boxes overlap when their intersection has a positive volume: touching faces,
/// edges or corners do not count. Touching boxes are built from the same doubles (one's
/// hi is the other's lo), so no tolerance is needed.
bool overlap(const LocalBox& a, const LocalBox& b) {
    for (int k = 0; k < 3; ++k)
        if (std::min(a.hi[k], b.hi[k]) <= std::max(a.lo[k], b.lo[k])) return false;
    return true;
}

bool inside(const LocalBox& a, const LocalBox& room) {
    for (int k = 0; k < 3; ++k)
        if (a.lo[k] < room.lo[k] || a.hi[k] > room.hi[k]) return false;
    return true;
}

/// An interval [a, b] along a wall or an axis.
struct Span {
    double a = 0, b = 0;
};

// ---- placement ---------------------------------------------------------------------------

/// Walls: 0 is y = 0, 1 is y = D, 2 is x = 0, 3 is x = W. Wall coordinates: s along the
/// wall (x for walls 0-1, y for 2-3), n the distance from the wall into the room, z up.
class Placer {
  public:
    Placer(const Vec3& size, Random& rnd) : size_(size), rnd_(rnd) {}

    double length(int wall) const { return wall < 2 ? size_.x : size_.y; }
    LocalBox room() const { return {{0, 0, 0}, size_}; }

    /// The local box of s in [s.a, s.b], n in [n.a, n.b] from `wall`, z in [z.a, z.b].
    /// A far wall's n interval is mirrored with the same subtractions for every box, so
    /// that boxes touching in wall coordinates touch exactly in local ones.
    LocalBox wallBox(int wall, Span s, Span n, Span z) const {
        const double far = wall < 2 ? size_.y : size_.x;
        const bool mirrored = wall == 1 || wall == 3;
        const Span m = mirrored ? Span{far - n.b, far - n.a} : n;
        if (wall < 2) return {{s.a, m.a, z.a}, {s.b, m.b, z.b}};
        return {{m.a, s.a, z.a}, {m.b, s.b, z.b}};
    }
    /// The along-wall extent of a local box.
    Span along(int wall, const LocalBox& b) const {
        return wall < 2 ? Span{b.lo.x, b.hi.x} : Span{b.lo.y, b.hi.y};
    }

    /// The depth of a local box measured from the wall.
    double across(int wall, const LocalBox& b) const {
        return wall < 2 ? b.hi.y - b.lo.y : b.hi.x - b.lo.x;
    }

    bool fits(const LocalBox& b) const {
        if (!inside(b, room())) return false;
        for (const LocalBox& t : taken_)
            if (overlap(b, t)) return false;
        return true;
    }
    void take(const LocalBox& b) { taken_.push_back(b); }

    /// A free place for a box of the given width along `wall`, depth n and height z (z
    /// from 0: standing on the floor). Mostly one in contact: against a corner or against
    /// a box already there (its side or the far side of a box on the next wall); else
    /// anywhere free. nullopt when nothing fits.
    std::optional<LocalBox> againstWall(int wall, double width, double depth, Span z) {
        const double L = length(wall);
        if (width > L) return std::nullopt;
        std::vector<Span> contact{{0, width}, {L - width, L}};
        for (const LocalBox& t : taken_) {
            const Span e = along(wall, t);
            contact.push_back({e.b, e.b + width});
            contact.push_back({e.a - width, e.a});
        }
        std::vector<LocalBox> free;
        for (const Span& s : contact) {
            const LocalBox b = wallBox(wall, s, {0, depth}, z);
            if (fits(b)) free.push_back(b);
        }
        if (!free.empty() && rnd_.chance(0.75)) return pick(free);
        for (int attempt = 0; attempt < 20; ++attempt) {
            const double a = rnd_.uniform(0, L - width);
            const LocalBox b = wallBox(wall, {a, a + width}, {0, depth}, z);
            if (fits(b)) return b;
        }
        if (free.empty()) return std::nullopt;
        return pick(free);
    }

    LocalBox pick(const std::vector<LocalBox>& boxes) {
        return boxes[static_cast<size_t>(rnd_.count({0, static_cast<int>(boxes.size()) - 1}))];
    }

  private:
    Vec3 size_;
    Random& rnd_;
    std::vector<LocalBox> taken_;  ///< solids and lamp slabs
};

class Mesher;

// ---- the room's content --------------------------------------------------------------------

class Builder {
  public:
    explicit Builder(const StressRoomOptions& o)
        : o_(o), rnd_(o.seed), size_(drawSize()), placer_(size_, rnd_) {}

    StressRoom build();

  private:
    Vec3 drawSize() {
        const double w = rnd_.uniform(2.5, 6), d = rnd_.uniform(2.5, 6);
        return {w, d, rnd_.uniform(2.4, 3.2)};
    }
    /// Furniture stays below this height: the package's camera looks from above it.
    double furnitureTop() const { return 0.75 * size_.z; }

    void addSolid(SolidKind kind, const LocalBox& b) {
        placer_.take(b);
        solids_.push_back({kind, b, -1});
    }
    void placeShelves();
    void placeShelf(int wall, const LocalBox& unit);
    void placeBooks(int wall, Span s, Span n, double z, double clearance);
    void placeFloorBoxes();
    void placeStacked(int wall, const LocalBox& below);
    void placeFreeBoxes();
    void placeLamps();
    bool placeCeilingLamp();
    bool placeWallLamp(LampMount mount);
    void meshRoom(Mesher& mesher, StressRoom& room);
    void meshSolids(Mesher& mesher, StressRoom& room);
    void meshLamps(Mesher& mesher, StressRoom& room);

    const StressRoomOptions& o_;
    Random rnd_;
    Vec3 size_;
    Placer placer_;
    std::vector<Solid> solids_;
    std::vector<Lamp> lamps_;
};

void Builder::placeShelves() {
    const int n = rnd_.count(o_.shelves);
    for (int i = 0; i < n; ++i) {
        const int wall = rnd_.count({0, 3});
        const double width = rnd_.uniform(0.6, 1.4), depth = rnd_.uniform(0.25, 0.4);
        const double height = rnd_.uniform(1.0, furnitureTop());
        if (auto unit = placer_.againstWall(wall, width, depth, {0, height}))
            placeShelf(wall, *unit);
    }
}

void Builder::placeShelf(int wall, const LocalBox& unit) {
    const double t = kBoardThickness;
    const Span s = placer_.along(wall, unit);
    const double depth = placer_.across(wall, unit);
    const double height = unit.hi.z;
    // A back board against the wall half the time; the rest stands in front of it.
    double n0 = 0;
    if (rnd_.chance(0.5)) {
        addSolid(SolidKind::shelfBack, placer_.wallBox(wall, s, {0, t}, {0, height}));
        n0 = t;
    }
    const Span n{n0, depth};
    addSolid(SolidKind::shelfSide, placer_.wallBox(wall, {s.a, s.a + t}, n, {0, height}));
    addSolid(SolidKind::shelfSide, placer_.wallBox(wall, {s.b - t, s.b}, n, {0, height}));
    // Boards from the floor (or a little above it) to the top, evenly spaced; their ends
    // touch the sides.
    const Span inner{s.a + t, s.b - t};
    const int boards = std::max(2, rnd_.count(o_.shelfBoards));
    const double bottom = rnd_.chance(0.5) ? 0.0 : rnd_.uniform(0.05, 0.12);
    std::vector<double> z(static_cast<size_t>(boards));
    for (int i = 0; i < boards; ++i)
        z[static_cast<size_t>(i)] = bottom + (height - t - bottom) * i / (boards - 1);
    z.back() = height - t;  // the top board's top is the sides' top exactly
    for (int i = 0; i < boards; ++i) {
        const double zb = z[static_cast<size_t>(i)];
        addSolid(SolidKind::shelfBoard, placer_.wallBox(wall, inner, n, {zb, zb + t}));
        if (i + 1 < boards)
            placeBooks(wall, inner, n, zb + t, z[static_cast<size_t>(i) + 1] - (zb + t));
    }
}

/// Books standing on a board whose top is at z, side by side from the left side board,
/// most touching their neighbour; `clearance` is the free height above the board.
void Builder::placeBooks(int wall, Span s, Span n, double z, double clearance) {
    if (clearance < 0.12) return;
    const int books = rnd_.count(o_.booksPerBoard);
    const double boardDepth = n.b - n.a;
    double cursor = s.a;
    for (int i = 0; i < books; ++i) {
        const double thick = rnd_.uniform(0.015, 0.05);
        const double height = rnd_.uniform(0.5, 0.9) * std::min(clearance, 0.4);
        const double depth = rnd_.uniform(0.6, 0.95) * boardDepth;
        const double front = n.b - rnd_.uniform(0, boardDepth - depth);
        if (cursor + thick > s.b) return;
        addSolid(SolidKind::book, placer_.wallBox(wall, {cursor, cursor + thick},
                                                  {front - depth, front}, {z, z + height}));
        cursor += thick;
        if (rnd_.chance(0.2)) cursor += rnd_.uniform(0.005, 0.04);
    }
}

void Builder::placeFloorBoxes() {
    const int n = rnd_.count(o_.floorBoxes);
    for (int i = 0; i < n; ++i) {
        const int wall = rnd_.count({0, 3});
        const double width = rnd_.uniform(0.3, 1.2), depth = rnd_.uniform(0.3, 0.8);
        const double height = rnd_.uniform(0.3, std::min(1.0, 0.5 * size_.z));
        const auto b = placer_.againstWall(wall, width, depth, {0, height});
        if (!b) continue;
        addSolid(SolidKind::floorBox, *b);
        if (rnd_.chance(o_.stackProbability)) placeStacked(wall, *b);
    }
}

/// A smaller box on top of `below`, against the same wall, flush with one end of it or
/// anywhere along it.
void Builder::placeStacked(int wall, const LocalBox& below) {
    const Span e = placer_.along(wall, below);
    const double belowDepth = placer_.across(wall, below);
    const double width = rnd_.uniform(0.3, 1.0) * (e.b - e.a);
    const double depth = rnd_.uniform(0.3, 1.0) * belowDepth;
    const double top = std::min(below.hi.z + rnd_.uniform(0.1, 0.5), furnitureTop());
    if (top <= below.hi.z) return;
    const int where = rnd_.count({0, 2});
    Span s = where == 0 ? Span{e.a, e.a + width} : Span{e.b - width, e.b};
    if (where == 2) {
        const double a = rnd_.uniform(e.a, e.b - width);
        s = {a, a + width};
    }
    const LocalBox b = placer_.wallBox(wall, s, {0, depth}, {below.hi.z, top});
    if (placer_.fits(b)) addSolid(SolidKind::stackedBox, b);
}

void Builder::placeFreeBoxes() {
    const int n = rnd_.count(o_.freeBoxes);
    for (int i = 0; i < n; ++i) {
        const double w = rnd_.uniform(0.3, 1.0), d = rnd_.uniform(0.3, 1.0);
        const double h = rnd_.uniform(0.2, 0.9);
        for (int attempt = 0; attempt < 20; ++attempt) {
            const double x = rnd_.uniform(0.3, size_.x - w - 0.3);
            const double y = rnd_.uniform(0.3, size_.y - d - 0.3);
            const LocalBox b{{x, y, 0}, {x + w, y + d, h}};
            if (!placer_.fits(b)) continue;
            addSolid(SolidKind::freeBox, b);
            break;
        }
    }
}

/// A ceiling lamp, flush with the ceiling half the time, else kLampGap below it. Its
/// slab (the kLampGap below the ceiling) is kept clear of other lamps.
bool Builder::placeCeilingLamp() {
    const double a = rnd_.uniform(0.1, 0.4), b = rnd_.uniform(0.1, 0.6);
    const double gap = rnd_.chance(0.5) ? 0.0 : kLampGap;
    for (int attempt = 0; attempt < 20; ++attempt) {
        const double x = rnd_.uniform(0.1, size_.x - a - 0.1);
        const double y = rnd_.uniform(0.1, size_.y - b - 0.1);
        const LocalBox slab{{x, y, size_.z - kLampGap}, {x + a, y + b, size_.z}};
        if (!placer_.fits(slab)) continue;
        placer_.take(slab);
        lamps_.push_back({LampMount::ceiling, -1, gap, slab});
        return true;
    }
    return false;
}

/// A wall lamp kLampGap in front of a wall, clear of the furniture and other lamps.
bool Builder::placeWallLamp(LampMount mount) {
    const int wall = rnd_.count({0, 3});
    const double a = rnd_.uniform(0.1, 0.4), b = rnd_.uniform(0.1, 0.4);
    const double L = placer_.length(wall);
    for (int attempt = 0; attempt < 20; ++attempt) {
        const double s = rnd_.uniform(0.05, L - a - 0.05);
        const double z = rnd_.uniform(0.35 * size_.z, 0.92 * size_.z - b);
        const LocalBox slab = placer_.wallBox(wall, {s, s + a}, {0, kLampGap}, {z, z + b});
        if (!placer_.fits(slab)) continue;
        placer_.take(slab);
        lamps_.push_back({mount, -1, kLampGap, slab});
        return true;
    }
    return false;
}

void Builder::placeLamps() {
    int ceiling = rnd_.count(o_.ceilingLamps);
    const int wall = rnd_.count(o_.wallLamps), facing = rnd_.count(o_.wallFacingLamps);
    if (ceiling + wall == 0) ceiling = 1;  // something must light the room
    // The ceiling is empty but for lamps, so a first ceiling lamp always finds a place.
    bool intoRoom = false;
    for (int i = 0; i < ceiling; ++i) intoRoom = placeCeilingLamp() || intoRoom;
    for (int i = 0; i < wall; ++i) intoRoom = placeWallLamp(LampMount::wallIntoRoom) || intoRoom;
    for (int i = 0; i < facing; ++i) placeWallLamp(LampMount::wallFacingWall);
    if (!intoRoom && !placeCeilingLamp())
        throw std::logic_error("stress room: no place for a lamp on an empty ceiling");
}

// ---- mesh --------------------------------------------------------------------------------

/// Grid coordinates of a box along one axis: lo + (hi - lo) i / n, with both ends exact.
/// Faces sharing an edge take its points from the same table, so the edge's vertices
/// are the same doubles on both faces (watertight, whichever way each face runs).
std::vector<double> axisTable(double lo, double hi, int n) {
    std::vector<double> t(static_cast<size_t>(n) + 1);
    for (int i = 0; i <= n; ++i) t[static_cast<size_t>(i)] = lo + (hi - lo) * i / n;
    t.back() = hi;
    return t;
}

class Mesher {
  public:
    Mesher(StressRoom& room, Random& rnd) : room_(room), rnd_(rnd) {}

    /// The 6 faces of a solid box, facing out of it.
    void box(const LocalBox& box, int object, const Rgb& rho);
    /// Face of `box` on axis k at its lo or hi side, normal sign `sign` (+1: +axis).
    void face(const LocalBox& box, int k, bool hiSide, int sign, int object, const Rgb& rho);
    /// The lamp's quad: on the slab's side away from its mounting surface (on the
    /// surface itself for a flush ceiling lamp), facing the room or the wall.
    void lamp(const Lamp& lamp, int object);

  private:
    void add(const std::vector<Vec3>& local, int object, const Rgb& rho, int light = -1);

    StressRoom& room_;
    Random& rnd_;
};

void Mesher::box(const LocalBox& b, int object, const Rgb& rho) {
    for (int k = 0; k < 3; ++k) {
        face(b, k, false, -1, object, rho);
        face(b, k, true, 1, object, rho);
    }
}

void Mesher::face(const LocalBox& b, int k, bool hiSide, int sign, int object, const Rgb& rho) {
    const StressRoomOptions& o = room_.options;
    const int n = o.triangles ? o.grid : 1;
    // u, v follow k cyclically (e_u x e_v = e_k): corners (u0,v0) (u1,v0) (u1,v1) (u0,v1)
    // run counter-clockwise about +k; reversed for -k.
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    const auto tu = axisTable(b.lo[u], b.hi[u], n), tv = axisTable(b.lo[v], b.hi[v], n);
    const double c = hiSide ? b.hi[k] : b.lo[k];
    auto point = [&](int i, int j) {  // i along the first edge, j along the last
        Vec3 p;
        p[k] = c;
        p[u] = tu[static_cast<size_t>(sign > 0 ? i : j)];
        p[v] = tv[static_cast<size_t>(sign > 0 ? j : i)];
        // Jitter moves interior vertices against the normal, into the solid behind the face.
        if (o.jitter > 0 && i > 0 && i < n && j > 0 && j < n)
            p[k] -= sign * rnd_.uniform(0, o.jitter);
        return p;
    };
    if (!o.triangles) {
        add({point(0, 0), point(1, 0), point(1, 1), point(0, 1)}, object, rho);
        return;
    }
    std::vector<Vec3> grid;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) grid.push_back(point(i, j));
    auto at = [&](int i, int j) { return grid[static_cast<size_t>(j * (n + 1) + i)]; };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            add({at(i, j), at(i + 1, j), at(i + 1, j + 1)}, object, rho);
            add({at(i, j), at(i + 1, j + 1), at(i, j + 1)}, object, rho);
        }
}

void Mesher::lamp(const Lamp& lamp, int object) {
    const LocalBox& s = lamp.slab;
    // The slab's thin axis, and which of its sides the quad lies on (the one away from the
    // mounting surface, or the ceiling itself for a flush ceiling lamp).
    int k = 2;
    for (int a = 0; a < 3; ++a)
        if (s.hi[a] - s.lo[a] < s.hi[k] - s.lo[k]) k = a;
    const bool mountAtHi = s.hi[k] == room_.size[k];
    double c = mountAtHi ? s.lo[k] : s.hi[k];
    if (lamp.gap == 0) c = mountAtHi ? s.hi[k] : s.lo[k];
    const bool facesRoom = lamp.mount != LampMount::wallFacingWall;
    const int sign = (mountAtHi == facesRoom) ? -1 : 1;
    LocalBox plane = s;
    plane.lo[k] = plane.hi[k] = c;
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    auto corner = [&](bool hu, bool hv) {
        Vec3 p;
        p[k] = c;
        p[u] = hu ? plane.hi[u] : plane.lo[u];
        p[v] = hv ? plane.hi[v] : plane.lo[v];
        return p;
    };
    std::vector<Vec3> q = {corner(false, false), corner(true, false), corner(true, true),
                           corner(false, true)};
    if (sign < 0) std::swap(q[1], q[3]);
    add(q, object, Rgb{}, lamp.light);
}

void Mesher::add(const std::vector<Vec3>& local, int object, const Rgb& rho, int light) {
    std::vector<Vec3> world;
    for (const Vec3& p : local) world.push_back(room_.toWorld(p));
    const radiosity::PolygonCheck check = radiosity::checkPolygon(world);
    if (check.status != radiosity::PolygonCheck::Status::ok)
        throw std::logic_error("stress room (seed " + std::to_string(room_.options.seed) +
                               "): made a bad polygon: " + check.message);
    radiosity::Polygon p = radiosity::makePolygon(world, object, rho);
    p.light = light;
    room_.scene.polygons.push_back(p);
}

// ---- frame and materials -----------------------------------------------------------------

/// A uniformly random rotation: a unit quaternion from rejection sampling in the 4-cube
/// (sqrt only: no trigonometry), as the columns of its matrix.
void randomRotation(Random& rnd, Vec3 axis[3]) {
    double q[4], n2 = 0;
    do {
        n2 = 0;
        for (double& x : q) {
            x = rnd.uniform(-1, 1);
            n2 += x * x;
        }
    } while (n2 > 1 || n2 < 1e-4);
    const double n = std::sqrt(n2);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    axis[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    axis[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
    axis[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
}

/// A random unit vector (rejection sampling in the cube).
Vec3 randomDirection(Random& rnd) {
    for (;;) {
        const Vec3 d{rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-1, 1)};
        const double n2 = glm::dot(d, d);
        if (n2 <= 1 && n2 > 1e-4) return d / std::sqrt(n2);
    }
}

/// Reflectance up to `max` per channel; a third of the objects are bright (every channel
/// in the top fifth), the hard case for convergence.
Rgb randomReflectance(Random& rnd, double max) {
    const double lo = rnd.chance(1.0 / 3) ? 0.8 * max : 0.0;
    return {rnd.uniform(lo, max), rnd.uniform(lo, max), rnd.uniform(lo, max)};
}

void validate(const StressRoomOptions& o) {
    auto fail = [](const std::string& m) { throw std::invalid_argument("stress room: " + m); };
    if (!(o.scale > 0) || !std::isfinite(o.scale)) fail("scale must be positive");
    if (!(o.maxReflectance >= 0 && o.maxReflectance < 1)) fail("maxReflectance must be in [0, 1)");
    if (o.grid < 1) fail("grid must be at least 1");
    if (!(o.jitter >= 0 && o.jitter < kMaxJitter))
        fail("jitter must be in [0, " + std::to_string(kMaxJitter) + ") m");
    if (o.jitter > 0 && !(o.triangles && o.grid >= 2))
        fail("jitter moves interior grid vertices: it needs triangles and grid >= 2");
    if (!(o.offset >= 0) || !std::isfinite(o.offset)) fail("offset must be >= 0");
    for (const Count& c : {o.floorBoxes, o.freeBoxes, o.shelves, o.shelfBoards, o.booksPerBoard,
                           o.ceilingLamps, o.wallLamps, o.wallFacingLamps})
        if (c.lo < 0 || c.hi < c.lo) fail("a count range must have 0 <= lo <= hi");
}

const char* kWallNames[4] = {"wall_y0", "wall_yD", "wall_x0", "wall_xW"};

void Builder::meshRoom(Mesher& mesher, StressRoom& room) {
    // Six faces, one object each (floor, ceiling, walls 0-3), facing inwards.
    const LocalBox air{{0, 0, 0}, size_};
    const int axisOf[6] = {2, 2, 1, 1, 0, 0};
    for (int i = 0; i < 6; ++i) {
        room.scene.objects.push_back(i == 0 ? "floor" : i == 1 ? "ceiling" : kWallNames[i - 2]);
        const bool hiSide = i % 2 == 1;
        mesher.face(air, axisOf[i], hiSide, hiSide ? -1 : 1, i,
                    randomReflectance(rnd_, o_.maxReflectance));
    }
}

void Builder::meshSolids(Mesher& mesher, StressRoom& room) {
    for (size_t i = 0; i < solids_.size(); ++i) {
        Solid s = solids_[i];
        s.object = static_cast<int>(room.scene.objects.size());
        room.scene.objects.push_back(std::string(solidKindName(s.kind)) + std::to_string(i));
        mesher.box(s.box, s.object, randomReflectance(rnd_, o_.maxReflectance));
        room.solids.push_back(s);
    }
}

/// Lamps last, each its own object "light:lampN", as relight::loadScene names them.
void Builder::meshLamps(Mesher& mesher, StressRoom& room) {
    radiosity::Scene& scene = room.scene;
    for (size_t i = 0; i < lamps_.size(); ++i) {
        Lamp l = lamps_[i];
        const std::string name = "lamp" + std::to_string(i);
        l.light = static_cast<int>(scene.lights.size());
        const int object = static_cast<int>(scene.objects.size());
        scene.objects.push_back("light:" + name);
        const Rgb radiance{rnd_.uniform(1, 4), rnd_.uniform(1, 4), rnd_.uniform(1, 4)};
        scene.lights.push_back({name, {static_cast<int>(scene.polygons.size())}, radiance});
        mesher.lamp(l, object);
        room.lamps.push_back(l);
    }
}

StressRoom Builder::build() {
    placeShelves();
    placeFloorBoxes();
    placeFreeBoxes();
    placeLamps();

    StressRoom room;
    room.options = o_;
    room.size = size_;
    if (o_.rotate) randomRotation(rnd_, room.axis);
    const Vec3 centre = room.directionToWorld(0.5 * size_);
    Vec3 at{0, 0, 0};
    if (o_.offset > 0) at = randomDirection(rnd_) * (o_.offset * glm::length(size_) * o_.scale);
    room.origin = at - centre;

    Mesher mesher(room, rnd_);
    meshRoom(mesher, room);
    meshSolids(mesher, room);
    meshLamps(mesher, room);
    return room;
}

}  // namespace

// ---- public ------------------------------------------------------------------------------

const char* solidKindName(SolidKind kind) {
    switch (kind) {
        case SolidKind::floorBox:
            return "box";
        case SolidKind::stackedBox:
            return "stacked_box";
        case SolidKind::freeBox:
            return "free_box";
        case SolidKind::shelfSide:
            return "shelf_side";
        case SolidKind::shelfBack:
            return "shelf_back";
        case SolidKind::shelfBoard:
            return "shelf_board";
        case SolidKind::book:
            return "book";
    }
    return "?";
}

const char* lampMountName(LampMount mount) {
    switch (mount) {
        case LampMount::ceiling:
            return "ceiling";
        case LampMount::wallIntoRoom:
            return "wall";
        case LampMount::wallFacingWall:
            return "facing_wall";
    }
    return "?";
}

Vec3 StressRoom::directionToWorld(const Vec3& local) const {
    const double s = options.scale;
    return axis[0] * (s * local.x) + axis[1] * (s * local.y) + axis[2] * (s * local.z);
}

Vec3 StressRoom::toWorld(const Vec3& local) const {
    return origin + directionToWorld(local);
}

Vec3 StressRoom::toLocal(const Vec3& world) const {
    const Vec3 d = (world - origin) / options.scale;
    return {glm::dot(d, axis[0]), glm::dot(d, axis[1]), glm::dot(d, axis[2])};
}

int StressRoom::polygonsPerFace() const {
    return options.triangles ? 2 * options.grid * options.grid : 1;
}

StressRoomOptions stressOptionsForSeed(uint64_t seed) {
    Random rnd(seed ^ kOptionsStream);
    StressRoomOptions o;
    o.seed = seed;
    o.triangles = rnd.chance(0.5);
    o.grid = o.triangles ? rnd.count({1, 3}) : 1;
    o.jitter = o.triangles && o.grid >= 2 && rnd.chance(0.5) ? 0.002 : 0.0;
    // A random decade from 1e-3 to 1e1, a uniform factor in it, redrawn outside [0.002, 20]:
    // close to log-uniform without std::pow.
    for (;;) {
        double scale = rnd.uniform(1, 10);
        const int decade = rnd.count({-3, 1});
        for (int i = 0; i < decade; ++i) scale *= 10;
        for (int i = decade; i < 0; ++i) scale /= 10;
        if (scale >= 0.002 && scale <= 20) {
            o.scale = scale;
            break;
        }
    }
    o.rotate = rnd.chance(0.5);
    o.offset = rnd.chance(0.25) ? rnd.uniform(1, 10) : 0.0;
    return o;
}

namespace {

/// The package's camera: from above the furniture near one corner (0.85 H; furniture
/// stays below 0.75 H, lamps are 5 mm from the walls and ceiling), towards the floor
/// near the opposite corner; 320 x 240, 170 px focal length (about 86 degrees wide).
nlohmann::json cameraJson(const StressRoom& room) {
    const Vec3& size = room.size;
    const Vec3 eye = room.toWorld({0.2 * size.x, 0.2 * size.y, 0.85 * size.z});
    const Vec3 target = room.toWorld({0.8 * size.x, 0.8 * size.y, 0.2 * size.z});
    const Vec3 forward = glm::normalize(target - eye);
    const Vec3 right = glm::normalize(glm::cross(forward, room.axis[2]));
    const Vec3 down = glm::cross(forward, right);  // OpenCV: x right, y down, z forward
    nlohmann::json rows = nlohmann::json::array();
    for (const Vec3& r : {right, down, forward}) rows.push_back({r.x, r.y, r.z, -glm::dot(r, eye)});
    return {{"width", 320},
            {"height", 240},
            {"K", {{170.0, 0.0, 159.5}, {0.0, 170.0, 119.5}, {0.0, 0.0, 1.0}}},
            {"world_to_camera", rows}};
}

void writeObj(const radiosity::Scene& scene, const std::filesystem::path& file) {
    std::FILE* f = std::fopen(file.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + file.string());
    std::fprintf(f, "# stress room: %zu polygons\n", scene.polygons.size());
    int current = -1, vertices = 0;
    for (const radiosity::Polygon& p : scene.polygons) {
        if (p.light >= 0) continue;  // lamps are scene.json lights
        if (p.object != current) {
            current = p.object;
            std::fprintf(f, "o %s\n", scene.objects[static_cast<size_t>(current)].c_str());
        }
        for (int i = 0; i < p.vertexCount; ++i)
            std::fprintf(f, "v %.17g %.17g %.17g\n", p.v[i].x, p.v[i].y, p.v[i].z);
        std::fprintf(f, p.vertexCount == 3 ? "f %d %d %d\n" : "f %d %d %d %d\n", vertices + 1,
                     vertices + 2, vertices + 3, vertices + 4);
        vertices += p.vertexCount;
    }
    const bool ok = std::ferror(f) == 0;
    if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace

void writeStressRoomPackage(const StressRoom& room, const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    const radiosity::Scene& scene = room.scene;
    writeObj(scene, dir / "room.obj");
    nlohmann::json objects = nlohmann::json::object(), lights = nlohmann::json::array();
    for (const radiosity::Polygon& p : scene.polygons) {
        if (p.light >= 0) continue;
        objects[scene.objects[static_cast<size_t>(p.object)]] = {
            {"reflectance", {p.rho.r, p.rho.g, p.rho.b}}};
    }
    for (const radiosity::Light& l : scene.lights) {
        const radiosity::Polygon& q = scene.polygons[static_cast<size_t>(l.polygons.front())];
        nlohmann::json corners = nlohmann::json::array();
        for (int i = 0; i < q.vertexCount; ++i) corners.push_back({q.v[i].x, q.v[i].y, q.v[i].z});
        lights.push_back({{"name", l.name},
                          {"type", "quad"},
                          {"vertices", corners},
                          {"radiance", {l.radiance.r, l.radiance.g, l.radiance.b}}});
    }
    const nlohmann::json j = {{"format", "relight-scene/1"},
                              {"geometry", {"room.obj"}},
                              {"objects", objects},
                              {"camera", cameraJson(room)},
                              {"lights", lights}};
    std::ofstream out(dir / "scene.json");
    out << j.dump(1) << "\n";
    if (!out) throw std::runtime_error("cannot write " + (dir / "scene.json").string());
}

StressRoom makeStressRoom(const StressRoomOptions& options) {
    validate(options);
    return Builder(options).build();
}

}  // namespace stress
