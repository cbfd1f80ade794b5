# Performance benchmarks against peers measured in the same run (results/bench/<name>.json;
# `snakemake -c2 bench` runs every one). Peers come from Debian packages installed by
# tools/scripts/install-deps.sh --peers; a rule whose peer is missing stops with a line saying so.
# Exit 1 of a benchmark executable is a missed goal, a result: METRIC_MISSED_IS_A_RESULT (common.smk).

import re

MPIRUN = "mpirun --oversubscribe --allow-run-as-root" if os.geteuid() == 0 else "mpirun --oversubscribe"

register_bench("poisson", "pressure Poisson solve on a stretched 3-D grid: finverse MG-PCG vs hypre PFMG/BoomerAMG")

rule bench_poisson:
    input:
        ours=EXE("fin-poisson-bench"),
        peer=EXE("fin-poisson-hypre"),
    output:
        json="results/bench/poisson.json",
        peer="results/bench/poisson_hypre.json",
    params:
        sizes=" ".join(f"-n {n}" for n in ([32, 64] if COARSE else [64, 128])),
    log:
        "results/logs/bench/poisson.log",
    threads: THREADS
    resources:
        mem_mb=4000,
    shell:
        "({MPIRUN} -np {threads} {input.peer} {params.sizes} --json {output.peer} && "
        " OMP_WAIT_POLICY=PASSIVE {input.ours} {params.sizes} --threads {threads} --peer {output.peer} --json {output.json}"
        " " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"

register_bench("scaling", "the pressure solve and the fin's flow step on MPI ranks against the threaded solver on "
               "the same cores; a strong/weak scaling model for 8-512 ranks (issue 48)")

# The whole flow step on ranks: fin-cfd fin on the tiny case's fin (h = c/20, 161 280 cells) as the
# closed body and as the sheet, threaded on 1 and 2 threads and on 1 and 2 ranks (1 rank through
# the ranks' path, FINVERSE_FLOW_RANKS_ON_ONE=1). Every run takes both cores so that none times
# beside another, and its threads spin between loops (OMP_WAIT_POLICY=ACTIVE, as the other timed
# benchmarks alone on the machine): sleeping threads made two threads' pressure solve 1.6x one
# thread's (docs/studies/flow_mpi.md, session 58). solver_seconds / (steps x cells) is the cost
# per cell-step. Each run is repeated (_SCALING_FLOW_REPEATS) and the fastest kept: on an idle
# machine single 40-step runs of the same command differed by up to 27 % (session 57), and the
# fastest of three still moved the one-rank ratio by 7 % between two runs of the rule (session 58).
_SCALING_FLOW_RUNS = {"threads1": "OMP_NUM_THREADS=1 {exe} --threads 1",
                      "threads2": "{exe} --threads 2",
                      "ranks1": "OMP_NUM_THREADS=1 FINVERSE_FLOW_RANKS_ON_ONE=1 " + MPIRUN + " -np 1 {exe} --threads 1",
                      "ranks2": "OMP_NUM_THREADS=1 " + MPIRUN + " -np 2 {exe} --threads 1"}
_SCALING_FLOW_REPEATS = 5
_TINY_FIN = os.path.join(REPO, "tests", "regression", "mesh", "tiny_case")

rule bench_scaling_flow:
    input:
        exe=EXE("fin-cfd"),
        mesh=os.path.join(_TINY_FIN, "mesh.h5"),
        motion=os.path.join(_TINY_FIN, "motion.h5"),
    output:
        summary="results/bench/scaling/flow_{surface}_{mode}_{rep}.json",
        loads=temp("results/bench/scaling/flow_{surface}_{mode}_{rep}.h5"),
    wildcard_constraints:
        surface="closed|sheet",
        mode="|".join(_SCALING_FLOW_RUNS),
        rep=r"\d+",
    params:
        launch=lambda wc, input: _SCALING_FLOW_RUNS[wc.mode].format(exe=input.exe),
    log:
        "results/logs/bench/scaling_flow_{surface}_{mode}_{rep}.log",
    threads: 2
    resources:
        mem_mb=2000,
    shell:
        "OMP_WAIT_POLICY=ACTIVE {params.launch} fin --surface {wildcards.surface} --mesh {input.mesh}"
        " --motion {input.motion} --cells-per-chord 20 --upstream 1.5 --downstream 3 --lateral 1.5 --spanwise 1.5"
        " --stretch-ratio 1.2 --out {output.loads} --summary {output.summary} > {log} 2>&1"

