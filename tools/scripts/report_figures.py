#!/usr/bin/env python3
"""The report's figures and page (issue 33 "Deliver" 3): reads what fin-report wrote into a
report directory (figures.json, summary.json) and writes the PNGs of the seed paper's figures and
index.html beside them. The page opens from disk (no server): figures by relative path, the
score table inline, each score marked met / missed / not available.

    tools/scripts/report_figures.py results/<case>/report

Figures: fig10_pressure_jump.png, fig11_moduli.png, fig12_root_pitch.png,
fig14_trailing_edge.png, fig15_profiles.png, fig16_forces.png, fig17_wake.png (lambda_2 from the
last frame of ../loads.flow.pvd or ../fsi.flow.pvd beside the stage files, linked on the page); a
figure whose data is absent is listed on the page as not available. Exit 2 with one line for a missing or malformed input.
With loop data (fin-report --loop): a "Closing the loop" section, loop_residual_maps.png (per-node
RMS residual before and after on one colour scale), the errors before/after and the decision trail.
"""
import html
import json
import os
import sys
import zlib

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
    # An interval beyond what a double holds (none: a fit with fewer independent residuals than
    # parameters) is drawn past the axis, which shows ±30x.
    lo = np.array([0.0 if r["E_lower"] is None else r["E_lower"] for r in rows])
    hi = np.array([np.inf if r["E_upper"] is None else r["E_upper"] for r in rows])
    lo, hi = np.maximum(lo, e / 1e6), np.minimum(hi, e * 1e6)
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


def read_vtr(path):
    """Coordinates and cell arrays of a VTK XML rectilinear grid as core/vtk_output.cpp writes it:
    appended raw data, zlib-compressed blocks (VTK's XML format; no VTK module needed)."""
    import xml.etree.ElementTree as ET

    with open(path, "rb") as f:
        raw = f.read()
    start = raw.index(b"<AppendedData")
    data = raw[raw.index(b"_", start) + 1:]
    root = ET.fromstring(raw[:start] + b"</VTKFile>")
    if root.get("compressor") != "vtkZLibDataCompressor" or root.get("type") != "RectilinearGrid":
        raise ValueError("expected a zlib-compressed VTK RectilinearGrid")
    head = np.dtype("<u8" if root.get("header_type") == "UInt64" else "<u4")
    types = {"Float64": "<f8", "Float32": "<f4", "Int32": "<i4", "Int64": "<i8", "UInt8": "u1"}

    def array(e):
        off = int(e.get("offset"))
        nblocks = int(np.frombuffer(data, head, 1, off)[0])
        sizes = np.frombuffer(data, head, 3 + nblocks, off).astype(np.int64)
        pos = off + head.itemsize * (3 + nblocks)
        chunks = []
        for size in sizes[3:]:
            chunks.append(zlib.decompress(data[pos:pos + size]))
            pos += size
        a = np.frombuffer(b"".join(chunks), types[e.get("type")])
        k = int(e.get("NumberOfComponents", "1"))
        return a.reshape(-1, k) if k > 1 else a

    piece = root.find("RectilinearGrid/Piece")
    coords = [array(e) for e in piece.find("Coordinates")]
    cells = {e.get("Name"): array(e) for e in piece.find("CellData")}
    return coords, cells


def flow_snapshot(out):
    """The last frame of a flow snapshot series beside the stage files (the loads stage writes
    loads.flow.pvd, rules/cfd.smk), or None."""
    import xml.etree.ElementTree as ET

    case_dir = os.path.dirname(os.path.abspath(out))
    for name in ("fsi.flow.pvd", "loads.flow.pvd"):
        pvd = os.path.join(case_dir, name)
        if os.path.exists(pvd):
            frames = ET.parse(pvd).getroot().findall("Collection/DataSet")
            if frames:
                last = max(frames, key=lambda d: float(d.get("timestep")))
                return pvd, float(last.get("timestep")), os.path.join(case_dir, last.get("file"))
    return None


