#!/usr/bin/env python3
"""Gather the Snakemake benchmark files of the pipeline's stages into one finverse summary
(results/bench/pipeline.json; format: tools/core/summary.hpp), so that the slowest stage is
visible (issue 33, "Benchmark"). Rule bench_pipeline (rules/bench.smk) runs it.

    pipeline_bench.py --case tiny --threads 2 --stage synth=results/tiny/benchmarks/synth.tsv ... \
        --out results/bench/pipeline.json

Per stage, info metrics: <stage>_wall_s (Snakemake's column s, exact), <stage>_cpu_s (column
cpu_time) and <stage>_max_rss_MB. Snakemake samples CPU time and memory of the job's process tree
every 0.5 s for 15 s, then every 30 s, so cpu_s can fall short of the true CPU time by up to 30 s
times the threads, and misses processes that ended between samples: it is flagged as a sample.
A file with several rows (benchmark repeats) contributes the mean of each column.
With --goal-minutes G the stages' total wall time is graded against G minutes (issue 50: the
default case's main job in 15 min on 2 cores); exit 1 when it is missed.
Exit 2 with one line when a benchmark file is missing or malformed.
"""
import argparse
import csv
import os
import subprocess
import sys

from summary import write_summary


def fail(message):
    print(f"pipeline_bench.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_benchmark(stage, path):
    """Mean of the columns s, cpu_time and max_rss over the rows of a Snakemake benchmark file."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f, delimiter="\t"))
    except OSError as e:
        fail(f"--stage {stage}={path}: {e.strerror}")
    if not rows:
        fail(f"--stage {stage}={path}: no rows; expected a Snakemake benchmark file (columns s, cpu_time, max_rss)")
    means = {}
    for column in ("s", "cpu_time", "max_rss"):
        try:
            values = [float(r[column]) for r in rows]
        except (KeyError, TypeError, ValueError):
            fail(f"--stage {stage}={path}: column {column} missing or not a number; expected a Snakemake benchmark file")
        means[column] = sum(values) / len(values)
    return means, len(rows)


def info(name, value, units):
    return {"name": name, "value": value, "units": units, "kind": "info", "reference": None, "source": "",
            "error": None, "tolerance": None, "pass": None}


def git_describe():
    try:
        here = os.path.dirname(os.path.abspath(__file__))
        out = subprocess.run(["git", "-C", here, "describe", "--always", "--dirty"], capture_output=True, text=True)
        return out.stdout.strip() or "unknown"
    except OSError:
        return "unknown"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--case", required=True, help="the case the stages ran on (config case)")
    p.add_argument("--threads", type=int, required=True, help="threads each stage was given (config threads)")
    p.add_argument("--stage", action="append", required=True, metavar="NAME=TSV",
                   help="a stage and its benchmark file, in pipeline order (repeat)")
    p.add_argument("--goal-minutes", type=float, help="grade the stages' total wall time against this many minutes")
    p.add_argument("--out", required=True, help="summary JSON to write")
    a = p.parse_args()
    if a.goal_minutes is not None and not a.goal_minutes > 0:
        fail(f"--goal-minutes {a.goal_minutes}: expected > 0")

    stages = []
    for spec in a.stage:
        name, sep, path = spec.partition("=")
        if not sep or not name or not path:
            fail(f"--stage {spec}: expected NAME=PATH")
        stages.append((name, path, *read_benchmark(name, path)))

    metrics = []
    for name, _, m, _ in stages:
        metrics.append(info(f"{name}_wall_s", m["s"], "s"))
        metrics.append(info(f"{name}_cpu_s", m["cpu_time"], "s"))
        metrics.append(info(f"{name}_max_rss_MB", m["max_rss"], "MB"))
    total = sum(m["s"] for _, _, m, _ in stages)
    slowest, _, slowest_m, _ = max(stages, key=lambda s: s[2]["s"])
    if a.goal_minutes is None:
        metrics.append(info("total_wall_s", total, "s"))
    else:
        goal = 60 * a.goal_minutes
        metrics.append({"name": "total_wall_s", "value": total, "units": "s", "kind": "max", "reference": None,
                        "source": "issue 50: the main job after the build on 2 cores", "error": total / goal,
                        "tolerance": goal, "pass": bool(total <= goal)})
    metrics.append(info("slowest_stage_wall_fraction", slowest_m["s"] / total if total > 0 else float("nan"), ""))

    write_summary(
        a.out, "bench", "pipeline",
        f"wall time per pipeline stage on case {a.case}, {a.threads} threads; slowest stage: {slowest}"
        " (cpu_s and max_rss_MB are Snakemake's samples, see tools/scripts/pipeline_bench.py)",
        [{**m, "value": None if m["value"] != m["value"] else m["value"]} for m in metrics],
        {"case": a.case, "threads": a.threads, "stages": [s[0] for s in stages],
         "slowest_stage": slowest, "benchmark_files": {s[0]: s[1] for s in stages},
         "benchmark_rows": {s[0]: s[3] for s in stages}},
        f"pipeline_bench.py finverse (git {git_describe()})", wall_s=total, threads=a.threads,
        passed=a.goal_minutes is None or total <= 60 * a.goal_minutes)
    print(f"slowest stage: {slowest} ({slowest_m['s']:.1f} s of {total:.1f} s)", file=sys.stderr)
    return 0 if a.goal_minutes is None or total <= 60 * a.goal_minutes else 1


if __name__ == "__main__":
    sys.exit(main())
