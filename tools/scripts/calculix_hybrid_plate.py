#!/usr/bin/env python3
"""CalculiX (ccx, Debian calculix-ccx) reference for the hybrid plate (data/cases/hybrid_plate.json).

Builds the plate with quadratic shells (S8R) and the three rays with quadratic beams (B32R)
sharing the plate's nodes on a structured mesh, runs the geometrically nonlinear static
(pressure) and dynamic (leading-edge heave) cases with NLGEOM, and writes the beam-tip
displacements and CalculiX's wall time as JSON:

    calculix_hybrid_plate.py --case data/cases/hybrid_plate.json --nx 16 --nz 16 --out ccx.json

The benchmark and the FEM validation run it at two or more meshes to show that CalculiX's own
answer is converged before it is used as a reference. The validation reference
(data/reference/hybrid_plate_calculix.json: finest meshes, mesh study, ccx version, command,
date) is written with --reference-out, from fresh runs or, with --merge, from earlier outputs:

    calculix_hybrid_plate.py --case data/cases/hybrid_plate.json --nx 8 --nx 16 --nx 32 \
        --analysis static --out runs.json --reference-out data/reference/hybrid_plate_calculix.json

Known limitation: the dynamic run (leading-edge heave) does not converge in ccx 2.20 for this
model (Newton diverges after ~0.1-0.2 s on every mesh tried, NLGEOM or not, ALPHA 0 or -0.1),
so the reference holds the static case only.
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


def node_id(i, k, nz2):
    return 1 + i * (nz2 + 1) + k


def build_mesh(case, nx, nz):
    """Nodes and S8R/B32R connectivity on a (2nx+1) x (2nz+1) node grid (quad centres unused)."""
    chord, span = case["plate"]["chord"], case["plate"]["span"]
    nx2, nz2 = 2 * nx, 2 * nz
    z0 = -0.5 * span
    nodes = {}
    for i in range(nx2 + 1):
        for k in range(nz2 + 1):
            if i % 2 and k % 2:
                continue
            nodes[node_id(i, k, nz2)] = (chord * i / nx2, 0.0, z0 + span * k / nz2)
    shells = []
    for ex in range(nx):
        for ez in range(nz):
            i, k = 2 * ex, 2 * ez
            c = [(i, k), (i + 2, k), (i + 2, k + 2), (i, k + 2), (i + 1, k), (i + 2, k + 1), (i + 1, k + 2), (i, k + 1)]
            shells.append([node_id(a, b, nz2) for a, b in c])
    beams = {}
    for b in case["beams"]:
        kb = round((b["z"] - z0) / span * nz2)
        if kb % 2 or abs(z0 + span * kb / nz2 - b["z"]) > 1e-12:
            raise SystemExit(f"calculix_hybrid_plate: beam {b['name']} at z={b['z']} is not on an element edge of nz={nz}")
        beams[b["name"]] = [[node_id(i, kb, nz2), node_id(i + 1, kb, nz2), node_id(i + 2, kb, nz2)] for i in range(0, nx2, 2)]
    leading = [node_id(0, k, nz2) for k in range(nz2 + 1)]
    tips = {name: conn[-1][-1] for name, conn in beams.items()}
    return nodes, shells, beams, leading, tips


def write_input(path, case, nx, nz, analysis):
    nodes, shells, beams, leading, tips = build_mesh(case, nx, nz)
    p = case["plate"]
    out = ["** finverse hybrid plate, CalculiX reference, " + analysis, "*NODE, NSET=NALL"]
    out += [f"{n},{x:.15g},{y:.15g},{z:.15g}" for n, (x, y, z) in sorted(nodes.items())]
    out.append("*ELEMENT, TYPE=S8R, ELSET=PLATE")
    out += [f"{e + 1}," + ",".join(map(str, c)) for e, c in enumerate(shells)]
    eid = len(shells)
    for name, conn in beams.items():
        out.append(f"*ELEMENT, TYPE=B32R, ELSET=BEAM_{name.upper()}")
        for c in conn:
            eid += 1
            out.append(f"{eid}," + ",".join(map(str, c)))
    out.append("*NSET, NSET=LE")
    out += [",".join(map(str, leading[i:i + 12])) for i in range(0, len(leading), 12)]
    out.append("*NSET, NSET=TIPS")
    out.append(",".join(str(tips[b["name"]]) for b in case["beams"]))
    out += ["*MATERIAL, NAME=PLATE", "*ELASTIC", f"{p['E']:.10g},{p['nu']:.10g}", "*DENSITY", f"{p['density']:.10g}",
            "*SHELL SECTION, ELSET=PLATE, MATERIAL=PLATE", f"{p['thickness']:.10g}"]
    for b in case["beams"]:
        n = b["name"].upper()
        # RECT a,b: a along the first section direction (given: z, in the plate plane), b along
        # tangent x first direction (here -y, the plate normal).
        # Engineering constants E, nu = 0, G = E / (2 (1 + nu)): ccx expands a B32R into C3D20R
        # bricks, and where a beam shares its nodes with the shell every node becomes a rigid
        # "knot" that keeps the section from contracting laterally; with the isotropic nu = 0.3
        # the fibres then act with the constrained modulus E (1 - nu) / ((1 + nu)(1 - 2 nu)) =
        # 1.35 E (measured: linear tips 26-35 % stiffer than finverse's). A beam's response depends
        # on E and G only, so nu = 0 with G kept is the same Euler-Bernoulli/Timoshenko beam as
        # finverse's and removes the artefact.
        g = b["E"] / (2 * (1 + b["nu"]))
        out += [f"*MATERIAL, NAME=M_{n}", "*ELASTIC, TYPE=ENGINEERING CONSTANTS",
                f"{b['E']:.10g},{b['E']:.10g},{b['E']:.10g},0,0,0,{g:.10g},{g:.10g}", f"{g:.10g}",
                "*DENSITY", f"{b['density']:.10g}",
                f"*BEAM SECTION, ELSET=BEAM_{n}, MATERIAL=M_{n}, SECTION=RECT", f"{b['width']:.10g},{b['thickness']:.10g}",
                "0.,0.,1."]
    if analysis == "static":
        s = case["static"]
        # Dead load, as in finverse (nodal loads keep their direction): ccx's *DLOAD P is a
        # follower pressure under NLGEOM, so the pressure enters as the consistent nodal forces
        # of the S8R serendipity interpolation on each rectangular element, -1/12 of p A at a
        # corner and 1/3 at a mid-side node, all along -y.
        out += ["*BOUNDARY", "LE,1,6", f"*STEP, NLGEOM, INC=1000", "*STATIC", f"{1.0 / s['load_steps']:.10g},1.0",
                "*CLOAD"]
        force = {}
        area = (p["chord"] / nx) * (p["span"] / nz)
        for c in shells:
            for j, n in enumerate(c):
                force[n] = force.get(n, 0.0) + (-1.0 / 12.0 if j < 4 else 1.0 / 3.0) * s["pressure"] * area
        out += [f"{n},2,{-f:.15g}" for n, f in sorted(force.items()) if f != 0.0]
    else:
        d = case["dynamic"]
        f, a = d["frequency"], d["heave_amplitude"]
        t_end = d["periods"] / f
        dt = d["time_step"]
        # ALPHA = 0: ccx's alpha method reduces to the trapezoidal rule (finverse: generalized-alpha
        # with rho_inf = 1). The increment is the case's time step, cut by ccx's automatic
        # incrementation only where its Newton iteration does not converge (a fixed DIRECT
        # increment diverges there); the output times are then not all on the case's grid.
        # Tabulated y_LE(t) = A (1 - cos 2 pi f t) / A; ccx interpolates linearly, so sample finely.
        samples = int(round(t_end / (dt / 4))) + 1
        amp = []
        for j in range(samples):
            t = t_end * j / (samples - 1)
            amp.append(f"{t:.10g},{1 - math.cos(2 * math.pi * f * t):.12g}")
        out += ["*AMPLITUDE, NAME=HEAVE"] + [",".join(amp[i:i + 4]) for i in range(0, len(amp), 4)]
        out += ["*BOUNDARY", "LE,1,1", "LE,3,6", "*STEP, NLGEOM, INC=100000", f"*DYNAMIC, ALPHA={case.get('_ccx_alpha', 0.0):.6g}",
                f"{dt:.10g},{t_end:.10g},{dt / 64:.10g},{dt:.10g}", "*BOUNDARY, AMPLITUDE=HEAVE", f"LE,2,2,{a:.10g}"]
    out += ["*NODE PRINT, NSET=TIPS", "U", "*END STEP"]
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")
    return tips, len(shells), eid - len(shells), len(nodes)


def parse_dat(path, tips):
    """Time series of the tip displacements from the .dat file."""
    by_node = {v: k for k, v in tips.items()}
    series = []
    block = re.compile(r"displacements \(vx,vy,vz\) for set TIPS and time\s+(\S+)")
    current = None
    with open(path) as fh:
        for line in fh:
            m = block.search(line)
            if m:
                current = {"time": float(m.group(1)), "u": {}}
                series.append(current)
                continue
            parts = line.split()
            if current is not None and len(parts) == 4 and parts[0].isdigit() and int(parts[0]) in by_node:
                current["u"][by_node[int(parts[0])]] = [float(x) for x in parts[1:]]
    return [s for s in series if len(s["u"]) == len(tips)]


def run(case, nx, nz, analysis, keep_dir=None):
    ccx = shutil.which("ccx")
    if not ccx:
        raise SystemExit("calculix_hybrid_plate: ccx not found (install with tools/scripts/install-deps.sh --peers)")
    work = keep_dir or tempfile.mkdtemp(prefix="finverse_ccx_")
    os.makedirs(work, exist_ok=True)
    job = os.path.join(work, f"hybrid_{analysis}_{nx}x{nz}")
    tips, nshell, nbeam, nnode = write_input(job + ".inp", case, nx, nz, analysis)
    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "2"),
               CCX_NPROC_EQUATION_SOLVER=os.environ.get("OMP_NUM_THREADS", "2"))
    t0 = time.perf_counter()
    proc = subprocess.run([ccx, "-i", os.path.basename(job)], cwd=work, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0 or "*ERROR" in proc.stdout:
        tail = "\n".join(proc.stdout.splitlines()[-15:])
        raise SystemExit(f"calculix_hybrid_plate: ccx failed on {job}.inp:\n{tail}")
    series = parse_dat(job + ".dat", tips)
    if not series:
        raise SystemExit(f"calculix_hybrid_plate: no tip displacements in {job}.dat")
    if keep_dir is None:
        shutil.rmtree(work, ignore_errors=True)
    return {"nx": nx, "nz": nz, "shell_elements": nshell, "beam_elements": nbeam, "nodes": nnode,
            "wall_s": wall, "series": series}


def tips_y(series_entry):
    return {name: u[1] for name, u in series_entry["u"].items()}


def relative_change(a, b):
    """Largest relative change of the final tip y displacements between two runs."""
    ya, yb = tips_y(a["series"][-1]), tips_y(b["series"][-1])
    return max(abs(yb[k] - ya[k]) / abs(yb[k]) for k in yb)


def build_reference(result, tolerance):
    """The reference file for tools/fem/validation/hybrid_plate.cpp: the finest static and
    dynamic runs, with the mesh study (successive relative changes of the final tip values)."""
    ref = {k: result[k] for k in ("peer", "case", "command", "date", "omp_threads", "sources") if k in result}
    ref["schema"] = "finverse/calculix_hybrid_plate"
    ref["mesh_study_tolerance"] = tolerance
    ref["mesh_study"] = []
    for analysis in ("static", "dynamic"):
        runs = sorted((r for r in result["runs"] if r["analysis"] == analysis), key=lambda r: r["nx"] * r["nz"])
        if not runs:
            continue
        for prev, r in zip([None] + runs[:-1], runs):
            row = {"analysis": analysis, "nx": r["nx"], "nz": r["nz"], "nodes": r["nodes"], "wall_s": r["wall_s"],
                   "final_time": r["series"][-1]["time"], "tips_y": tips_y(r["series"][-1])}
            if prev is not None:
                row["relative_change"] = relative_change(prev, r)
            ref["mesh_study"].append(row)
        fine = runs[-1]
        entry = {"nx": fine["nx"], "nz": fine["nz"], "wall_s": fine["wall_s"],
                 "converged": len(runs) > 1 and relative_change(runs[-2], fine) < tolerance}
        if analysis == "static":
            entry["tips_y"] = tips_y(fine["series"][-1])
        else:
            entry["time"] = [s["time"] for s in fine["series"]]
            entry["tips_y"] = {k: [s["u"][k][1] for s in fine["series"]] for k in fine["series"][0]["u"]}
        ref[analysis] = entry
    return ref


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", required=True)
    ap.add_argument("--nx", type=int, action="append", help="elements along the chord (repeatable: mesh study)")
    ap.add_argument("--nz", type=int, action="append", help="elements along the span (same count as --nx)")
    ap.add_argument("--analysis", choices=["static", "dynamic", "both"], default="both")
    ap.add_argument("--out", required=True)
    ap.add_argument("--reference-out", help="also write the validation reference (finest meshes + mesh study) here")
    ap.add_argument("--study-tolerance", type=float, default=0.005,
                    help="mesh study: converged when the finest two meshes differ by less than this")
    ap.add_argument("--merge", nargs="+", metavar="RUNS_JSON",
                    help="run nothing: merge the runs of earlier outputs of this script (each keeps its command and date)")
    ap.add_argument("--keep", help="keep CalculiX's files in this directory")
    ap.add_argument("--alpha", type=float, default=0.0,
                    help="ccx *DYNAMIC ALPHA in [-1/3, 0] (0: trapezoidal rule, as finverse's rho_inf = 1)")
    args = ap.parse_args()
    with open(args.case) as fh:
        case = json.load(fh)
    case["_ccx_alpha"] = args.alpha
    nxs = args.nx or [8, 16]
    nzs = args.nz or nxs
    if len(nxs) != len(nzs):
        raise SystemExit("calculix_hybrid_plate: give as many --nz as --nx")
    version = subprocess.run(["ccx", "-v"], capture_output=True, text=True).stdout.strip().splitlines()
    result = {"peer": "CalculiX " + (version[-1].split()[-1] if version else "?"), "case": args.case,
              "command": " ".join([os.path.basename(sys.argv[0])] + sys.argv[1:]),
              "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
              "omp_threads": int(os.environ.get("OMP_NUM_THREADS", "2")), "runs": []}
    analyses = ["static", "dynamic"] if args.analysis == "both" else [args.analysis]
    if args.merge:
        analyses = []
        result["sources"] = []
        for path in args.merge:
            with open(path) as fh:
                earlier = json.load(fh)
            result["peer"] = earlier["peer"]
            result["sources"].append({k: earlier.get(k) for k in ("command", "date", "omp_threads")})
            result["runs"] += earlier["runs"]
    for analysis in analyses:
        for nx, nz in zip(nxs, nzs):
            r = run(case, nx, nz, analysis, args.keep)
            r["analysis"] = analysis
            final = r["series"][-1]["u"]
            print(f"{analysis:7s} {nx:3d}x{nz:<3d} {r['wall_s']:7.2f} s  tips " +
                  "  ".join(f"{k}: {v[1]:+.5f}" for k, v in final.items()), file=sys.stderr)
            result["runs"].append(r)
    outputs = [(args.out, result)]
    if args.reference_out:
        outputs.append((args.reference_out, build_reference(result, args.study_tolerance)))
    for path, data in outputs:
        tmp = path + ".tmp"
        with open(tmp, "w") as fh:
            json.dump(data, fh, indent=1)
        os.replace(tmp, path)


if __name__ == "__main__":
    main()