# Issue 48's scaling benchmark (docs/studies/flow_mpi.md): 1 and 2 ranks of fin-poisson-ranks, each
# against the threaded solver with as many threads, the flow step's runs above, then the file and
# the model (tools/scripts/scaling_bench.py). OpenMP's default wait policy (spin briefly, then
# sleep): the threaded run's spare thread must not spin through the ranks' run that follows it
# in the same process. No core binding: Open MPI binds each of 2 ranks to one core, and rank 0's
# threaded run then had its two threads on one core (0.44 s against 0.29 s unbound, session 58).
rule bench_scaling:
    input:
        exe=EXE("fin-poisson-ranks"),
        flow=expand("results/bench/scaling/flow_{surface}_{mode}_{rep}.json", surface=["closed", "sheet"],
                    mode=list(_SCALING_FLOW_RUNS), rep=range(1, _SCALING_FLOW_REPEATS + 1)),
    output:
        json="results/bench/scaling.json",
        ranks1="results/bench/scaling/ranks1.json",
        ranks2="results/bench/scaling/ranks2.json",
    params:
        n=48 if COARSE else 96,
    log:
        "results/logs/bench/scaling.log",
    threads: 2
    resources:
        mem_mb=3000,
    shell:
        "(env -u OMP_WAIT_POLICY {MPIRUN} --bind-to none -np 1 {input.exe} -n {params.n} --json {output.ranks1} && "
        " env -u OMP_WAIT_POLICY {MPIRUN} --bind-to none -np 2 {input.exe} -n {params.n} --json {output.ranks2} && "
        " /usr/bin/python3 {SCRIPTS}/scaling_bench.py --record {output.ranks1} --record {output.ranks2}"
        " $(for f in {input.flow}; do echo --flow-record $f; done) --out {output.json}"
        " " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"

# DFG 2D-2 (Re 100) wall time against OpenFOAM (pimpleFoam on an O-grid) on the same cores: each
# code on a sequence of meshes; fin-cfd-bench compares the cheapest run of each within 1 % of the
# bound midpoints. Every job takes all THREADS cores, so with -c THREADS they run one at a time.
# Full variant only (the coarse grids grade nothing). finverse grids are named <box>c<core>[w<ratio>]:
# h = D / box in the wake box, D / core over the boundary layer, cell ratio towards the channel
# walls; 24c48w0.97 is fin-cfd dfg_2d2's default. The meshes' and steps' study:
# docs/studies/dfg_2d2_lift_maximum.md. cfd.json (about an hour) times the default grid against the
# peer's meshes; the studies beside it go to cfd_dfg_studies.json (about an hour more).
DFG_BENCH_FINVERSE = config["bench"]["dfg2d2_finverse"] or ["24c48w0.97"]
DFG_STUDY_FINVERSE = ["24c48w0.97", "24c64w0.97"]


def dfg_grid_flags(name):
    m = re.fullmatch(r"(\d+)(?:c(\d+))?(?:w([0-9.]+))?", name)
    flags = f"--cells-per-diameter {m[1]} --core-cells-per-diameter {m[2] or 0}"
    return flags + (f" --wall-stretch-ratio {m[3]}" if m[3] else "")


def repeated_flags(**paths):
    """fin-cfd-bench's file arguments: repeated_flags(dfg=[a, b]) -> '--dfg a --dfg b'."""
    return " ".join(f"--{flag} {p}" for flag, ps in paths.items() for p in ps)

# The peer's meshes: 48, the first within 1 % on all three metrics, and 32, the next coarser, which
# misses (docs/studies/dfg_2d2_lift_maximum.md, section 8).
DFG_BENCH_OPENFOAM = config["bench"]["dfg2d2_openfoam"] or [32, 48]

