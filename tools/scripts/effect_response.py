#!/usr/bin/python3
"""Trailing-edge response of structural runs with candidate effects against a baseline run
(docs/studies/candidate_effects.md): for every response file (finverse/motion, fin-fem run) the
ray tips' lateral (y) excursion over the run -- peak to peak when the run is periodic (T), else
last minus first frame -- its change against the baseline, and the RMS / largest distance of the
ray tips from the baseline's over all frames, in chords.

  effect_response.py --mesh mesh.h5 --base base.h5 [--json out.json] run1.h5 run2.h5 ...
"""
import argparse
import json
import sys

import h5py
import numpy as np


def tips_of(mesh):
    el, s = mesh["beams/elements"][:], mesh["beams/s"][:]
    return sorted({int(el[e, 1] if s[e, 1] >= s[e, 0] else el[e, 0]) for e in range(len(el)) if max(s[e]) == 1.0})


def excursion(points, tips, periodic):
    y = points[:, tips, 1]
    return (y.max(axis=0) - y.min(axis=0)) if periodic else (y[-1] - y[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mesh", required=True)
    ap.add_argument("--base", required=True)
    ap.add_argument("--json")
    ap.add_argument("runs", nargs="+")
    a = ap.parse_args()
    with h5py.File(a.mesh, "r") as m:
        tips = tips_of(m)
        chord = float(m.attrs["chord"])
    with h5py.File(a.base, "r") as b:
        base = b["points"][:]
        periodic = "T" in b.attrs
    if not tips:
        sys.exit(f"{a.mesh}: no ray tip (beams/s == 1)")
    e0 = excursion(base, tips, periodic)
    out = {"mesh": a.mesh, "base": a.base, "chord_m": chord, "ray_tips": len(tips), "periodic": periodic,
           "base_excursion_over_c": float(np.abs(e0).mean() / chord), "runs": {}}
    print(f"baseline {a.base}: ray-tip excursion {np.abs(e0).mean() / chord:.4f} c "
          f"({'peak to peak over the period' if periodic else 'last - first frame'}), {len(tips)} tips")
    for path in a.runs:
        with h5py.File(path, "r") as f:
            p = f["points"][:]
            eff = f.attrs.get("effects", "")
        if p.shape != base.shape:
            sys.exit(f"{path}: /points {p.shape}, the baseline {base.shape}: not the same run set-up")
        e = excursion(p, tips, periodic)
        d = np.linalg.norm(p[:, tips, :] - base[:, tips, :], axis=2)
        r = {"effects": eff.decode() if isinstance(eff, bytes) else str(eff),
             "excursion_over_c": float(np.abs(e).mean() / chord),
             "excursion_change_pct": float(100 * (np.abs(e).mean() / np.abs(e0).mean() - 1)),
             "tip_shift_rms_over_c": float(np.sqrt((d ** 2).mean()) / chord),
             "tip_shift_max_over_c": float(d.max() / chord)}
        out["runs"][path] = r
        print(f"{path}: excursion {r['excursion_over_c']:.4f} c ({r['excursion_change_pct']:+.1f} %), "
              f"tip shift rms {r['tip_shift_rms_over_c']:.4f} c, max {r['tip_shift_max_over_c']:.4f} c")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main()
