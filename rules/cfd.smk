# The flow solver in the workflow (DESIGN.md sections 5.1 and 6), run by fin-cfd: its validation
# cases, and the pipeline's loads stage (mesh.h5 + motion.h5 -> loads.h5).
#
#   snakemake -c2 results/validation/<case>/summary.json      <case>: a key of _CFD_CASES below
#   snakemake -c2 results/<case>/loads.h5                      the fin's loads (the default target's last stage)
#
# validation.coarse selects the CI variants (fin-cfd --coarse <case>: coarser grids, fewer steps).
# OpenMP threads wait passively, and the 2-D cases run on one thread each (THREADS_2D) so that
# snakemake runs them side by side: docs/studies/workflow_openmp_wait_policy.md.

THREADS_2D = 1

_CFD_REFERENCE = os.path.join(REPO, "data", "reference")
_CFD_CASE_FILES = os.path.join(REPO, "data", "cases", "cfd")
_FORCES = {"forces": "forces.csv"}

# case -> (description, reference file in data/reference or None, threads, mem_mb, outputs besides
#          summary.json). Every case runs from its case file, data/cases/cfd/<case>.yaml (grids,
#          times, flags and the coarse variant are there):
#   fin-cfd --threads T --out-dir results/validation [--coarse] run data/cases/cfd/<case>.yaml
# DFG 2-D: graded against 1 % of each bound interval's midpoint (Schaefer & Turek 1996) on the full
# grid; the coarse variant (12 cells per diameter, short runs) reports them as information only.
_CFD_CASES = {
    "taylor_green": ("2-D Taylor-Green vortex: observed order of accuracy in space and time",
                     None, THREADS_2D, 300, {}),
    "channel": ("inlet/outlet channel: developed Poiseuille profile and pressure gradient",
                None, THREADS_2D, 300,
                {"checkpoint": "checkpoint.h5", "pvd": "flow.pvd"}),
    "dfg_2d1": ("DFG 2D-1 (Re 20): CD, CL, dp of the ghost-cell immersed cylinder",
                "schaefer_turek.json", THREADS_2D, 500, _FORCES),
    "dfg_2d2": ("DFG 2D-2 (Re 100): CD_max, CL_max, St of the ghost-cell immersed cylinder",
                "schaefer_turek.json", THREADS_2D, 500, _FORCES),
    # Graded against John (2004) on 2D-2's default grid; the coarse variant runs the whole 8 s.
    "dfg_2d3": ("DFG 2D-3 (sine inflow, 8 s): CD_max, CL_max and their times against John (2004)",
                "schaefer_turek.json", THREADS_2D, 500, _FORCES),
    "turek_hron_cfd2": ("Turek-Hron CFD2 (Re 100, rigid flag): drag and lift of the ghost-cell immersed body",
                        "turek_hron.json", THREADS_2D, 500, _FORCES),
    "turek_hron_cfd3": ("Turek-Hron CFD3 (Re 200, rigid flag): drag/lift mean and amplitude, frequency",
                        "turek_hron.json", THREADS_2D, 500, _FORCES),
    "ib_couette": ("Couette flow between two immersed circles: observed L2 order of the velocity",
                   None, THREADS_2D, 300, {}),
    "cylinder_towed": ("towed cylinder vs fixed cylinder in a stream (Re 20): moving-body drag",
                       None, THREADS_2D, 300, _FORCES),
    "cylinder_oscillating": ("in-line oscillating cylinder (KC 5, Re 100): force spikes from cleared cells",
                             None, THREADS_2D, 300, _FORCES),
    "sphere_re100": ("sphere at Re 100 (3-D triangulated ghost-cell boundary): drag vs Johnson & Patel 1999",
                     "sphere.json", THREADS, 3000, _FORCES),
    # A user's own flow: the same sphere from an STL file (case: flow), reported beside sphere_re100.
    "sphere_re100_stl": ("sphere at Re 100 from an STL file (fin-cfd run, case: flow): drag, reported",
                         None, THREADS, 3000, _FORCES),
    "cylinder_channel_2d": ("the DFG 2D-1 geometry as a plane flow case (case: flow): drag and lift, reported",
                            None, THREADS_2D, 500, _FORCES),
    # Graded: cD within 2 % of 6.18533, run to steady state; grids and times in
    # docs/studies/cfd_run_cost.md.
    "dfg_3d1z": ("DFG 3D-1Z (Re 20, wall-to-wall cylinder, 3-D triangulated body crossing the walls): drag",
                 "schaefer_turek.json", THREADS, 3000, _FORCES),
    # Graded: C_T within 10 % of Garrick (1936) at the smallest amplitude; grid, Re and cost in
    # docs/studies/garrick_heaving_plate.md.
    "heaving_plate_garrick": ("thin plate heaving at k 2, Re 1000: mean thrust per amplitude vs Garrick's linear theory",
                              "garrick_heaving_plate.json", THREADS_2D, 500, _FORCES),
    # Graded: centreline speed and wall shear within 2 %, dp/dz within 3 % of Poiseuille flow, the
    # fluid inside the immersed wall (issue 49, goal 4); a ball in the same pipe as a user's case
    # file beside it, reported. Numbers in docs/studies/pipe_flow.md.
    "pipe_poiseuille": ("Poiseuille flow in a round pipe, fluid inside the immersed wall (Re 1283): profile, shear, dp/dz",
                        None, THREADS, 1000, {}),
    "pipe_flow": ("a ball in a round pipe as a user's case file (fluid: inside, pipe inlet): forces, reported",
                  None, THREADS, 1500, _FORCES),
    # Graded: the 3-D paths' mean C_T and C_L amplitude within 2 % of the 2-D solver's on the same
    # section, grid and step, closed body (slip-walled slab) and sheet (periodic slab, issue 44
    # goal 5); numbers in docs/studies/spanwise_plate_2d3d.md and thin_surface.md.
    "spanwise_plate_2d3d": ("heaving/pitching plate across a slab: 3-D closed body and sheet vs their 2-D sections",
                            None, THREADS_2D, 500, _FORCES),
    # Graded: C_D and C_L within 5 % of Dickson's measurements (issue 44, goal 3), the plate a
    # zero-thickness sheet of a user's case file; numbers in docs/studies/thin_surface.md.
    "plate_ar2_re100": ("flat plate AR 2 at 10 deg, Re 100, as a zero-thickness sheet (case: flow): C_D, C_L vs Dickson",
                        None, THREADS, 3000, _FORCES),
    # Graded: the sheet's towed and fixed force histories within 0.5 % (issue 44, goal 2); the
    # closed body beside it; numbers in docs/studies/thin_surface.md.
    "sheet_towed_plate": ("plate towed through still fluid vs fixed in a stream (Re 100): zero-thickness sheet and closed body",
                          None, THREADS_2D, 300, _FORCES),
    # Reported: a moving body as a user's case file (issue 44, deliverable 4); its mean C_x is
    # within 1 % of the same plate through fin-cfd fin --surface sheet (docs/studies/thin_surface.md).
    "heaving_pitching_plate": ("heaving/pitching plate as a sheet moved by its case file's motion: section (Re 100): C_T, reported",
                               None, THREADS, 1000, _FORCES),
}