# The 2-D run waits actively: it runs alone, and its loops are too short for sleeping threads
# (docs/studies/workflow_openmp_wait_policy.md).
rule bench_dfg2d2_finverse:
    input:
        exe=EXE("fin-cfd"),
        reference=os.path.join(REPO, "data", "reference", "schaefer_turek.json"),
    output:
        "results/bench/dfg2d2/finverse_N{n}/dfg_2d2/summary.json",
    log:
        "results/logs/bench/dfg2d2_finverse_N{n}.log",
    wildcard_constraints:
        n=r"\d+(c\d+)?(w[0-9.]+)?",
    threads: THREADS
    resources:
        mem_mb=500,
    params:
        grid=lambda wildcards: dfg_grid_flags(wildcards.n),
    shell:
        "OMP_WAIT_POLICY=ACTIVE {input.exe} --threads {threads} --out-dir results/bench/dfg2d2/finverse_N{wildcards.n}"
        " dfg_2d2 {params.grid} --reference {input.reference} > {log} 2>&1 " + METRIC_MISSED_IS_A_RESULT

rule bench_dfg2d2_openfoam:
    input:
        script=os.path.join(SCRIPTS, "openfoam_dfg.py"),
    output:
        "results/bench/dfg2d2/openfoam.json",
    log:
        "results/logs/bench/dfg2d2_openfoam.log",
    threads: THREADS
    resources:
        mem_mb=2000,
    params:
        cells=" ".join(f"--cells {n}" for n in DFG_BENCH_OPENFOAM),
    shell:
        "if ! command -v pimpleFoam > /dev/null; then"
        "   echo 'bench_dfg2d2_openfoam: OpenFOAM (pimpleFoam) not found; install the Debian package openfoam"
        " (tools/scripts/install-deps.sh --peers)' >&2; exit 2; fi;"
        " python3 {input.script} {params.cells} --ranks {threads} --t-end 10 --window 3 --out {output} > {log} 2>&1"

# The peer's time-step error: its finest mesh again at half the step (Courant 0.25); its lift
# maximum is first order in its step (docs/studies/dfg_2d2_lift_maximum.md, section 8), so
# fin-cfd-bench reports the change (dfg2d2_openfoam_CL_max_time_step_change) beside the comparison.
DFG_BENCH_OPENFOAM_STEP = [max(DFG_BENCH_OPENFOAM)]

rule bench_dfg2d2_openfoam_half_step:
    input:
        script=os.path.join(SCRIPTS, "openfoam_dfg.py"),
    output:
        "results/bench/dfg2d2/openfoam_courant0.25.json",
    log:
        "results/logs/bench/dfg2d2_openfoam_courant0.25.log",
    threads: THREADS
    resources:
        mem_mb=2000,
    params:
        cells=" ".join(f"--cells {n}" for n in DFG_BENCH_OPENFOAM_STEP),
    shell:
        "if ! command -v pimpleFoam > /dev/null; then"
        "   echo 'bench_dfg2d2_openfoam_half_step: OpenFOAM (pimpleFoam) not found; install the Debian package"
        " openfoam (tools/scripts/install-deps.sh --peers)' >&2; exit 2; fi;"
        " python3 {input.script} {params.cells} --courant 0.25 --ranks {threads} --t-end 10 --window 3"
        " --out {output} > {log} 2>&1"

# DFG 2D-3 (sine inflow over 8 s) the same way, against the high-precision values of John (2004):
# reported beside 2D-2, not graded (numbers: docs/studies/dfg_2d2_lift_maximum.md, section 7).
DFG3_BENCH_FINVERSE = ["24c48w0.97"]
DFG3_BENCH_OPENFOAM = [32, 48]

