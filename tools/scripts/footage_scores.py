#!/usr/bin/env python3
"""Scores of the realistic-footage validation cases (issue 35, item 8; rules/footage.smk) against
fin-synth's truth, written as finverse validation summaries (tools/core/summary.hpp).

    footage_scores.py three-view --track-summary S.json --name footage_3view --out summary.json
    footage_scores.py midline --midline m.h5 --truth truth.h5 --cameras cameras.yml --view ventral \
        --name footage_2d --out summary.json
    footage_scores.py single-view --exit-code N --log track.log --kinematics k.h5 \
        --name footage_single_view --out summary.json

three-view re-grades fin-track's own summary (--truth) on the issue's goals: mean vertex error <=
1 % c, 95th percentile <= 2 % c, and the fin separated from the body in every frame: in each view
the segmented fin's IoU with the true fin's silhouette, worst frame, >= 0.85 (a body left in
the mask halves it). midline compares fin-track midline's tail tip with the projected truth: the
truth's tip is the fin vertex farthest along the record's head-to-tail axis (where the midline
puts the silhouette's end); frequency against 1/T, amplitude against half the truth tip's lateral
peak-to-peak per beat. single-view grades the exit status 1 and its one-line reason.
Exit 0 when every graded metric passes, 1 when one misses, 2 with one line for a bad input.
"""
import argparse
import json
import os
import re
import sys

import h5py
import numpy as np
import yaml

from summary import write_summary


