#!/usr/bin/env python3
"""OpenFOAM (Debian package openfoam, pimpleFoam) peer for the DFG benchmark 2D-2
(Schaefer & Turek 1996; ../shared/reference/schaefer_turek.json): flow past a cylinder in a
channel at Re = 100, periodic vortex shedding; with --benchmark 2d3 the same channel under the
inflow 1.5 sin(pi t/8) over t in [0, 8] (2D-3), whose largest drag and lift and their times have
high-precision reference values (John 2004) to measure the peer's own accuracy against.

Writes a structured 12-block mesh (an O-grid around the cylinder inside a square, and the
channel around it), the parabolic inflow profile on the exact inlet face centres, runs
blockMesh + pimpleFoam (second order in space and time) on the given cores, and reports CD_max,
CL_max, CL_min, St, the lift amplitude of the pressure and the viscous force (to compare with the
split of fin-cfd's forces.csv) and the wall time as JSON:

    openfoam_dfg.py --cells 32 --out results/bench/openfoam_dfg2.json [--ranks 2] [--t-end 10] [--window 3]
    openfoam_dfg.py --cells 48 --courant 0.25 --out F     (half the default step: the peer's time error)
    openfoam_dfg.py --cells 48 --outer-correctors 3 --out F   (PIMPLE: without PISO's splitting error)
    openfoam_dfg.py --benchmark 2d3 --cells 48 --out F     (CD_max, CL_max and their times; t_end 8)

--cells is the number of cells on each quarter of the cylinder; the others follow from it. The
benchmark runs a sequence of meshes and takes the cheapest that is within 1% of the bounds'
midpoints, i.e. the mesh "that reaches the same accuracy" as finverse.
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

H, L, XC, YC, R = 0.41, 2.2, 0.2, 0.2, 0.05
UM, NU = 1.5, 1e-3          # 2D-2: Um = 1.5, Ubar = 1, Re = Ubar D / nu = 100
UBAR, D, DZ = 1.0, 0.1, 0.01

HEADER = """FoamFile
{{
    version 2.0;
    format ascii;
    class {cls};
    object {obj};
}}
"""


def foam(path, cls, obj, body):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as fh:
        fh.write(HEADER.format(cls=cls, obj=obj) + body)


def block_mesh(n):
    """Vertices, blocks, arc edges and patches of the 12-block mesh; n cells per quarter circle."""
    a = R / math.sqrt(2)
    xs, ys = [0.0, 0.1, 0.3, L], [0.0, 0.1, 0.3, H]
    pts = [(x, y) for y in ys for x in xs]                      # 16 channel points, index 4*row+col
    cyl = [(XC - a, YC - a), (XC + a, YC - a), (XC + a, YC + a), (XC - a, YC + a)]   # 225, 315, 45, 135 deg
    pts += cyl                                                  # 16..19
    P = lambda r, c: 4 * r + c
    sq = [P(1, 1), P(1, 2), P(2, 2), P(2, 1)]                   # square corners matching cyl[]
    n_left, n_bottom, n_top = max(2, n // 2), max(2, n // 2), max(2, round(0.55 * n))
    n_rad = max(4, round(0.75 * n))
    h_near = 2 * math.pi * R / (4 * n)                          # arc spacing at the cylinder
    # Downstream: first cell as on the square side (0.2/n), growing to about 4x that.
    h0 = 0.2 / n
    n_down = max(8, round((L - 0.3) / (2.5 * h0)))
    grow_down = 4.0
    n_of_col = [n_left, n, n_down]
    n_of_row = [n_bottom, n, n_top]
    blocks, patches = [], {"inlet": [], "outlet": [], "walls": [], "cylinder": []}
    for r in range(3):
        for c in range(3):
            if r == 1 and c == 1:
                continue
            v = [P(r, c), P(r, c + 1), P(r + 1, c + 1), P(r + 1, c)]
            gx = grow_down if c == 2 else 1.0
            blocks.append((v, (n_of_col[c], n_of_row[r]), (gx, 1.0)))
            if c == 0: patches["inlet"].append((v[3], v[0]))
            if c == 2: patches["outlet"].append((v[1], v[2]))
            if r == 0: patches["walls"].append((v[0], v[1]))
            if r == 2: patches["walls"].append((v[2], v[3]))
    # O-grid: cylinder point, square corner, next square corner, next cylinder point (CCW): the
    # first local direction is radial (graded so the cells at the cylinder are about square).
    grow_rad = max(1.0, (0.1 - R) / n_rad / h_near) ** 1.0
    edges = []
    for q in range(4):
        p1, p2 = 16 + q, 16 + (q + 1) % 4
        v = [p1, sq[q], sq[(q + 1) % 4], p2]
        blocks.append((v, (n_rad, n), (grow_rad * 1.6, 1.0)))
        ang = math.radians(225 + 90 * q + 45)
        edges.append((p1, p2, (XC + R * math.cos(ang), YC + R * math.sin(ang))))
        patches["cylinder"].append((p2, p1))
    return pts, blocks, edges, patches


def write_case(case, n, t_end, dt, ranks, outer=1):
    pts, blocks, edges, patches = block_mesh(n)
    nv = len(pts)
    verts = "".join(f"    ({x:.12g} {y:.12g} 0)\n" for x, y in pts) + "".join(f"    ({x:.12g} {y:.12g} {DZ})\n" for x, y in pts)
    blks = ""
    for v, (nx, ny), (gx, gy) in blocks:
        ids = " ".join(map(str, v + [i + nv for i in v]))
        blks += f"    hex ({ids}) ({nx} {ny} 1) simpleGrading ({gx:.6g} {gy:.6g} 1)\n"
    edg = ""
    for p1, p2, (x, y) in edges:
        edg += f"    arc {p1} {p2} ({x:.12g} {y:.12g} 0)\n    arc {p1 + nv} {p2 + nv} ({x:.12g} {y:.12g} {DZ})\n"
    bnd = ""
    kinds = {"inlet": "patch", "outlet": "patch", "walls": "wall", "cylinder": "wall"}
    for name, faces in patches.items():
        fl = "".join(f"            ({a} {b} {b + nv} {a + nv})\n" for a, b in faces)
        bnd += f"    {name}\n    {{\n        type {kinds[name]};\n        faces\n        (\n{fl}        );\n    }}\n"
    bnd += "    frontAndBack\n    {\n        type empty;\n        faces\n        (\n"
    for v, _, _ in blocks:
        bnd += f"            ({v[0]} {v[3]} {v[2]} {v[1]})\n            ({v[0] + nv} {v[1] + nv} {v[2] + nv} {v[3] + nv})\n"
    bnd += "        );\n    }\n"
    foam(f"{case}/system/blockMeshDict", "dictionary", "blockMeshDict",
         f"convertToMeters 1;\nvertices\n(\n{verts});\nblocks\n(\n{blks});\nedges\n(\n{edg});\nboundary\n(\n{bnd});\n")
    write_every = max(1, int(round(t_end / dt)))
    foam(f"{case}/system/controlDict", "dictionary", "controlDict", f"""application pimpleFoam;