rule bench_dfg2d3_finverse:
    input:
        exe=EXE("fin-cfd"),
        reference=os.path.join(REPO, "data", "reference", "schaefer_turek.json"),
    output:
        "results/bench/dfg2d3/finverse_N{n}/dfg_2d3/summary.json",
    log:
        "results/logs/bench/dfg2d3_finverse_N{n}.log",
    wildcard_constraints:
        n=r"\d+(c\d+)?(w[0-9.]+)?",
    threads: THREADS
    resources:
        mem_mb=500,
    params:
        grid=lambda wildcards: dfg_grid_flags(wildcards.n),
    shell:
        "OMP_WAIT_POLICY=ACTIVE {input.exe} --threads {threads} --out-dir results/bench/dfg2d3/finverse_N{wildcards.n}"
        " dfg_2d3 {params.grid} --reference {input.reference} > {log} 2>&1 " + METRIC_MISSED_IS_A_RESULT

rule bench_dfg2d3_openfoam:
    input:
        script=os.path.join(SCRIPTS, "openfoam_dfg.py"),
    output:
        "results/bench/dfg2d3/openfoam.json",
    log:
        "results/logs/bench/dfg2d3_openfoam.log",
    threads: THREADS
    resources:
        mem_mb=2000,
    params:
        cells=" ".join(f"--cells {n}" for n in DFG3_BENCH_OPENFOAM),
    shell:
        "if ! command -v pimpleFoam > /dev/null; then"
        "   echo 'bench_dfg2d3_openfoam: OpenFOAM (pimpleFoam) not found; install the Debian package openfoam"
        " (tools/scripts/install-deps.sh --peers)' >&2; exit 2; fi;"
        " python3 {input.script} --benchmark 2d3 {params.cells} --ranks {threads} --out {output} > {log} 2>&1"

# The flow solver's benchmark file (issue 4): the Poisson comparison above (when hypre is built),
# the cost per cell per time step of the fractional step on the 3-D Taylor-Green vortex at three
# grid sizes (graded for flatness), and DFG 2D-2 against OpenFOAM (full variant).
register_bench("cfd", "flow solver: Poisson vs hypre, cost per cell per time step, DFG 2D-2 vs OpenFOAM")

rule bench_cfd:
    input:
        exe=EXE("fin-cfd-bench"),
        poisson=["results/bench/poisson.json"] if have("fin-poisson-hypre") else [],
        dfg=[] if COARSE else
            [f"results/bench/dfg2d2/finverse_N{n}/dfg_2d2/summary.json" for n in DFG_BENCH_FINVERSE],
        openfoam=[] if COARSE else ["results/bench/dfg2d2/openfoam.json"],
    output:
        json="results/bench/cfd.json",
    params:
        sizes=" ".join(f"-n {n}" for n in ([16, 24, 32] if COARSE else [64, 96, 128])),
        steps="--warmup 1 --steps 2" if COARSE else "--warmup 2 --steps 5",
        poisson=lambda wildcards, input: f"--poisson {input.poisson}" if input.poisson else "",
        dfg=lambda wildcards, input: repeated_flags(dfg=input.dfg, openfoam=input.openfoam),
    log:
        "results/logs/bench/cfd.log",
    threads: THREADS
    resources:
        mem_mb=3000,
    shell:
        "(OMP_WAIT_POLICY=PASSIVE {input.exe} {params.sizes} {params.steps} {params.poisson} {params.dfg} --threads {threads}"
        " --json {output.json} " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"

# The studies beside the DFG comparison (full variant only; about an hour more): fin-cfd on a finer
# core, the peer's finest mesh at half its step (its CL_max time-step change), and DFG 2D-3 against
# John (2004), reported. fin-cfd-bench's cost-per-cell part runs once on 16^3 only, ungraded.
if not COARSE:
    register_bench("cfd_dfg_studies", "DFG 2D-2 grid and peer time-step studies, DFG 2D-3 vs OpenFOAM")

