#!/usr/bin/env python3
"""The report's figures and page (issue 33 "Deliver" 3): reads what fin-report wrote into a
report directory (figures.json, summary.json) and writes the PNGs of the seed paper's figures and
index.html beside them. The page opens from disk (no server): figures by relative path, the
score table inline, each score marked met / missed / not available.

    tools/scripts/report_figures.py results/<case>/report

Figures: fig10_pressure_jump.png, fig11_moduli.png, fig12_root_pitch.png,
fig14_trailing_edge.png, fig15_profiles.png, fig16_forces.png (a figure whose data is absent is
listed on the page as not available). Exit 2 with one line for a missing or malformed input.
"""
import html
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Fixed metadata so reruns give the same bytes.
PNG_META = {"Software": None}


def save(fig, path, tight=True):
    if tight:  # not with a colour bar spanning several axes (Fig. 10)
        fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=90, metadata=PNG_META)
    plt.close(fig)
    os.replace(path + ".tmp.png", path)


def fig10(d, out):
    pj = d.get("pressure_jump")
    if not pj:
        return None
    pts = np.array(pj["points"]).reshape(-1, 3)
    tri = np.array(pj["triangles"]).reshape(-1, 3)
    inst = pj["instants"]
    vmax = max(np.abs(np.array(i["values"])).max() for i in inst) or 1.0
    fig, axes = plt.subplots(1, len(inst), figsize=(4 * len(inst), 4))
    for ax, i in zip(np.atleast_1d(axes), inst):
        m = ax.tripcolor(pts[:, 0] * 1e3, pts[:, 2] * 1e3, tri, facecolors=np.array(i["values"]), cmap="RdBu_r",
                         vmin=-vmax, vmax=vmax)
        ax.set_aspect("equal")
        ax.set_title(f"t = {i['time']:.4f} s")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("z [mm]")
    fig.colorbar(m, ax=axes, label="pressure jump [Pa]")
    save(fig, os.path.join(out, "fig10_pressure_jump.png"), tight=False)
    return "fig10_pressure_jump.png"


def fig11(d, out):
    rows = [r for r in d.get("moduli", []) if "ray" in r]
    if not rows:
        return None
    ray = np.array([r["ray"] for r in rows])
    e = np.array([r["E"] for r in rows])
    lo = np.array([r["E_lower"] for r in rows])
    hi = np.array([r["E_upper"] for r in rows])
    truth = np.array([np.nan if r["E_truth"] is None else r["E_truth"] for r in rows])
    ident = np.array([bool(r["identified"]) for r in rows])
    inertia = np.array([r.get("I", np.nan) for r in rows])
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    panels = [("E [Pa]", 1.0), ("I [m$^4$]", None), ("EI [N m$^2$]", inertia)]
    for ax, (label, scale) in zip(axes, panels):
        if scale is None:
            ax.semilogy(ray, inertia, "ks-")
        else:
            s = scale
            yerr = np.array([np.maximum(e - lo, 0), np.maximum(hi - e, 0)]) * s
            ax.errorbar(ray[ident], (e * s)[ident], yerr=yerr[:, ident], fmt="o", color="C0", capsize=3,
                        label="fitted, identified (95 %)")
            ax.errorbar(ray[~ident], (e * s)[~ident], yerr=yerr[:, ~ident], fmt="x", color="0.5", capsize=3,
                        label="fitted, not identified (95 %)")
            ax.plot(ray, truth * s, "r_", markersize=14, mew=2, label="truth")
            ax.set_yscale("log")
            lim = np.nanmin(e * s) / 30, np.nanmax(e * s) * 30
            ax.set_ylim(lim)
        ax.set_xlabel("ray (1 dorsal)")
        ax.set_ylabel(label)
    axes[0].legend(fontsize=7)
    save(fig, os.path.join(out, "fig11_moduli.png"))
    return "fig11_moduli.png"


def fig12(d, out):
    rp = d.get("root_pitch")
    if not rp:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    rec = np.array(rp["reconstruction"])
    t = np.array(rp["time"])
    for r in range(rec.shape[0]):
        axes[0].plot(t, rec[r], color=plt.cm.viridis(r / max(1, rec.shape[0] - 1)), lw=1)
    axes[0].set_xlabel("t [s]")
    axes[0].set_ylabel("root pitch [deg]")
    axes[0].set_title("reconstruction, per ray (dark: ray 1)")
    rays = np.arange(1, rec.shape[0] + 1)
    axes[1].plot(rays, rec.max(axis=1) - rec.min(axis=1), "o-", label="reconstruction")
    if "truth" in rp:
        tr = np.array(rp["truth"])
        axes[1].plot(rays, tr.max(axis=1) - tr.min(axis=1), "r_", markersize=12, mew=2, label="truth")
    axes[1].set_xlabel("ray (1 dorsal)")
    axes[1].set_ylabel("root pitch peak-to-peak over the record [deg]")
    axes[1].legend(fontsize=8)
    save(fig, os.path.join(out, "fig12_root_pitch.png"))
    return "fig12_root_pitch.png"


def fig14(d, out):
    te = d.get("trailing_edge", [])
    if not te:
        return None
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), sharey=True)
    for k, s in enumerate(te):
        for p in range(3):
            axes[p].plot(s["time"], s["points"][p], marker=".", color=f"C{k}",
                         label=f"{s['label']}: {s['peak_to_peak_over_chord'][p]:.3f} c")
    for p in range(3):
        axes[p].set_title(f"trailing-edge point {p + 1}")
        axes[p].set_xlabel("t [s]")
        axes[p].legend(fontsize=6, title="peak-to-peak", title_fontsize=6)
    axes[0].set_ylabel("lateral displacement / c")
    save(fig, os.path.join(out, "fig14_trailing_edge.png"))
    return "fig14_trailing_edge.png"


