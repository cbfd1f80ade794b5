#!/usr/bin/env python3
"""Print validation and benchmark summaries (results/validation/*/summary.json,
results/bench/*.json) as a table, one row per metric.

    tools/scripts/summary.py results/validation/*/summary.json
    tools/scripts/summary.py --failed results/validation/*/summary.json   only failing metrics

Exit status: 0 when every graded metric passes, 1 when one fails (0 with --no-fail), 2 when a
file is not a finverse summary. The format is defined once, in tools/core/summary.hpp; the Python
scripts that produce summaries write them through write_summary() below.
"""
import argparse
import json
import os
import socket
import sys

REQUIRED = ("schema", "schema_version", "kind", "name", "metrics", "timing")
METRIC_KEYS = ("name", "value", "units", "kind", "reference", "source", "error", "tolerance", "pass")


def load(path):
    try:
        with open(path) as f:
            s = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        raise SystemExit(f"summary.py: error: {path}: {e}")
    missing = [k for k in REQUIRED if k not in s]
    if s.get("schema") != "finverse/summary" or missing:
        print(f"summary.py: error: {path}: not a finverse/summary file (missing {missing})", file=sys.stderr)
        sys.exit(2)
    for m in s["metrics"]:
        absent = [k for k in METRIC_KEYS if k not in m]
        if absent:
            print(f"summary.py: error: {path}: metric {m.get('name')} lacks {absent}", file=sys.stderr)
            sys.exit(2)
    return s


def write_summary(out, kind, name, description, metrics, parameters, producer, wall_s=None, threads=1,
                  passed=None, inputs=None):
    """Writes a finverse/summary file (tools/core/summary.hpp's layout, indent 2, a final newline)
    to `out` through a temporary and a rename. passed None: every graded metric passes. inputs:
    the files read, listed in provenance after the host (None: no such key)."""
    if passed is None:
        passed = all(m["pass"] for m in metrics if m["pass"] is not None)
    provenance = {"producer": producer, "host": socket.gethostname()}
    if inputs is not None:
        provenance["inputs"] = list(inputs)
    summary = {"schema": "finverse/summary", "schema_version": 1, "kind": kind, "name": name,
               "description": description, "pass": passed, "metrics": metrics, "parameters": parameters,
               "timing": {"wall_s": wall_s, "threads": threads}, "provenance": provenance}
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out + ".tmp", "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    os.replace(out + ".tmp", out)
    return summary


def fmt(x, digits=5):
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "NO"
    if isinstance(x, (int, float)):
        if x == 0 or (1e-3 <= abs(x) < 1e5):
            return f"{x:.{digits}g}"
        return f"{x:.{digits - 1}e}"
    return str(x)


def error_text(m):
    e = m["error"]
    if e is None:
        return "-"
    if m["kind"] == "relative":
        return f"{100 * e:.3g}%"
    if m["kind"] == "max":
        return f"{100 * e:.3g}% of goal"
    return fmt(e, 3)


def tolerance_text(m):
    t = m["tolerance"]
    if t is None:
        return "-"
    if m["kind"] == "relative":
        return f"{100 * t:.3g}%"
    if m["kind"] == "max":
        return f"<= {fmt(t, 3)}"
    if m["kind"] == "min":
        return f">= {fmt(t, 3)}"
    return fmt(t, 3)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("--failed", action="store_true", help="show only failing metrics")
    ap.add_argument("--no-fail", action="store_true", help="exit 0 even when a metric fails")
    args = ap.parse_args()

    header = ("case", "metric", "value", "units", "reference", "error", "tolerance", "pass", "source")
    rows, failed = [], 0
    for path in args.files:
        s = load(path)
        for m in s["metrics"]:
            if m["pass"] is False:
                failed += 1
            if args.failed and m["pass"] is not False:
                continue
            rows.append((s["name"], m["name"], fmt(m["value"]), m["units"] or "-", fmt(m["reference"]),
                         error_text(m), tolerance_text(m), fmt(m["pass"]), m["source"][:48]))
        t = s["timing"]
        rows.append((s["name"], "(wall time)", fmt(t.get("wall_s"), 3), "s", "-", "-", "-", "-",
                     f"{t.get('threads')} threads"))
    widths = [max(len(str(r[i])) for r in rows + [header]) for i in range(len(header))]
    line = lambda r: "  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip()
    print(line(header))
    print("  ".join("-" * w for w in widths))
    for r in rows:
        print(line(r))
    graded = sum(1 for p in args.files for m in load(p)["metrics"] if m["pass"] is not None)
    print(f"\n{len(args.files)} file(s), {graded} graded metric(s), {failed} failing")
    return 0 if (failed == 0 or args.no_fail) else 1


if __name__ == "__main__":
    sys.exit(main())
