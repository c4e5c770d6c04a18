"""The furnished room (issue 34): geometry, materials, lights, camera and edits, in one place.

Plain Python (no Blender, no numpy), imported by gen.py (writes the scene package) and by
render.py (builds the identical scene in Blender Cycles and renders the truths), so that the
OBJ the engine reads and the scene Cycles renders come from the same vertex lists.

A 4 x 5 x 2.6 m box room (metres, z up): a brick wall on the left (x = 0), a striped
wallpaper at the back (y = 5), plain plaster on the right, a plank floor. Two ceiling lamps.
A bookshelf (sides, back, boards and books) stands against the brick wall, a cabinet in the
back-right corner against the striped wall and the plaster wall: the two removable objects.
Every material is diffuse with albedo <= 0.85.
"""
import math
import random

W, D, H = 4.0, 5.0, 2.6  # room size along x, y, z

# Materials: "flat" (an albedo), "bricks" (Cycles' Brick texture in the plane's two world
# axes, metres), "stripes" (two colours alternating along one world axis).
MATERIALS = {
    "plaster": {"type": "flat", "rgb": (0.72, 0.72, 0.66)},
    "ceiling": {"type": "flat", "rgb": (0.78, 0.78, 0.76)},
    "front": {"type": "flat", "rgb": (0.7, 0.7, 0.7)},
    "bricks": {"type": "bricks", "axes": (1, 2), "c1": (0.56, 0.26, 0.17),
               "c2": (0.44, 0.2, 0.14), "mortar": (0.7, 0.68, 0.62), "width": 0.25,
               "row": 0.075, "mortar_size": 0.012},
    "planks": {"type": "bricks", "axes": (0, 1), "c1": (0.52, 0.35, 0.2),
               "c2": (0.4, 0.26, 0.15), "mortar": (0.22, 0.14, 0.09), "width": 1.2,
               "row": 0.16, "mortar_size": 0.006},
    "stripes": {"type": "stripes", "axis": 0, "width": 0.12, "c1": (0.74, 0.7, 0.56),
                "c2": (0.5, 0.58, 0.68)},
    "wood": {"type": "flat", "rgb": (0.46, 0.3, 0.17)},
    "cabinet": {"type": "flat", "rgb": (0.62, 0.6, 0.55)},
    "cabinet_top": {"type": "flat", "rgb": (0.3, 0.22, 0.16)},
}


def material_mean(name):
    """The nominal mean albedo of a material (a user's knowledge of a surface the photo misses)."""
    m = MATERIALS[name]
    if m["type"] == "flat":
        return m["rgb"]
    if m["type"] == "stripes":
        return tuple(0.5 * (a + b) for a, b in zip(m["c1"], m["c2"]))
    # bricks: the mortar's share of the area, the rest half c1 half c2 on average
    s = m["mortar_size"]
    f = 1.0 - (1.0 - 2 * s / m["width"]) * (1.0 - 2 * s / m["row"])
    return tuple(f * c + (1 - f) * 0.5 * (a + b) for a, b, c in zip(m["c1"], m["c2"], m["mortar"]))


def box(x0, x1, y0, y1, z0, z1):
    """A closed axis-aligned box, faces outward (CCW seen from outside): (vertices, quads)."""
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return v, f


def quad(*vs):
    return list(vs), [(0, 1, 2, 3)]


def parts():
    """Every object of the model: name -> list of (material, vertices, faces)."""
    o = {
        # room surfaces, fronts facing into the room
        "floor": [("planks",) + quad((0, 0, 0), (W, 0, 0), (W, D, 0), (0, D, 0))],
        "ceiling": [("ceiling",) + quad((0, D, H), (W, D, H), (W, 0, H), (0, 0, H))],
        "wall_left": [("bricks",) + quad((0, 0, 0), (0, D, 0), (0, D, H), (0, 0, H))],
        "wall_right": [("plaster",) + quad((W, 0, H), (W, D, H), (W, D, 0), (W, 0, 0))],
        "wall_back": [("stripes",) + quad((0, D, 0), (W, D, 0), (W, D, H), (0, D, H))],
        "wall_front": [("front",) + quad((0, 0, H), (W, 0, H), (W, 0, 0), (0, 0, 0))],
    }
    o["bookshelf"] = bookshelf()
    o["cabinet"] = [("cabinet",) + box(3.28, 3.98, 4.44, 4.98, 0.0, 0.92),
                    ("cabinet_top",) + box(3.26, 3.98, 4.42, 4.98, 0.921, 0.96)]
    return o


