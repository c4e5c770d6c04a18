#!/usr/bin/python3
"""Render rpkCpp's solution (its VRML export) through a relight scene's camera.

    /usr/bin/python3 bench/rpkcpp/render_vrml.py SCENE_DIR model.wrl out.exr [--spp-side 4]

rpkCpp writes its hierarchical solution as an IndexedFaceSet: every leaf element with its
own corners and the radiance of its basis functions at them (with
bench/rpkcpp/raw_radiance_vrml.patch: the radiance itself, 9 digits, no tone map). This
casts side x side stratified rays per pixel through scene.json's pinhole camera (K and
world_to_camera, OpenCV convention, (0, 0) the centre of the top-left pixel), takes the
nearest front-facing element each ray meets, interpolates its corner radiances
(barycentric on each triangle; a quad as two triangles) and writes the pixel mean, as
Cycles' Box filter of 1 px does for the truth. It is rpkCpp's own display (Gouraud
shading of its elements' corner values), cast at relight's camera and resolution.
"""
import json
import re
import sys

import numpy as np
import OpenImageIO as oiio


def parse_vrml(path):
    text = open(path).read()
    def block(key):
        m = re.search(key + r"\s*\[([^\]]*)\]", text)
        if not m:
            sys.exit(f"{path}: no '{key} [ ... ]' block (not an rpkCpp Galerkin VRML export?)")
        return np.array([float(v) for v in m.group(1).replace(",", " ").split()])
    points = block(r"point").reshape(-1, 3)
    colours = block(r"color").reshape(-1, 3)
    index = block(r"coordIndex").astype(np.int64)
    if len(points) != len(colours):
        sys.exit(f"{path}: {len(points)} points but {len(colours)} colours")
    tris = []
    face = []
    for i in index:
        if i < 0:
            for k in range(1, len(face) - 1):
                tris.append((face[0], face[k], face[k + 1]))
            face = []
        else:
            face.append(int(i))
    return points, colours, np.array(tris, dtype=np.int64)


def main():
    args = sys.argv[1:]
    side = 4
    if "--spp-side" in args:
        k = args.index("--spp-side")
        side = int(args[k + 1])
        del args[k:k + 2]
    if len(args) != 3:
        sys.exit(__doc__)
    scene_dir, wrl, out = args
    cam = json.load(open(f"{scene_dir}/scene.json"))["camera"]
    W, H = cam["width"], cam["height"]
    K = np.array(cam["K"], dtype=np.float64)
    Rt = np.array(cam["world_to_camera"], dtype=np.float64)
    R, t = Rt[:, :3], Rt[:, 3]
    origin = -R.T @ t
    points, colours, tris = parse_vrml(wrl)

    # Sample grid: (H*side, W*side) rays, stratified at the sub-cell centres.
    off = (np.arange(side) + 0.5) / side - 0.5
    us = (np.arange(W)[:, None] + off[None, :]).ravel()
    vs = (np.arange(H)[:, None] + off[None, :]).ravel()
    uu, vv = np.meshgrid(us, vs)
    dcam = np.stack([(uu - K[0, 2]) / K[0, 0], (vv - K[1, 2]) / K[1, 1], np.ones_like(uu)], -1)
    dirs = dcam @ R  # R^T d, row vectors
    depth = np.full(uu.shape, np.inf)
    image = np.zeros(uu.shape + (3,))

    def project(p):
        c = (p - origin) @ R.T
        return K[0, 0] * c[..., 0] / c[..., 2] + K[0, 2], K[1, 1] * c[..., 1] / c[..., 2] + K[1, 2], c[..., 2]

    pu, pv, pz = project(points)
    for a, b, c in tris:
        if min(pz[a], pz[b], pz[c]) <= 1e-9:
            continue  # behind the camera: not in the Cornell box's view
        # samples whose centre may fall inside the projected triangle
        x0 = int(np.floor((min(pu[a], pu[b], pu[c]) + 0.5) * side)) - 1
        x1 = int(np.ceil((max(pu[a], pu[b], pu[c]) + 0.5) * side)) + 1
        y0 = int(np.floor((min(pv[a], pv[b], pv[c]) + 0.5) * side)) - 1
        y1 = int(np.ceil((max(pv[a], pv[b], pv[c]) + 0.5) * side)) + 1
        x0, y0 = max(x0, 0), max(y0, 0)
        x1, y1 = min(x1, W * side), min(y1, H * side)
        if x0 >= x1 or y0 >= y1:
            continue
        d = dirs[y0:y1, x0:x1]
        e1 = points[b] - points[a]
        e2 = points[c] - points[a]
        n = np.cross(e1, e2)
        if n @ dirs[(y0 + y1) // 2, (x0 + x1) // 2] >= 0:
            continue  # one-sided surfaces: seen from behind
        # Moller-Trumbore
        pvec = np.cross(d, e2)
        det = pvec @ e1
        ok = np.abs(det) > 1e-15
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        s = origin - points[a]
        bu = (pvec @ s) * inv
        q = np.cross(s, e1)
        bv = (d * q).sum(-1) * inv
        tt = (q @ e2) * inv
        hit = ok & (bu >= 0) & (bv >= 0) & (bu + bv <= 1) & (tt > 0) & (tt < depth[y0:y1, x0:x1])
        if not hit.any():
            continue
        col = ((1 - bu - bv)[..., None] * colours[a] + bu[..., None] * colours[b]
               + bv[..., None] * colours[c])
        depth[y0:y1, x0:x1] = np.where(hit, tt, depth[y0:y1, x0:x1])
        image[y0:y1, x0:x1] = np.where(hit[..., None], col, image[y0:y1, x0:x1])
    pixels = image.reshape(H, side, W, side, 3).mean(axis=(1, 3)).astype(np.float32)
    buf = oiio.ImageBuf(oiio.ImageSpec(W, H, 3, oiio.FLOAT))
    buf.set_pixels(oiio.ROI(0, W, 0, H, 0, 1, 0, 3), pixels)
    if not buf.write(out):
        sys.exit(f"{out}: {buf.geterror()}")
    print(f"wrote {out} ({W}x{H}, {side * side} rays per pixel, {len(tris)} triangles)")


if __name__ == "__main__":
    main()
