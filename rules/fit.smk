# The inverse fit (DESIGN.md section 5.4, issue 31): fin-fit finds the membrane's and every ray's
# Young's modulus and one Poisson ratio for which the FEM under the fin's loads reproduces the
# reconstructed motion; and the fit's validation cases.
#
#   snakemake -c2                                     the pipeline, the fit its last stage
#   snakemake -c2 -R fit                              rerun the fit alone
#   snakemake -c2 results/validation/fit_hybrid_plate/summary.json
#
# The fit's own check (parameters the data cannot constrain) is in materials.h5
# (uncertainty/identified, verdict) and in fit_summary.json, and is warned about in the log.

_FIT = config["fit"]
_FIT_OUT = f"results/{config['case']}"


rule fit:
    input:
        exe=EXE("fin-fit"),
        mesh=f"{_FIT_OUT}/mesh.h5",
        motion=f"{_FIT_OUT}/motion.h5",
        loads=f"{_FIT_OUT}/loads.h5",
        materials=os.path.join(REPO, _FIT["materials"]),
    output:
        materials=f"{_FIT_OUT}/materials.h5",
        summary=f"{_FIT_OUT}/fit_summary.json",
    log:
        f"results/logs/{config['case']}/fit.log",
    benchmark:
        stage_benchmark("fit"),
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        flags=f"--seed {config['seed']} " + _FIT["flags"],
    shell:
        stage_shell(
            "fit",
            "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} run --mesh {input.mesh} --motion {input.motion}"
            " --loads {input.loads} --materials {input.materials} --out {output.materials}"
            " --summary {output.summary} {params.flags} 2> {log}",
        )


# The 22-parameter fin twin (issue 31, validation 4; seed paper sec. 4.3): truth = fin-fem's
# quasi-static response of the case's mesh with the known modulus field of trout_fin_materials.json
# under the case's loads.h5 and motion.h5's root drive; fin-fit run fits all 22 parameters by
# eq. (2) to that response; fin-fit grade_twin compares them with the field.
_TWIN = "results/validation/fit_trout_twin"
_TWIN_TRUTH = os.path.join(REPO, "data", "cases", "trout_fin_materials.json")
_TWIN_FLAGS = (
    "--objective quasi_static --instant-count 1 --runs 1 --population 2 --generations 1 --polish-evaluations 24"
    if COARSE
    else "--objective quasi_static --instant-count 4 --runs 1 --population 44 --generations 8 --polish-evaluations 400"
)
register_validation("fit_trout_twin", "22-parameter trout fin twin by eq. (2): median ray error <= 5 %, each "
                    "identified ray <= 15 %, membrane <= 10 %")


rule fit_trout_twin_truth:
    input:
        exe=EXE("fin-fem"),
        mesh=f"{_FIT_OUT}/mesh.h5",
        motion=f"{_FIT_OUT}/motion.h5",
        loads=f"{_FIT_OUT}/loads.h5",
        materials=_TWIN_TRUTH,
    output:
        f"{_TWIN}/twin_motion.h5",
    log:
        "results/logs/validation/fit_trout_twin_truth.log",
    threads: THREADS
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} run --analysis quasi_static --mesh {input.mesh}"
        " --materials {input.materials} --loads {input.loads} --motion {input.motion} --out {output} 2> {log}"


rule fit_trout_twin_fit:
    input:
        exe=EXE("fin-fit"),
        mesh=f"{_FIT_OUT}/mesh.h5",
        motion=f"{_TWIN}/twin_motion.h5",
        loads=f"{_FIT_OUT}/loads.h5",
        materials=_TWIN_TRUTH,
    output:
        materials=f"{_TWIN}/materials.h5",
        summary=f"{_TWIN}/fit_summary.json",
    log:
        "results/logs/validation/fit_trout_twin_fit.log",
    threads: THREADS
    params:
        flags=f"--seed {config['seed']} " + _TWIN_FLAGS,
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} run --mesh {input.mesh} --motion {input.motion}"
        " --loads {input.loads} --materials {input.materials} --out {output.materials}"
        " --summary {output.summary} {params.flags} 2> {log}"


rule validation_fit_trout_twin:
    input:
        exe=EXE("fin-fit"),
        materials=f"{_TWIN}/materials.h5",
        truth=_TWIN_TRUTH,
    output:
        f"{_TWIN}/summary.json",
    log:
        "results/logs/validation/fit_trout_twin.log",
    shell:
        "{input.exe} grade_twin --materials-h5 {input.materials} --truth {input.truth} --out-dir results/validation"
        " 2> {log} " + METRIC_MISSED_IS_A_RESULT


