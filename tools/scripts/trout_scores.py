#!/usr/bin/env python3
"""The virtual trout's scores (issue 33, "Scores") as a validation summary: reads the scores that
fin-report graded into results/<case>/report/summary.json and writes them in the finverse summary
format (tools/core/summary.hpp) as results/validation/trout/summary.json. Nothing is recomputed:
a score fin-report marks "not available" stays so (value null, pass null, the reason in source).

    trout_scores.py --report results/<case>/report/summary.json --out results/validation/trout/summary.json

Exit 0 when every available score meets its goal, 1 when one misses (the summary is written
either way), 2 with one line for a missing or malformed report or a score of the table it lacks.
"""
import argparse
import json
import sys

from summary import write_summary

# Issue 33's Scores table, in its order: fin-report's score names (tools/report/fin_report.cpp).
TABLE = [
    "fitted ray E vs truth, median relative error",
    "fitted ray E vs truth, worst identified ray",
    "membrane E vs truth, relative error",
    "trailing-edge point 1 peak-to-peak, FSI vs reconstruction",
    "trailing-edge point 2 peak-to-peak, FSI vs reconstruction",
    "trailing-edge point 3 peak-to-peak, FSI vs reconstruction",
    "W-shape alpha1, FSI vs reconstruction",
    "W-shape alpha2, FSI vs reconstruction",
    "W-shape d1, FSI vs reconstruction",
    "W-shape d2, FSI vs reconstruction",
    "mean C_T, FSI vs reconstruction",
    "C_T peak, FSI vs reconstruction",
    "FSI motion vs truth motion, mean vertex distance",
]


def fail(message):
    print(f"trout_scores.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def metric(score):
    """A fin-report score as a summary metric: value = the relative difference (or distance / c)
    that the issue grades, kind max (passes when value <= goal)."""
    available = score["status"] in ("met", "missed") and score["value"] is not None
    source = score.get("source", "")
    if not available:
        source = f"not available: {score.get('note', '')}" + (f" ({source})" if source else "")
    elif score.get("note"):
        source = f"{source}; {score['note']}" if source else score["note"]
    value = score["value"] if available else None
    return {"name": score["name"], "value": value, "units": score.get("units", ""), "kind": "max",
            "reference": None, "source": source, "error": value, "tolerance": score["goal"],
            "pass": (score["status"] == "met") if available else None}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--report", required=True, help="results/<case>/report/summary.json (fin-report)")
    p.add_argument("--out", required=True, help="summary JSON to write")
    a = p.parse_args()
    try:
        with open(a.report) as f:
            report = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        fail(f"--report {a.report}: {e}")
    if report.get("schema") != "finverse/report" or "scores" not in report:
        fail(f"--report {a.report}: expected fin-report's summary.json (schema finverse/report with scores)")
    by_name = {s["name"]: s for s in report["scores"]}
    missing = [n for n in TABLE if n not in by_name]
    if missing:
        fail(f"--report {a.report}: lacks the score(s) {missing}; expected every score of issue 33's table")
    metrics = [metric(by_name[n]) for n in TABLE]
    # The reconstruction's own distance to the truth, beside the graded FSI one (info).
    for s in report["scores"]:
        if s["status"] == "info" and s["value"] is not None:
            metrics.append({"name": s["name"], "value": s["value"], "units": s.get("units", ""), "kind": "info",
                            "reference": None, "source": s.get("note", ""), "error": None, "tolerance": None,
                            "pass": None})
    summary = write_summary(
        a.out, "validation", "trout",
        f"the virtual trout's scores (issue 33) on case {report.get('case')}: "
        f"{sum(m['pass'] is True for m in metrics)} met, {sum(m['pass'] is False for m in metrics)} "
        f"missed, {sum(m['pass'] is None and m['kind'] != 'info' for m in metrics)} not available",
        metrics, {"case": report.get("case"), "report": a.report, "inputs": report.get("inputs")},
        "trout_scores.py finverse")
    passed = summary["pass"]
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
