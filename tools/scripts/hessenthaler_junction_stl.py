#!/usr/bin/python3
"""Writes the Hessenthaler et al. (2017) flap phantom's fluid volume as a closed binary STL file: two
inlet pipes (21.9 mm) that open, side by side, through the floor of the outlet pipe (76.2 mm), for
fin-cfd case files with `fluid: inside` (docs/studies/pipe_flow.md, "The junction").

The paper gives the diameters, the inlets' centres at y = +-27.15 mm, the inlet plane z = -29.5 mm
and the outlet plane z = 89.5 mm (../shared/reference/hessenthaler2017/README.md); z = 0 is the
clamp. Choices it leaves open, made here:
  - the inlet pipes run straight along z up to the clamp's plane z = 0, which is the outlet pipe's
    flat floor;
  - 27.15 + 10.95 = 38.1 mm: the inlets touch the outlet's wall, and a floor with holes that touch
    its rim is not a manifold surface. The inlets are moved inwards by --gap (default 0.25 mm, a
    quarter of the finest grid cell planned) so the floor keeps a sliver there;
  - every pipe reaches --beyond (5 mm) past its plane, closed by a flat cap outside the domain.
The floor is a Delaunay triangulation (scipy) of its rims and a hexagonal lattice of spacing
--spacing; the walls are rings of the rims' vertices. The script checks that the surface is closed
and consistently oriented and that it encloses the volume of the three pipes.

    /usr/bin/python3 tools/scripts/hessenthaler_junction_stl.py --out data/cases/cfd/hessenthaler/junction.stl
"""
import argparse
import math
import os
import struct
import sys

import numpy as np
from scipy.spatial import Delaunay


def ring(cx, cy, r, n, z):
    a = 2 * math.pi * np.arange(n) / n
    return np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a), np.full(n, z)])