for _case, (_description, _ref, _threads, _mem_mb, _outputs) in _CFD_CASES.items():
    register_validation(_case, _description)
    _reference = os.path.join(_CFD_REFERENCE, _ref) if _ref else None

    rule:
        name:
            f"validation_{_case}"
        input:
            exe=EXE("fin-cfd"),
            case=os.path.join(_CFD_CASE_FILES, _case + ".yaml"),
            **({"reference": _reference} if _reference else {}),
        output:
            summary=f"results/validation/{_case}/summary.json",
            **{key: f"results/validation/{_case}/{file}" for key, file in _outputs.items()},
        log:
            f"results/logs/validation/{_case}.log",
        threads: _threads
        resources:
            mem_mb=_mem_mb,
        params:
            coarse="--coarse" if COARSE else "",
        shell:
            "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} --out-dir results/validation {params.coarse}"
            " run {input.case} > {log} 2>&1 " + METRIC_MISSED_IS_A_RESULT


# The fin's loads path on a heaving and pitching rigid thin plate: fin-cfd thin_plate writes a
# mesh.h5 / motion.h5 pair, fin-cfd fin writes loads.h5 and checks that the nodal loads sum to the
# integrated surface force (within 0.5 %). Grids and times: docs/studies/cfd_run_cost.md. The full
# variant's plate is two cells thick with 100 outputs per period, so the summary also grades issue
# 30's smoothness goals over the last period (docs/studies/fin_load_noise.md).
register_validation("thin_plate_loads", "heaving/pitching thin plate through fin-cfd fin: nodal loads sum to the integrated force; smooth loads")

