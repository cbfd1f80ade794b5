#!/usr/bin/env python3
"""The Hessenthaler (2017) flap's report page (issue 49, deliverable 5): the measured and simulated
Phase I centrelines, the flow on two cross-sections of the outlet pipe (z = 10 and 30 mm above the
clamp, the finest grid's flow_planes.h5 from `fin-fsi flap --planes`), the grid study's verdicts
and costs, and the decision trail of the finest grid's steady-state search (each held tip, the
structure's answer and the load that gave it), and with --loop the loop on the MRI centreline (fin-loop
flap --phase1: each run's fit, the candidates' scores, what was added or refused and why). Reads the
grid study's summary (flap_phase1_study.py) and the grid summaries it lists; writes index.html and
its figures.

    flap_phase1_report.py --study results/validation/flap_phase1/summary.json \
        --planes results/validation/flap_phase1/grid_h1.43mm/flow_planes.h5 \
        --centreline data/reference/hessenthaler2017/phaseI_centreline.csv \
        --loop results/validation/flap_phase1/loop/summary.json \
        --out results/validation/flap_phase1/report/index.html

Exit 2 with one line naming the input when one is missing or malformed.
"""
import argparse
import html
import json
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

OUTLET_RADIUS_MM = 38.1  # the outlet pipe's 76.2 mm diameter (the paper; pipe_flow.md)


