# The virtual trout as a whole (issue 33): its scores as a validation case, and the check that the
# default case's size still gives meaningful numbers.
#
#   snakemake -c2 results/validation/trout/summary.json               the scores of results/<case>/report
#   snakemake -c2 results/validation/default_case_grid/summary.json   the case against a finer grid (heavy)
#
# trout reads what fin-report graded (results/<case>/report/summary.json); the tiny case grades
# its own coarse pipeline. default_case_grid reruns the loads, the fit and the fsi stage of the case
# at twice its near-fin resolution (same mesh, motion, bodies and fit settings) and grades the mean
# C_T, the C_T peak and every fitted modulus within 5 % of that run: docs/studies/default_case.md.
# It costs about twice the case's own pipeline, so it is not in the coarse (CI) set of cases.

import re

_TROUT = f"results/{config['case']}"

register_validation("trout", "the virtual trout's scores of issue 33 (from fin-report): moduli vs truth, "
                    "FSI vs reconstruction, FSI vs truth")

rule validation_trout:
    input:
        report=f"{_TROUT}/report/summary.json",
        script=os.path.join(SCRIPTS, "trout_scores.py"),
    output:
        "results/validation/trout/summary.json",
    log:
        "results/logs/validation/trout.log",
    threads: 1
    shell:
        "/usr/bin/python3 {input.script} --report {input.report} --out {output} 2> {log} " + METRIC_MISSED_IS_A_RESULT


# The finer grid: twice the case's resolution near the fin in the loads and the fsi stage, the same
# bodies (mesh.h5's closed body; the fsi stage's body kept as thick in chords: twice its cells).
def _cells_per_chord(flags, default):
    found = re.findall(r"--cells-per-chord[ =](\S+)", flags)
    return float(found[-1]) if found else default


def _twice_as_fine(flags, default_cells, thickness_flag=None):
    n = _cells_per_chord(flags, default_cells)
    if n is None:
        return None
    out = re.sub(r"--cells-per-chord[ =]\S+", "", flags) + f" --cells-per-chord {2 * n:g}"
    if thickness_flag:
        k = ([2.0] + [float(v) for v in re.findall(r"--thickness-cells[ =](\S+)", flags)])[-1]
        out = re.sub(r"--thickness-cells[ =]\S+", "", out) + f" --thickness-cells {2 * k:g}"
    return out


_GRID = "results/validation/default_case_grid"
# fin-fsi fin's default cell width without --cells-per-chord: c/16 (fin_fsi_run.cpp).
# fin-cfd fin's cell width without --cells-per-chord follows mesh.h5's body, which is not known here.
_GRID_LOADS_FINE = _twice_as_fine(config["loads"]["flags"], None)


def _grid_loads_flags(wildcards):
    if _GRID_LOADS_FINE is None:
        raise ValueError("config loads.flags: default_case_grid needs the loads' --cells-per-chord to double it")
    return f"--reynolds {config['fin']['reynolds']} --checkpoint-every 100 {_GRID_LOADS_FINE}"


_GRID_FSI_FLAGS = _twice_as_fine(config["fsi"]["flags"], 16, thickness_flag=True)
_GRID_FSI = f"{_TROUT}/fsi.h5" if f"{_TROUT}/fsi.h5" in STAGE_OUTPUTS else None

if not COARSE:
    register_validation("default_case_grid", "the case's mean C_T, C_T peak (loads and FSI) and fitted moduli "
                        "within 5 % of the same pipeline at twice the resolution near the fin")

rule default_case_grid_loads:
    input:
        exe=EXE("fin-cfd"),
        mesh=f"{_TROUT}/mesh.h5",
        motion=f"{_TROUT}/motion.h5",
    output:
        loads=f"{_GRID}/loads.h5",
        summary=f"{_GRID}/loads_summary.json",
    log:
        "results/logs/validation/default_case_grid_loads.log",
    threads: THREADS
    resources:
        mem_mb=4000,
    params:
        flags=_grid_loads_flags,
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} fin --mesh {input.mesh} --motion {input.motion}"
        " --out {output.loads} --summary {output.summary} {params.flags} 2> {log} " + METRIC_MISSED_IS_A_RESULT


rule default_case_grid_fit:
    input:
        exe=EXE("fin-fit"),
        mesh=f"{_TROUT}/mesh.h5",
        motion=f"{_TROUT}/motion.h5",
        loads=f"{_GRID}/loads.h5",
        materials=os.path.join(REPO, config["fit"]["materials"]),
    output:
        materials=f"{_GRID}/materials.h5",
        summary=f"{_GRID}/fit_summary.json",
    log:
        "results/logs/validation/default_case_grid_fit.log",
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        flags=f"--seed {config['seed']} " + config["fit"]["flags"],
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} run --mesh {input.mesh} --motion {input.motion}"
        " --loads {input.loads} --materials {input.materials} --out {output.materials}"
        " --summary {output.summary} {params.flags} 2> {log}"


