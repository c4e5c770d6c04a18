// Stress rooms: a deterministic generator of random furnished rooms, the kind of input
// users bring (reconstructed rooms: furniture in contact, thin boards, lamps mounted on
// walls), for the solver's tests (tests/radiosity/stress_rooms_test.cpp) and its bench
// (bench/stress_rooms.cpp).
//
// A room is built in a local frame, in metres before scaling: the air of the room is
// [0, W] x [0, D] x [0, H] with z up. Everything in it is an axis-aligned box there:
//   - the room itself: floor, ceiling and four walls, facing inwards;
//   - floor boxes standing against a wall, often touching a neighbour or a corner, some
//     carrying a smaller box on top (stacked: the faces in contact are coplanar);
//   - free boxes standing in the room, touching only the floor;
//   - shelf units against a wall: two 2 cm side boards, 2 cm shelf boards between them
//     (their ends touch the sides, their backs the wall or a 2 cm back board), and books,
//     thin boxes standing on the boards side by side, most touching their neighbours;
//   - lamps: one emitting quad each (radiosity::Light with one polygon), on the ceiling
//     facing down (flush with it or 5 mm below), on a wall 5 mm in front of it facing the
//     room, or 5 mm in front of a wall facing the wall (lighting only the wall behind it).
// Boxes touch but never overlap: every placement is checked against all the solids and
// lamp slabs placed before it (touching faces are allowed, a positive overlap volume is
// not). Then the room is scaled by `scale`, rotated and moved (world frame), and every box
// face is output as one quad or as a grid of triangles.
//
// Randomness: one splitmix64 stream seeded by `seed`, drawn in a fixed order, and only
// +, -, *, / and sqrt on its numbers (no std::*_distribution, no exp/log/sin/cos, whose
// results differ across standard libraries): a seed gives the same room, bit for bit, on
// every platform.
//
// Options (StressRoomOptions below), each fixed here or drawn from the seed:
//   seed                 the random stream
//   scale                every length is multiplied by it (a 2.5-6 m room at 0.002 is 5-12 mm
//                        wide, at 20 it is 50-120 m)
//   floorBoxes           boxes against the walls (count drawn in the range)
//   stackProbability     chance that a floor box carries another box on top
//   freeBoxes            boxes standing free in the room
//   shelves, shelfBoards shelf units, and horizontal boards per unit (its top one included)
//   booksPerBoard        books standing on each board but the top one (fewer where the
//                        board is full)
//   ceilingLamps, wallLamps, wallFacingLamps
//                        lamp counts per mount; at least one lamp faces the room (a ceiling
//                        lamp is added when the drawn counts give none)
//   maxReflectance       reflectance per channel and object drawn up to this (< 1)
//   triangles, grid      output each face as one quad, or as a grid x grid cells of two
//                        triangles each (as /work/shared/tools/tessellate.py cuts a scene)
//   jitter               triangles only: interior grid vertices move by a uniform amount in
//                        [0, jitter] (metres before scaling) along the face's inward normal,
//                        into the solid behind the face, so that faces in contact never
//                        cross (a ± jitter would push a box into the wall it stands against).
//                        The face is then no longer planar, each triangle is.
//   rotate, offset       rotate the room randomly (so that no face is axis-aligned), and put
//                        its centre `offset` room diagonals away from the world origin
// stressOptionsForSeed(seed) draws the mesh, scale and placement options from the seed too
// (the bench's variety); makeStressRoom() then draws the room's content.
//
// Lamps are the spec's measured quads (scene-format.md, "lights"): never tessellated nor
// jittered, so that the scene package (writeStressRoomPackage) is the same scene as the
// in-memory one: the OBJ holds the geometry in the same order, and the lamps come last, as
// relight::loadScene appends them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "radiosity/scene.h"

namespace stress {

using radiosity::Rgb;
using radiosity::Vec3;

/// An inclusive integer range [lo, hi]; lo == hi fixes the count.
struct Count {
    int lo = 0, hi = 0;
};

struct StressRoomOptions {
    uint64_t seed = 1;
    double scale = 1;  ///< multiplies every length; > 0