rule bench_cfd_dfg_studies:
    input:
        exe=EXE("fin-cfd-bench"),
        dfg=[f"results/bench/dfg2d2/finverse_N{n}/dfg_2d2/summary.json" for n in DFG_STUDY_FINVERSE],
        openfoam=["results/bench/dfg2d2/openfoam.json", "results/bench/dfg2d2/openfoam_courant0.25.json"],
        dfg3=[f"results/bench/dfg2d3/finverse_N{n}/dfg_2d3/summary.json" for n in DFG3_BENCH_FINVERSE],
        openfoam3=["results/bench/dfg2d3/openfoam.json"],
    output:
        json="results/bench/cfd_dfg_studies.json",
    params:
        dfg=lambda wildcards, input: repeated_flags(dfg=input.dfg, openfoam=input.openfoam,
                                                    dfg2d3=input.dfg3, openfoam2d3=input.openfoam3),
    log:
        "results/logs/bench/cfd_dfg_studies.log",
    threads: THREADS
    resources:
        mem_mb=1000,
    shell:
        "(OMP_WAIT_POLICY=PASSIVE {input.exe} -n 16 --warmup 1 --steps 1 {params.dfg} --threads {threads}"
        " --json {output.json} " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"

# Structural FEM against CalculiX (issue 3): the Sze end-shear strip and the hybrid plate, each
# code on its coarsest mesh within 1 % of the reference, both run here one after the other; and
# the cost of a Newton iteration against DOFs up to ~56k. Needs ccx (Debian calculix-ccx); the
# rule installs nothing and stops with a message when ccx is missing.
register_bench("fem", "structural FEM: finverse vs CalculiX (Sze strip, hybrid plate), Newton-iteration scaling")

rule bench_fem:
    input:
        exe=EXE("fin-fem-bench"),
        sze_script=os.path.join(SCRIPTS, "calculix_sze_strip.py"),
        plate_script=os.path.join(SCRIPTS, "calculix_hybrid_plate.py"),
        structures=os.path.join(REPO, "data", "reference", "structures.json"),
        case=os.path.join(REPO, "data", "cases", "hybrid_plate.json"),
        plate_reference=os.path.join(REPO, "data", "reference", "hybrid_plate_calculix.json"),
    output:
        json="results/bench/fem.json",
        sze_peer="results/bench/fem_calculix_sze.json",
        plate_peer="results/bench/fem_calculix_plate.json",
    params:
        # CalculiX: 4 S8R along the strip is within 0.6 % of Sze's table (finer strips do not
        # converge in ccx 2.20, see calculix_sze_strip.py); plate 16 x 16 is within 0.5 % of
        # its 32 x 32 answer (data/reference/hybrid_plate_calculix.json mesh study).
        plate_meshes="--nx 8" if COARSE else "--nx 8 --nx 16",
        scaling="--scaling 8 --scaling 16" if COARSE else
                " ".join(f"--scaling {n}" for n in (16, 32, 48, 64, 96)),
    log:
        "results/logs/bench/fem.log",
    threads: THREADS
    resources:
        mem_mb=4000,
    shell:
        "if ! command -v ccx > /dev/null; then"
        "   echo 'bench_fem: CalculiX (ccx) not found; install the Debian package calculix-ccx"
        " (tools/scripts/install-deps.sh --peers)' >&2; exit 2; fi;"
        " (export OMP_NUM_THREADS={threads};"
        " python3 {input.sze_script} --reference {input.structures} --nx 4 --out {output.sze_peer} &&"
        " python3 {input.plate_script} --case {input.case} {params.plate_meshes} --analysis static"
        "   --out {output.plate_peer} &&"
        " {input.exe} --threads {threads} --structures {input.structures} --case {input.case}"
        "   --plate-reference {input.plate_reference} --peer-sze {output.sze_peer}"
        "   --peer-plate {output.plate_peer} {params.scaling} --json {output.json}"
        " " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"

# The inverse fit (issue 31): pagmo GA alone (the seed paper's procedure), CMA-ES and GA + LM
# polish, each until every parameter of the hybrid plate twin (the fit validations' small heave at
# full density) is within 1 % of the truth, with the FEM evaluations and wall time each needed
# (goal: the best <= 1/10 of the GA's); evaluations per second of eq. (1) vs eq. (2); a generation
# on 2 threads against 1. The arms use eq. (2): a GA on eq. (1) would need hours (thousands of
# 1-3 s evaluations, tools/fit/validation/fit_bench.hpp). 2 to 4 min on 2 cores; no peer. The
# coarse variant runs every part small on a 4 x 4 plate (a smoke test).
register_bench("fit", "inverse fit: GA vs CMA-ES vs GA + LM polish to 1 % on the hybrid plate twin, objective cost, speed-up")

