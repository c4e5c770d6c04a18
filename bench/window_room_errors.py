"""Where a relit image's error lies (bench/RESULTS.md, 2026-11-27, seventh session), with the
spec's 4 x 4 blocks (docs/scene-format.md, "Metric"); a bench may read the truth, the engine
never does. Run with /usr/bin/python3 (numpy, OpenImageIO).

  window_room_errors.py edit SCENE EDIT IMAGE...
      per image: rel_rmse; R/T summed over the blocks away from any sun patch (the indirect
      light and the sky's); over the "new patch" (blocks that the edit lights to more than
      3 times the image's median while the photo had them below it): the mean and spread of
      R/T and their share of the squared error; and the error over blocks of 4, 8, 16 and
      40 pixels (noise halves with each doubling, a wrong light does not)
  window_room_errors.py ratio IMAGE TRUTH
      image / truth (channel mean) over blocks of 40 x 40 pixels
"""
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[..., :3]


def blocks(a, k):
    h, w = a.shape[0] // k * k, a.shape[1] // k * k
    return a[:h, :w].reshape(h // k, k, w // k, k, -1).mean(axis=(1, 3))


def edit(scene, name, images):
    truth_full = read(f"{scene}/truth/{name}.exr")
    photo = blocks(read(f"{scene}/photo.exr"), 4).mean(-1)
    T = blocks(truth_full, 4)
    Tl = T.mean(-1)
    med = np.median(Tl)
    patch = (Tl > 3 * med) & (photo < 3 * np.median(photo))
    rest = Tl < 3 * med
    print(f"{scene} {name}: {patch.sum()} new-patch blocks, {rest.sum()} away from a patch, of {Tl.size}")
    for path in images:
        full = read(path)
        R = blocks(full, 4)
        e2 = ((R - T) ** 2).mean(-1)
        r = R.mean(-1) / np.maximum(Tl, 1e-9)
        scales = []
        for k in (4, 8, 16, 40):
            Tk, Rk = blocks(truth_full, k), blocks(full, k)
            scales.append(np.sqrt(((Rk - Tk) ** 2).mean()) / Tk.mean())
        line = f"  {path}: rel_rmse {np.sqrt(e2.mean()) / T.mean():.4f}  rest R/T {R.mean(-1)[rest].sum() / Tl[rest].sum():.4f}"
        if patch.any():
            line += (f"  new patch R/T mean {r[patch].mean():.4f} spread {r[patch].std():.4f}"
                     f" share of error {e2[patch].sum() / e2.sum():.3f}")
        print(line)
        print("    error over blocks of 4/8/16/40 px: " + " ".join(f"{s:.4f}" for s in scales))


def ratio(image, truth):
    a, b = read(image).mean(-1), read(truth).mean(-1)
    h, w = a.shape[0] // 40 * 40, a.shape[1] // 40 * 40
    r = a[:h, :w].reshape(h // 40, 40, w // 40, 40).sum(axis=(1, 3)) / \
        b[:h, :w].reshape(h // 40, 40, w // 40, 40).sum(axis=(1, 3))
    np.set_printoptions(precision=3, suppress=True, linewidth=150)
    print(f"{image} / {truth}, 40 px blocks: min {r.min():.3f} median {np.median(r):.3f} max {r.max():.3f}")
    print(r)


if __name__ == "__main__":
    if len(sys.argv) >= 5 and sys.argv[1] == "edit":
        edit(sys.argv[2], sys.argv[3], sys.argv[4:])
    elif len(sys.argv) == 4 and sys.argv[1] == "ratio":
        ratio(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
