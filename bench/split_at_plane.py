#!/usr/bin/python3
"""Copy a scene package with the OBJ triangles that cross an axis-aligned plane cut along it
(each into a triangle and a quad, the quad as two triangles; winding kept), for the light-leak
experiments of bench/RESULTS.md (2026-11-28): a polygon that runs through a wall or a floor
slab is one element lit on both sides until the refinement splits it.
usage: split_at_plane.py SRC DST [--only-added-light EDIT] CUT [CUT ...]
  CUT  AXIS=VALUE[:AXIS(min|max)(<|>)LIMIT]   e.g. "y=-0.853:zmax>3.9" cuts the triangles
       that cross y = -0.853 and reach above z = 3.9; "z=3.96:ymax<-0.80".
  --only-added-light EDIT   the copy's only light is the quad that edit EDIT (a file of the
       package's edits/) adds, on in the photo: a forward `relight solve` of that light alone
       (the leak experiments' "lamp-only copy")."""
import json, os, re, sys

from subdivide_scene import face_indices, rewrite_package

AX = {'x': 0, 'y': 1, 'z': 2}


def parse(cut):
    m = re.fullmatch(r'([xyz])=([-+.\deE]+)(?::([xyz])(min|max)([<>])([-+.\deE]+))?', cut)
    if not m:
        raise SystemExit('bad cut: ' + cut)
    a, v = AX[m.group(1)], float(m.group(2))
    if not m.group(3):
        return a, v, None
    ca, f, op, lim = AX[m.group(3)], min if m.group(4) == 'min' else max, m.group(5), float(m.group(6))

    def cond(P):
        x = f(p[ca] for p in P)
        return x > lim if op == '>' else x < lim

    return a, v, cond


def cut_once(lines, a, v, cond):
    verts = [tuple(map(float, l.split()[1:4])) for l in lines if l.startswith('v ')]
    out, count = [], 0
    for l in lines:
        if l.startswith('f '):
            idx = [i + 1 for i in face_indices(l, len(verts))]  # 1-based, as written back
            P = [verts[i - 1] for i in idx]
            vals = [p[a] for p in P]
            if len(idx) == 3 and min(vals) < v - 1e-4 and max(vals) > v + 1e-4 and (not cond or cond(P)):
                count += 1
                for side in (1, -1):
                    poly = []
                    for k in range(3):
                        pa, pb, ia = P[k], P[(k + 1) % 3], idx[k]
                        ina, inb = (pa[a] - v) * side >= 0, (pb[a] - v) * side >= 0
                        if ina:
                            poly.append(ia)
                        if ina != inb:
                            t = (v - pa[a]) / (pb[a] - pa[a])
                            verts.append(tuple(pa[i] + t * (pb[i] - pa[i]) for i in range(3)))
                            poly.append(len(verts))
                    for k in range(1, len(poly) - 1):
                        out.append('f %d %d %d' % (poly[0], poly[k], poly[k + 1]))
                continue
        if not l.startswith('v '):
            out.append(l)
    return ['v %.10g %.10g %.10g' % p for p in verts] + out, count


def only_added_light(dst, edit):
    """Makes the added quad of edits/`edit` the scene's only light, on in every photo."""
    added = json.load(open(os.path.join(dst, 'edits', edit)))['add_lights'][0]
    path = os.path.join(dst, 'scene.json')
    scene = json.load(open(path))
    scene['lights'] = [{'name': added['name'], 'type': 'quad', 'vertices': added['vertices'],
                        'radiance': added['radiance']}]
    for photo in scene.get('photos', []):
        photo['lights_on'] = [added['name']]
    json.dump(scene, open(path, 'w'), indent=1)


def main():
    args = sys.argv[1:]
    edit = None
    if '--only-added-light' in args:
        k = args.index('--only-added-light')
        edit = args[k + 1]
        del args[k:k + 2]
    src, dst, texts = args[0], args[1], args[2:]
    cuts = [parse(c) for c in texts]

    def rewrite(name, lines):
        for (a, v, cond), text in zip(cuts, texts):
            lines, count = cut_once(lines, a, v, cond)
            print('%s: %s cut %d triangles' % (name, text, count))
        return lines

    rewrite_package(src, dst, rewrite)
    if edit:
        only_added_light(dst, edit)


if __name__ == '__main__':
    main()
