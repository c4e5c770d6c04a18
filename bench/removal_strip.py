#!/usr/bin/python3
"""A README strip of a removal: the photo, the removal and the truth side by side, cropped
around what the removal changed, in sRGB 8-bit.

  /usr/bin/python3 bench/removal_strip.py OUT.png PHOTO.exr REMOVED.exr TRUTH.exr [more.exr]
      [--pad 12] [--scale 2] [--box X0,Y0,W,H]

The crop is the bounding box of the pixels where REMOVED differs from PHOTO by more than 15 %
of the photo's mean, padded, widened to 4:3 and clamped to the image.
"""
import argparse

import numpy as np
import OpenImageIO as oiio


def read(path):
    buf = oiio.ImageBuf(path)
    px = buf.get_pixels(oiio.FLOAT)
    if px is None or px.size == 0:
        raise SystemExit(f"{path}: cannot read")
    return np.asarray(px)[:, :, :3]


def crop_box(photo, removed, pad):
    d = np.abs(removed - photo).max(axis=2)
    ys, xs = np.nonzero(d > 0.15 * photo.mean())
    if len(xs) == 0:
        raise SystemExit("the removal changed nothing")
    h, w = photo.shape[:2]
    x0, x1 = max(xs.min() - pad, 0), min(xs.max() + pad + 1, w)
    y0, y1 = max(ys.min() - pad, 0), min(ys.max() + pad + 1, h)
    # Widen to 4:3 around the centre, then clamp.
    cw, ch = x1 - x0, y1 - y0
    if cw * 3 < ch * 4:
        cw = (ch * 4 + 2) // 3
    else:
        ch = (cw * 3 + 3) // 4
    cw, ch = min(cw, w), min(ch, h)
    cx, cy = (x0 + x1) // 2, (y0 + y1) // 2
    x0 = min(max(cx - cw // 2, 0), w - cw)
    y0 = min(max(cy - ch // 2, 0), h - ch)
    return x0, y0, cw, ch


def srgb(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("images", nargs="+")
    ap.add_argument("--pad", type=int, default=12)
    ap.add_argument("--scale", type=int, default=2)
    ap.add_argument("--box", help="X0,Y0,W,H: this crop instead of the changed pixels' box")
    a = ap.parse_args()
    imgs = [read(p) for p in a.images]
    if a.box:
        x0, y0, cw, ch = (int(v) for v in a.box.split(","))
    else:
        x0, y0, cw, ch = crop_box(imgs[0], imgs[1], a.pad)
    panels = [im[y0:y0 + ch, x0:x0 + cw] for im in imgs]
    strip = np.concatenate(panels, axis=1)
    strip = np.repeat(np.repeat(strip, a.scale, axis=0), a.scale, axis=1)
    out = (srgb(strip) * 255 + 0.5).astype(np.uint8)
    spec = oiio.ImageSpec(out.shape[1], out.shape[0], 3, oiio.UINT8)
    buf = oiio.ImageBuf(spec)
    buf.set_pixels(oiio.ROI(), out)
    if not buf.write(a.out):
        raise SystemExit(f"{a.out}: {buf.geterror()}")
    print(f"wrote {a.out}: crop ({x0}, {y0}) {cw}x{ch}, {len(imgs)} panels")


main()