def fail(message):
    print(f"footage_scores.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def metric(name, value, kind, reference, tol, source, units=""):
    value = float(value)
    if kind == "relative":
        err = abs(value - reference) / abs(reference)
        ok = err <= tol
    elif kind == "absolute":
        err = abs(value - reference)
        ok = err <= tol
    elif kind == "max":
        err = value / tol
        ok = value <= tol
    elif kind == "min":
        err = value / tol
        ok = value >= tol
    else:
        err, ok, reference, tol = None, None, None, None
    if kind != "info" and not np.isfinite(value):
        err, ok = None, False
    return {"name": name, "value": value if np.isfinite(value) else None, "units": units, "kind": kind,
            "reference": reference, "source": source, "error": err, "tolerance": tol, "pass": ok}


def info(name, value, units="", source=""):
    return metric(name, value, "info", None, None, source, units)


def write(out, name, description, metrics, parameters):
    passed = write_summary(out, "validation", name, description, metrics, parameters, "footage_scores.py finverse")["pass"]
    for m in metrics:
        if m["pass"] is not None:
            print(f"{name}: {m['name']} = {m['value']} ({'pass' if m['pass'] else 'MISSED'})", file=sys.stderr)
    return 0 if passed else 1


ISSUE = "issue 35 validation"
ISSUE_2D = "issue 47 validation"


def three_view(a):
    try:
        with open(a.track_summary) as f:
            s = json.load(f)
        got = {m["name"]: m for m in s["metrics"]}
    except (OSError, ValueError, KeyError, TypeError) as e:
        fail(f"--track-summary {a.track_summary}: {e}; expected fin-track's summary.json")
    for key in ("mean_vertex_error", "p95_vertex_error"):
        if key not in got:
            fail(f"--track-summary {a.track_summary}: no metric {key}; expected fin-track --truth --summary output")
    views = [k[len("worst_truth_iou_"):] for k in got if k.startswith("worst_truth_iou_")]
    if not views:
        fail(f"--track-summary {a.track_summary}: no worst_truth_iou_<view> metrics")
    metrics = [metric("mean_vertex_error", got["mean_vertex_error"]["value"], "max", None, 0.01,
                      f"{ISSUE}: mean vertex error <= 1 % of the chord", "1"),
               metric("p95_vertex_error", got["p95_vertex_error"]["value"], "max", None, 0.02,
                      f"{ISSUE}: 95th percentile <= 2 % of the chord", "1")]
    for v in views:
        metrics.append(metric(f"fin_mask_iou_worst_frame_{v}", got[f"worst_truth_iou_{v}"]["value"], "absolute", 1.0,
                              0.15, f"{ISSUE}: fin separated from the body in every frame (segmented fin vs true "
                              "fin silhouette IoU >= 0.85)", "1"))
    for k, m in got.items():
        if k not in ("mean_vertex_error", "p95_vertex_error") and m.get("value") is not None:
            metrics.append(info(f"fin-track {k}", m["value"], m.get("units", ""), m.get("source", "")))
    return write(a.out, a.name, "realistic virtual footage (body, vignetting, gradient, saturation, debris, JPEG), "
                 "three views: fin-track vertex error and fin-body separation against truth", metrics,
                 {"track_summary": a.track_summary})


def read_camera(path, view):
    def matrix(loader, node):
        m = loader.construct_mapping(node, deep=True)
        return np.array(m["data"], dtype=float).reshape(m["rows"], m["cols"])
    yaml.SafeLoader.add_constructor("tag:yaml.org,2002:opencv-matrix", matrix)
    try:
        with open(path) as f:
            text = f.read()
        text = re.sub(r"^%YAML:1\.0", "%YAML 1.1", text)
        cams = yaml.safe_load(text)
        c = cams[view]
        return (np.asarray(c["camera_matrix"]), np.asarray(c["distortion_coefficients"]).ravel(),
                np.asarray(c["rvec"]).ravel(), np.asarray(c["tvec"]).ravel(), int(c["image_width"]),
                int(c["image_height"]))
    except (OSError, yaml.YAMLError, KeyError, TypeError) as e:
        fail(f"--cameras {path}: view {view!r}: {e}; expected fin-synth's cameras.yml")


def project(X, K, dist, rvec, tvec):
    """cv::projectPoints (k1 k2 p1 p2 k3) of world points X [..., 3]."""
    th = np.linalg.norm(rvec)
    R = np.eye(3)
    if th > 0:
        k = rvec / th
        Kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        R = np.eye(3) + np.sin(th) * Kx + (1 - np.cos(th)) * Kx @ Kx
    Xc = X @ R.T + tvec
    x, y = Xc[..., 0] / Xc[..., 2], Xc[..., 1] / Xc[..., 2]
    k1, k2, p1, p2, k3 = dist[:5]
    r2 = x * x + y * y
    rad = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2 ** 3
    xd = x * rad + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * rad + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    return np.stack([K[0, 0] * xd + K[0, 1] * yd + K[0, 2], K[1, 1] * yd + K[1, 2]], axis=-1)


def fin_silhouette_middle(uv_fin, triangles, u, step=2.0):
    """The middle of the fin's true silhouette across the axis `u`, per frame: a list of [m, 2]
    polylines, root to tip. Seen from above the fin is a plate edge-on whose span its twist and
    cupping spread across the axis; the 2-D mode sees only that spread, so its axis there is the
    spread's middle: in slices `step` px long along `u`, the middle between the outermost points of
    the projected triangles (their corners, edge midpoints and centroids)."""
    n = np.array([-u[1], u[0]])
    A, B, C = (uv_fin[:, triangles[:, k], :] for k in range(3))
    pts = np.concatenate([A, B, C, 0.5 * (A + B), 0.5 * (B + C), 0.5 * (C + A), (A + B + C) / 3], axis=1)
    out = []
    for p in pts:
        along, across = p @ u, p @ n
        k = np.floor((along - along.min()) / step).astype(int)
        lo = np.full(k.max() + 1, np.inf)
        hi = np.full(k.max() + 1, -np.inf)
        np.minimum.at(lo, k, across)
        np.maximum.at(hi, k, across)
        s = np.bincount(k, weights=along) / np.maximum(np.bincount(k), 1)
        ok = np.isfinite(lo)
        out.append(s[ok, None] * u + (0.5 * (lo[ok] + hi[ok]))[:, None] * n)
    return out


def distance_to_polyline(q, line):
    """Distance of points q [n, 2] to the polyline `line` [m, 2]; NaN for a point whose nearest
    point is the polyline's far end (beyond it)."""
    a, b = line[:-1], line[1:]
    ab = b - a
    t = np.clip(np.einsum("nmk,mk->nm", q[:, None, :] - a[None], ab) / np.maximum((ab * ab).sum(1), 1e-12), 0, 1)
    foot = a[None] + t[..., None] * ab[None]
    d = np.sqrt(((q[:, None, :] - foot) ** 2).sum(-1))
    nearest = d.argmin(axis=1)
    beyond = (nearest == len(ab) - 1) & (t[np.arange(len(q)), nearest] >= 1)
    return np.where(beyond, np.nan, d.min(axis=1))


def axis_scores(mid, valid, uv, uv_axis, triangles, u, width, height):
    """Per-station RMS distance of the measured midline to the true axis (the body's projected axis,
    snout to peduncle, then the middle of the caudal fin's true silhouette), and which frames show
    the whole fish."""
    fin = fin_silhouette_middle(uv, triangles, u)
    dist = np.full(mid.shape[:2], np.nan)
    for i in np.flatnonzero(valid):
        behind = fin[i] @ u > uv_axis[i, -1] @ u  # the fin's part behind the peduncle's end
        line = np.concatenate([uv_axis[i], fin[i][behind]], axis=0)
        ok = np.isfinite(mid[i, :, 0])
        dist[i, ok] = distance_to_polyline(mid[i, ok], line)
    graded = np.isfinite(dist).sum(axis=0) >= 0.5 * max(1, valid.sum())
    with np.errstate(invalid="ignore"):
        per_station = np.where(graded, np.sqrt(np.nanmean(dist ** 2, axis=0)), np.nan)
    allpts = np.concatenate([uv, uv_axis], axis=1)
    whole = np.all((allpts[..., 0] >= 1) & (allpts[..., 0] <= width - 2) & (allpts[..., 1] >= 1) &
                   (allpts[..., 1] <= height - 2), axis=1)
    return per_station, whole


def midline(a):
    try:
        with h5py.File(a.midline, "r") as f:
            tip = np.asarray(f["px/tip"][...], float)
            mid = np.asarray(f["px/midline"][...], float)
            valid = np.asarray(f["valid"][...]).astype(bool)
            freq = float(f.attrs["tail_beat_frequency_hz"])
            amp = float(f.attrs["tail_beat_amplitude_px"])
            wavelength = float(f.attrs["body_wavelength_px"])
            fps = float(f.attrs["fps"])
    except (OSError, KeyError, ValueError) as e:
        fail(f"--midline {a.midline}: {e}; expected fin-track midline's midline.h5")
    try:
        with h5py.File(a.truth, "r") as f:
            P = np.asarray(f["points"][...], float)
            T = float(f.attrs["T"]) if "T" in f.attrs else float(f["points"].attrs["T"])
            axis = np.asarray(f["body/axis"][...], float) if "body/axis" in f else None
            triangles = np.asarray(f["template/triangles"][...], int)
    except (OSError, KeyError, ValueError) as e:
        fail(f"--truth {a.truth}: {e}; expected fin-synth's truth.h5 with points and T")
    if P.shape[0] != tip.shape[0]:
        fail(f"--midline {a.midline}: {tip.shape[0]} frames, but --truth {a.truth} has {P.shape[0]}")
    camera = read_camera(a.cameras, a.view)
    uv = project(P, *camera[:4])  # [nf, nv, 2]
    # The record's head-to-tail axis: the midline's mean direction.
    d = np.nanmean(mid[valid, -1, :] - mid[valid, 0, :], axis=0)
    u = d / np.linalg.norm(d)
    n = np.array([-u[1], u[0]])
    truth_tip = uv[np.arange(len(uv)), np.argmax(uv @ u, axis=1)]
    err = np.linalg.norm(tip - truth_tip, axis=1)[valid]
    lat = truth_tip @ n
    per = fps * T
    beats = int(np.floor(len(lat) / per + 1e-9))
    if beats < 1:
        fail(f"--truth {a.truth}: {len(lat)} frames hold no whole beat of {per:.1f} frames")
    halves = [0.5 * np.ptp(lat[int(np.ceil(b * per)):int(np.ceil((b + 1) * per))]) for b in range(beats)]
    truth_amp = float(np.mean(halves))
    metrics = [metric("tail_tip_error_mean", err.mean(), "max", None, 1.0, f"{ISSUE}: tail-tip position error <= 1 px mean", "px"),
               metric("tail_beat_frequency", freq, "relative", 1 / T, 0.01, f"{ISSUE}: within 1 % of the truth's 1/T", "Hz"),
               metric("tail_beat_amplitude", amp, "relative", truth_amp, 0.02,
                      f"{ISSUE}: within 2 % of the projected truth tip's half peak-to-peak per beat", "px")]
    if axis is not None:
        uv_axis = project(axis, *camera[:4])
        per_station, whole = axis_scores(mid, valid, uv, uv_axis, triangles, u, camera[4], camera[5])
        length = float(np.median(np.linalg.norm(truth_tip - uv_axis[:, 0], axis=1)))
        metrics += [
            metric("midline_axis_rms_worst_station", np.nanmax(per_station), "max", None, min(2.0, 0.01 * length),
                   f"{ISSUE_2D}: midline RMS distance to the true axis <= 2 px (<= 1 % of the length), every station", "px"),
            metric("frames_valid_when_whole", valid[whole].mean() if whole.any() else np.nan, "min", 0.98, 0.98,
                   f"{ISSUE_2D}: frames valid when the fish is whole in view >= 98 %"),
            info("midline_axis_rms_mean", float(np.sqrt(np.nanmean(per_station ** 2))), "px"),
            info("midline_stations_graded", int(np.isfinite(per_station).sum())),
            info("fish_length", length, "px"), info("frames_whole", int(whole.sum()))]
    metrics += [info("tail_tip_error_max", err.max(), "px"), info("tail_tip_error_p95", np.percentile(err, 95), "px"),
                info("frames_with_fish", int(valid.sum())), info("frames", len(valid)),
                info("body_wavelength", wavelength, "px")]
    return write(a.out, a.name, "realistic virtual footage, one view: fin-track midline's midline against the true "
                 "axis, tail tip, tail-beat frequency and amplitude against the projected truth", metrics,
                 {"midline": a.midline, "truth": a.truth, "cameras": a.cameras, "view": a.view,
                  "midline_axis_rms_per_station_px": None if axis is None else
                  [round(float(x), 3) if np.isfinite(x) else None for x in per_station]})


def single_view(a):
    try:
        with open(a.log) as f:
            lines = f.read().splitlines()
    except OSError as e:
        fail(f"--log {a.log}: {e}")
    errors = [ln for ln in lines if "error:" in ln]
    status = ""
    if os.path.exists(a.kinematics):
        try:
            with h5py.File(a.kinematics, "r") as f:
                if "fit_status" in f:
                    v = f["fit_status"][()]
                    status = v.decode() if isinstance(v, bytes) else str(v)
                elif "fit_status" in f.attrs:
                    status = str(f.attrs["fit_status"])
        except OSError as e:
            fail(f"--kinematics {a.kinematics}: {e}")
    reason = errors[-1].split("error:", 1)[1].strip() if errors else ""
    names_depth = "view" in reason and ("constrain" in reason or "depth" in reason)
    metrics = [metric("exit_status", a.exit_code, "absolute", 1, 0, f"{ISSUE}: a single view given to the 3-D fit exits 1"),
               metric("reason_given", 1 if names_depth else 0, "absolute", 1, 0,
                      f"{ISSUE}: ... with its reason (one error line naming the views / the free depth)"),
               metric("fit_status_recorded", 1 if status else 0, "absolute", 1, 0, "kinematics.h5 fit_status is written")]
    return write(a.out, a.name, "realistic virtual footage, one view given to the 3-D fit: exit 1 with its reason",
                 metrics, {"reason": reason, "fit_status": status, "log": a.log})


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="mode", required=True)
    t = sub.add_parser("three-view")
    t.add_argument("--track-summary", required=True)
    m = sub.add_parser("midline")
    m.add_argument("--midline", required=True)
    m.add_argument("--truth", required=True)
    m.add_argument("--cameras", required=True)
    m.add_argument("--view", required=True)
    s = sub.add_parser("single-view")
    s.add_argument("--exit-code", type=int, required=True)
    s.add_argument("--log", required=True)
    s.add_argument("--kinematics", required=True)
    for q in (t, m, s):
        q.add_argument("--name", required=True)
        q.add_argument("--out", required=True)
    a = p.parse_args()
    return {"three-view": three_view, "midline": midline, "single-view": single_view}[a.mode](a)


if __name__ == "__main__":
    sys.exit(main())
