#!/usr/bin/env python3
"""The grid study of the Hessenthaler (2017) Phase I run in 3-D (issue 49; fin-fsi flap, one
summary per grid): the finest grid's tip and centreline RMS graded as the run grades them, the
change of the tip between the two finest grids graded against 0.5 mm, the number of grids graded
against the issue's three, over the finest three the tip's apparent order and Richardson
extrapolate with the fine grid's convergence index (Celik et al. 2008, J. Fluids Eng. 130:078001,
for unequal refinement ratios; reported, not graded), and per grid its cells, wall time, memory
peak and flow steps (the benchmark's cost of a steady state on this machine). With --loop (fin-loop
flap --phase1's summary) the centreline RMS before and after the loop on the MRI points is graded
against the issue's 1 mm and 0.5 mm, with what the loop added.
Writes results/validation/flap_phase1/summary.json (tools/core/summary.hpp's layout).

    flap_phase1_study.py --grid results/validation/flap_phase1/grid_h2.0mm/summary.json \
        --grid .../grid_h1.5mm/summary.json --grid .../grid_h1.25mm/summary.json --out summary.json

Exit 0 when every graded metric passes, 1 when one misses, 2 with one line for a missing or
malformed input or fewer than two grids.
"""
import argparse
import json
import math
import sys

from summary import write_summary


