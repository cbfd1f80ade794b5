#!/usr/bin/env python3
"""results/bench/scaling.json from fin-poisson-ranks records and fin-cfd fin summaries (issue 48's
scaling benchmark: the pressure solve and the fin's flow step; docs/studies/flow_mpi.md).

    scaling_bench.py --record ranks1.json --record ranks2.json \
        --flow-record flow_sheet_threads1.json ... --out results/bench/scaling.json

Graded: the pressure solve, and the whole flow step of fin-cfd fin (the --flow-record summaries,
named flow_<closed|sheet>_<threads1|threads2|ranks1|ranks2>[_<repeat>].json; of a run repeated,
the fastest counts), on one rank against the
threaded solver on one thread (goal <= 1.1: the decomposition must not slow the single-rank
path). Reported: two ranks against two threads, halo and reduction bytes per iteration per rank,
a strong- and weak-scaling model of the pressure solve for 8-512 ranks from the measured cost
per cell-iteration and traffic, and a strong-scaling model of the whole flow step (today's
whole-flow ranks and the planned blocks) from the one-rank step's measured pressure share, with
their assumptions.
"""
import argparse
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from summary import load, write_summary  # noqa: E402

# Model assumptions (written into the file): one network, per message latency and bandwidth.
LATENCY_S = 2e-6
BANDWIDTH_BPS = 10e9


def fail(msg):
    print(f"scaling_bench.py: error: {msg}", file=sys.stderr)
    sys.exit(2)


def metric(name, value, units, kind, reference, source, tolerance=None, passed=None, error=None):
    return {"name": name, "value": value, "units": units, "kind": kind, "reference": reference, "source": source,
            "error": error, "tolerance": tolerance, "pass": passed}


def pencil_split(ny, nz, p):
    """The split BlockDecomposition picks: py x pz = p with the smallest largest-block perimeter."""
    best = None
    for py in range(p, 0, -1):
        if p % py:
            continue
        pz = p // py
        if ny // py < 2 or nz // pz < 2:
            continue
        by, bz = math.ceil(ny / py), math.ceil(nz / pz)
        per = (2 * bz if py > 1 else 0) + (2 * by if pz > 1 else 0)
        if best is None or per < best[0]:
            best = (per, py, pz, by, bz)
    return best


SERIAL_BELOW_CELLS = 1 << 15  # DistributedMultigrid's default threshold


def gathered_levels(t_cell_iter, cells, ny, nz, p, py, pz):
    """Seconds per iteration for the level gathered below the distributed ones and all under it."""
    level_cells, ly, lz = cells, ny, nz
    while ly // 2 // py >= 2 and lz // 2 // pz >= 2:
        level_cells //= 8
        ly //= 2
        lz //= 2
    move = 2 * 8 * level_cells / BANDWIDTH_BPS + 2 * math.log2(max(p, 2)) * LATENCY_S
    half = p // 2
    sub = pencil_split(ly, lz, half) if half >= 2 and level_cells > SERIAL_BELOW_CELLS else None
    if sub is None:
        return move + t_cell_iter * level_cells * 8 / 7
    _, spy, spz, _, _ = sub
    return move + t_cell_iter * level_cells * 8 / 7 / half + gathered_levels(t_cell_iter, level_cells, ly, lz, half, spy, spz)


def block_halo(nx, py, pz, by, bz):
    """One halo layer of a pencil block of by x bz lines: its cells, (nx + 2) per line of each cut
    side, and its messages."""
    face_cells = (nx + 2) * ((2 * bz if py > 1 else 0) + (2 * (by + 2) if pz > 1 else 0))
    return face_cells, (2 if py > 1 else 0) + (2 if pz > 1 else 0)


