#!/usr/bin/env python3
"""Write data/cornell as an MGF file for rpkCpp (bench/rpkcpp/compare.sh).

    python3 bench/rpkcpp/cornell_mgf.py data/cornell out.mgf [--scene-copy DIR]

--scene-copy DIR also writes DIR/scene.json: data/cornell's with these reflectances as
each object's `reflectance`, and links to its other files, so that
`relight solve DIR --no-photo-reflectance` solves the problem rpkCpp solves.

Geometry: cornell.obj's faces as they are (one-sided, counter-clockwise from the front,
which is MGF's convention too) and scene.json's light quad. Materials: the reflectances
data/cornell/README.md publishes (white, red, green; rpkCpp solves the forward problem,
it is given the true reflectances, while relight estimates them from the photo) and the
light's radiance from scene.json.

rpkCpp reads a colour as CIE xy plus a luminance Y and turns it into its RGB with the
inverse of its RGB->XYZ matrix (src/common/cie.cpp, monitor primaries of
src/tonemap/ToneMappingContext.cpp: r (0.64, 0.33), g (0.29, 0.60), b (0.15, 0.06), white
(1/3, 1/3)); writing M * rgb here gives back the RGB values within float rounding.
Emission: rpkCpp divides `ed` (lm/m^2) by its white efficacy 183.07 to get the exitance
in W/m^2, and a diffuse emitter's radiance is exitance / pi, so ed = Y(M * pi * L) * 183.07.
"""
import json
import math
import os
import sys

WHITE_EFFICACY = 183.07  # rpkCpp src/common/cie.cpp
PRIMARIES = [(0.64, 0.33), (0.29, 0.60), (0.15, 0.06)]
WHITE = (1.0 / 3.0, 1.0 / 3.0)
# data/cornell/README.md: reflectances per material, objects per material
REFLECTANCE = {
    "white": (0.725, 0.71, 0.68),
    "red": (0.63, 0.065, 0.05),
    "green": (0.14, 0.45, 0.091),
}
MATERIAL_OF = {"left_wall": "red", "right_wall": "green"}  # every other object: white


def solve3(a, b):
    """Solve the 3x3 system a x = b (Cramer's rule)."""
    def det(m):
        return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    d = det(a)
    out = []
    for k in range(3):
        m = [row[:] for row in a]
        for i in range(3):
            m[i][k] = b[i]
        out.append(det(m) / d)
    return out


def rgb_to_xyz_matrix():
    """Columns: the primaries' XYZ, scaled so that RGB (1, 1, 1) is the white (Y = 1)."""
    p = [[x / y for x, y in PRIMARIES], [1.0, 1.0, 1.0],
         [(1 - x - y) / y for x, y in PRIMARIES]]
    xw, yw = WHITE
    s = solve3(p, [xw / yw, 1.0, (1 - xw - yw) / yw])
    return [[p[i][j] * s[j] for j in range(3)] for i in range(3)]


def mgf_colour(rgb, m):
    xyz = [sum(m[i][j] * rgb[j] for j in range(3)) for i in range(3)]
    total = sum(xyz)
    return xyz[0] / total, xyz[1] / total, xyz[1]


def main():
    args = sys.argv[1:]
    copy = None
    if "--scene-copy" in args:
        k = args.index("--scene-copy")
        copy = args[k + 1]
        del args[k:k + 2]
    if len(args) != 2:
        sys.exit("usage: cornell_mgf.py SCENE_DIR OUT.mgf [--scene-copy DIR]")
    scene_dir, out = args
    scene = json.load(open(os.path.join(scene_dir, "scene.json")))
    if copy:
        write_scene_copy(scene_dir, scene, copy)
    m = rgb_to_xyz_matrix()
    lines = ["# data/cornell for rpkCpp, written by bench/rpkcpp/cornell_mgf.py"]
    for name, rgb in REFLECTANCE.items():
        x, y, lum = mgf_colour(rgb, m)
        lines += [f"m {name} =", "\tsides 1", "\tc", f"\t\tcxy {x:.9f} {y:.9f}", f"\trd {lum:.9f}"]
    verts, obj = [], None
    for raw in open(os.path.join(scene_dir, "cornell.obj")):
        t = raw.split()
        if not t or t[0].startswith("#"):
            continue
        if t[0] == "o":
            obj = t[1]
            lines.append(f"o {obj}")
            lines.append(f"m {MATERIAL_OF.get(obj, 'white')}")
        elif t[0] == "v":
            verts.append(t[1:4])
            lines += [f"v v{len(verts)} =", "\tp " + " ".join(t[1:4])]
        elif t[0] == "f":
            lines.append("f " + " ".join("v" + i.split("/")[0] for i in t[1:]))
    lines = close_objects(lines)
    for light in scene["lights"]:
        pi_l = [math.pi * c * WHITE_EFFICACY for c in light["radiance"]]
        x, y, lum = mgf_colour(pi_l, m)
        name = light["name"]
        lines += [f"o light_{name}", f"m emitter_{name} =", "\tsides 1", "\tc",
                  f"\t\tcxy {x:.9f} {y:.9f}", f"\ted {lum:.9f}", "\tc", "\trd 0"]
        ids = []
        for k, v in enumerate(light["vertices"]):
            ids.append(f"l{name}{k}")
            lines += [f"v {ids[-1]} =", "\tp " + " ".join(f"{c:.9g}" for c in v)]
        lines += ["f " + " ".join(ids), "o"]
    open(out, "w").write("\n".join(lines) + "\n")


def write_scene_copy(scene_dir, scene, copy):
    os.makedirs(copy, exist_ok=True)
    for name in os.listdir(scene_dir):
        if name != "scene.json" and not os.path.exists(os.path.join(copy, name)):
            os.symlink(os.path.abspath(os.path.join(scene_dir, name)), os.path.join(copy, name))
    objects = {}
    for raw in open(os.path.join(scene_dir, "cornell.obj")):
        t = raw.split()
        if t and t[0] == "o":
            objects[t[1]] = {"reflectance": list(REFLECTANCE[MATERIAL_OF.get(t[1], "white")])}
    s = dict(scene)
    s["objects"] = {k: dict(scene.get("objects", {}).get(k, {}), **v) for k, v in objects.items()}
    json.dump(s, open(os.path.join(copy, "scene.json"), "w"), indent=1)


def close_objects(lines):
    """MGF objects nest: end each `o NAME` before the next one opens."""
    out, open_obj = [], False
    for line in lines:
        if line.startswith("o "):
            if open_obj:
                out.append("o")
            open_obj = True
        out.append(line)
    if open_obj:
        out.append("o")
    return out


if __name__ == "__main__":
    main()