def fail(message):
    print(f"flap_phase1_study.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_grid(path):
    try:
        with open(path) as f:
            s = json.load(f)
        metrics = {m["name"]: m for m in s["metrics"]}
        h = float(s["parameters"]["h_m"])
        for key in ("tip_deflection", "centreline_rms", "steady_state_reached", "cells", "wall_seconds",
                    "peak_memory", "flow_steps"):
            metrics[key]["value"]
    except (OSError, json.JSONDecodeError, KeyError, TypeError, ValueError) as e:
        fail(f"--grid {path}: {e}; expected a fin-fsi flap summary")
    return {"path": path, "h": h, "metrics": metrics}


def metric(name, value, units, kind, reference=None, tolerance=None, source=""):
    if kind == "absolute":
        error = abs(value - reference)
        passed = error <= tolerance
    elif kind == "max":
        error = value / tolerance
        passed = value <= tolerance
    elif kind == "min":
        error = value / tolerance
        passed = value >= tolerance
    else:
        error, passed = None, None
    return {"name": name, "value": value, "units": units, "kind": kind, "reference": reference, "source": source,
            "error": error, "tolerance": tolerance, "pass": passed}


def loop_metrics(path):
    """The loop on the MRI centreline: the Phase I run's RMS before and after, graded as fin-loop
    grades them, and the count of effects it added."""
    try:
        with open(path) as f:
            s = json.load(f)
        m = {x["name"]: x for x in s["metrics"]}
        before, after = m["phase_I_centreline_rms_before_loop"], m["phase_I_centreline_rms_after_loop"]
        added = m["loop_phase_I_effects_added"]["value"]
        grid = s["parameters"]["phase_I_3d"]["base"]["h_m"]
    except (OSError, json.JSONDecodeError, KeyError, TypeError) as e:
        fail(f"--loop {path}: {e}; expected fin-loop flap --phase1's summary")
    where = f"the loop (fin-loop flap --phase1, the 3-D load at h = {grid * 1e3:g} mm)"
    return [metric("centreline_rms_before_loop", before["value"], "m", "max", None, before["tolerance"],
                   f"{where}: E from the no-flow centreline; issue 49 < 1 mm"),
            metric("centreline_rms_after_loop", after["value"], "m", "max", None, after["tolerance"],
                   f"{where}: after its trace on the Phase I residual; issue 49 < 0.5 mm"),
            metric("loop_effects_added", added, "", "info", source=where)]


def richardson(grids):
    """Apparent order p, extrapolated tip and the fine grid's GCI (1.25 safety factor) from the
    finest three grids (Celik et al. 2008, eqs. 3-6); None where the changes oscillate or vanish."""
    (h3, f3), (h2, f2), (h1, f1) = [(g["h"], g["metrics"]["tip_deflection"]["value"]) for g in grids[-3:]]
    e21, e32 = f2 - f1, f3 - f2
    if e21 == 0 or e32 == 0 or e32 / e21 < 0:
        return None
    r21, r32 = h2 / h1, h3 / h2
    p = 2.0
    for _ in range(200):  # fixed point p = |ln|e32/e21| + q(p)| / ln r21, q(p) = ln((r21^p - 1)/(r32^p - 1))
        q = math.log((r21 ** p - 1) / (r32 ** p - 1))
        p_new = abs(math.log(abs(e32 / e21)) + q) / math.log(r21)
        if abs(p_new - p) < 1e-10:
            break
        p = p_new
    extrapolated = (r21 ** p * f1 - f2) / (r21 ** p - 1)
    gci = 1.25 * abs(e21 / f1) / (r21 ** p - 1)
    return p, extrapolated, gci


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--grid", action="append", required=True, help="a fin-fsi flap summary (one per grid)")
    p.add_argument("--loop", help="fin-loop flap --phase1's summary (the loop on the MRI centreline)")
    p.add_argument("--out", required=True)
    a = p.parse_args()
    grids = sorted((read_grid(g) for g in a.grid), key=lambda g: -g["h"])
    if len(grids) < 2:
        fail("give two or more --grid summaries (the tip's grid change needs the finest two)")
    fine, second = grids[-1], grids[-2]
    fm = fine["metrics"]
    tip = fm["tip_deflection"]
    rms = fm["centreline_rms"]
    out = [
        metric("tip_deflection", tip["value"], "m", "absolute", tip["reference"], tip["tolerance"],
               f"finest grid (h = {fine['h'] * 1e3:g} mm): {tip['source']}"),
        metric("centreline_rms", rms["value"], "m", "max", None, rms["tolerance"],
               f"finest grid (h = {fine['h'] * 1e3:g} mm): {rms['source']}"),
        metric("tip_grid_change", abs(tip["value"] - second["metrics"]["tip_deflection"]["value"]), "m", "max", None,
               0.5e-3, f"|tip(h = {fine['h'] * 1e3:g} mm) - tip(h = {second['h'] * 1e3:g} mm)|; issue 49 goal < 0.5 mm"),
        metric("grids", len(grids), "", "min", None, 3, "grids in the study; issue 49: at least three"),
        metric("steady_state_reached", min(g["metrics"]["steady_state_reached"]["value"] for g in grids), "",
               "absolute", 1, 0, "every grid's root bracketed within its tolerance"),
    ]
    fit = richardson(grids) if len(grids) >= 3 else None
    if fit:
        p, extrapolated, gci = fit
        out.append(metric("tip_apparent_order", p, "", "info", source="finest three grids (Celik et al. 2008)"))
        out.append(metric("tip_extrapolated", extrapolated, "m", "info", source="Richardson, finest three grids"))
        out.append(metric("tip_gci_fine", gci, "", "info", source="fine grid's convergence index, safety 1.25"))
    inputs = [g["path"] for g in grids]
    if a.loop:
        out += loop_metrics(a.loop)
        inputs.append(a.loop)
    per_grid = []
    for g in grids:
        m = g["metrics"]
        tag = f"h{g['h'] * 1e3:g}mm"
        for key, units in (("tip_deflection", "m"), ("centreline_rms", "m"), ("cells", ""), ("wall_seconds", "s"),
                           ("peak_memory", "MB"), ("flow_steps", "")):
            out.append(metric(f"{key}_{tag}", m[key]["value"], units, "info"))
        per_grid.append({"h_m": g["h"], "summary": g["path"]})
    write_summary(a.out, "validation", "flap_phase1",
                  "Hessenthaler 2017 Phase I in 3-D: the flap as a sheet in the junction, grid study "
                  "(tip, centreline RMS against the 59 MRI points, grid change, cost per grid on this machine)",
                  out, {"grids": per_grid}, "tools/scripts/flap_phase1_study.py", inputs=inputs)
    sys.exit(0 if all(m["pass"] for m in out if m["pass"] is not None) else 1)


if __name__ == "__main__":
    main()