rule bench_fit:
    input:
        exe=EXE("fin-fit-bench"),
        case=os.path.join(REPO, "data", "cases", "hybrid_plate_small_heave.json"),
    output:
        json="results/bench/fit.json",
    params:
        sizes="--nx 4 --nz 4 --max-evaluations 600 --max-arm-seconds 30 --rate-points 2 --rate-repeats 2"
              " --speedup-repeats 1" if COARSE else "",
    log:
        "results/logs/bench/fit.log",
    threads: THREADS
    resources:
        mem_mb=1000,
    shell:
        "(OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} --case {input.case} {params.sizes}"
        " --out {output.json} " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"

# Eq. (2) evaluations per second on the case's own fin (issue 45, goal 8: >= 10 converged on 2
# threads): the converged Newton increment from the base, the same converged increment from a stored
# reference solution (fem/stored_tangent_increment.hpp) and the linearised one on stored element
# tangents (fem/linear_increment.hpp), the same seeded points, from the pipeline's mesh, motion and
# loads and the fit stage's materials file. Under config/cases/tiny.yaml this is the default fin's
# mesh on a tenth of a period. Numbers and commands: docs/studies/fit_evaluation_speed.md.
register_bench("fit_fin_rate", "eq. (2) evaluations per second on the fin: Newton vs stored-reference vs linearised increment")

rule bench_fit_fin_rate:
    input:
        exe=EXE("fin-fit-bench"),
        mesh=f"results/{config['case']}/mesh.h5",
        motion=f"results/{config['case']}/motion.h5",
        loads=f"results/{config['case']}/loads.h5",
        materials=os.path.join(REPO, config["fit"]["materials"]),
    output:
        json="results/bench/fit_fin_rate.json",
    params:
        sizes="--points 4" if COARSE else "",
    log:
        "results/logs/bench/fit_fin_rate.log",
    threads: THREADS
    resources:
        mem_mb=2000,
    shell:
        "(OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} fin_rate --mesh {input.mesh}"
        " --motion {input.motion} --loads {input.loads} --materials {input.materials} {params.sizes}"
        " --out {output.json} " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"

# The coupled FSI (issue 32): coupling iterations per step at relative residual 1e-5, Aitken against
# IQN-ILS, on Turek-Hron FSI2 and FSI3 over their limit cycle, and the wall time of one coupled FSI3
# step against one step of the same flow with the flag held rigid (tools/fsi/validation/
# fsi_bench.hpp). Affordable on one core: each case runs once with IQN-ILS to its limit cycle and
# writes a checkpoint (FSI3 D/16 cfl 0.3 to t = 6 s, FSI2 to 9 s: the grids of rules/fsi.smk), then
# every arm restarts from it for 0.5 s (fin-fsi --restart --restart-new-coupling). The coarse variant
# runs the same chain on a short start (a smoke test; its numbers are not the benchmark's).
# Numbers and commands: docs/studies/fsi_restart_cost_conservation.md.
register_bench("fsi", "coupled FSI: Aitken vs IQN-ILS iterations on Turek-Hron FSI2/FSI3, coupled vs rigid-flag step "
               "cost, the fin's fsi stage step against its flow's step")

# case -> (fin-fsi flags, limit-cycle time [s], restart length [s]; full, then coarse).
_FSI_BENCH = {
    "fsi3": ("--case FSI3 --cells-per-diameter 16 --cfl 0.3 --output-every 10", (6.0, 0.5), (0.1, 0.05)),
    "fsi2": ("--case FSI2 --cells-per-diameter 16 --cfl 0.3 --output-every 10", (9.0, 0.5), (0.1, 0.05)),
}
_FSI_BENCH_REFERENCE = os.path.join(REPO, "data", "reference", "turek_hron.json")


def _fsi_bench_times(case):
    return _FSI_BENCH[case][2 if COARSE else 1]