# The same twin fitted through tracking noise (issue 45, goal 6): the twin's target with
# fin-track's mean vertex error (0.3 % c) as independent Gaussian noise, target and drive alike,
# one fit per seed (fin-fit run --target-noise); fin-fit grade_twin_noise grades the intervals'
# coverage, the rays identified and the median ray error over the seeds.
_TWIN_NOISE = "results/validation/fit_trout_noise"
_TWIN_NOISE_SEEDS = range(2 if COARSE else 10)
register_validation("fit_trout_noise", "22-parameter trout fin twin through fin-track's noise, 10 seeds: 95 % "
                    "interval coverage >= 80 %, rays identified >= 80 %, median ray error <= 5 %")


rule fit_trout_noise_fit:
    input:
        exe=EXE("fin-fit"),
        mesh=f"{_FIT_OUT}/mesh.h5",
        motion=f"{_TWIN}/twin_motion.h5",
        loads=f"{_FIT_OUT}/loads.h5",
        materials=_TWIN_TRUTH,
    output:
        f"{_TWIN_NOISE}/seed{{seed}}/materials.h5",
    log:
        "results/logs/validation/fit_trout_noise_seed{seed}.log",
    wildcard_constraints:
        seed=r"\d+",
    threads: THREADS
    params:
        # Stress-free bases: a carried base turns the noise into stress (docs/studies/fit_noise_twin.md).
        flags=f"--seed {config['seed']} " + _TWIN_FLAGS + " --target-noise 0.003 --base stress_free --increment hybrid",
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} run --mesh {input.mesh} --motion {input.motion}"
        " --loads {input.loads} --materials {input.materials} --out {output} {params.flags}"
        " --target-noise-seed $((1000 + {wildcards.seed})) 2> {log}"


rule validation_fit_trout_noise:
    input:
        exe=EXE("fin-fit"),
        materials=expand(f"{_TWIN_NOISE}/seed{{seed}}/materials.h5", seed=_TWIN_NOISE_SEEDS),
        truth=_TWIN_TRUTH,
    output:
        f"{_TWIN_NOISE}/summary.json",
    log:
        "results/logs/validation/fit_trout_noise.log",
    shell:
        "{input.exe} grade_twin_noise --materials-h5 {input.materials} --truth {input.truth}"
        " --out-dir results/validation 2> {log} " + METRIC_MISSED_IS_A_RESULT


# The fit is the pipeline's last stage (after loads): `snakemake -c2` writes materials.h5. Its
# budget (config fit.flags) keeps it to minutes: a short GA for the basin, the Levenberg-Marquardt
# polish for the digits and the Jacobian that the uncertainty comes from. Its bases are stress-free
# (--base stress_free): the synthetic reconstruction stretches the membrane up to 60 % between the
# fanning rays, a stress the FEM would carry from the flat mesh and fail on (Newton stalls at
# round-off under it, measured on the tiny case); the twin below carries it, as its truth does.
register_stage_output(f"{_FIT_OUT}/materials.h5")

# Validation cases of the fit (tools/fit/validation): case -> (description, flags of the full
# case, flags of the coarse one).
# The hybrid plate with the small heave (A = 0.001 c): the loads of the rigid heave then dominate the
# plate's inertia without folding its soft middle (tools/fit/validation/hybrid_plate_fit.hpp).
_HYBRID_PLATE = os.path.join(REPO, "data", "cases", "hybrid_plate_small_heave.json")
_FIT_CASES = {
    "fit_uniform_plate": (
        "sec. 3.3 flexible pitching plate twin: E within 0.5 %, nu within 5 % by eq. (1)",
        "uniform_plate --runs 1 --population 16 --generations 15",
        # The default 8 x 4 grid even when coarse: on 6 x 3 the truth's Newton stalls at t = 1.8 T.
        "uniform_plate --runs 1 --population 6 --generations 2",
    ),
    "fit_hybrid_plate": (
        "hybrid plate twin: E_s, E_b1..3, nu by eq. (1) within 1 % and eq. (2) within 5 %, eq. (2) >= 25x faster",
        "hybrid_plate --case " + _HYBRID_PLATE + " --runs 1 --population 20 --generations 15 --polish-evaluations 150",
        "hybrid_plate --case " + _HYBRID_PLATE + " --nx 4 --nz 4 --runs 1 --population 10 --generations 3",
    ),
    "fit_noise": (
        "hybrid plate twin, target with fin-track's noise: errors and 95 % interval coverage over 10 seeds",
        "noise --case " + _HYBRID_PLATE + " --runs 1 --population 20 --generations 15 --polish-evaluations 150 --noise-seeds 10",
        "noise --case " + _HYBRID_PLATE + " --nx 4 --nz 4 --runs 1 --population 10 --generations 2 --noise-seeds 2",
    ),
    "fit_identifiability": (
        "eq. (2) without loads: the modulus scale reported not identified",
        "identifiability --case " + _HYBRID_PLATE + " --runs 1 --population 20 --generations 15",
        "identifiability --case " + _HYBRID_PLATE + " --nx 4 --nz 4 --runs 1 --population 10 --generations 3",
    ),
}
for _case, (_description, _full, _coarse) in _FIT_CASES.items():
    register_validation(_case, _description)


