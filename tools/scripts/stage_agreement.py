#!/usr/bin/env python3
"""Do the loads stage and the truth see the same fin? (issue 50, "The stages agree"): the force
history of fin-cfd fin run on the truth's own motion (loads.h5) against the force the truth's FSI
felt (its fsi.h5), each over its record (the last period). Graded: the mean C_T (time-weighted
trapezoidal mean) and the amplitude of C_L's fundamental (least-squares fit of the period's first
harmonic), each within a relative tolerance of the truth's. Reported: the C_T peaks and the share
of C_T's energy above the 10th harmonic (the closed body's cell-kind impulses:
docs/studies/fin_load_noise.md). Writes a finverse validation summary (tools/core/summary.hpp).

    stage_agreement.py --truth results/<case>/truth/fsi.h5 --loads L.h5 [--tolerance 0.05] --out summary.json

Exit 0 when both graded metrics pass, 1 when one misses, 2 with one line for a missing or
malformed input.
"""
import argparse
import sys

import h5py
import numpy as np

from summary import write_summary


def fail(message):
    print(f"stage_agreement.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def forces(path, flag, period=None):
    try:
        with h5py.File(path, "r") as f:
            t = np.asarray(f["time"][...], dtype=float)
            ct = np.asarray(f["coefficients/thrust"][...], dtype=float)
            cl = np.asarray(f["coefficients/lateral"][...], dtype=float)
            period = float(f.attrs["T"]) if period is None and "T" in f.attrs else period
    except (OSError, KeyError, ValueError) as e:
        fail(f"{flag} {path}: {e}; expected time, coefficients/thrust and coefficients/lateral")
    if t.size < 4 or t.shape != ct.shape or t.shape != cl.shape:
        fail(f"{flag} {path}: time {t.shape}, thrust {ct.shape}, lateral {cl.shape}; expected 4 or more equal-length series")
    if period is None or not period > 0:
        fail(f"{flag} {path}: no period (attribute T); expected a periodic record")
    w = 2 * np.pi / period
    basis = np.column_stack([np.ones_like(t), np.cos(w * t), np.sin(w * t)])
    c = np.linalg.lstsq(basis, cl, rcond=None)[0]
    spectrum = np.abs(np.fft.rfft(ct - ct.mean())) ** 2
    return {"mean_ct": float(np.sum(0.5 * (ct[1:] + ct[:-1]) * np.diff(t)) / (t[-1] - t[0])),
            "peak_ct": float(ct.max()), "cl_amplitude": float(np.hypot(c[1], c[2])),
            "ct_energy_above_10th": float(spectrum[11:].sum() / max(spectrum[1:].sum(), 1e-300)),
            "period": period}


def graded(name, value, reference, tol, source):
    err = abs(value - reference) / abs(reference) if reference != 0 else float("nan")
    ok = bool(np.isfinite(err) and err <= tol)
    return {"name": name, "value": value, "units": "", "kind": "relative", "reference": reference, "source": source,
            "error": err if np.isfinite(err) else None, "tolerance": tol, "pass": ok}


def reported(name, value, source):
    return {"name": name, "value": value, "units": "", "kind": "info", "reference": None, "source": source,
            "error": None, "tolerance": None, "pass": None}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--truth", required=True, help="the truth's fsi.h5")
    p.add_argument("--loads", required=True, help="fin-cfd fin's loads.h5 on the truth's motion")
    p.add_argument("--name", default="stage_agreement")
    p.add_argument("--tolerance", type=float, default=0.05)
    p.add_argument("--out", required=True)
    a = p.parse_args()
    truth = forces(a.truth, "--truth")
    loads = forces(a.loads, "--loads", truth["period"])
    src = "the truth's FSI (fsi.h5), its last period"
    metrics = [graded("mean C_T, loads on the truth's motion", loads["mean_ct"], truth["mean_ct"], a.tolerance, src),
               graded("C_L fundamental amplitude, loads on the truth's motion", loads["cl_amplitude"],
                      truth["cl_amplitude"], a.tolerance, src)]
    for key, label in (("peak_ct", "C_T peak"), ("ct_energy_above_10th", "C_T energy above the 10th harmonic")):
        metrics.append(reported(f"{label}, loads on the truth's motion", loads[key], "loads.h5"))
        metrics.append(reported(f"{label}, truth", truth[key], "fsi.h5"))
    summary = write_summary(
        a.out, "validation", a.name,
        "fin-cfd fin on the truth's own motion reproduces the force the truth's FSI felt: mean C_T and C_L "
        f"amplitude within {100 * a.tolerance:.3g} %", metrics, {"tolerance": a.tolerance},
        "stage_agreement.py finverse", inputs=[a.truth, a.loads])
    return 0 if summary["pass"] else 1


if __name__ == "__main__":
    sys.exit(main())