rule validation_thin_plate_loads:
    input:
        exe=EXE("fin-cfd"),
    output:
        summary="results/validation/thin_plate_loads/summary.json",
        mesh="results/validation/thin_plate_loads/mesh.h5",
        motion="results/validation/thin_plate_loads/motion.h5",
        loads="results/validation/thin_plate_loads/loads.h5",
    log:
        "results/logs/validation/thin_plate_loads.log",
    threads: THREADS
    resources:
        mem_mb=800,
    params:
        plate="--coarse" if COARSE else "",
        thickness=0.2 if COARSE else 0.1,
        flow=(
            "--reynolds 100 --speed 0.1 --periods 0.5 --output-periods 0 --cells-per-chord 12"
            " --upstream 1.5 --downstream 3 --lateral 1.5 --spanwise 1.5 --stretch-ratio 1.2"
            if COARSE
            else "--reynolds 100 --speed 0.1 --periods 2 --output-periods 1 --cells-per-chord 20 --output-interval 0.002"
        ),
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} {params.plate} thin_plate --thickness {params.thickness}"
        " --mesh {output.mesh} --motion {output.motion} > {log} 2>&1 &&"
        " OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} fin --mesh {output.mesh} --motion {output.motion}"
        " --out {output.loads} --summary {output.summary} {params.flow} >> {log} 2>&1 " + METRIC_MISSED_IS_A_RESULT


# The same plate as a zero-thickness sheet (fin-cfd fin --surface sheet; issue 44, goal 1): the raw
# force of the step on each output time, graded with the same smoothness metrics; the closed body's
# raw loads beside it in docs/studies/thin_surface.md.
register_validation("thin_plate_sheet", "heaving/pitching plate as a zero-thickness sheet through fin-cfd fin: raw per-step loads, smoothness")

rule validation_thin_plate_sheet:
    input:
        exe=EXE("fin-cfd"),
    output:
        summary="results/validation/thin_plate_sheet/summary.json",
        mesh="results/validation/thin_plate_sheet/mesh.h5",
        motion="results/validation/thin_plate_sheet/motion.h5",
        loads="results/validation/thin_plate_sheet/loads.h5",
    log:
        "results/logs/validation/thin_plate_sheet.log",
    threads: THREADS
    resources:
        mem_mb=800,
    params:
        plate="--coarse" if COARSE else "",
        flow=(
            "--reynolds 100 --speed 0.1 --periods 0.5 --output-periods 0 --cells-per-chord 12"
            " --upstream 1.5 --downstream 3 --lateral 1.5 --spanwise 1.5 --stretch-ratio 1.2"
            if COARSE
            else "--reynolds 100 --speed 0.1 --periods 2 --output-periods 1 --cells-per-chord 20 --output-interval 0.002"
        ),
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} {params.plate} thin_plate"
        " --mesh {output.mesh} --motion {output.motion} > {log} 2>&1 &&"
        " OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} fin --surface sheet --mesh {output.mesh}"
        " --motion {output.motion} --out {output.loads} --summary {output.summary} {params.flow} >> {log} 2>&1 "
        + METRIC_MISSED_IS_A_RESULT


