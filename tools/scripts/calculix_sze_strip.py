#!/usr/bin/env python3
"""CalculiX (ccx, Debian calculix-ccx) run of the Sze, Liu & Lo (2004) cantilever strip under an
end shear force (data/reference/structures.json "sze_cantilever_end_shear"), the peer side of
the FEM benchmark (results/bench/fem.json):

    calculix_sze_strip.py --reference data/reference/structures.json --nx 8 --nx 16 --out ccx_sze.json

S8R shells on an nx x ny strip, clamped at x = 0, a dead force P_max along +z at x = L spread
over the end edge with the consistent shares of the quadratic edge (1/6, 2/3, 1/6 per element),
NLGEOM, ccx's automatic incrementation (at most 0.1 P_max per increment; a fixed DIRECT increment
diverges) with *TIME POINTS at the reference levels. Writes, per mesh, the end-edge mean deflection w and shortening -u at the ten levels,
the largest relative error against the table, and ccx's wall time.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time


def write_input(path, ref, nx, ny):
    L, b, h = ref["L"], ref["b"], ref["h"]
    nx2, ny2 = 2 * nx, 2 * ny

    def nid(i, k):
        return 1 + i * (ny2 + 1) + k

    lines = ["** finverse: Sze end-shear strip, CalculiX peer", "*NODE, NSET=NALL"]
    for i in range(nx2 + 1):
        for k in range(ny2 + 1):
            if i % 2 and k % 2:
                continue
            lines.append(f"{nid(i, k)},{L * i / nx2:.15g},{b * k / ny2:.15g},0")
    lines.append("*ELEMENT, TYPE=S8R, ELSET=STRIP")
    e = 0
    for ex in range(nx):
        for ey in range(ny):
            i, k = 2 * ex, 2 * ey
            c = [(i, k), (i + 2, k), (i + 2, k + 2), (i, k + 2), (i + 1, k), (i + 2, k + 1), (i + 1, k + 2), (i, k + 1)]
            e += 1
            lines.append(f"{e}," + ",".join(str(nid(a, bb)) for a, bb in c))
    root = [nid(0, k) for k in range(ny2 + 1)]
    tip = [nid(nx2, k) for k in range(ny2 + 1)]
    lines += ["*NSET, NSET=ROOT"] + [",".join(map(str, root[j:j + 12])) for j in range(0, len(root), 12)]
    lines += ["*NSET, NSET=TIP"] + [",".join(map(str, tip[j:j + 12])) for j in range(0, len(tip), 12)]
    lines += ["*MATERIAL, NAME=STRIP", "*ELASTIC", f"{ref['E']:.10g},{ref['nu']:.10g}",
              "*SHELL SECTION, ELSET=STRIP, MATERIAL=STRIP", f"{h:.10g}",
              "*TIME POINTS, NAME=LEVELS"]
    # ccx reads at most 8 entries per data line (a 9th and 10th on the same line are dropped).
    lines += [",".join(f"{f:.12g}" for f in ref["P_frac"][j:j + 4]) for j in range(0, len(ref["P_frac"]), 4)]
    lines += ["*BOUNDARY", "ROOT,1,6", "*STEP, NLGEOM, INC=1000", "*STATIC", "0.1,1.0,1e-6,0.1", "*CLOAD"]
    share = {}
    for ey in range(ny):
        k = 2 * ey
        for kk, w in ((k, 1 / 6), (k + 1, 2 / 3), (k + 2, 1 / 6)):
            share[kk] = share.get(kk, 0.0) + w / ny
    lines += [f"{nid(nx2, k)},3,{ref['P_max'] * s:.15g}" for k, s in sorted(share.items())]
    lines += ["*NODE PRINT, NSET=TIP, TIME POINTS=LEVELS", "U", "*END STEP"]
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    return tip, e


def parse_dat(path, tip):
    block = re.compile(r"displacements \(vx,vy,vz\) for set TIP and time\s+(\S+)")
    out, cur = [], None
    tipset = set(tip)
    with open(path) as fh:
        for line in fh:
            m = block.search(line)
            if m:
                cur = {"time": float(m.group(1)), "u": []}
                out.append(cur)
                continue
            parts = line.split()
            if cur is not None and len(parts) == 4 and parts[0].isdigit() and int(parts[0]) in tipset:
                cur["u"].append([float(x) for x in parts[1:]])
    return [s for s in out if len(s["u"]) == len(tip)]


def run(ref, nx, ny, keep=None):
    ccx = shutil.which("ccx")
    if not ccx:
        raise SystemExit("calculix_sze_strip: ccx not found (Debian package calculix-ccx; "
                         "tools/scripts/install-deps.sh --peers)")
    work = keep or tempfile.mkdtemp(prefix="finverse_ccx_sze_")
    os.makedirs(work, exist_ok=True)
    job = os.path.join(work, f"sze_strip_{nx}x{ny}")
    tip, nel = write_input(job + ".inp", ref, nx, ny)
    t0 = time.perf_counter()
    proc = subprocess.run([ccx, "-i", os.path.basename(job)], cwd=work, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0 or "*ERROR" in proc.stdout:
        tail = "\n".join(proc.stdout.splitlines()[-15:])
        raise SystemExit(f"calculix_sze_strip: ccx failed on {job}.inp:\n{tail}")
    series = parse_dat(job + ".dat", tip)
    if keep is None:
        shutil.rmtree(work, ignore_errors=True)
    levels, w, mu = [], [], []
    for s in series:
        n = len(s["u"])
        levels.append(s["time"])
        w.append(sum(u[2] for u in s["u"]) / n)
        mu.append(-sum(u[0] for u in s["u"]) / n)
    err = 0.0
    for k, frac in enumerate(ref["P_frac"]):
        j = min(range(len(levels)), key=lambda j: abs(levels[j] - frac)) if levels else None
        if j is None or abs(levels[j] - frac) > 1e-6:
            raise SystemExit(f"calculix_sze_strip: no ccx output at P/Pmax = {frac} in {job}.dat")
        err = max(err, abs(w[j] - ref["w_tip"][k]) / abs(ref["w_tip"][k]),
                  abs(mu[j] - ref["minus_u_tip"][k]) / abs(ref["minus_u_tip"][k]))
    return {"nx": nx, "ny": ny, "elements": nel, "wall_s": wall, "P_frac": levels, "w_tip": w,
            "minus_u_tip": mu, "max_relative_error": err}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", required=True, help="structures.json")
    ap.add_argument("--nx", type=int, action="append", help="S8R elements along the strip (repeatable)")
    ap.add_argument("--ny", type=int, default=1, help="S8R elements across the strip")
    ap.add_argument("--out", required=True)
    ap.add_argument("--keep", help="keep CalculiX's files in this directory")
    args = ap.parse_args()
    with open(args.reference) as fh:
        ref = json.load(fh)["sze_cantilever_end_shear"]
    version = subprocess.run(["ccx", "-v"], capture_output=True, text=True).stdout.strip().splitlines()
    result = {"peer": "CalculiX " + (version[-1].split()[-1] if version else "?"),
              "command": " ".join([os.path.basename(sys.argv[0])] + sys.argv[1:]),
              "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
              "omp_threads": int(os.environ.get("OMP_NUM_THREADS", "0") or 0), "runs": []}
    for nx in args.nx or [4, 8]:
        try:
            r = run(ref, nx, args.ny, args.keep)
        except SystemExit as e:  # a mesh ccx cannot solve is part of the study, not its end
            print(str(e).splitlines()[0], file=sys.stderr)
            result["runs"].append({"nx": nx, "ny": args.ny, "error": str(e).splitlines()[-1].strip()})
            continue
        print(f"sze strip {nx:3d}x{args.ny}: {r['wall_s']:.2f} s, max error {100 * r['max_relative_error']:.2f} %",
              file=sys.stderr)
        result["runs"].append(r)
    if not any("wall_s" in r for r in result["runs"]):
        raise SystemExit("calculix_sze_strip: ccx solved none of the meshes")
    tmp = args.out + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(result, fh, indent=1)
    os.replace(tmp, args.out)


if __name__ == "__main__":
    main()
