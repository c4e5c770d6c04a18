"""A room lit only through a window (issue 31): a 5 x 4 x 3 m room of thick walls (0.2 m boxes),
one window of 1.6 x 1.3 m in the east wall (x = 5), a box on the floor, lit by a sun and an SH9
sky from outside; the camera stands by the window looking into the room (it sees no sky).

Writes the scene package (relight-scene/1, docs/scene-format.md) into OUT:
  window_room.obj, scene.json, edits/{identity,sun_moved,sky_rotated,sun_off}.json
and geometry.json (the same faces with their reflectances) that render.py builds in Cycles.
Run: python3 gen.py OUT          (then blender -b --factory-startup -P render.py -- OUT ...)
Conventions as data/courtyard/README.md: metres, z up, faces CCW seen from their front,
camera K and world_to_camera in OpenCV's convention."""
import json, math, os, sys

OUT = sys.argv[1] if len(sys.argv) > 1 else "out"

# Reflectances (linear RGB, all diffuse): the truth's materials; the engine estimates them.
WALL, FLOOR, CEIL, BOX = (0.70, 0.68, 0.64), (0.45, 0.34, 0.24), (0.80, 0.80, 0.80), (0.62, 0.25, 0.20)
SUN = {"name": "sun", "type": "sun", "direction": [0.70, 0.25, 0.55], "angle": 0.53,
       "irradiance": [4.5, 4.2, 3.7]}
SKY = [[0.3, 0.33, 0.408], [0.015, 0.018, 0.024], [0.168, 0.18, 0.24], [0.06, 0.054, 0.036],
       [0.006, 0.006, 0.006], [0.009, 0.009, 0.012], [0.03, 0.036, 0.054], [0.03, 0.027, 0.015],
       [0.012, 0.012, 0.009]]
EDITS = {
    "identity": {},
    # Higher and from further south: the patch moves and shrinks, still through the window.
    "sun_moved": {"lights": {"sun": {"direction": [0.62, -0.30, 0.72]}}},
    # The sky turned by 90 degrees about the vertical; the sun stays.
    "sky_rotated": {"lights": {"sky": {"rotate": {"axis": [0, 0, 1], "degrees": 90}}}},
    # The sky alone: what comes in without the sun.
    "sun_off": {"lights": {"sun": {"scale": 0.0}}},
}


def box(lo, hi):
    """A box's 6 faces, CCW seen from outside (fronts outward)."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (3, 0, 4, 7)]
    return [[v[i] for i in q] for q in quads]


def objects():
    """name -> (reflectance, faces). Walls overlap at the corners: no crack for light to leak."""
    T, X, Y, Z = 0.2, 5.0, 4.0, 3.0
    wy0, wy1, wz0, wz1 = 1.2, 2.8, 0.9, 2.2   # the window's opening in the east wall
    o = {
        "floor": (FLOOR, box((-T, -T, -T), (X + T, Y + T, 0))),
        "ceiling": (CEIL, box((-T, -T, Z), (X + T, Y + T, Z + T))),
        "wall_west": (WALL, box((-T, -T, 0), (0, Y + T, Z))),
        "wall_south": (WALL, box((0, -T, 0), (X, 0, Z))),
        "wall_north": (WALL, box((0, Y, 0), (X, Y + T, Z))),
        "wall_east": (WALL, box((X, -T, 0), (X + T, wy0, Z)) + box((X, wy1, 0), (X + T, Y + T, Z))
                      + box((X, wy0, 0), (X + T, wy1, wz0)) + box((X, wy0, wz1), (X + T, wy1, Z))),
        "box": (BOX, box((1.6, 1.5, 0), (2.2, 2.1, 0.6))),
    }
    return o


def camera():
    """By the window (x = 4.6), looking west into the room and down a little."""
    def unit(a):
        n = math.sqrt(sum(x * x for x in a)); return [x / n for x in a]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    eye, target = [4.7, 3.5, 1.7], [1.5, 1.6, 0.5]
    f = unit([target[i] - eye[i] for i in range(3)])
    r = unit(cross(f, [0, 0, 1.0]))
    d = cross(f, r)                         # OpenCV: x right, y down, z forward
    R = [r, d, f]
    t = [-sum(R[i][j] * eye[j] for j in range(3)) for i in range(3)]
    return {"width": 320, "height": 240, "K": [[200.0, 0, 159.5], [0, 200.0, 119.5], [0, 0, 1]],
            "world_to_camera": [list(R[i]) + [t[i]] for i in range(3)]}


def main():
    os.makedirs(os.path.join(OUT, "edits"), exist_ok=True)
    objs = objects()
    lines = ["# window_room.obj: bench/scenes/window_room/gen.py; metres, z up; faces CCW seen from their front"]
    n = 0
    for name, (_, faces) in objs.items():
        lines.append("o " + name)
        for f in faces:
            lines += ["v %g %g %g" % p for p in f]
            lines.append("f " + " ".join(str(n + k + 1) for k in range(len(f))))
            n += len(f)
    open(os.path.join(OUT, "window_room.obj"), "w").write("\n".join(lines) + "\n")
    scene = {"format": "relight-scene/1", "geometry": ["window_room.obj"], "camera": camera(),
             "photos": [{"file": "photo.exr", "encoding": "linear", "lights_on": ["sun", "sky"]}],
             "lights": [SUN, {"name": "sky", "type": "environment", "sh9": SKY}],
             "average_reflectance": 0.6}
    json.dump(scene, open(os.path.join(OUT, "scene.json"), "w"), indent=1)
    for name, e in EDITS.items():
        json.dump(dict({"format": "relight-edit/1"}, **e), open(os.path.join(OUT, "edits", name + ".json"), "w"),
                  indent=1)
    json.dump({k: {"reflectance": v[0], "faces": v[1]} for k, v in objs.items()},
              open(os.path.join(OUT, "geometry.json"), "w"))
    print("wrote", OUT)


if __name__ == "__main__":
    main()