# The pipeline's loads stage (DESIGN.md section 1) on the case's fin at its chord Reynolds number
# (U = Re nu / c, water), on fin-cfd fin's default grid plus config loads.flags; its cost:
# docs/studies/cfd_run_cost.md. A checkpoint every 100 steps: after an interruption rerun the
# command with --restart results/<case>/loads.checkpoint.h5 (the same loads.h5, bit for bit).
import math
import re

_CFD_CASE_OUT = f"results/{config['case']}"
_LOADS_FLAGS = f"--reynolds {config['fin']['reynolds']} --checkpoint-every 100"
if config["loads"]["flags"]:
    _LOADS_FLAGS += " " + config["loads"]["flags"]


def _loads_last_output():
    """Index of the loads run's last output when the motion is periodic (whole fin.periods), else
    None. fin-cfd fin counts outputs from the start in steps of T / ceil(T fps) (the largest
    interval up to a frame that divides T; cfd/io/fin_flow_case.cpp) over its --periods (2 unless
    loads.flags says), with T = A / (St U), U = Re nu / c (core/flow_scales.hpp, water)."""
    fin = config["fin"]
    if not float(fin["periods"]).is_integer():
        return None
    speed = fin["reynolds"] * 1.0e-6 / fin["chord_m"]
    period = fin["strouhal_excursion_over_chord"] * fin["chord_m"] / (fin["strouhal"] * speed)
    cfd_periods = ([2.0] + [float(p) for p in re.findall(r"--periods[ =](\S+)", _LOADS_FLAGS)])[-1]
    return round(cfd_periods * math.ceil(period * fin["fps"] - 1e-9))


# Fig. 17: one flow snapshot (velocity, pressure, vorticity, lambda_2) at the last output, beside
# loads.h5 as loads.flow.pvd + loads.flow/*.vtr (ParaView), drawn by the report
# (tools/scripts/report_figures.py). Only on a periodic record, where the last output is known here.
_LOADS_LAST = _loads_last_output()
_LOADS_SNAPSHOT = {"flow": f"{_CFD_CASE_OUT}/loads.flow.pvd"} if _LOADS_LAST else {}
if _LOADS_LAST:
    _LOADS_FLAGS += f" --snapshot-every {_LOADS_LAST}"

rule loads:
    input:
        exe=EXE("fin-cfd"),
        mesh=f"{_CFD_CASE_OUT}/mesh.h5",
        motion=f"{_CFD_CASE_OUT}/motion.h5",
    output:
        loads=f"{_CFD_CASE_OUT}/loads.h5",
        # The run's check: nodal loads against the integrated force, and issue 30's smoothness
        # goals over the last period (a missed goal is a result, not a failed stage).
        summary=f"{_CFD_CASE_OUT}/loads_summary.json",
        **_LOADS_SNAPSHOT,
    log:
        f"results/logs/{config['case']}/loads.log",
    benchmark:
        stage_benchmark("loads"),
    threads: THREADS
    resources:
        mem_mb=2500,
    params:
        flags=_LOADS_FLAGS,
        launch=mpi_launch,  # the pressure solve on MPI ranks where the profile says (fin-cfd fin)
    shell:
        stage_shell(
            "loads",
            "OMP_WAIT_POLICY=PASSIVE {params.launch} {input.exe} --threads {threads} fin --mesh {input.mesh} --motion {input.motion}"
            " --out {output.loads} --summary {output.summary} {params.flags} 2> {log} " + METRIC_MISSED_IS_A_RESULT,
        )

register_stage_output(f"{_CFD_CASE_OUT}/loads.h5")
