"""The window room's geometry three ways, for the diagnosis of bench/RESULTS.md (2026-11-27,
seventh session): the light, camera and truth of data/window_room, the true reflectances
given as scene.json "objects" (for `relight solve --no-photo-reflectance` and
bench/transport_check), photo, edits and truth linked from data/window_room.
  as_is:        window_room.obj as gen.py writes it (0.2 m boxes overlapping at the corners)
  no_exterior:  the same without the faces on the boxes' outer planes (the walls', floor's
                and ceiling's outsides, lit by the sun and the sky, which no camera sees)
  interior:     only the room's inner faces, one quad per wall around the window, and the
                window's four reveals: no face buried in another box, none outside
Usage: python3 bench/scenes/window_room/variants.py OUT_DIR
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen  # noqa: E402

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "data", "window_room")
T, X, Y, Z = 0.2, 5.0, 4.0, 3.0
WY0, WY1, WZ0, WZ1 = 1.2, 2.8, 0.9, 2.2


def on_outer_plane(face):
    for axis, values in ((0, (-T, X + T)), (1, (-T, Y + T)), (2, (-T, Z + T))):
        for v in values:
            if all(abs(p[axis] - v) < 1e-9 for p in face):
                return True
    return False


def interior():
    """name -> faces, fronts towards the room (CCW seen from the front)."""
    def east(y0, y1, z0, z1):  # normal -x
        return [(X, y0, z0), (X, y0, z1), (X, y1, z1), (X, y1, z0)]
    walls = [east(0, WY0, 0, Z), east(WY1, Y, 0, Z), east(WY0, WY1, 0, WZ0), east(WY0, WY1, WZ1, Z),
             [(X, WY0, WZ0), (X + T, WY0, WZ0), (X + T, WY1, WZ0), (X, WY1, WZ0)],  # sill, +z
             [(X, WY0, WZ1), (X, WY1, WZ1), (X + T, WY1, WZ1), (X + T, WY0, WZ1)],  # lintel, -z
             [(X, WY0, WZ0), (X, WY0, WZ1), (X + T, WY0, WZ1), (X + T, WY0, WZ0)],  # jamb, +y
             [(X, WY1, WZ0), (X + T, WY1, WZ0), (X + T, WY1, WZ1), (X, WY1, WZ1)]]  # jamb, -y
    return {
        "floor": [[(0, 0, 0), (X, 0, 0), (X, Y, 0), (0, Y, 0)]],
        "ceiling": [[(0, 0, Z), (0, Y, Z), (X, Y, Z), (X, 0, Z)]],
        "wall_west": [[(0, 0, 0), (0, Y, 0), (0, Y, Z), (0, 0, Z)]],
        "wall_south": [[(0, 0, 0), (0, 0, Z), (X, 0, Z), (X, 0, 0)]],
        "wall_north": [[(0, Y, 0), (X, Y, 0), (X, Y, Z), (0, Y, Z)]],
        "wall_east": walls,
        "box": gen.box((1.6, 1.5, 0), (2.2, 2.1, 0.6))[1:],  # its bottom lies on the floor
    }


def write(out, faces_by_object):
    os.makedirs(out, exist_ok=True)
    lines, n = [], 0
    for name, faces in faces_by_object.items():
        lines.append("o " + name)
        for f in faces:
            lines += ["v %g %g %g" % tuple(p) for p in f]
            lines.append("f " + " ".join(str(n + k + 1) for k in range(len(f))))
            n += len(f)
    open(os.path.join(out, "window_room.obj"), "w").write("\n".join(lines) + "\n")
    scene = json.load(open(os.path.join(DATA, "scene.json")))
    scene["objects"] = {k: {"reflectance": list(v[0])} for k, v in gen.objects().items()}
    json.dump(scene, open(os.path.join(out, "scene.json"), "w"), indent=1)
    for name in ("photo.exr", "photo.mask.png", "edits", "truth"):
        link = os.path.join(out, name)
        if not os.path.lexists(link):
            os.symlink(os.path.abspath(os.path.join(DATA, name)), link)


def main():
    out = sys.argv[1]
    objs = {k: v[1] for k, v in gen.objects().items()}
    write(os.path.join(out, "as_is"), objs)
    write(os.path.join(out, "no_exterior"),
          {k: [f for f in v if not on_outer_plane(f)] for k, v in objs.items()})
    write(os.path.join(out, "interior"), interior())
    print("wrote", out)


if __name__ == "__main__":
    main()