rule validation_fit:
    input:
        exe=EXE("fin-fit"),
        case=_HYBRID_PLATE,
    output:
        "results/validation/{case}/summary.json",
    wildcard_constraints:
        case="|".join(_FIT_CASES),
    log:
        "results/logs/validation/{case}.log",
    threads: THREADS
    params:
        flags=lambda wildcards: _FIT_CASES[wildcards.case][2 if COARSE else 1],
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} {params.flags} --out-dir results/validation"
        " 2> {log} " + METRIC_MISSED_IS_A_RESULT


# Issue 45, goal 9: a truth from another structural code. CalculiX (ccx, a peer: tools/scripts/
# install-deps.sh --peers) solves the hybrid plate (data/cases/hybrid_plate.json) static and
# geometrically nonlinear at four load levels on a 16 x 16 mesh; fin-fit sees it as a user's own FEM
# data would be given (mesh.h5 without /ibm, nodal_loads.h5, --objective static) on the 8 x 8 corner
# nodes, and each parameter passes within 5 %, or when its 95 % interval covers the truth, or when
# it is flagged not identified (docs/studies/fit_model_misfit.md). About 45 s on 2 cores. Not in the
# coarse (CI) set, which may not need a peer:
#   snakemake -c2 results/validation/fit_calculix_plate/summary.json
_CALCULIX_PLATE = os.path.join(REPO, "data", "cases", "hybrid_plate.json")
if not COARSE:
    register_validation("fit_calculix_plate", "fit on CalculiX's static nonlinear hybrid plate: each parameter "
                        "within 5 %, or its interval covers the truth, or flagged not identified")


rule validation_fit_calculix_plate:
    input:
        exe=EXE("fin-fit"),
        case=_CALCULIX_PLATE,
        levels=os.path.join(SCRIPTS, "calculix_static_levels.py"),
        scores=os.path.join(SCRIPTS, "fit_other_code_scores.py"),
    output:
        summary="results/validation/fit_calculix_plate/summary.json",
        fit="results/validation/fit_calculix_plate/fit.json",
    log:
        "results/logs/validation/fit_calculix_plate.log",
    threads: THREADS
    params:
        work="results/validation/fit_calculix_plate/ccx",
    shell:
        "if ! command -v ccx > /dev/null; then"
        "   echo 'validation_fit_calculix_plate: CalculiX (ccx) not found; install the Debian package"
        " calculix-ccx (tools/scripts/install-deps.sh --peers)' >&2; exit 2; fi;"
        " (OMP_NUM_THREADS={threads} /usr/bin/python3 {input.levels} --case {input.case} --ccx-nx 16 --nx 8"
        " --levels 4 --out-dir {params.work}"
        " && OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} run --mesh {params.work}/mesh.h5"
        " --motion {params.work}/motion.h5 --loads {params.work}/nodal_loads.h5"
        " --materials {params.work}/materials.json --parameters {params.work}/parameters.json"
        " --objective static --runs 1 --population 20 --generations 15 --polish-evaluations 150 --seed 1"
        " --out {params.work}/fit.h5 --summary {output.fit}"
        " && /usr/bin/python3 {input.scores} --fit {output.fit} --truth {params.work}/materials.json"
        " --run {params.work}/ccx.json --name fit_calculix_plate --out {output.summary}) > {log} 2>&1"