    Count floorBoxes{2, 6};
    double stackProbability = 0.4;
    Count freeBoxes{0, 1};
    Count shelves{0, 2};
    Count shelfBoards{2, 4};  ///< horizontal boards per shelf unit (its top included)
    Count booksPerBoard{0, 10};

    Count ceilingLamps{0, 2};
    Count wallLamps{0, 2};
    Count wallFacingLamps{0, 1};

    double maxReflectance = 0.95;  ///< in [0, 1)

    bool triangles = false;
    int grid = 2;       ///< cells per face side when `triangles`; >= 1
    double jitter = 0;  ///< metres before scaling, < kMaxJitter; triangles with grid >= 2 only
    bool rotate = false;
    double offset = 0;  ///< room diagonals between the world origin and the room's centre
};

/// The thinnest solid is a 15 mm book: interior vertices of both of its faces moving in
/// by up to a quarter of that leave the faces 7.5 mm apart.
inline constexpr double kMaxJitter = 0.015 / 4;
/// Gap between a wall lamp and its wall, metres before scaling.
inline constexpr double kLampGap = 0.005;
/// Thickness of shelf boards, metres before scaling.
inline constexpr double kBoardThickness = 0.02;

/// Mesh and placement options drawn from the seed (counts keep their defaults): quads or
/// triangles with grid 1-3, jitter 0 or 2 mm, scale from 0.002 to 20 (a random decade,
/// then a uniform factor in it), rotation half the time, an offset a quarter of the time.
StressRoomOptions stressOptionsForSeed(uint64_t seed);

/// An axis-aligned box of the local frame (metres before scaling).
struct LocalBox {
    Vec3 lo, hi;
};

enum class SolidKind { floorBox, stackedBox, freeBox, shelfSide, shelfBack, shelfBoard, book };
const char* solidKindName(SolidKind kind);

/// One closed box of the room: 6 outward faces (one quad or grid^2 triangle pairs each).
struct Solid {
    SolidKind kind;
    LocalBox box;
    int object = -1;  ///< index into Scene::objects
};

enum class LampMount { ceiling, wallIntoRoom, wallFacingWall };
const char* lampMountName(LampMount mount);

struct Lamp {
    LampMount mount;
    int light = -1;  ///< index into Scene::lights
    /// Distance from the emitting quad to the surface it is mounted on (metres before
    /// scaling): kLampGap, or 0 for a ceiling lamp flush with the ceiling.
    double gap = 0;
    LocalBox slab;  ///< the lamp quad thickened to its mounting surface (kept clear)
};

struct StressRoom {
    StressRoomOptions options;
    radiosity::Scene scene;
    Vec3 size;  ///< W, D, H of the room's air, metres before scaling
    /// world = origin + rotation * (scale * local); columns of `rotation` are the local
    /// axes in the world.
    Vec3 origin{0, 0, 0};
    Vec3 axis[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    std::vector<Solid> solids;
    std::vector<Lamp> lamps;
    int roomObjectCount = 6;  ///< objects 0-5: floor, ceiling, 4 walls

    Vec3 toWorld(const Vec3& local) const;
    Vec3 toLocal(const Vec3& world) const;
    Vec3 directionToWorld(const Vec3& local) const;
    /// Polygons each box face becomes: 1 (quads) or 2 grid^2 (triangles).
    int polygonsPerFace() const;
};

/// Builds the room. Throws std::invalid_argument for options out of range and
/// std::logic_error when a polygon it made fails radiosity::checkPolygon (a bug here).
StressRoom makeStressRoom(const StressRoomOptions& options);

/// Writes a scene package (relight-scene/1, docs/scene-format.md) to `dir`
/// (created; files of the same names replaced): scene.json with each object's
/// reflectance, the lamps as quad lights (all on; no photo: the format does not require
/// one, and `relight solve` works without), and a camera inside the room above the
/// furniture looking down across it; room.obj with one `o` block per object and every
/// coordinate to 17 significant digits (the loaded scene is this scene, bit for bit).
/// Throws std::runtime_error when a file cannot be written.
void writeStressRoomPackage(const StressRoom& room, const std::filesystem::path& dir);

}  // namespace stress