rule bench_fsi_limit_cycle:
    input:
        exe=EXE("fin-fsi"),
        reference=_FSI_BENCH_REFERENCE,
    output:
        checkpoint="results/bench/fsi/{case}_limit_cycle.h5",
        summary="results/bench/fsi/{case}_limit_cycle/summary.json",
    wildcard_constraints:
        case="fsi2|fsi3",
    log:
        "results/logs/bench/fsi_{case}_limit_cycle.log",
    threads: 1
    resources:
        mem_mb=500,
    params:
        flags=lambda wildcards: _FSI_BENCH[wildcards.case][0],
        t_end=lambda wildcards: _fsi_bench_times(wildcards.case)[0],
    shell:
        "(OMP_WAIT_POLICY=PASSIVE {input.exe} --threads 1 turek_hron {params.flags} --acceleration iqn-ils"
        " --t-end {params.t_end} --checkpoint {output.checkpoint} --checkpoint-every 1000"
        " --reference {input.reference} --summary {output.summary} " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"


rule bench_fsi_restart:
    input:
        exe=EXE("fin-fsi"),
        reference=_FSI_BENCH_REFERENCE,
        checkpoint="results/bench/fsi/{case}_limit_cycle.h5",
    output:
        summary="results/bench/fsi/{case}_{arm}/summary.json",
    wildcard_constraints:
        case="fsi2|fsi3",
        arm="aitken|iqn-ils|rigid",
    log:
        "results/logs/bench/fsi_{case}_{arm}.log",
    threads: 1
    resources:
        mem_mb=500,
    params:
        flags=lambda wildcards: _FSI_BENCH[wildcards.case][0],
        t_end=lambda wildcards: sum(_fsi_bench_times(wildcards.case)),
        arm=lambda wildcards: "--acceleration iqn-ils --hold-flag-rigid" if wildcards.arm == "rigid"
        else f"--acceleration {wildcards.arm}",
    shell:
        "(OMP_WAIT_POLICY=PASSIVE {input.exe} --threads 1 turek_hron {params.flags} {params.arm}"
        " --t-end {params.t_end} --restart {input.checkpoint} --restart-new-coupling"
        " --reference {input.reference} --summary {output.summary} " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"


# The fin's pair (issue 50, Deliver 2; docs/studies/fsi_step_cost.md): the pipeline's fsi stage as it
# runs (config fsi.flags) on the case's reconstruction with the truth's materials, one thread, and
# the flow alone (fin-cfd fin) on the same grid, box and step: its cost per coupled step over the
# flow's per step. Only fin-cfd fin's flags are passed on to the flow run.
_FIN_FLOW_FLAGS = {"--cells-per-chord", "--cfl", "--periods", "--output-periods", "--motion-harmonics", "--upstream",
                   "--downstream", "--lateral", "--spanwise", "--stretch-ratio", "--core-margin", "--wake",
                   "--reynolds", "--speed"}


def _fin_flow_flags(flags):
    words, out = flags.split(), []
    for n, w in enumerate(words):
        if w in _FIN_FLOW_FLAGS and n + 1 < len(words):
            out += [w, words[n + 1]]
    return " ".join(out)


rule bench_fsi_fin_coupled:
    input:
        exe=EXE("fin-fsi"),
        mesh=f"results/{config['case']}/mesh.h5",
        motion=f"results/{config['case']}/motion.h5",
        materials=os.path.join(REPO, config["truth"]["materials"]),
    output:
        summary="results/bench/fsi/fin_coupled/summary.json",
        fsi=temp("results/bench/fsi/fin_coupled/fsi.h5"),
    log:
        "results/logs/bench/fsi_fin_coupled.log",
    threads: 1
    resources:
        mem_mb=2000,
    params:
        flags=config["fsi"]["flags"],
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads 1 fin --mesh {input.mesh} --motion {input.motion}"
        " --materials {input.materials} {params.flags} --out {output.fsi} --summary {output.summary} > {log} 2>&1"