def model(t_cell_iter, nx, ny, nz, p, exchanges_per_iter, reductions_per_iter):
    """Seconds per MG-PCG iteration on p ranks: compute, halo, reductions, the gathered level."""
    split = pencil_split(ny, nz, p)
    if split is None:
        return None
    _, py, pz, by, bz = split
    cells = nx * ny * nz
    compute = t_cell_iter * cells / p
    # Halo: the fine level's faces, every level down adding about 1/4 more (3-D coarsening halves
    # both face directions), one layer per exchange.
    face_cells, messages = block_halo(nx, py, pz, by, bz)
    face_cells *= 4 / 3
    halo = exchanges_per_iter * (messages * LATENCY_S + 8 * face_cells / exchanges_per_iter * 2 / BANDWIDTH_BPS)
    # Reductions: an allgather of ny x nz line sums (recursive doubling).
    reductions = reductions_per_iter * (math.log2(p) * LATENCY_S + 8 * ny * nz / BANDWIDTH_BPS)
    # The gathered level: every level halved until a rank would hold fewer than 2 lines; it goes
    # through rank 0 to half the ranks when large (DistributedMultigrid's agglomeration), else it
    # is solved on rank 0.
    gathered = gathered_levels(t_cell_iter, cells, ny, nz, p, py, pz)
    return {"ranks": p, "split": [py, pz], "compute_s": compute, "halo_s": halo, "reductions_s": reductions,
            "gathered_s": gathered, "total_s": compute + halo + reductions + gathered}


# The explicit parts of a step on blocks (the planned blocks-only flow): one-layer exchanges per
# step of the face velocities and the pressure (predictor, projection, update; an assumption).
STEP_EXCHANGES = 8


def step_model(t_rest, t_pressure, pressure, nx, ny, nz, exchanges=STEP_EXCHANGES):
    """Seconds per flow step on p ranks from the measured one-rank costs per cell-step of the
    pressure solves (t_pressure) and of everything else (t_rest), and the pressure solve's model
    per iteration (model(), one entry per rank count, in `pressure`): today, every rank holds the
    whole flow and shares only the pressure; planned, the rest also runs on blocks."""
    cells = nx * ny * nz
    base = pressure[0]["total_s"]
    rows = []
    for m in pressure:
        p, (py, pz) = m["ranks"], m["split"]
        face_cells, messages = block_halo(nx, py, pz, math.ceil(ny / py), math.ceil(nz / pz))
        halo = exchanges * (messages * LATENCY_S + 8 * face_cells * 2 / BANDWIDTH_BPS)
        pressure_s = cells * t_pressure * m["total_s"] / base
        today = cells * t_rest + pressure_s
        blocks = cells * t_rest / p + halo + pressure_s
        rows.append({"ranks": p, "pressure_s": pressure_s, "today_s": today, "blocks_s": blocks,
                     "blocks_halo_s": halo})
    for r in rows:
        r["today_speedup"] = rows[0]["today_s"] / r["today_s"]
        r["blocks_speedup"] = rows[0]["blocks_s"] / r["blocks_s"]
        r["blocks_efficiency"] = r["blocks_speedup"] / r["ranks"]
    return rows


FLOW_RECORD = re.compile(r"flow_(closed|sheet)_(threads1|threads2|ranks1|ranks2)(_\d+)?\.json$")


def read_flow_records(paths):
    """({surface: {mode: seconds per cell-step}}, {surface: {mode: pressure solve share}}) from fin-cfd
    fin summaries, the fastest of a mode's repeats (a shared or noisy machine only ever slows a run
    down) and that run's share of its time in the pressure solves (None where not recorded)."""
    out, share = {}, {}
    for path in paths:
        m = FLOW_RECORD.search(path)
        if not m:
            fail(f"--flow-record {path}: expected a name flow_<closed|sheet>_<threads1|threads2|ranks1|ranks2>"
                 "[_<repeat>].json")
        values = {x["name"]: x["value"] for x in load(path)["metrics"]}
        try:
            cost = values["solver_seconds"] / (values["steps"] * values["cells"])
        except (KeyError, TypeError, ZeroDivisionError) as e:
            fail(f"--flow-record {path}: {e}; expected fin-cfd fin's summary with solver_seconds, steps and cells")
        modes = out.setdefault(m.group(1), {})
        if cost < modes.get(m.group(2), math.inf):
            modes[m.group(2)] = cost
            solve = values.get("pressure_solve_seconds")
            share.setdefault(m.group(1), {})[m.group(2)] = None if solve is None else solve / values["solver_seconds"]
    return out, share