def fig17(d, out):
    """lambda_2 < 0 (vortex cores, Jeong & Hussain 1995) in the wake at the snapshot's time: the
    mid-span plane (x-y) and the minimum over y (x-z, a side projection), in units of (U/c)^2."""
    snap = flow_snapshot(out)
    if not snap:
        return None
    pvd, t, vtr = snap
    try:
        (x, y, z), cells = read_vtr(vtr)
    except (OSError, ValueError, KeyError, AttributeError, zlib.error) as e:
        print(f"report_figures.py: {vtr}: {e}; expected the flow snapshot that {os.path.basename(pvd)} names",
              file=sys.stderr)
        sys.exit(2)
    nx, ny, nz = len(x) - 1, len(y) - 1, len(z) - 1
    lam = cells["lambda2"].reshape(nz, ny, nx)  # VTK cell order: x fastest
    c = d["chord"]
    u = cells["velocity"][:, 0]
    speed = float(np.median(u)) or 1.0  # the free stream fills most of the box
    lam = lam / (speed / c) ** 2
    xc, yc, zc = (0.5 * (a[1:] + a[:-1]) / c for a in (x, y, z))
    k = int(np.argmin(np.abs(zc - 0.5 * (zc[0] + zc[-1]))))  # the box is centred on the swept fin
    levels = [-100, -30, -10, -3, -1, -0.3, 0]
    panels = [(lam[k], (xc, yc), ("x / c", "y / c"), f"mid-span plane z = {zc[k]:.2f} c")]
    if nz > 1:  # a 3-D box: the side projection too
        panels.append((lam.min(axis=1), (xc, zc), ("x / c", "z / c"), "minimum over y (side projection)"))
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.2), squeeze=False)
    axes = axes[0]
    for ax, (field, (h, v), (hl, vl), title) in zip(axes, panels):
        m = ax.contourf(h, v, np.minimum(field, 0), levels=levels, cmap="Blues_r",
                        extend="min")
        ax.set_aspect("equal")
        ax.set_xlabel(hl)
        ax.set_ylabel(vl)
        ax.set_title(title, fontsize=9)
    fig.colorbar(m, ax=axes, label="λ2 (c/U)$^2$ where < 0")
    fig.suptitle(f"λ2 at t = {t:.4f} s ({os.path.basename(pvd)}, ParaView)", fontsize=10)
    save(fig, os.path.join(out, "fig17_wake.png"), tight=False)
    return "fig17_wake.png"


def loop_maps(d, out):
    """Per-node RMS residual on the planform (x, z) before and after, one colour scale; nodes the
    tracer does not compare (the prescribed root) are grey crosses."""
    lp = d.get("loop") or {}
    maps = lp.get("maps")
    if not maps:
        return None
    import matplotlib.tri as mtri

    pts = np.array(lp["points"], dtype=float).reshape(-1, 3) * 1e3
    tri = np.array(lp["triangles"], dtype=int).reshape(-1, 3)
    vmax = (lp.get("vmax") or 0.0) * 1e3 or 1.0
    fig, axes = plt.subplots(1, len(maps), figsize=(4.8 * len(maps), 4.2), squeeze=False)
    axes = axes[0]
    for ax, m in zip(axes, maps):
        v = np.array([np.nan if x is None else x for x in m["rms"]], dtype=float) * 1e3
        bad = np.isnan(v)
        if len(tri):
            t = mtri.Triangulation(pts[:, 0], pts[:, 2], tri)
            t.set_mask(bad[tri].any(axis=1))
            h = ax.tripcolor(t, np.nan_to_num(v), shading="gouraud", cmap="magma_r", vmin=0, vmax=vmax)
        else:
            h = ax.scatter(pts[~bad, 0], pts[~bad, 2], c=v[~bad], cmap="magma_r", vmin=0, vmax=vmax, s=12)
        if bad.any():
            ax.plot(pts[bad, 0], pts[bad, 2], "x", color="0.5", ms=3, label="not compared")
            ax.legend(fontsize=7, loc="lower right")
        ax.set_aspect("equal")
        ax.set_title(f"{m['label']}\nmax {np.nanmax(v) if (~bad).any() else 0:.3g} mm", fontsize=9)
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("z [mm]")
    fig.colorbar(h, ax=axes, label="RMS residual over the frames [mm]")
    save(fig, os.path.join(out, "loop_residual_maps.png"), tight=False)
    return "loop_residual_maps.png"


