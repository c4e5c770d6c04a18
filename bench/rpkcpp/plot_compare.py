#!/usr/bin/python3
"""Log-log plot of bench/rpkcpp/compare.sh's output: rel_rmse against solve seconds.

    /usr/bin/python3 bench/rpkcpp/plot_compare.py OUT.png NOW.txt [BEFORE.txt]

Series: relight's `--epsilon` rows (photo reflectance, and given reflectance), rpkCpp's
lower envelope over its thresholds and iterations (the best error reached within each
time), and, from BEFORE.txt, relight's photo-reflectance rows of an earlier build. Dashed
grey: the issue's 0.018 and the data's noise floor 0.0132; the vertical line: 0.4 s.
"""
import math
import sys

import OpenImageIO as oiio

W, H, L, R, T, B = 900, 600, 90, 220, 30, 70
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"  # Debian fonts-dejavu-core
X0, X1, Y0, Y1 = 0.01, 10.0, 0.01, 0.1


def rows(path, solver, only_epsilon=True):
    out = []
    for line in open(path):
        if not line.startswith(solver):
            continue
        f = line.split()
        if only_epsilon and ("--time-budget" in line or "--min-rays" in line):
            continue
        try:
            t, e = float(f[-5]), float(f[-1])
        except (ValueError, IndexError):
            continue  # a row without a score
        out.append((t, e))
    return sorted(out)


def envelope(points):
    best, out = math.inf, []
    for t, e in sorted(points):
        if e < best:
            best = e
            out.append((t, e))
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    now = sys.argv[2]
    series = [("relight, photo rho", (0.1, 0.3, 0.9), rows(now, "relight photo")),
              ("relight, given rho", (0.5, 0.7, 1.0), rows(now, "relight given")),
              ("rpkCpp Galerkin", (0.9, 0.3, 0.1), envelope(rows(now, "rpkCpp", False)))]
    if len(sys.argv) > 3:
        series.append(("relight before", (0.6, 0.6, 0.6), rows(sys.argv[3], "relight photo")))
    img = oiio.ImageBuf(oiio.ImageSpec(W, H, 3, oiio.UINT8))
    oiio.ImageBufAlgo.fill(img, (1, 1, 1))
    px = lambda x: L + int((math.log10(x) - math.log10(X0)) / (math.log10(X1) - math.log10(X0)) * (W - L - R))
    py = lambda y: H - B - int((math.log10(y) - math.log10(Y0)) / (math.log10(Y1) - math.log10(Y0)) * (H - T - B))
    grey, black = (0.85, 0.85, 0.85), (0, 0, 0)
    for d in (0.01, 0.1, 1, 10):
        oiio.ImageBufAlgo.render_line(img, px(d), T, px(d), H - B, grey)
        oiio.ImageBufAlgo.render_text(img, px(d) - 10, H - B + 20, f"{d:g}", 16, FONT, black)
    for d in (0.01, 0.02, 0.03, 0.05, 0.1):
        oiio.ImageBufAlgo.render_line(img, L, py(d), W - R, py(d), grey)
        oiio.ImageBufAlgo.render_text(img, 20, py(d) + 5, f"{d:g}", 16, FONT, black)
    for y in (0.018, 0.0132):
        for x in range(L, W - R, 12):
            oiio.ImageBufAlgo.render_line(img, x, py(y), x + 6, py(y), (0.5, 0.5, 0.5))
    oiio.ImageBufAlgo.render_line(img, px(0.4), T, px(0.4), H - B, (0.5, 0.5, 0.5))
    oiio.ImageBufAlgo.render_text(img, L + 200, H - 15, "solve seconds (one core)", 16, FONT, black)
    oiio.ImageBufAlgo.render_text(img, 5, T - 8, "rel_rmse vs truth", 16, FONT, black)
    for k, (label, c, pts) in enumerate(series):
        pts = [(t, e) for t, e in pts if X0 <= t <= X1 and Y0 <= e <= Y1]
        for (ta, ea), (tb, eb) in zip(pts, pts[1:]):
            oiio.ImageBufAlgo.render_line(img, px(ta), py(ea), px(tb), py(eb), c)
        for t, e in pts:
            oiio.ImageBufAlgo.render_box(img, px(t) - 3, py(e) - 3, px(t) + 3, py(e) + 3, c, True)
        oiio.ImageBufAlgo.render_box(img, W - R + 15, T + 20 + 25 * k, W - R + 27, T + 32 + 25 * k, c, True)
        oiio.ImageBufAlgo.render_text(img, W - R + 35, T + 33 + 25 * k, label, 15, FONT, black)
    if not img.write(sys.argv[1]):
        sys.exit(f"{sys.argv[1]}: {img.geterror()}")
    print(f"wrote {sys.argv[1]}")


if __name__ == "__main__":
    main()