startFrom startTime; startTime 0; stopAt endTime; endTime {t_end};
deltaT {dt}; writeControl timeStep; writeInterval {write_every};
purgeWrite 1; writeFormat ascii; writePrecision 10; writeCompression off;
timeFormat general; timePrecision 8; runTimeModifiable false;
functions
{{
    forceCoeffs
    {{
        type forceCoeffs; libs ("libforces.so"); writeControl timeStep; writeInterval 1;
        patches (cylinder); rho rhoInf; rhoInf 1; CofR ({XC} {YC} 0);
        liftDir (0 1 0); dragDir (1 0 0); pitchAxis (0 0 1);
        magUInf {UBAR}; lRef {D}; Aref {D * DZ};
    }}
    forces
    {{
        type forces; libs ("libforces.so"); writeControl timeStep; writeInterval 1;
        patches (cylinder); rho rhoInf; rhoInf 1; CofR ({XC} {YC} 0);
    }}
}}
""")
    foam(f"{case}/system/fvSchemes", "dictionary", "fvSchemes", """ddtSchemes { default backward; }
gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; div((nuEff*dev2(T(grad(U))))) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
""")
    foam(f"{case}/system/fvSolution", "dictionary", "fvSolution", """solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-8; relTol 0.01; }
    pFinal { $p; relTol 0; }
    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-9; relTol 0; }
    UFinal { $U; }
}
PIMPLE { nOuterCorrectors %d; nCorrectors 2; nNonOrthogonalCorrectors 1; pRefCell 0; pRefValue 0; }
""" % outer)
    foam(f"{case}/system/decomposeParDict", "dictionary", "decomposeParDict",
         # Debian's OpenFOAM ships only a stub of scotch; a split along x is what a channel wants.
         f"numberOfSubdomains {ranks};\nmethod simple;\nsimpleCoeffs {{ n ({ranks} 1 1); delta 0.001; }}\n")
    foam(f"{case}/constant/transportProperties", "dictionary", "transportProperties",
         f"transportModel Newtonian;\nnu {NU};\n")
    foam(f"{case}/constant/turbulenceProperties", "dictionary", "turbulenceProperties", "simulationType laminar;\n")


def inlet_face_centres(case):
    """y of each inlet face centre, in patch order, from the ASCII polyMesh blockMesh wrote."""
    mesh = f"{case}/constant/polyMesh"
    text = open(f"{mesh}/boundary").read()
    m = re.search(r"inlet\s*\{[^}]*nFaces\s+(\d+);[^}]*startFace\s+(\d+);", text, re.S)
    nfaces, start = int(m.group(1)), int(m.group(2))
    def body(name):
        t = open(f"{mesh}/{name}").read()
        t = t[t.index("(", t.index("FoamFile") + t[t.index("FoamFile"):].index("}")):]
        return t
    pts = [tuple(map(float, p.split())) for p in re.findall(r"\(([-\d.eE+ ]+)\)", body("points"))]
    faces = re.findall(r"\d+\(([\d ]+)\)", body("faces"))
    ys = []
    for f in faces[start:start + nfaces]:
        ids = list(map(int, f.split()))
        ys.append(sum(pts[i][1] for i in ids) / len(ids))
    return ys


def write_sine_inflow(case, ys, t_end, every=0.02):
    # 2D-3's inlet: the parabola at the face centres times sin(pi t / 8), sampled every `every`
    # seconds for timeVaryingMappedFixedValue (linear in time between samples: 1e-5 of the peak).
    # The points repeat at both faces of the one-cell-thick 2-D mesh so that they span a plane.
    # Raw lists, without the FoamFile header (v1912 reads them with operator>>).
    root = f"{case}/constant/boundaryData/inlet"
    pts = [(0.0, y, z) for z in (0.0, DZ) for y in ys]

    def raw(path, rows):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as fh:
            fh.write(f"{len(rows)}\n(\n" + "".join(rows) + ")\n")

    raw(f"{root}/points", [f"({x:.12g} {y:.12g} {z:.12g})\n" for x, y, z in pts])
    steps = int(round(t_end / every))
    for m in range(steps + 1):
        t = m * every
        amp = math.sin(math.pi * t / 8)
        raw(f"{root}/{t:.6g}/U", [f"({amp * 4 * UM * y * (H - y) / H ** 2:.12g} 0 0)\n" for _, y, _ in pts])


def write_fields(case, sine_t_end=None):
    ys = inlet_face_centres(case)
    prof = "".join(f"({4 * UM * y * (H - y) / H ** 2:.12g} 0 0)\n" for y in ys)
    if sine_t_end:
        write_sine_inflow(case, ys, sine_t_end)
        inlet = f"inlet {{ type timeVaryingMappedFixedValue; offset (0 0 0); setAverage false; value uniform (0 0 0); }}"
    else:
        inlet = f"""inlet {{ type fixedValue; value nonuniform List<vector> {len(ys)}
(
{prof}); }}"""
    foam(f"{case}/0/U", "volVectorField", "U", f"""dimensions [0 1 -1 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{{
    {inlet}
    outlet {{ type zeroGradient; }}
    walls {{ type noSlip; }}
    cylinder {{ type noSlip; }}
    frontAndBack {{ type empty; }}
}}
""")
    foam(f"{case}/0/p", "volScalarField", "p", """dimensions [0 2 -2 0 0 0 0];
internalField uniform 0;
boundaryField
{
    inlet { type zeroGradient; }
    outlet { type fixedValue; value uniform 0; }
    walls { type zeroGradient; }
    cylinder { type zeroGradient; }
    frontAndBack { type empty; }
}
""")


FOAM_BASHRC = "/usr/share/openfoam/etc/bashrc"   # Debian's OpenFOAM environment


def run(cmd, case, log):
    # OpenFOAM's tools find their etc/ files through the environment its bashrc sets up.
    line = f"source {FOAM_BASHRC} >/dev/null 2>&1; exec " + " ".join(cmd)
    with open(os.path.join(case, log), "w") as fh:
        p = subprocess.run(["bash", "-c", line], cwd=case, stdout=fh, stderr=subprocess.STDOUT)
    if p.returncode != 0:
        tail = open(os.path.join(case, log)).read().splitlines()[-12:]
        raise SystemExit(f"openfoam_dfg: {' '.join(cmd)} failed:\n" + "\n".join(tail))


def coefficients(case):
    files = []
    for root, _, names in os.walk(os.path.join(case, "postProcessing", "forceCoeffs")):
        files += [os.path.join(root, n) for n in names if n.startswith("coefficient") or n.startswith("forceCoeffs")]
    if not files:
        raise SystemExit("openfoam_dfg: no forceCoeffs output")
    t, cd, cl = [], [], []
    with open(sorted(files)[0]) as fh:
        header = None
        for line in fh:
            if line.startswith("#"):
                cols = line[1:].split()
                if "Cd" in cols:
                    header = cols
                continue
            v = line.split()
            if header is None or len(v) < len(header):
                continue
            row = dict(zip(header, map(float, v)))
            t.append(row["Time"]); cd.append(row["Cd"]); cl.append(row["Cl"])
    return t, cd, cl


def analyse_2d3(case):
    t, cd, cl = coefficients(case)
    i = max(range(len(cd)), key=lambda m: cd[m])
    j = max(range(len(cl)), key=lambda m: cl[m])
    return {"CD_max": cd[i], "t_CD_max": t[i], "CL_max": cl[j], "t_CL_max": t[j]}


def analyse(case, t_from):
    t, cd, cl = coefficients(case)
    sel = [i for i, ti in enumerate(t) if ti >= t_from]
    up = [t[i - 1] + (t[i] - t[i - 1]) * (-cl[i - 1]) / (cl[i] - cl[i - 1])
          for i in sel[1:] if cl[i - 1] < 0 <= cl[i]]
    period = (up[-1] - up[0]) / (len(up) - 1) if len(up) >= 3 else float("nan")
    # CL_min too: the lift's mean over a period (its asymmetry, the cylinder sits 0.005 below the
    # channel's centre line) decides how much of the amplitude CL_max shows.
    out = {"CD_max": max(cd[i] for i in sel), "CL_max": max(cl[i] for i in sel), "CL_min": min(cl[i] for i in sel),
           "St": D / (UBAR * period) if period == period else float("nan"), "periods_used": max(0, len(up) - 1)}
    out.update(lift_parts(case, t_from))
    return out


def lift_parts(case, t_from):
    # The lift amplitude ((max - min) / 2 over the window) of the pressure and the viscous force
    # (the forces function object's force.dat: time, (total), (pressure), (viscous)), to compare
    # with fin-cfd's pressure/viscous split of the surface traction.
    files = []
    for root, _, names in os.walk(os.path.join(case, "postProcessing", "forces")):
        files += [os.path.join(root, n) for n in names if n.startswith("force")]
    if not files:
        return {}
    scale = 2 / (UBAR * UBAR * D * DZ)
    parts = {"total": [], "pressure": [], "viscous": []}
    with open(sorted(files)[0]) as fh:
        for line in fh:
            if line.startswith("#"):
                continue
            v = line.replace("(", " ").replace(")", " ").split()
            if len(v) < 10 or float(v[0]) < t_from:
                continue
            for n, key in enumerate(("total", "pressure", "viscous")):
                parts[key].append(scale * float(v[2 + 3 * n]))
    if not parts["total"]:
        return {}
    return {f"CL_{k}_amplitude": (max(x) - min(x)) / 2 for k, x in parts.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cells", type=int, action="append", help="cells per cylinder quarter (repeatable)")
    # The same simulated time and evaluation window as fin-cfd dfg_2d2's full variant.
    ap.add_argument("--t-end", type=float, default=10.0)
    ap.add_argument("--window", type=float, default=3.0, help="evaluate CD_max, CL_max, St over the last WINDOW s")
    ap.add_argument("--dt", type=float, default=None, help="time step (default: from --courant)")
    # PISO's splitting error makes the 2D-2 lift first order in the step, so the peer's step is part
    # of its accuracy (docs/studies/dfg_2d2_lift_maximum.md).
    ap.add_argument("--courant", type=float, default=0.5,
                    help="time step: Courant number of the cylinder's cells at 1.5 Um (default 0.5)")
    # PIMPLE: several outer iterations per step re-solve the momentum equation with the corrected
    # convecting flux, which PISO (1, the default) lags by one step; with 3 the 2D-2 lift maximum is
    # converged in the step at Courant 0.5 (docs/studies/dfg_2d2_lift_maximum.md).
    ap.add_argument("--outer-correctors", type=int, default=1,
                    help="PIMPLE outer iterations per time step (default 1: PISO)")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--out", required=True)
    ap.add_argument("--keep", help="keep the OpenFOAM cases below this directory")
    ap.add_argument("--benchmark", choices=["2d2", "2d3"], default="2d2")
    args = ap.parse_args()
    if args.outer_correctors < 1:
        raise SystemExit(f"openfoam_dfg: --outer-correctors {args.outer_correctors}: expected an integer >= 1")
    if not shutil.which("pimpleFoam"):
        raise SystemExit("openfoam_dfg: pimpleFoam not found (tools/scripts/install-deps.sh --peers)")
    sine = args.benchmark == "2d3"
    if sine:
        args.t_end = 8.0
    # 2D-2: the 1996 bounds (their midpoints); 2D-3: John (2004)'s values.
    ref = ({"CD_max": 2.950921575, "CL_max": 0.47795} if sine else
           {"CD_max": (3.22, 3.24), "CL_max": (0.99, 1.01), "St": (0.295, 0.305)})
    out = {"peer": "OpenFOAM v1912 pimpleFoam (Debian)", "case": "DFG 2D-3" if sine else "DFG 2D-2", "runs": []}
    for n in args.cells or [16, 24, 32]:
        root = args.keep or tempfile.mkdtemp(prefix="finverse_of_")
        case = os.path.join(root, f"dfg{args.benchmark[-1]}_{n}")
        shutil.rmtree(case, ignore_errors=True)
        dt = args.dt or args.courant * (2 * math.pi * R / (4 * n)) / (1.5 * UM)
        if sine:
            dt = args.t_end / math.ceil(args.t_end / dt)  # lands on t = 8
        write_case(case, n, args.t_end, dt, args.ranks, args.outer_correctors)
        t0 = time.perf_counter()
        run(["blockMesh"], case, "log.blockMesh")
        write_fields(case, args.t_end if sine else None)
        if args.ranks > 1:
            run(["decomposePar", "-force"], case, "log.decomposePar")
            mpi = ["mpirun", "--oversubscribe", "-np", str(args.ranks)] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
            run(mpi + ["pimpleFoam", "-parallel"], case, "log.pimpleFoam")
        else:
            run(["pimpleFoam"], case, "log.pimpleFoam")
        wall = time.perf_counter() - t0
        cells = sum(nx * ny for _, (nx, ny), _ in block_mesh(n)[1])
        res = analyse_2d3(case) if sine else analyse(case, args.t_end - args.window)
        mid = {k: v if sine else sum(v) / 2 for k, v in ref.items()}
        err = {k: abs(res[k] - m) / m for k, m in mid.items()}
        courant = dt * 1.5 * UM / (2 * math.pi * R / (4 * n))
        r = {"cells_per_quarter": n, "cells": cells, "dt": dt, "courant": courant, "outer_correctors": args.outer_correctors, "ranks": args.ranks, "t_end": args.t_end, "wall_s": wall, **res,
             "rel_error_to_midpoint": err, "within_1pct": all(e <= 0.01 for e in err.values())}
        print(json.dumps(r), file=sys.stderr)
        out["runs"].append(r)
        if not args.keep:
            shutil.rmtree(root, ignore_errors=True)
    # Strict JSON (no NaN): a quantity that could not be measured (too few periods) is null.
    def strict(v):
        if isinstance(v, float) and v != v:
            return None
        if isinstance(v, dict):
            return {k: strict(x) for k, x in v.items()}
        if isinstance(v, list):
            return [strict(x) for x in v]
        return v
    out = strict(out)
    tmp = args.out + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(out, fh, indent=1, allow_nan=False)
    os.replace(tmp, args.out)


if __name__ == "__main__":
    main()