def loop_html(d, maps_png):
    """The "Closing the loop" section: errors before/after, the residual maps, the decision trail."""
    lp = d.get("loop")
    if not lp:
        return ""
    esc = html.escape
    added = ", ".join(lp["added"]) or "none"
    parts = ["<h2>Closing the loop</h2>",
             f"<p>fin-loop trace: {len(lp['candidates'])} candidate effects ({esc(', '.join(lp['candidates']))}); "
             f"added: <b>{esc(added)}</b>; stopped: {esc(lp['stop_reason'])}; held-out frames: "
             f"{esc(lp['held_out_kind'])}.</p>",
             "<h3>Error before (refitted base) and after (last accepted effect)</h3>"
             "<table border='1' cellpadding='4' style='border-collapse:collapse'>"
             "<tr><th>measure</th><th>before</th><th>after</th><th>before / after</th></tr>"]
    e = lp["errors"]
    exc = lp.get("excursion")
    for label, key, unit in (("trailing-edge residual RMS", "trailing_edge", " m"),
                             ("held-out RMS error", "held_out", " m")):
        b, a, f = e[key]
        rel = ""
        if key == "trailing_edge" and exc and b is not None and a is not None:
            rel = f" ({fmt(b / exc)} → {fmt(a / exc)} of its excursion)"
        parts.append(f"<tr class='loop-error'><td>{label}{rel}</td><td>{fmt(b)}{unit}</td><td>{fmt(a)}{unit}</td>"
                     f"<td>{fmt(f)}</td></tr>")
    b, a, c = e["bic"]
    parts.append(f"<tr class='loop-error'><td>BIC (training frames)</td><td>{fmt(b)}</td><td>{fmt(a)}</td>"
                 f"<td>change {fmt(c)}</td></tr></table>")
    parts.append("<h3>Residual maps before and after (one colour scale)</h3>")
    if maps_png:
        parts.append(f"<img src='{maps_png}' style='max-width:100%'>")
    else:
        parts.append(f"<p><i>not available: {esc(lp.get('maps_missing', 'no per-node residual in loop.h5'))}</i></p>")
    parts.append("<h3>Decision trail</h3><table border='1' cellpadding='4' style='border-collapse:collapse'>"
                 "<tr><th>step</th><th>candidates, ranked (score, p)</th><th>tried</th>"
                 "<th>fitted magnitude [95 % interval]</th><th>trailing-edge RMS before → after [m]</th>"
                 "<th>BIC before → after</th><th>held-out RMS before → after [m]</th><th>verdict</th></tr>")
    for row in lp["trail"]:
        ranking = "<br>".join(f"{esc(r['candidate'])} {fmt(r['score'])} (p {fmt(r['p_value'])})" for r in row["ranking"])
        mags = "<br>".join(f"{esc(m['name'])} = {fmt(m['value'])} [{fmt(m['lower95'])}, {fmt(m['upper95'])}]"
                           for m in row["magnitude"])
        arrow = lambda p: f"{fmt(p[0])} → {fmt(p[1])}"  # noqa: E731
        colour = COLOURS["met"] if row["accepted"] else "#fff"
        parts.append(f"<tr class='loop-step' style='background:{colour}'><td>{row['step']}</td><td>{ranking}</td>"
                     f"<td>{esc(row['tried']) or '—'}</td><td>{mags or '—'}</td><td>{arrow(row['trailing_edge'])}</td>"
                     f"<td>{arrow(row['bic'])}</td><td>{arrow(row['held_out'])}</td><td>{esc(row['verdict'])}</td></tr>")
    parts.append("</table>")
    return "".join(parts)


FIGURES = [
    ("Fig. 10: pressure jump at two instants", fig10),
    ("Fig. 11: fitted E, I and EI per ray against the truth (95 % intervals)", fig11),
    ("Fig. 12: root pitch per ray", fig12),
    ("Fig. 14: trailing-edge points 1-3, lateral displacement", fig14),
    ("Fig. 15: chordwise and spanwise profiles, W-shape measures", fig15),
    ("Fig. 16: C_T and C_L over the record", fig16),
    ("Fig. 17: the wake, λ2 < 0 at the last output", fig17),
]
COLOURS = {"met": "#c8f0c8", "missed": "#f6c4c4", "not available": "#e4e4e4", "info": "#ffffff"}


def fmt(v):
    return "—" if v is None else f"{v:.4g}"


def page(summary, figures, out, extra=""):
    rows = []
    for s in summary["scores"]:
        rows.append(
            f"<tr style='background:{COLOURS.get(s['status'], '#fff')}'><td>{html.escape(s['name'])}</td>"
            f"<td>{fmt(s['value'])} {html.escape(s.get('units', ''))}</td><td>{fmt(s['goal'])}</td>"
            f"<td><b>{html.escape(s['status'])}</b></td><td>{html.escape(s.get('note', ''))}</td></tr>")
    counts = ", ".join(f"{v} {k}" for k, v in summary["counts"].items())
    # What the case's scores can test (a coarse case: the grading, not the method), above them.
    scope = f"<p><b>Scope:</b> {html.escape(summary['scope'])}</p>" if summary.get("scope") else ""
    inputs = ", ".join(f"{k}: {'yes' if v is True else ('no' if v is False else html.escape(str(v)))}"
                       for k, v in summary["inputs"].items())
    figs = []
    for title, name in figures:
        if name:
            figs.append(f"<h3>{html.escape(title)}</h3><img src='{name}' style='max-width:100%'>")
            snap = flow_snapshot(out) if name == "fig17_wake.png" else None
            if snap:
                link = html.escape(os.path.relpath(snap[0], os.path.abspath(out)))
                figs.append(f"<p>ParaView (velocity, pressure, vorticity, λ2): <a href='{link}'>{link}</a></p>")
        else:
            figs.append(f"<h3>{html.escape(title)}</h3><p><i>not available: its input file is absent</i></p>")
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>finverse report: "
            f"{html.escape(summary['case'])}</title></head><body style='font-family:sans-serif'>"
            f"<h1>finverse report: {html.escape(summary['case'])}</h1>{scope}<p>Scores: {counts}.</p>"
            f"<p>Inputs: {inputs}</p><table border='1' cellpadding='4' style='border-collapse:collapse'>"
            "<tr><th>score</th><th>value</th><th>goal (≤)</th><th>status</th><th>note</th></tr>"
            + "".join(rows) + "</table>" + "".join(figs) + extra + "</body></html>\n")


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
    extra = loop_html(data, loop_maps(data, out))
    tmp = os.path.join(out, "index.html.tmp")
    with open(tmp, "w") as f:
        f.write(page(summary, figures, out, extra))
    os.replace(tmp, os.path.join(out, "index.html"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
