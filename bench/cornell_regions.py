#!/usr/bin/python3
"""Mean of an image over the Cornell box's surfaces against the truth's, per channel.

    /usr/bin/python3 bench/cornell_regions.py data/cornell IMAGE [EDIT]

Prints image / truth over pixel boxes of data/cornell's 256 x 256 view (the ceiling, the
floor and its rows, the walls), the pixels that see no lamp only (truth/EDIT.mask.png). A
bench reads the truth to judge; the engine never does. Used for the forward solve's level
(bench/RESULTS.md, 2026-11-29, eighteenth session): where a uniformly dark indirect light
shows, surface by surface.
"""
import sys

import numpy as np
import OpenImageIO as oiio


def pixels(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"cornell_regions: {path}: {buf.geterror()}")
    return buf.get_pixels(oiio.FLOAT)


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    scene, image = sys.argv[1], sys.argv[2]
    edit = sys.argv[3] if len(sys.argv) == 4 else "identity"
    a = pixels(image)[:, :, :3]
    t = pixels(f"{scene}/truth/{edit}.exr")[:, :, :3]
    mask = pixels(f"{scene}/truth/{edit}.mask.png")[:, :, 0] > 0.99
    if a.shape != t.shape:
        sys.exit(f"cornell_regions: {image} is {a.shape[1]}x{a.shape[0]}, the truth "
                 f"{t.shape[1]}x{t.shape[0]}")
    # (rows, columns) of data/cornell's camera, 256 x 256.
    regions = [("ceiling", (0, 40), (40, 216)), ("floor", (225, 256), (40, 216)),
               ("left wall", (60, 200), (0, 30)), ("right wall", (60, 200), (226, 256)),
               ("back wall", (60, 120), (90, 170)), ("all", (0, 256), (0, 256))]
    regions += [(f"floor rows {y}-{y + 7}", (y, y + 8), (100, 156)) for y in range(200, 256, 8)]
    for name, (y0, y1), (x0, x1) in regions:
        keep = mask[y0:y1, x0:x1]
        A = a[y0:y1, x0:x1][keep].mean(axis=0)
        T = t[y0:y1, x0:x1][keep].mean(axis=0)
        print(f"{name:18s} image/truth {np.round(A / T, 3)}  truth {np.round(T, 4)}")


if __name__ == "__main__":
    main()