def floor(r_out, holes, spacing):
    """The floor's 2-D points (outer rim first, then each hole's rim, then the lattice) and its
    triangles, clockwise seen from +z (normal -z: out of the fluid above it)."""
    n_out = 4 * math.ceil(2 * math.pi * r_out / spacing / 4)
    rims = [ring(0, 0, r_out, n_out, 0)[:, :2]]
    for cx, cy, r in holes:
        rims.append(ring(cx, cy, r, 4 * math.ceil(2 * math.pi * r / spacing / 4), 0)[:, :2])
    dy = spacing * math.sqrt(3) / 2
    lattice = []
    for j, y in enumerate(np.arange(-r_out, r_out + dy, dy)):
        for x in np.arange(-r_out + (j % 2) * spacing / 2, r_out + spacing, spacing):
            if math.hypot(x, y) > r_out - 0.6 * spacing:
                continue
            if any(math.hypot(x - cx, y - cy) < r + 0.6 * spacing for cx, cy, r in holes):
                continue
            lattice.append((x, y))
    pts = np.vstack(rims + [np.array(lattice)])
    tri = Delaunay(pts).simplices
    c = pts[tri].mean(axis=1)
    keep = np.hypot(c[:, 0], c[:, 1]) < r_out
    for cx, cy, r in holes:
        keep &= np.hypot(c[:, 0] - cx, c[:, 1] - cy) > r
    tri = tri[keep]
    a, b, d = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
    ccw = (b[:, 0] - a[:, 0]) * (d[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (d[:, 0] - a[:, 0]) > 0
    tri[ccw] = tri[ccw][:, [0, 2, 1]]
    return pts, [len(r) for r in rims], tri


def tube(points, tris, rim_index, n, centre, r, z_from, z_to, layer):
    """A pipe's wall from its rim at z_from (vertex indices rim_index, n of them, counter-clockwise
    seen from +z) to a capped end at z_to, outward (away from the axis and, at the cap, along z)."""
    layers = max(1, round(abs(z_to - z_from) / layer))
    prev = list(rim_index)
    up = z_to > z_from
    for l in range(1, layers + 1):
        z = z_from + (z_to - z_from) * l / layers
        start = len(points)
        points.extend(ring(centre[0], centre[1], r, n, z))
        cur = list(range(start, start + n))
        lo, hi = (prev, cur) if up else (cur, prev)
        for k in range(n):
            k1 = (k + 1) % n
            tris.append((lo[k], lo[k1], hi[k1]))
            tris.append((lo[k], hi[k1], hi[k]))
        prev = cur
    c = len(points)
    points.append((centre[0], centre[1], z_to))
    for k in range(n):
        k1 = (k + 1) % n
        tris.append((c, prev[k], prev[k1]) if up else (c, prev[k1], prev[k]))


def check_closed(tris, points):
    edges = {}
    for t in tris:
        for e in range(3):
            a, b = t[e], t[(e + 1) % 3]
            edges[(a, b)] = edges.get((a, b), 0) + 1
    bad = [e for e, m in edges.items() if m != 1 or edges.get((e[1], e[0]), 0) != 1]
    if bad:
        sys.exit(f"hessenthaler_junction_stl: {len(bad)} edges are not shared by exactly two consistently oriented "
                 f"triangles (e.g. {bad[0]}); try a smaller --spacing or a larger --gap")
    p = np.asarray(points)
    t = np.asarray(tris)
    return float(np.einsum("ij,ij->i", p[t[:, 0]], np.cross(p[t[:, 1]], p[t[:, 2]])).sum() / 6)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--spacing", type=float, default=1.0, help="vertex spacing on the rims and floor [mm]")
    ap.add_argument("--gap", type=float, default=0.25, help="floor left between an inlet and the outlet's wall [mm]")
    ap.add_argument("--beyond", type=float, default=5.0, help="pipe length past the inlet and outlet planes [mm]")
    args = ap.parse_args()
    r_in, r_out, z_in, z_out = 21.9 / 2, 76.2 / 2, -29.5, 89.5
    y_in = r_out - r_in - args.gap
    holes = [(0.0, y_in, r_in), (0.0, -y_in, r_in)]
    pts2, counts, ftri = floor(r_out, holes, args.spacing)
    points = [(x, y, 0.0) for x, y in pts2]
    tris = [tuple(t) for t in ftri]
    first = np.cumsum([0] + counts)
    layer = 2 * args.spacing
    tube(points, tris, range(first[0], first[1]), counts[0], (0, 0), r_out, 0.0, z_out + args.beyond, layer)
    for h, (cx, cy, r) in enumerate(holes):
        tube(points, tris, range(first[h + 1], first[h + 2]), counts[h + 1], (cx, cy), r, 0.0, z_in - args.beyond,
             layer)
    volume = check_closed(tris, points)
    expected = math.pi * (r_out ** 2 * (z_out + args.beyond) + 2 * r_in ** 2 * (args.beyond - z_in))
    if abs(volume / expected - 1) > 0.01:
        sys.exit(f"hessenthaler_junction_stl: enclosed volume {volume:.1f} mm^3, expected {expected:.1f}")
    p = np.asarray(points) * 1e-3  # metres
    tmp = args.out + ".tmp"
    with open(tmp, "wb") as f:
        f.write(b"Hessenthaler 2017 flap phantom: fluid volume, m".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for a, b, c in tris:
            n = np.cross(p[b] - p[a], p[c] - p[a])
            n = n / np.linalg.norm(n)
            f.write(struct.pack("<12fH", *n, *p[a], *p[b], *p[c], 0))
    os.replace(tmp, args.out)
    print(f"{args.out}: {len(tris)} triangles, {len(points)} vertices, volume {volume / 1e3:.2f} cm^3 "
          f"({volume / expected - 1:+.2e} from the pipes'), inlets at y = +-{y_in:.2f} mm")


if __name__ == "__main__":
    main()