def fail(message):
    print(f"flap_phase1_report.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def load_json(path, what):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        fail(f"{what} {path}: {e}")


def read_inputs(a):
    study = load_json(a.study, "--study")
    try:
        grids = [load_json(g["summary"], "grid summary") for g in study["parameters"]["grids"]]
        for g in grids:
            g["parameters"]["h_m"], g["parameters"]["centreline_zy_m"], g["parameters"]["iterates"]
    except (KeyError, TypeError) as e:
        fail(f"--study {a.study}: {e}; expected flap_phase1_study.py's summary listing fin-fsi flap summaries")
    try:
        with open(a.centreline) as f:
            lines = [ln for ln in f if ln.strip() and not ln.startswith("#")]
        header = [c.strip() for c in lines[0].split(",")]
        rows = np.array([[float(c) for c in ln.split(",")] for ln in lines[1:]])
        mri_zy = np.column_stack([rows[:, header.index("z_mm")], rows[:, header.index("y_mm")]])
    except (OSError, ValueError, IndexError) as e:
        fail(f"--centreline {a.centreline}: {str(e).splitlines()[0]}; expected columns x_mm, y_mm, z_mm")
    planes = []
    try:
        with h5py.File(a.planes, "r") as f:
            for name in f:
                g = f[name]
                planes.append({k: np.asarray(g[k]) for k in ("x", "y", "u", "v", "w")} | {"z": float(g.attrs["z_m"])})
    except (OSError, KeyError) as e:
        fail(f"--planes {a.planes}: {e}; expected fin-fsi flap's flow_planes.h5")
    return study, sorted(grids, key=lambda g: -g["parameters"]["h_m"]), mri_zy, sorted(planes, key=lambda p: p["z"])


def centreline_figure(grids, mri_zy, loop, path):
    fig, ax = plt.subplots(figsize=(5, 6))
    ax.plot(mri_zy[:, 1], mri_zy[:, 0], "ko", ms=3, label="MRI (59 points)")
    for g in grids:
        zy = np.array(g["parameters"]["centreline_zy_m"]) * 1e3
        ax.plot(zy[:, 1], zy[:, 0], "-", label=f"fin-fsi, h = {g['parameters']['h_m'] * 1e3:.3g} mm")
    if loop:
        f = loop["parameters"]["runs"]["phase_I"]["frames"][1]
        z = np.array(f["measured_zy_m"])[:, 0] * 1e3
        ax.plot(np.array(f["model_y_before_m"]) * 1e3, z, "k--", lw=1, label="loop model, before")
        ax.plot(np.array(f["model_y_after_m"]) * 1e3, z, "k:", lw=1.5, label="loop model, after")
    ax.set_xlabel("y [mm] (deflection, the faster inlet's side +)")
    ax.set_ylabel("z [mm] above the clamp")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title("Phase I centreline")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def planes_figure(planes, path):
    fig, axes = plt.subplots(1, len(planes), figsize=(5 * len(planes), 4.6), squeeze=False)
    wmax = max(np.nanmax(np.abs(p["w"])) for p in planes)
    for ax, p in zip(axes[0], planes):
        X, Y = np.meshgrid(p["x"] * 1e3, p["y"] * 1e3)
        m = ax.pcolormesh(X, Y, p["w"], cmap="RdBu_r", vmin=-wmax, vmax=wmax, shading="nearest")
        step = max(1, len(p["x"]) // 16)
        ax.quiver(X[::step, ::step], Y[::step, ::step], p["u"][::step, ::step], p["v"][::step, ::step])
        t = np.linspace(0, 2 * np.pi, 200)
        ax.plot(OUTLET_RADIUS_MM * np.cos(t), OUTLET_RADIUS_MM * np.sin(t), "k-", lw=0.8)
        ax.set_aspect("equal")
        ax.set_title(f"z = {p['z'] * 1e3:g} mm: w (colour), (u, v) (arrows)")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        fig.colorbar(m, ax=ax, label="w [m/s]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def table(header, rows):
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>" for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def loop_section(loop):
    """The loop's decision trail: per run, the modulus, each frame's RMS before and after, what the
    tracer added or the loop refused and why; the Phase I run's scores and closures."""
    if not loop:
        return "<h2>The loop on the MRI centreline</h2><p>Not run (no --loop).</p>"
    runs = loop["parameters"]["runs"]
    rows = []
    for name, r in runs.items():
        frames = "; ".join(f"{f['frame']} ({f['role']}) {f['rms_before_m'] * 1e3:.3f} → {f['rms_after_m'] * 1e3:.3f}"
                           for f in r["frames"])
        rows.append((name, f"{r['youngs_modulus_start_Pa'] / 1e3:.1f} → {r['youngs_modulus_after_Pa'] / 1e3:.1f}",
                     frames, ", ".join(r["added"]) or "nothing", r["tracer_stop_reason"]))
    runs_table = table(["run", "E [kPa]", "RMS [mm] per frame, before → after", "added", "tracer's stop"], rows)
    p1 = runs.get("phase_I", {})
    scores = [(c["candidate"], f"{c['statistic']:.3g}", f"{c['p_value']:.2g}", f"{c['projected_fraction']:.2g}")
              for c in p1.get("scores", [])]
    closures = [(c["candidate"], f"{c.get('value', float('nan')):.4g} {c.get('unit', '')}",
                 "yes" if c.get("at_bound") else "no", f"{c.get('training_rms_m', float('nan')) * 1e3:.3f}")
                for c in p1.get("closures", [])]
    return f"""<h2>The loop on the MRI centreline</h2>
<p><code>fin-loop flap --phase1</code>: frames are the zero-flow centreline (the paper's fit, sampled) and the 59 MRI
points of Phase I, the flap in the 3-D run's load, which is linear in the tip about the root; the flow-side
candidates from the runs with the viscosity and the inflows perturbed. Runs: E held at the tensile test's value
(uniaxial), E fitted to the no-flow centreline (fitted), and E held there while the Phase I residual is traced
(phase_I).</p>{runs_table}
<h3>Phase I run: the candidates' scores (first step)</h3>
{table(["candidate", "score", "p", "fraction off span(J)"], scores)}
<h3>Phase I run: each candidate alone, refitted to the Phase I points</h3>
{table(["candidate", "value", "at a bound", "RMS [mm]"], closures)}"""


def page(study, grids, loop):
    verdict = {True: "met", False: "missed", None: "reported"}
    goals = [(m["name"], f"{m['value']:.4g} {m['units']}", "" if m.get("tolerance") is None else m["tolerance"], verdict[m["pass"]])
             for m in study["metrics"] if m["pass"] is not None or m["name"].startswith("tip_")]
    cost = [(f"{g['parameters']['h_m'] * 1e3:.3g}", int(m["cells"]["value"]), int(m["flow_steps"]["value"]),
             f"{m['wall_seconds']['value']:.0f}", f"{m['peak_memory']['value']:.0f}",
             f"{m['tip_deflection']['value'] * 1e3:.2f}", f"{m['centreline_rms']['value'] * 1e3:.2f}")
            for g in grids for m in [{x["name"]: x for x in g["metrics"]}]]
    fine = grids[-1]["parameters"]
    trail = [(k + 1, f"{it['t'][0]:.2f}-{it['t'][1]:.2f}", f"{it['tip_held_m'] * 1e3:.2f}",
              f"{it['tip_answer_m'] * 1e3:.2f}", f"{it['force_n'][1]:.4g}", f"{it['force_y_std_n']:.2g}")
             for k, it in enumerate(fine["iterates"])]
    return f"""<!DOCTYPE html><html><head><meta charset="utf-8"><title>Hessenthaler flap, Phase I</title>
<style>body{{font-family:sans-serif;max-width:1100px;margin:2em auto}}td,th{{border:1px solid #999;padding:2px 8px}}
table{{border-collapse:collapse;margin:1em 0}}</style></head><body>
<h1>The Hessenthaler et al. (2017) flap: Phase I in 3-D</h1>
<p>The silicone flap in the junction, steady inflow (630 / 615 mm/s), simulated by <code>fin-fsi flap</code>
and compared with the MRI. Method and choices: docs/studies/hessenthaler_flap.md ("Phase I in 3-D").</p>
<h2>Goals</h2>{table(["metric", "value", "tolerance", "verdict"], goals)}
<h2>Centreline</h2><img src="centrelines.png" alt="centrelines">
<h2>The flow across the outlet pipe</h2><p>The grid of flow_planes.h5 (the rule takes the finest), at the end of its run (the flap held at the
steady state's root); the outlet pipe's wall drawn in black.</p><img src="planes.png" alt="planes" width="100%">
<h2>Grids and cost (2 cores, one run per core)</h2>
{table(["h [mm]", "cells", "flow steps", "wall [s]", "memory [MB]", "tip [mm]", "centreline RMS [mm]"], cost)}
<h2>Decision trail: the finest grid's steady-state search</h2>
<p>Each evaluation holds the flap at a first-mode shape with the given tip, averages the flow's load over a
window and asks the static structure for its answer; the steady state is the root of answer &minus; held
(secant steps, then regula falsi). Time-accurate coupling, fixed points on the load (Aitken, IQN-ILS)
and filtered relaxation were tried first and failed (the study lists why).</p>
{table(["evaluation", "window [s]", "tip held [mm]", "answer [mm]", "F_y [N]", "F_y std [N]"], trail)}
{loop_section(loop)}
</body></html>
"""


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--study", required=True)
    p.add_argument("--planes", required=True)
    p.add_argument("--centreline", required=True)
    p.add_argument("--loop", help="fin-loop flap --phase1's summary (the loop on the MRI centreline)")
    p.add_argument("--out", required=True)
    a = p.parse_args()
    study, grids, mri_zy, planes = read_inputs(a)
    loop = load_json(a.loop, "--loop") if a.loop else None
    if loop and "phase_I" not in loop.get("parameters", {}).get("runs", {}):
        fail(f"--loop {a.loop}: expected fin-loop flap --phase1's summary (runs.phase_I)")
    out_dir = os.path.dirname(os.path.abspath(a.out))
    os.makedirs(out_dir, exist_ok=True)
    centreline_figure(grids, mri_zy, loop, os.path.join(out_dir, "centrelines.png"))
    planes_figure(planes, os.path.join(out_dir, "planes.png"))
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        f.write(page(study, grids, loop))
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
