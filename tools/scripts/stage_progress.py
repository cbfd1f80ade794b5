#!/usr/bin/python3
"""One progress line per finished pipeline stage, with the pipeline's ETA (issue 50, "Also").

Snakemake's own lines say which job finished, not how long the main command still has to run.
Each stage rule of the pipeline ends its shell command with this script (rules/common.smk,
stage_shell), which
  1. records the stage's wall time in results/<case>/benchmarks/stage_times.json (kept across
     runs, so the next run's estimate is this run's measurement);
  2. prints to the terminal, e.g.
       finverse: stage 4/8 mesh done in 12 s; 31 min so far, about 52 min left (loads, fit, fsi, report)

The stages run one after the other (each needs the one before), so the stages left are the ones
after this one. Their cost is the last measured time of each (stage_times.json), else the case's
expected minutes (config progress.expected_minutes, measured on 2 cores), scaled by how this run's
finished stages compared with their own estimates (a slower or shared machine).
"""
import argparse
import json
import os
import sys
import tempfile
import time


def minutes_text(seconds):
    if seconds < 60:
        return f"{seconds:.0f} s"
    if seconds < 3600:
        return f"{seconds / 60:.0f} min"
    return f"{int(seconds // 3600)} h {round((seconds % 3600) / 60):02d} min"


def read_times(path):
    if not os.path.exists(path):
        return {"runs": {}, "run_start": None, "this_run": {}}
    with open(path) as f:
        data = json.load(f)
    for key, empty in (("runs", {}), ("this_run", {})):
        data.setdefault(key, empty)
    data.setdefault("run_start", None)
    return data


def write_atomic(path, data):
    folder = os.path.dirname(path) or "."
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".stage_times.")
    with os.fdopen(fd, "w") as f:
        json.dump(data, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, path)


def parse_expected(text):
    expected = {}
    for item in filter(None, text.split(",")):
        name, _, minutes = item.partition("=")
        try:
            expected[name] = 60.0 * float(minutes)
        except ValueError:
            sys.exit(f"stage_progress: --expected: '{item}' is not stage=minutes")
    return expected


def estimate(stage, data, expected):
    """The stage's cost before this run: its last measured wall time, else the configured one."""
    return data["runs"].get(stage, expected.get(stage))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--times", required=True, help="stage_times.json of the case (created if missing)")
    p.add_argument("--stage", help="the stage that finished")
    p.add_argument("--order", default="", help="the pipeline's stages in run order, comma-separated")
    p.add_argument("--expected", default="", help="stage=minutes,... (config progress.expected_minutes)")
    p.add_argument("--start", type=float, help="the stage's start (seconds since the epoch); omit with --begin")
    p.add_argument("--begin", action="store_true", help="a new pipeline run starts (Snakefile onstart)")
    a = p.parse_args()

    order = [s for s in a.order.split(",") if s]
    data = read_times(a.times)
    now = time.time()
    if a.begin:
        data["run_start"], data["this_run"] = now, {}
        write_atomic(a.times, data)
        return
    if a.stage not in order:
        sys.exit(f"stage_progress: --stage {a.stage}: not one of --order {','.join(order)}")
    if a.start is None:
        sys.exit("stage_progress: --start: expected the stage's start time")
    expected = parse_expected(a.expected)

    wall = max(now - a.start, 0.0)
    estimated = estimate(a.stage, data, expected)
    data["this_run"][a.stage] = {"wall_s": wall, "estimate_s": estimated}
    data["runs"][a.stage] = wall
    if data["run_start"] is None or data["run_start"] > a.start:
        data["run_start"] = a.start
    write_atomic(a.times, data)

    # This run's pace against the estimates of the stages it finished (clamped: one odd stage
    # must not swing the ETA by more than 4x either way).
    done = [v for v in data["this_run"].values() if v.get("estimate_s")]
    pace = sum(v["wall_s"] for v in done) / sum(v["estimate_s"] for v in done) if done else 1.0
    pace = min(max(pace, 0.25), 4.0)
    left = order[order.index(a.stage) + 1:]
    unknown = [s for s in left if estimate(s, data, expected) is None]
    remaining = pace * sum(estimate(s, data, expected) or 0.0 for s in left)

    line = f"finverse: stage {order.index(a.stage) + 1}/{len(order)} {a.stage} done in {minutes_text(wall)}"
    line += f"; {minutes_text(now - data['run_start'])} so far"
    if left:
        line += f", about {minutes_text(remaining)} left ({', '.join(left)})"
        if unknown:
            line += f"; no estimate for {', '.join(unknown)}"
    else:
        line += "; the pipeline is done"
    print(line, file=sys.stderr, flush=True)


if __name__ == "__main__":
    main()