def fig15(d, out):
    prof = d.get("profiles", [])
    if not prof:
        return None
    c = d["chord"]
    fig, axes = plt.subplots(2, len(prof), figsize=(4 * len(prof), 7), squeeze=False)
    for k, p in enumerate(prof):
        cw = np.array(p["chordwise_y"])
        sw = np.array(p["spanwise_y"])
        for f in range(cw.shape[0]):
            col = plt.cm.coolwarm(f / max(1, cw.shape[0] - 1))
            axes[0, k].plot(np.array(p["chordwise_x"]) / c, cw[f] / c, color=col, lw=0.8)
            axes[1, k].plot(sw[f] / c, np.array(p["spanwise_z"]) / c, color=col, lw=0.8)
        mid = p["midway_frame"]
        axes[1, k].plot(sw[mid] / c, np.array(p["spanwise_z"]) / c, "k", lw=2)
        w = p["w_shape"]
        axes[0, k].set_title(p["label"], fontsize=9)
        axes[0, k].set_xlabel("x / c (chordwise line, mid-span)")
        axes[0, k].set_ylabel("y / c")
        axes[1, k].set_xlabel("y / c (spanwise line, 0.8 c)")
        axes[1, k].set_ylabel("z / c")
        axes[1, k].set_title(f"α1 {w['alpha1_deg']:.1f}°, α2 {w['alpha2_deg']:.1f}°, "
                             f"d1 {w['d1_over_chord']:.3f}c, d2 {w['d2_over_chord']:.3f}c", fontsize=8)
    save(fig, os.path.join(out, "fig15_profiles.png"))
    return "fig15_profiles.png"


def fig16(d, out):
    forces = d.get("forces", [])
    if not forces:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8))
    for k, f in enumerate(forces):
        axes[0].plot(f["time"], f["C_T"], marker=".", color=f"C{k}", label=f["label"])
        axes[1].plot(f["time"], f["C_L"], marker=".", color=f"C{k}", label=f["label"])
    axes[0].set_ylabel("C_T (thrust, force along -x)")
    axes[1].set_ylabel("C_L (lateral)")
    for ax in axes:
        ax.set_xlabel("t [s]")
        ax.legend(fontsize=7)
    save(fig, os.path.join(out, "fig16_forces.png"))
    return "fig16_forces.png"


FIGURES = [
    ("Fig. 10: pressure jump at two instants", fig10),
    ("Fig. 11: fitted E, I and EI per ray against the truth (95 % intervals)", fig11),
    ("Fig. 12: root pitch per ray", fig12),
    ("Fig. 14: trailing-edge points 1-3, lateral displacement", fig14),
    ("Fig. 15: chordwise and spanwise profiles, W-shape measures", fig15),
    ("Fig. 16: C_T and C_L over the record", fig16),
]
COLOURS = {"met": "#c8f0c8", "missed": "#f6c4c4", "not available": "#e4e4e4", "info": "#ffffff"}


def fmt(v):
    return "—" if v is None else f"{v:.4g}"


def page(summary, figures):
    rows = []
    for s in summary["scores"]:
        rows.append(
            f"<tr style='background:{COLOURS.get(s['status'], '#fff')}'><td>{html.escape(s['name'])}</td>"
            f"<td>{fmt(s['value'])} {html.escape(s.get('units', ''))}</td><td>{fmt(s['goal'])}</td>"
            f"<td><b>{html.escape(s['status'])}</b></td><td>{html.escape(s.get('note', ''))}</td></tr>")
    counts = ", ".join(f"{v} {k}" for k, v in summary["counts"].items())
    inputs = ", ".join(f"{k}: {'yes' if v is True else ('no' if v is False else html.escape(str(v)))}"
                       for k, v in summary["inputs"].items())
    figs = []
    for title, name in figures:
        if name:
            figs.append(f"<h3>{html.escape(title)}</h3><img src='{name}' style='max-width:100%'>")
        else:
            figs.append(f"<h3>{html.escape(title)}</h3><p><i>not available: its input file is absent</i></p>")
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>finverse report: "
            f"{html.escape(summary['case'])}</title></head><body style='font-family:sans-serif'>"
            f"<h1>finverse report: {html.escape(summary['case'])}</h1><p>Scores: {counts}.</p>"
            f"<p>Inputs: {inputs}</p><table border='1' cellpadding='4' style='border-collapse:collapse'>"
            "<tr><th>score</th><th>value</th><th>goal (≤)</th><th>status</th><th>note</th></tr>"
            + "".join(rows) + "</table>" + "".join(figs) + "</body></html>\n")


def main():
    if len(sys.argv) != 2:
        print("usage: report_figures.py <report dir>", file=sys.stderr)
        return 2
    out = sys.argv[1]
    try:
        with open(os.path.join(out, "figures.json")) as f:
            data = json.load(f)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        if summary.get("schema") != "finverse/report" or "chord" not in data:
            raise ValueError("not a fin-report output (schema finverse/report, figures with a chord)")
    except (OSError, ValueError) as e:
        print(f"report_figures.py: {out}: {e}", file=sys.stderr)
        return 2
    figures = [(title, fn(data, out)) for title, fn in FIGURES]
    tmp = os.path.join(out, "index.html.tmp")
    with open(tmp, "w") as f:
        f.write(page(summary, figures))
    os.replace(tmp, os.path.join(out, "index.html"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
