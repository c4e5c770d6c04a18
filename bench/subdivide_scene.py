#!/usr/bin/python3
"""Copy a scene package with every triangle of its OBJ files cut into 4 by its edges'
midpoints, LEVELS times (x4^LEVELS faces). The surface is the same, so the package's
truths still hold and are copied: the engine's cost and scores against the input's size
with the lighting unchanged (issue 30, "the staircase subdivided once and twice").
Midpoints are shared between the faces of an edge, so the mesh stays watertight.
usage: subdivide_scene.py SRC DST LEVELS"""
import json, os, shutil, sys


def face_indices(line, vertex_count):
    """The 0-based vertex indices of OBJ face line `line` (negative indices count back from
    the vertices read so far, `vertex_count`; texture and normal indices dropped)."""
    idx = [int(t.split('/')[0]) for t in line.split()[1:]]
    return [i - 1 if i > 0 else vertex_count + i for i in idx]


def subdivide(lines):
    verts = [tuple(map(float, l.split()[1:4])) for l in lines if l.startswith('v ')]
    mid = {}

    def midpoint(a, b):
        key = (a, b) if a < b else (b, a)
        if key not in mid:
            pa, pb = verts[a], verts[b]
            verts.append(tuple((x + y) / 2 for x, y in zip(pa, pb)))
            mid[key] = len(verts) - 1
        return mid[key]

    body = []
    for l in lines:
        if l.startswith('f '):
            idx = face_indices(l, len(verts))
            if len(idx) != 3:
                raise SystemExit('only triangles are subdivided: ' + l)
            a, b, c = idx
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            for f in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)):
                body.append('f %d %d %d' % tuple(i + 1 for i in f))
        elif not l.startswith('v '):
            body.append(l)
    return ['v %.10g %.10g %.10g' % v for v in verts] + body


def rewrite_package(src, dst, rewrite):
    """Copies package src to dst (its .relight cache left out) and replaces the lines of each
    of its OBJ files by rewrite(name, lines). The truths are copied: the engine never reads
    them, and a rewrite that keeps the surface keeps them valid."""
    shutil.rmtree(dst, ignore_errors=True)
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns('.relight'))
    scene = json.load(open(os.path.join(dst, 'scene.json')))
    for g in scene['geometry']:
        path = os.path.join(dst, g)
        os.chmod(path, 0o644)
        lines = rewrite(g, open(path).read().splitlines())
        open(path, 'w').write('\n'.join(lines) + '\n')


def main():
    src, dst, levels = sys.argv[1], sys.argv[2], int(sys.argv[3])

    def rewrite(name, lines):
        for _ in range(levels):
            lines = subdivide(lines)
        print('%s: %d faces' % (name, sum(1 for l in lines if l.startswith('f '))))
        return lines

    rewrite_package(src, dst, rewrite)


if __name__ == '__main__':
    main()
