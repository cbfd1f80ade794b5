#!/usr/bin/env python3
"""The grid study of the Hessenthaler (2017) Phase I run in 3-D (issue 49; fin-fsi flap, one
summary per grid): the finest grid's tip and centreline RMS graded as the run grades them, the
change of the tip between the two finest grids graded against 0.5 mm, and per grid its cells,
wall time, memory peak and flow steps (the benchmark's cost of a steady state on this machine).
Writes results/validation/flap_phase1/summary.json (tools/core/summary.hpp's layout).

    flap_phase1_study.py --grid results/validation/flap_phase1/grid_h2.0mm/summary.json \
        --grid .../grid_h1.5mm/summary.json --grid .../grid_h1.25mm/summary.json --out summary.json

Exit 0 when every graded metric passes, 1 when one misses, 2 with one line for a missing or
malformed input or fewer than two grids.
"""
import argparse
import json
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
    else:
        error, passed = None, None
    return {"name": name, "value": value, "units": units, "kind": kind, "reference": reference, "source": source,
            "error": error, "tolerance": tolerance, "pass": passed}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--grid", action="append", required=True, help="a fin-fsi flap summary (one per grid)")
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
        metric("steady_state_reached", min(g["metrics"]["steady_state_reached"]["value"] for g in grids), "",
               "absolute", 1, 0, "every grid's root bracketed within its tolerance"),
    ]
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
                  out, {"grids": per_grid}, "tools/scripts/flap_phase1_study.py",
                  inputs=[g["path"] for g in grids])
    sys.exit(0 if all(m["pass"] for m in out if m["pass"] is not None) else 1)


if __name__ == "__main__":
    main()
