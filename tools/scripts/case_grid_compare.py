#!/usr/bin/env python3
"""Is the default case meaningful at its size? (issue 33, "Deliver" 4): compares the case's mean
C_T, C_T peak (loads.h5 coefficients/thrust over the record, the last period: time-weighted
trapezoidal mean and maximum, as fin-report's force_statistics) and fitted moduli (materials.h5
best) with the same pipeline on a finer near-fin grid, each graded within a relative tolerance of
the finer run's value. Writes a finverse validation summary (tools/core/summary.hpp).

    case_grid_compare.py --name default_case_grid --loads L.h5 --materials M.h5 \
        --fine-loads Lf.h5 --fine-materials Mf.h5 [--fsi F.h5 [--fine-fsi Ff.h5]] [--tolerance 0.05] \
        --out summary.json

Every E parameter is graded; nu is reported (a Poisson ratio is not a modulus). A parameter the
fit marks not identified (materials.h5 uncertainty/identified) in either run is graded too, with
that said in its source. Exit 0 when every graded metric passes, 1 when one misses, 2 with one
line for a missing or malformed input or runs that differ in their parameters.
"""
import argparse
import json
import sys

import h5py
import numpy as np

from summary import write_summary


def fail(message):
    print(f"case_grid_compare.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def thrust(path, flag):
    try:
        with h5py.File(path, "r") as f:
            t = np.asarray(f["time"][...], dtype=float)
            ct = np.asarray(f["coefficients/thrust"][...], dtype=float)
            grid = json.loads(f.attrs["config"]).get("achieved", {}) if "config" in f.attrs else {}
    except (OSError, KeyError, ValueError) as e:
        fail(f"{flag} {path}: {e}; expected loads.h5 with time and coefficients/thrust")
    if t.size < 2 or t.shape != ct.shape:
        fail(f"{flag} {path}: time {t.shape} and coefficients/thrust {ct.shape}; expected two or more equal-length series")
    mean = float(np.sum(0.5 * (ct[1:] + ct[:-1]) * np.diff(t)) / (t[-1] - t[0]))
    return mean, float(ct.max()), grid


def moduli(path, flag):
    try:
        with h5py.File(path, "r") as f:
            names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["parameters/names"][...]]
            best = np.asarray(f["best"][...], dtype=float)
            ident = (np.asarray(f["uncertainty/identified"][...]).astype(bool) if "uncertainty/identified" in f
                     else np.ones(len(names), bool))
    except (OSError, KeyError, ValueError) as e:
        fail(f"{flag} {path}: {e}; expected materials.h5 with parameters/names and best")
    if best.shape != (len(names),) or ident.shape != (len(names),):
        fail(f"{flag} {path}: best {best.shape}, identified {ident.shape} for {len(names)} parameters")
    return names, best, ident


def relative(name, value, reference, tol, source, units=""):
    err = abs(value - reference) / abs(reference) if reference != 0 else float("nan")
    ok = bool(np.isfinite(err) and err <= tol)
    return {"name": name, "value": value, "units": units, "kind": "relative", "reference": reference,
            "source": source, "error": err if np.isfinite(err) else None, "tolerance": tol, "pass": ok}


def info(name, value, units, source):
    return {"name": name, "value": value, "units": units, "kind": "info", "reference": None, "source": source,
            "error": None, "tolerance": None, "pass": None}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--name", required=True, help="validation case name (results/validation/<name>)")
    p.add_argument("--loads", required=True)
    p.add_argument("--materials", required=True)
    p.add_argument("--fine-loads", required=True)
    p.add_argument("--fine-materials", required=True)
    p.add_argument("--fsi", help="the case's fsi.h5 (optional): its mean C_T and peak")
    p.add_argument("--fine-fsi", help="the fsi stage on the finer grid: the case's FSI mean C_T and peak graded "
                   "against it (without it they are reported)")
    p.add_argument("--tolerance", type=float, default=0.05)
    p.add_argument("--out", required=True)
    a = p.parse_args()

    ct, ct_peak, grid = thrust(a.loads, "--loads")
    ct_f, ct_peak_f, grid_f = thrust(a.fine_loads, "--fine-loads")
    names, best, ident = moduli(a.materials, "--materials")
    names_f, best_f, ident_f = moduli(a.fine_materials, "--fine-materials")
    if names != names_f:
        fail(f"--materials {a.materials} and --fine-materials {a.fine_materials}: different parameters")
    ref = "the same pipeline on the finer grid"
    metrics = [relative("mean C_T (last period)", ct, ct_f, a.tolerance, ref),
               relative("C_T peak (last period)", ct_peak, ct_peak_f, a.tolerance, ref)]
    for n, v, vf, i, i_f in zip(names, best, best_f, ident, ident_f):
        if n.startswith("E"):
            note = ref if (i and i_f) else ref + "; not identified by the fit in " + (
                "both runs" if not (i or i_f) else ("this run" if not i else "the finer run"))
            metrics.append(relative(f"fitted {n}", float(v), float(vf), a.tolerance, note, "Pa"))
        else:
            metrics.append(info(f"fitted {n}", float(v), "", f"finer grid: {float(vf):.6g}"))
    rays = [k for k, n in enumerate(names) if n.startswith("E_ray")]
    if rays:
        d = np.abs(best[rays] - best_f[rays]) / np.abs(best_f[rays])
        metrics.append(info("fitted ray E, median relative difference to the finer grid", float(np.median(d)), "", ref))
    if a.fine_fsi and not a.fsi:
        fail("--fine-fsi needs --fsi (the case's fsi.h5)")
    if a.fsi and a.fine_fsi:
        fsi_ct, fsi_peak, _ = thrust(a.fsi, "--fsi")
        fine_ct, fine_peak, _ = thrust(a.fine_fsi, "--fine-fsi")
        fsi_ref = "the fsi stage at twice the resolution, with the finer fit's materials"
        metrics.append(relative("FSI mean C_T (fsi.h5)", fsi_ct, fine_ct, a.tolerance, fsi_ref))
        metrics.append(relative("FSI C_T peak (fsi.h5)", fsi_peak, fine_peak, a.tolerance, fsi_ref))
    elif a.fsi:
        fsi_ct, fsi_peak, _ = thrust(a.fsi, "--fsi")
        metrics.append(info("FSI mean C_T (fsi.h5)", fsi_ct, "", "the case's fsi stage, reported"))
        metrics.append(info("FSI C_T peak (fsi.h5)", fsi_peak, "", "the case's fsi stage, reported"))
    summary = write_summary(
        a.out, "validation", a.name,
        "the case's mean C_T, C_T peak and fitted moduli within "
        f"{100 * a.tolerance:.3g} % of the same pipeline on a finer near-fin grid",
        metrics,
        {"loads": a.loads, "materials": a.materials, "fine_loads": a.fine_loads,
         "fine_materials": a.fine_materials, "grid": grid, "fine_grid": grid_f},
        "case_grid_compare.py finverse")
    passed = summary["pass"]
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