rule bench_fsi_fin_flow:
    input:
        exe=EXE("fin-cfd"),
        mesh=f"results/{config['case']}/mesh.h5",
        motion=f"results/{config['case']}/motion.h5",
    output:
        summary="results/bench/fsi/fin_flow/summary.json",
        loads=temp("results/bench/fsi/fin_flow/loads.h5"),
    log:
        "results/logs/bench/fsi_fin_flow.log",
    threads: 1
    resources:
        mem_mb=2000,
    params:
        flags=_fin_flow_flags(config["fsi"]["flags"]),
        reynolds=config["fin"]["reynolds"],
    shell:
        "(OMP_WAIT_POLICY=PASSIVE {input.exe} --threads 1 fin --mesh {input.mesh} --motion {input.motion}"
        " --reynolds {params.reynolds} {params.flags} --out {output.loads} --summary {output.summary} "
        + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"


rule bench_fsi:
    input:
        exe=EXE("fin-fsi-bench"),
        fsi3_iqn="results/bench/fsi/fsi3_iqn-ils/summary.json",
        fsi3_aitken="results/bench/fsi/fsi3_aitken/summary.json",
        fsi2_iqn="results/bench/fsi/fsi2_iqn-ils/summary.json",
        fsi2_aitken="results/bench/fsi/fsi2_aitken/summary.json",
        fsi3_rigid="results/bench/fsi/fsi3_rigid/summary.json",
        fin_coupled="results/bench/fsi/fin_coupled/summary.json",
        fin_flow="results/bench/fsi/fin_flow/summary.json",
    output:
        json="results/bench/fsi.json",
    log:
        "results/logs/bench/fsi.log",
    threads: 1
    resources:
        mem_mb=200,
    shell:
        "({input.exe} --fsi3-iqn-ils {input.fsi3_iqn} --fsi3-aitken {input.fsi3_aitken}"
        " --fsi2-iqn-ils {input.fsi2_iqn} --fsi2-aitken {input.fsi2_aitken} --fsi3-rigid {input.fsi3_rigid}"
        " --fin-coupled {input.fin_coupled} --fin-flow {input.fin_flow} --out {output.json} " + METRIC_MISSED_IS_A_RESULT + ") > {log} 2>&1"

# Wall time per pipeline stage (issue 33, "Benchmark"): the benchmark file of every stage rule
# (PIPELINE_STAGES, common.smk) in one summary, with the slowest stage named. It covers the case of
# the current config: `snakemake -c2 results/bench/pipeline.json` times the default case (its loads
# take about 50 min), `... --configfile config/cases/tiny.yaml` the tiny one; each run overwrites it
# (parameters.case says which). Stages already built are not rerun: their files time the last run.
# A thin body's step cost (issue 44's benchmark): the heaving/pitching plate of thin_plate_loads at
# c/20 as a zero-thickness sheet and as the closed two-cell body, against the same grid and step
# with no body, in one run (fin-cfd thin_surface_bench; numbers in docs/studies/thin_surface.md).
register_bench("thin_surface", "a flow step with a thin body (sheet, closed body) against the same grid with no body")

rule bench_thin_surface:
    input:
        exe=EXE("fin-cfd"),
    output:
        json="results/bench/thin_surface.json",
    log:
        "results/logs/bench/thin_surface.log",
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        coarse="--coarse" if COARSE else "",
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} {params.coarse} thin_surface_bench --out {output.json}"
        " > {log} 2>&1 " + METRIC_MISSED_IS_A_RESULT


register_bench("pipeline", "wall and CPU time of each pipeline stage on the case (the truth's FSI, synth to report), slowest stage named")

rule bench_pipeline:
    input:
        script=os.path.join(SCRIPTS, "pipeline_bench.py"),
        stages=[stage_benchmark(s) for s in progress_order()],
    output:
        json="results/bench/pipeline.json",
    log:
        "results/logs/bench/pipeline.log",
    threads: 1
    resources:
        mem_mb=200,
    params:
        stages=" ".join(f"--stage {s}={stage_benchmark(s)}" for s in progress_order()),
        goal=f"--goal-minutes {config['progress']['goal_minutes']}" if config["progress"]["goal_minutes"] else "",
    shell:
        "/usr/bin/python3 {input.script} --case {config[case]} --threads " + str(THREADS) +
        " {params.stages} {params.goal} --out {output.json} 2> {log} " + METRIC_MISSED_IS_A_RESULT
