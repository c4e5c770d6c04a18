#!/usr/bin/python3
"""Copy a scene package with the OBJ triangles that cross an axis-aligned plane cut along it
(each into a triangle and a quad, the quad as two triangles; winding kept), for the light-leak
experiments of bench/RESULTS.md (2026-11-28): a polygon that runs through a wall or a floor
slab is one element lit on both sides until the refinement splits it.
usage: split_at_plane.py SRC DST CUT [CUT ...]
  CUT  AXIS=VALUE[:AXIS(min|max)(<|>)LIMIT]   e.g. "y=-0.853:zmax>3.9" cuts the triangles
       that cross y = -0.853 and reach above z = 3.9; "z=3.96:ymax<-0.80"."""
import re, sys

from subdivide_scene import rewrite_package

AX = {'x': 0, 'y': 1, 'z': 2}


def parse(cut):
    m = re.fullmatch(r'([xyz])=([-+.\deE]+)(?::([xyz])(min|max)([<>])([-+.\deE]+))?', cut)
    if not m:
        raise SystemExit('bad cut: ' + cut)
    a, v = AX[m.group(1)], float(m.group(2))
    cond = None
    if m.group(3):
        ca, f, op, lim = AX[m.group(3)], min if m.group(4) == 'min' else max, m.group(5), float(m.group(6))
        cond = lambda P: (f(p[ca] for p in P) > lim) if op == '>' else (f(p[ca] for p in P) < lim)
    return a, v, cond


def cut_once(lines, a, v, cond):
    verts = [tuple(map(float, l.split()[1:4])) for l in lines if l.startswith('v ')]
    n0, out, count = len(verts), [], 0
    for l in lines:
        if l.startswith('f '):
            idx = [int(t.split('/')[0]) for t in l.split()[1:]]
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


def main():
    src, dst, cuts = sys.argv[1], sys.argv[2], [parse(c) for c in sys.argv[3:]]

    def rewrite(name, lines):
        for (a, v, cond), text in zip(cuts, sys.argv[3:]):
            lines, count = cut_once(lines, a, v, cond)
            print('%s: %s cut %d triangles' % (name, text, count))
        return lines

    rewrite_package(src, dst, rewrite)


if __name__ == '__main__':
    main()
