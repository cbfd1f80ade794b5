#!/usr/bin/python3
"""A truth from another structural code for the fit (issue 45, goal 9): the hybrid plate
(data/cases/hybrid_plate.json) under its dead pressure, geometrically nonlinear static, computed by
CalculiX (ccx, Debian calculix-ccx; S8R shells and B32R beams, tools/scripts/calculix_hybrid_plate.py),
written as a user with their own FEM data would give it to fin-fit (docs/studies/fit_structural_data.md):

    calculix_static_levels.py --case data/cases/hybrid_plate.json --ccx-nx 16 --nx 8 --levels 4 --out-dir DIR

DIR receives
    mesh.h5          the structural mesh on the nx x nx corner nodes (no /ibm): the plate as shells
                     (region 0, the membrane), each beam as a ray (ids 1, 2, 3), the leading edge as root
    motion.h5        positions at rest at each load level (time = load fraction 1/levels .. 1)
    nodal_loads.h5   this mesh's own nodal forces of the pressure at each level (a third of each
                     triangle's force per vertex, along -y): what a user's load case gives
    materials.json   densities and the case's moduli (the truth; fin-fit takes only densities and
                     the values of parameters not fitted from it)
    parameters.json  E_membrane, E_ray1..3 over three decades around the truth, nu in [0.15, 0.45]
    ccx.json         the run: ccx version, mesh sizes, wall time, tip displacements per level
ccx's mesh is ccx-nx x ccx-nx (a multiple of nx): the fit's nodes are every (ccx-nx / nx)-th corner
node, so that the truth is CalculiX's converged answer, not its coarse-mesh error.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import calculix_hybrid_plate as chp  # noqa: E402


def ccx_version():
    try:
        out = subprocess.run(["ccx", "-v"], capture_output=True, text=True, timeout=30).stdout
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    return " ".join(out.split()[-2:]) if out else "unknown"


def run_ccx(case, nx, levels, work):
    """ccx's static NLGEOM run with fixed increments 1/levels, every node's displacement printed at
    each level. Returns {level fraction: {node id: (ux, uy, uz)}} and the node coordinates."""
    inp = os.path.join(work, "plate.inp")
    case = dict(case)
    case["static"] = dict(case["static"], load_steps=levels)
    chp.write_input(inp, case, nx, nx, "static")
    nodes, *_ = chp.build_mesh(case, nx, nx)
    with open(inp) as fh:
        text = fh.read()
    # Fixed increments, so that every level is printed; all nodes instead of the tips.
    text = text.replace("*STATIC\n", "*STATIC, DIRECT\n").replace("*NODE PRINT, NSET=TIPS", "*NODE PRINT, NSET=NALL")
    with open(inp, "w") as fh:
        fh.write(text)
    t0 = time.time()
    r = subprocess.run(["ccx", "-i", "plate"], cwd=work, capture_output=True, text=True)
    wall = time.time() - t0
    if r.returncode != 0 or not os.path.exists(os.path.join(work, "plate.dat")):
        raise SystemExit(f"calculix_static_levels: ccx failed (exit {r.returncode}): {r.stdout[-400:]}")
    by_level = parse_all_nodes(os.path.join(work, "plate.dat"), levels)
    want = [k / levels for k in range(1, levels + 1)]
    missing = [w for w in want if w not in by_level]
    if missing:
        raise SystemExit(f"calculix_static_levels: ccx printed no displacements at load fractions {missing}")
    return {w: by_level[w] for w in want}, nodes, wall


def parse_all_nodes(path, levels):
    """{load fraction (rounded to the levels): {node: (ux, uy, uz)}} of the NALL blocks."""
    block = re.compile(r"displacements \(vx,vy,vz\) for set NALL and time\s+(\S+)")
    out, current = {}, None
    with open(path) as fh:
        for line in fh:
            m = block.search(line)
            if m:
                current = out.setdefault(round(float(m.group(1)) * levels) / levels, {})
                continue
            parts = line.split()
            if current is not None and len(parts) == 4 and parts[0].isdigit():
                current[int(parts[0])] = tuple(float(x) for x in parts[1:])
    return out


def provenance(f, config, inputs):
    f.attrs["producer"] = "calculix_static_levels.py (CalculiX " + ccx_version() + ")"
    f.attrs["config"] = json.dumps(config)
    f.attrs["inputs"] = json.dumps(inputs)


def dataset(f, name, data, units=None):
    d = f.create_dataset(name, data=data)
    if units is not None:
        d.attrs["units"] = units
    return d


def write_files(case, nx, ccx_nx, levels, u, ccx_nodes, out_dir, config):
    p = case["plate"]
    step = ccx_nx // nx
    # Our nodes: corner (i, k) of the nx x nx grid = ccx grid node (2 step i, 2 step k).
    ids, X = [], []
    for i in range(nx + 1):
        for k in range(nx + 1):
            n = chp.node_id(2 * step * i, 2 * step * k, 2 * ccx_nx)
            ids.append(n)
            X.append(ccx_nodes[n])
    X = np.array(X)
    idx = lambda i, k: i * (nx + 1) + k  # noqa: E731
    tri = []
    for i in range(nx):
        for k in range(nx):
            a, b, c, d = idx(i, k), idx(i + 1, k), idx(i + 1, k + 1), idx(i, k + 1)
            tri += [[a, b, c], [a, c, d]]
    tri = np.array(tri, dtype=np.int32)
    beams, ray, s, thick, width = [], [], [], [], []
    for r, b in enumerate(case["beams"], start=1):
        kb = round((b["z"] + 0.5 * p["span"]) / p["span"] * nx)
        for i in range(nx):
            beams.append([idx(i, kb), idx(i + 1, kb)])
            ray.append(r)
            s.append([i / nx, (i + 1) / nx])
            thick.append([b["thickness"]] * 2)
            width.append([b["width"]] * 2)
    root = np.array([idx(0, k) for k in range(nx + 1)], dtype=np.int32)
    mesh_path = os.path.join(out_dir, "mesh.h5")
    with h5py.File(mesh_path + ".tmp", "w") as f:
        f.attrs["schema"] = "finverse/mesh"
        f.attrs["schema_version"] = 1
        provenance(f, config, [])
        f.attrs["chord"] = p["chord"]
        dataset(f, "points", X, "m")
        dataset(f, "triangles", tri)
        dataset(f, "shell/thickness", np.full(len(tri), p["thickness"]), "m")
        dataset(f, "shell/region", np.zeros(len(tri), dtype=np.int32))
        dataset(f, "beams/elements", np.array(beams, dtype=np.int32))
        dataset(f, "beams/ray", np.array(ray, dtype=np.int32))
        dataset(f, "beams/s", np.array(s), "1")
        dataset(f, "beams/thickness", np.array(thick), "m")
        dataset(f, "beams/width", np.array(width), "m")
        dataset(f, "root_nodes", root)
    os.replace(mesh_path + ".tmp", mesh_path)

    fractions = sorted(u)
    pts = np.array([[X[j] + np.array(u[w][ids[j]]) for j in range(len(ids))] for w in fractions])
    # The mesh's own consistent nodal forces of the dead pressure: a third of each triangle's.
    f0 = np.zeros((len(ids), 3))
    for t in tri:
        e1, e2 = X[t[1]] - X[t[0]], X[t[2]] - X[t[0]]
        area = 0.5 * np.linalg.norm(np.cross(e1, e2))
        for v in t:
            f0[v, 1] -= case["static"]["pressure"] * area / 3.0
    forces = np.array([w * f0 for w in fractions])
    for name, schema, fields in (
        ("motion.h5", "finverse/motion", [("time", np.array(fractions), "s"), ("points", pts, "m")]),
        ("nodal_loads.h5", "finverse/nodal_loads", [("time", np.array(fractions), "s"), ("nodal_force", forces, "N")]),
    ):
        path = os.path.join(out_dir, name)
        with h5py.File(path + ".tmp", "w") as f:
            f.attrs["schema"] = schema
            f.attrs["schema_version"] = 1
            provenance(f, config, [])
            for key, data, units in fields:
                dataset(f, key, data, units)
        os.replace(path + ".tmp", path)

    rays = {str(r): {"E": b["E"], "nu": b["nu"], "density": b["density"]} for r, b in enumerate(case["beams"], start=1)}
    materials = {"description": "hybrid plate truth (data/cases/hybrid_plate.json) for the CalculiX static levels",
                 "membrane": {"E": p["E"], "nu": p["nu"], "density": p["density"]},
                 "rays": dict(rays["1"]), "ray": rays}
    with open(os.path.join(out_dir, "materials.json"), "w") as fh:
        json.dump(materials, fh, indent=2)
    params = [{"name": "E_membrane", "lower": p["E"] * 10 ** -1.3, "upper": p["E"] * 10 ** 1.7, "scale": "log10", "unit": "Pa"}]
    for r, b in enumerate(case["beams"], start=1):
        params.append({"name": f"E_ray{r}", "lower": b["E"] * 10 ** -1.3, "upper": b["E"] * 10 ** 1.7, "scale": "log10",
                       "unit": "Pa"})
    params.append({"name": "nu", "lower": 0.15, "upper": 0.45, "scale": "linear", "unit": "1"})
    with open(os.path.join(out_dir, "parameters.json"), "w") as fh:
        json.dump({"parameters": params}, fh, indent=2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--case", required=True)
    ap.add_argument("--nx", type=int, default=8, help="the fit's mesh: nx x nx cells")
    ap.add_argument("--ccx-nx", type=int, default=16, help="CalculiX's mesh (a multiple of --nx)")
    ap.add_argument("--levels", type=int, default=4, help="load levels, equally spaced up to the full pressure")
    ap.add_argument("--out-dir", required=True)
    a = ap.parse_args()
    if a.ccx_nx % a.nx or a.nx < 2 or a.levels < 1:
        raise SystemExit("calculix_static_levels: --ccx-nx must be a multiple of --nx >= 2, --levels >= 1")
    if shutil.which("ccx") is None:
        raise SystemExit("calculix_static_levels: ccx not found (tools/scripts/install-deps.sh --peers)")
    with open(a.case) as fh:
        case = json.load(fh)
    os.makedirs(a.out_dir, exist_ok=True)
    config = {"case": chp.portable(a.case), "nx": a.nx, "ccx_nx": a.ccx_nx, "levels": a.levels}
    with tempfile.TemporaryDirectory() as work:
        u, nodes, wall = run_ccx(case, a.ccx_nx, a.levels, work)
    write_files(case, a.nx, a.ccx_nx, a.levels, u, nodes, a.out_dir, config)
    _, _, _, _, _, tips, _ = chp.build_mesh(case, a.ccx_nx, a.ccx_nx)
    report = dict(config, ccx=ccx_version(), ccx_wall_seconds=wall,
                  tips={name: {str(w): u[w][n] for w in sorted(u)} for name, n in tips.items()})
    with open(os.path.join(a.out_dir, "ccx.json"), "w") as fh:
        json.dump(report, fh, indent=2)
    print(f"calculix_static_levels: {a.levels} levels, ccx {a.ccx_nx}x{a.ccx_nx} in {wall:.1f} s, wrote {a.out_dir}")


if __name__ == "__main__":
    main()