def flow_metrics(flow):
    """The flow step's metrics: one rank over one thread graded (the larger of the surfaces)."""
    metrics, ratios = [], []
    for surface, c in sorted(flow.items()):
        for mode in ("threads1", "threads2", "ranks1", "ranks2"):
            if mode not in c:
                fail(f"--flow-record: no {mode} record for the {surface} surface")
        ratio = c["ranks1"] / c["threads1"]
        ratios.append((ratio, surface))
        metrics += [
            metric(f"flow_step_one_rank_over_threaded_{surface}", ratio, "", "info", None,
                   f"fin-cfd fin, tiny fin at c/20 as the {surface} surface: {c['ranks1']:.4g} s per cell-step on 1 "
                   f"rank (the ranks' path) vs {c['threads1']:.4g} s threaded on 1 thread, the fastest of each's runs"),
            metric(f"flow_step_two_ranks_over_two_threads_{surface}", c["ranks2"] / c["threads2"], "", "info", None,
                   f"{c['ranks2']:.4g} s per cell-step on 2 ranks vs {c['threads2']:.4g} s on 2 threads, the same cores"),
            metric(f"flow_step_two_ranks_speedup_{surface}", c["ranks1"] / c["ranks2"], "", "info", None,
                   "1 rank over 2 ranks (every rank holds the whole flow: the solves and the surface's set-up are "
                   "shared, the explicit kernels are not yet)"),
        ]
    worst, surface = max(ratios)
    metrics.insert(0, metric("flow_step_one_rank_over_threaded", worst, "", "max", None,
                             f"the larger of the surfaces' ratios ({surface}), cost per cell-step (goal <= 1.1)",
                             1.1, worst <= 1.1, worst))
    return metrics


