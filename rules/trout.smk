# The virtual trout as a whole (issue 33): its scores as a validation case, and the check that the
# default case's size still gives meaningful numbers.
#
#   snakemake -c2 results/validation/trout/summary.json               the scores of results/<case>/report
#   snakemake -c2 results/validation/default_case_grid/summary.json   the case against a finer grid (heavy)
#
# trout reads what fin-report graded (results/<case>/report/summary.json); the tiny case grades
# its own coarse pipeline. default_case_grid reruns the loads and the fit of the case on a finer
# near-fin grid (same mesh, motion, body thickness and fit settings) and grades the mean C_T, the
# C_T peak and every fitted modulus within 5 % of that run: docs/studies/default_case.md.
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


# The finer grid: the case's loads flags with the near-fin cell width c / 20 (the case's own:
# config loads.flags --cells-per-chord), the body as thick as in the case's mesh.h5.
_GRID = "results/validation/default_case_grid"
_GRID_CELLS_PER_CHORD = 20
_GRID_LOADS_FLAGS = (
    f"--reynolds {config['fin']['reynolds']} --checkpoint-every 100 "
    + re.sub(r"--cells-per-chord[ =]\S+", "", config["loads"]["flags"])
    + f" --cells-per-chord {_GRID_CELLS_PER_CHORD}"
)
_GRID_FSI = f"{_TROUT}/fsi.h5" if f"{_TROUT}/fsi.h5" in STAGE_OUTPUTS else None

if not COARSE:
    register_validation("default_case_grid", f"the case's mean C_T, C_T peak and fitted moduli within 5 % of the "
                        f"same pipeline with c/{_GRID_CELLS_PER_CHORD} near the fin")

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
        flags=_GRID_LOADS_FLAGS,
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


rule validation_default_case_grid:
    input:
        loads=f"{_TROUT}/loads.h5",
        materials=f"{_TROUT}/materials.h5",
        fine_loads=f"{_GRID}/loads.h5",
        fine_materials=f"{_GRID}/materials.h5",
        script=os.path.join(SCRIPTS, "case_grid_compare.py"),
        **({"fsi": _GRID_FSI} if _GRID_FSI else {}),
    output:
        f"{_GRID}/summary.json",
    log:
        "results/logs/validation/default_case_grid.log",
    threads: 1
    params:
        fsi=lambda wildcards, input: f"--fsi {input.fsi}" if "fsi" in input.keys() else "",
    shell:
        "/usr/bin/python3 {input.script} --name default_case_grid --loads {input.loads} --materials {input.materials}"
        " --fine-loads {input.fine_loads} --fine-materials {input.fine_materials} {params.fsi} --tolerance 0.05"
        " --out {output} 2> {log} " + METRIC_MISSED_IS_A_RESULT
