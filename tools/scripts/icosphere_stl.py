#!/usr/bin/python3
"""Writes a sphere as a binary STL file: an icosahedron whose triangles are split into four, s
times, with every new vertex pushed out onto the sphere (20 * 4^s triangles, counter-clockwise
seen from outside). It is the geometry of fin-cfd's built-in sphere (tools/cfd/immersed/
surface_shapes.hpp) written independently, for the case file data/cases/cfd/sphere_re100_stl.yaml:
a body that reaches the solver through a user's surface file instead of C++.

    /usr/bin/python3 tools/scripts/icosphere_stl.py --subdivisions 5 --radius 0.5 --out sphere.stl
"""
import argparse
import os
import struct

import numpy as np


def icosahedron():
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
         (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    v = np.array(v, float)
    return v / np.linalg.norm(v, axis=1)[:, None], f


def subdivide(v, f):
    v = list(map(tuple, v))
    mid = {}

    def middle(a, b):
        key = (min(a, b), max(a, b))
        if key not in mid:
            p = (np.array(v[a]) + np.array(v[b])) / 2
            v.append(tuple(p / np.linalg.norm(p)))
            mid[key] = len(v) - 1
        return mid[key]

    out = []
    for a, b, c in f:
        ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
        out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return np.array(v), out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--subdivisions", type=int, default=5)
    ap.add_argument("--radius", type=float, default=0.5)
    ap.add_argument("--centre", type=float, nargs=3, default=[0.0, 0.0, 0.0])
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    v, f = icosahedron()
    for _ in range(a.subdivisions):
        v, f = subdivide(v, f)
    v = a.radius * v + np.array(a.centre)
    body = bytearray(b"icosphere: tools/scripts/icosphere_stl.py".ljust(80, b" "))
    body += struct.pack("<I", len(f))
    for tri in f:
        p = v[list(tri)]
        n = np.cross(p[1] - p[0], p[2] - p[0])
        n /= np.linalg.norm(n)
        assert np.dot(n, p.mean(axis=0) - a.centre) > 0, "triangle not counter-clockwise from outside"
        body += struct.pack("<12fH", *n, *p[0], *p[1], *p[2], 0)
    tmp = a.out + ".tmp"
    with open(tmp, "wb") as out:
        out.write(body)
    os.replace(tmp, a.out)
    print(f"wrote {a.out}: {len(f)} triangles, {len(v)} vertices")


if __name__ == "__main__":
    main()