BOOK_COLOURS = [(0.62, 0.12, 0.1), (0.12, 0.25, 0.5), (0.15, 0.42, 0.2), (0.75, 0.65, 0.3),
                (0.3, 0.3, 0.32), (0.8, 0.78, 0.72), (0.45, 0.15, 0.35), (0.2, 0.5, 0.55)]


def bookshelf():
    """Sides, back, five boards and rows of books against the brick wall (x = 0)."""
    x0, x1, y0, y1, top = 0.02, 0.34, 2.0, 3.0, 1.8
    p = [("wood",) + box(x0, x1, y0, y0 + 0.02, 0, top),
         ("wood",) + box(x0, x1, y1 - 0.02, y1, 0, top),
         ("wood",) + box(x0, x0 + 0.01, y0 + 0.02, y1 - 0.02, 0, top)]
    boards = [(0.0, 0.06), (0.44, 0.46), (0.88, 0.9), (1.32, 1.34), (1.78, 1.8)]
    for b0, b1 in boards:
        p.append(("wood",) + box(x0 + 0.01, x1, y0 + 0.02, y1 - 0.02, b0, b1))
    rng = random.Random(34)
    for (_, base), (ceil, _) in zip(boards[:-1], boards[1:]):
        y = y0 + 0.03 + rng.uniform(0.0, 0.06)
        while True:
            wdt = rng.uniform(0.03, 0.06)
            if y + wdt > y1 - 0.03:
                break
            hgt = min(rng.uniform(0.2, 0.34), ceil - base - 0.04)
            dep = rng.uniform(0.17, 0.26)
            mat = "book%d" % rng.randrange(len(BOOK_COLOURS))
            p.append((mat,) + box(x0 + 0.02, x0 + 0.02 + dep, y, y + wdt, base + 0.001,
                                  base + 0.001 + hgt))
            y += wdt + (0.002 if rng.random() < 0.8 else rng.uniform(0.05, 0.15))
    return p


for _i, _c in enumerate(BOOK_COLOURS):
    MATERIALS["book%d" % _i] = {"type": "flat", "rgb": _c}

REMOVABLE = ["bookshelf", "cabinet"]

# Lamps: one-sided quads just under the ceiling, emitting downwards (CCW seen from below).
LIGHTS = [
    {"name": "A", "type": "quad", "radiance": [14.0, 12.4, 10.2],
     "vertices": [[1.2, 2.0, 2.595], [1.2, 2.5, 2.595], [1.7, 2.5, 2.595], [1.7, 2.0, 2.595]]},
    {"name": "B", "type": "quad", "radiance": [11.5, 11.8, 12.6],
     "vertices": [[2.4, 3.5, 2.595], [2.4, 4.0, 2.595], [2.9, 4.0, 2.595], [2.9, 3.5, 2.595]]},
]

WIDTH, HEIGHT, FOCAL = 320, 240, 170.0
EYE, TARGET = (3.1, 0.45, 1.55), (1.55, 4.1, 0.75)


def camera():
    """OpenCV pinhole: K and world_to_camera = [R | t], R's rows = right, down, forward."""
    f = [t - e for t, e in zip(TARGET, EYE)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    up = (0.0, 0.0, 1.0)
    r = [f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]]
    n = math.sqrt(sum(c * c for c in r))
    r = [c / n for c in r]
    d = [f[1] * r[2] - f[2] * r[1], f[2] * r[0] - f[0] * r[2], f[0] * r[1] - f[1] * r[0]]
    R = [r, d, f]
    t = [-sum(R[i][j] * EYE[j] for j in range(3)) for i in range(3)]
    K = [[FOCAL, 0.0, (WIDTH - 1) / 2.0], [0.0, FOCAL, (HEIGHT - 1) / 2.0], [0.0, 0.0, 1.0]]
    return K, [R[i] + [t[i]] for i in range(3)]


def project(p):
    """Pixel (u, v) and depth of a world point."""
    K, Rt = camera()
    xc = [sum(Rt[i][j] * p[j] for j in range(3)) + Rt[i][3] for i in range(3)]
    return K[0][0] * xc[0] / xc[2] + K[0][2], K[1][1] * xc[1] / xc[2] + K[1][2], xc[2]


EDITS = {"identity": {}, "remove_bookshelf": {"remove_objects": ["bookshelf"]},
         "remove_cabinet": {"remove_objects": ["cabinet"]}}