# The fsi stage on the finer grid with the finer pipeline's fit.
rule default_case_grid_fsi:
    input:
        exe=EXE("fin-fsi"),
        mesh=f"{_TROUT}/mesh.h5",
        motion=f"{_TROUT}/motion.h5",
        materials=f"{_GRID}/materials.h5",
        base=os.path.join(REPO, config["fit"]["materials"]),
    output:
        fsi=f"{_GRID}/fsi.h5",
        summary=f"{_GRID}/fsi_summary.json",
    log:
        "results/logs/validation/default_case_grid_fsi.log",
    threads: THREADS
    resources:
        mem_mb=4000,
    params:
        flags=_GRID_FSI_FLAGS,
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} fin --mesh {input.mesh} --motion {input.motion}"
        " --materials {input.materials} --base-materials {input.base} --out {output.fsi}"
        " --summary {output.summary} --checkpoint-every 50 {params.flags} 2> {log}"


rule validation_default_case_grid:
    input:
        loads=f"{_TROUT}/loads.h5",
        materials=f"{_TROUT}/materials.h5",
        fine_loads=f"{_GRID}/loads.h5",
        fine_materials=f"{_GRID}/materials.h5",
        script=os.path.join(SCRIPTS, "case_grid_compare.py"),
        **({"fsi": _GRID_FSI, "fine_fsi": f"{_GRID}/fsi.h5"} if _GRID_FSI else {}),
    output:
        f"{_GRID}/summary.json",
    log:
        "results/logs/validation/default_case_grid.log",
    threads: 1
    params:
        fsi=lambda wildcards, input: f"--fsi {input.fsi} --fine-fsi {input.fine_fsi}" if "fsi" in input.keys() else "",
    shell:
        "/usr/bin/python3 {input.script} --name default_case_grid --loads {input.loads} --materials {input.materials}"
        " --fine-loads {input.fine_loads} --fine-materials {input.fine_materials} {params.fsi} --tolerance 0.05"
        " --out {output} 2> {log} " + METRIC_MISSED_IS_A_RESULT


# The stages agree (issue 50, "Also"): fin-cfd fin with the loads stage's own mesh flags and flags,
# on the truth's own motion (truth.h5's surface carried onto the case's mesh), against the force the
# truth's FSI felt. Only with an FSI truth (the prescribed kinematics felt no force).
_AGREE = "results/validation/stage_agreement"

if _TRUTH_FSI:
    register_validation("stage_agreement", "fin-cfd fin on the truth's own motion against the truth's FSI force: "
                        "mean C_T and C_L amplitude within 5 %")


rule stage_agreement_motion:
    input:
        exe=EXE("fin-mesh"),
        truth=f"{_TROUT}/truth.h5",
    output:
        mesh=f"{_AGREE}/mesh.h5",
        motion=f"{_AGREE}/motion.h5",
    log:
        "results/logs/validation/stage_agreement_motion.log",
    threads: 1
    params:
        flags=_TEMPLATE_FLAGS + (" " + config["mesh"]["flags"] if config["mesh"]["flags"] else ""),
    shell:
        "{input.exe} {params.flags} --mesh {output.mesh} --motion-source {input.truth} --motion {output.motion}"
        " --threads {threads} 2> {log}"


rule stage_agreement_loads:
    input:
        exe=EXE("fin-cfd"),
        mesh=f"{_AGREE}/mesh.h5",
        motion=f"{_AGREE}/motion.h5",
    output:
        loads=f"{_AGREE}/loads.h5",
        summary=f"{_AGREE}/loads_summary.json",
    log:
        "results/logs/validation/stage_agreement_loads.log",
    threads: THREADS
    resources:
        mem_mb=2500,
    params:
        flags=f"--reynolds {config['fin']['reynolds']} {config['loads']['flags']}",
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} fin --mesh {input.mesh} --motion {input.motion}"
        " --out {output.loads} --summary {output.summary} {params.flags} 2> {log} " + METRIC_MISSED_IS_A_RESULT


rule validation_stage_agreement:
    input:
        truth=f"{_TROUT}/truth/fsi.h5",
        loads=f"{_AGREE}/loads.h5",
        script=os.path.join(SCRIPTS, "stage_agreement.py"),
    output:
        f"{_AGREE}/summary.json",
    log:
        "results/logs/validation/stage_agreement.log",
    threads: 1
    shell:
        "/usr/bin/python3 {input.script} --truth {input.truth} --loads {input.loads} --tolerance 0.05 --out {output}"
        " 2> {log} " + METRIC_MISSED_IS_A_RESULT