def step_models(flow, flow_share, strong, nx, ny, nz, metrics):
    """The whole flow step's strong-scaling model per surface (step_model) from the fastest one-rank
    run's cost and pressure share; its 512-rank figures appended to metrics."""
    step = {}
    for surface, modes in sorted(flow.items()):
        share = flow_share.get(surface, {}).get("ranks1")
        if share is None:
            continue
        c = modes["ranks1"]
        rows = step_model(c * (1 - share), c * share, strong, nx, ny, nz)
        step[surface] = {"pressure_share_one_rank": share, "cost_per_cell_step_s": c, "strong": rows,
                         "notes": "today: every rank runs all but the pressure solve on the whole grid (Amdahl); "
                                  "blocks: the rest on blocks at the one-rank cost per cell, plus "
                                  f"{STEP_EXCHANGES} one-layer halo exchanges per step; the pressure as the "
                                  "per-iteration model, scaled by its measured one-rank share"}
        last = rows[-1]
        metrics += [
            metric(f"model_step_speedup_{last['ranks']}_ranks_today_{surface}", last["today_speedup"], "", "info", None,
                   f"modelled, {nx}x{ny}x{nz} cells: the whole flow on every rank, the pressure ({share:.0%} of a "
                   "one-rank step) shared (parameters.model.step)"),
            metric(f"model_step_efficiency_{last['ranks']}_ranks_blocks_{surface}", last["blocks_efficiency"], "", "info",
                   None, f"modelled, {nx}x{ny}x{nz} cells: the planned blocks-only flow (parameters.model.step)"),
        ]
    return step


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--record", action="append", required=True, help="a fin-poisson-ranks JSON (one per rank count)")
    ap.add_argument("--flow-record", action="append", default=[],
                    help="a fin-cfd fin summary named flow_<surface>_<mode>.json (the flow step's runs)")
    ap.add_argument("--model-grid", default="320,160,164", help="nx,ny,nz of the modelled grid (paper.yaml's c/40: 8.4 M cells)")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    recs = {}
    for path in a.record:
        try:
            with open(path) as f:
                r = json.load(f)
            recs[int(r["ranks"])] = r
        except (OSError, ValueError, KeyError) as e:
            fail(f"--record {path}: {e}; expected fin-poisson-ranks' JSON")
    if 1 not in recs:
        fail("--record: expected the 1-rank record")
    one = recs[1]
    ratio = one["ranks_run"]["solve_s"] / one["threaded"]["solve_s"]
    iters = max(1, one["ranks_run"]["iterations"])
    t_cell_iter = one["ranks_run"]["solve_s"] / (one["cells"] * iters)
    metrics = [
        metric("pressure_solve_one_rank_over_threaded", ratio, "", "max", None,
               f"MG-PCG solve, {one['cells']} cells: {one['ranks_run']['solve_s']:.4g} s on 1 rank vs "
               f"{one['threaded']['solve_s']:.4g} s threaded on 1 thread (goal <= 1.1)", 1.1, ratio <= 1.1, ratio),
        metric("pressure_solution_difference_relative", one["solution_max_difference_relative"], "", "info", None,
               "1 rank vs threaded, max |dp| / max |p| (all-Neumann: the singular projections sum by lines)"),
    ]
    flow, flow_share = read_flow_records(a.flow_record) if a.flow_record else ({}, {})
    metrics += flow_metrics(flow) if a.flow_record else [
        metric("flow_step_one_rank_over_threaded", None, "", "max", None, "not measured: no --flow-record given",
               1.1, None)]
    # Traffic counts from the most ranks measured (one rank skips its exchanges: nothing to send).
    most = recs[max(recs)]
    most_iters = max(1, most["ranks_run"]["iterations"])
    exchanges_per_iter = most["ranks_run"]["exchanges_per_solve"] / most_iters
    reductions_per_iter = most["ranks_run"]["reductions_per_solve"] / most_iters
    if 2 in recs:
        two = recs[2]
        it2 = max(1, two["ranks_run"]["iterations"])
        metrics += [
            metric("pressure_solve_two_ranks_over_two_threads", two["ranks_run"]["solve_s"] / two["threaded"]["solve_s"], "",
                   "info", None, f"{two['ranks_run']['solve_s']:.4g} s on 2 ranks vs {two['threaded']['solve_s']:.4g} s on 2 "
                   "threads, the same cores"),
            metric("pressure_solve_two_ranks_speedup", one["ranks_run"]["solve_s"] / two["ranks_run"]["solve_s"], "", "info",
                   None, "1 rank over 2 ranks"),
            metric("halo_bytes_per_iteration_per_rank", 8 * two["ranks_run"]["halo_doubles_per_solve_max_rank"] / it2, "B",
                   "info", None, f"2 ranks, split {two['split']['py']} x {two['split']['pz']}, every level, largest rank"),
            metric("reduction_bytes_per_iteration", 8 * two["lines"] * two["ranks_run"]["reductions_per_solve"] / it2, "B",
                   "info", None, "line sums gathered per reduction (ny x nz doubles), every reduction of an iteration"),
        ]
    nx, ny, nz = (int(v) for v in a.model_grid.split(","))
    strong = [m for m in (model(t_cell_iter, nx, ny, nz, p, exchanges_per_iter, reductions_per_iter)
                          for p in (1, 8, 16, 32, 64, 128, 256, 512)) if m]
    base = strong[0]["total_s"]
    for m in strong:
        m["speedup"] = base / m["total_s"]
        m["efficiency"] = m["speedup"] / m["ranks"]
    per_rank = one["cells"]
    weak = []
    for p in (1, 8, 64, 512):
        s = round((per_rank * p) ** (1 / 3))
        m = model(t_cell_iter, s, s, s, p, exchanges_per_iter, reductions_per_iter)
        if m:
            m["cells"] = s ** 3
            weak.append(m)
    for m in weak:
        m["efficiency"] = weak[0]["total_s"] / m["total_s"]
    eff512 = next((m["efficiency"] for m in strong if m["ranks"] == 512), None)
    metrics.append(metric("model_strong_efficiency_512_ranks", eff512, "", "info", None,
                          f"modelled, {nx}x{ny}x{nz} cells, per MG-PCG iteration (parameters.model)"))
    step = step_models(flow, flow_share, strong, nx, ny, nz, metrics)
    params = {"records": {str(k): v for k, v in sorted(recs.items())},
              "model": {"assumptions": {"latency_s": LATENCY_S, "bandwidth_B_per_s": BANDWIDTH_BPS,
                                        "cost_per_cell_iteration_s": t_cell_iter,
                                        "exchanges_per_iteration": exchanges_per_iter,
                                        "reductions_per_iteration": reductions_per_iter,
                                        "notes": "compute scales as cells per rank at the 1-rank cost; halo as the largest "
                                                 "block's faces over all levels (x 4/3); reductions allgather ny x nz line "
                                                 "sums; the gathered level (every level halved until a rank would hold fewer "
                                                 "than 2 lines) is solved on rank 0 at the 1-rank cost"},
                        "grid": [nx, ny, nz], "strong": strong, "weak": weak, "step": step}}
    write_summary(a.out, "bench", "scaling", "the pressure solve and the flow step on MPI ranks against the threaded "
                  "solver; scaling model", metrics, params, "scaling_bench.py finverse", threads=2,
                  inputs=a.record + a.flow_record)


if __name__ == "__main__":
    main()
