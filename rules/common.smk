# Helpers shared by every rule file: where executables live, the one rule that stands for an
# executable not built yet, and the registry of validation cases, benchmarks and pipeline outputs
# that the targets in the Snakefile draw from.
import os
import sys

REPO = workflow.basedir
# A relative build_dir is relative to the repository, so the workflow can run in another
# working directory (snakemake -d DIR), as the workflow test does.
BUILD = config["build_dir"] if os.path.isabs(config["build_dir"]) else os.path.join(REPO, config["build_dir"])
SCRIPTS = os.path.join(REPO, "tools", "scripts")
THREADS = config["threads"]
COARSE = config["validation"]["coarse"]

# Exit code 1 of a finverse executable means it ran to the end and wrote its summary.json or
# benchmark file, but a graded metric missed its tolerance (README, exit codes): that is a result,
# read in results/validation/index.txt, not a failed job. Validation and benchmark rules end their
# command with this; exit 2 (an error) and any other failure still fail the rule.
METRIC_MISSED_IS_A_RESULT = "|| [ $? -eq 1 ]"

# Every executable a rule runs: name -> how to get it when it is missing. All of them here: rule
# missing_executable (below) only covers the names listed when it is defined.
_CMAKE_BUILD = "cmake -S {src} -B {build} -G Ninja && cmake --build {build} -j2"
EXECUTABLES = {
    name: _CMAKE_BUILD
    for name in ["fin-synth", "fin-track", "fin-mesh", "fin-cfd", "fin-fem", "fin-fit", "fin-fsi", "fin-cfd-bench",
                 "fin-fem-bench", "fin-fit-bench", "fin-poisson-bench", "fin-report", "fin-fsi-bench", "fin-calibrate",
                 "fin-loop"]
}
# Built only where hypre and MPI are installed (tools/apps/cfd.cmake).
EXECUTABLES["fin-poisson-hypre"] = "{src}/tools/scripts/install-deps.sh --peers (hypre), then " + _CMAKE_BUILD
# Built where Open MPI is (tools/apps/cfd.cmake; install-deps.sh installs it).
EXECUTABLES["fin-poisson-ranks"] = _CMAKE_BUILD


def EXE(name):
    """Path of an executable in the build; rules list it as an input, so a rebuilt tool reruns its stage."""
    if name not in EXECUTABLES:
        raise ValueError(f"EXE({name!r}): add it to EXECUTABLES in rules/common.smk")
    return os.path.join(BUILD, "bin", name)


def have(name):
    return os.path.exists(EXE(name))


# Every rule is in the DAG whether or not its executable is built yet, so `snakemake -n` on a fresh
# clone shows the whole workflow. An executable that is missing is the output of this rule, which
# fails with one line saying how to build it (the dry run prints the same line as the job's
# message). It matches only the executables that are missing, so nothing stands for one that is
# built (not even with --forceall), and with a complete build it does not exist.
_MISSING_EXECUTABLES = sorted(name for name in EXECUTABLES if not have(name))
if _MISSING_EXECUTABLES:

    def _how_to_build(name):
        def shown(path):  # relative to where snakemake runs, when inside it
            rel = os.path.relpath(path)
            return path if rel.startswith("..") else rel

        build = shown(BUILD)
        return f"{build}/bin/{name} is missing: run " + EXECUTABLES[name].format(src=shown(REPO), build=build)

    rule missing_executable:
        output:
            os.path.join(BUILD, "bin", "{exe}"),
        wildcard_constraints:
            exe="|".join(_MISSING_EXECUTABLES),
        message:
            "{params.how}"
        params:
            how=lambda wildcards: _how_to_build(wildcards.exe),
        shell:
            "echo '{params.how}' >&2; exit 2"


# name -> description; each rules/<area>.smk registers the cases it defines.
VALIDATION_CASES = {}
BENCHMARKS = {}
# Final outputs of the pipeline stages on the case (each rules/<area>.smk adds its own): the
# default target.
STAGE_OUTPUTS = []


def register_validation(name, description):
    VALIDATION_CASES[name] = description


def register_stage_output(path):
    STAGE_OUTPUTS.append(path)


def register_bench(name, description):
    BENCHMARKS[name] = description


# The pipeline's stages in the order they run. Each stage rule has a Snakemake benchmark file
# (wall s, max RSS, CPU s of the job), which rule bench_pipeline (rules/bench.smk) gathers.
PIPELINE_STAGES = ("synth", "track", "mesh", "loads", "fit", "fsi", "report")


def stage_benchmark(stage):
    """The benchmark file of pipeline stage <stage> on the case: results/<case>/benchmarks/<stage>.tsv
    (the truth's FSI, when the case has one: truth_fsi.tsv)."""
    if stage == "truth":
        return f"results/{config['case']}/benchmarks/truth_fsi.tsv"
    if stage not in PIPELINE_STAGES:
        raise ValueError(f"stage_benchmark({stage!r}): not one of PIPELINE_STAGES {PIPELINE_STAGES}")
    return f"results/{config['case']}/benchmarks/{stage}.tsv"


# One progress line per finished stage of the main job, with the pipeline's ETA (issue 50, "Also";
# tools/scripts/stage_progress.py): every stage rule's shell command is wrapped by stage_shell(). The
# order is the run's (each stage needs the one before); the truth's FSI runs first when the case has
# one. The ETA starts from config progress.expected_minutes, then from each stage's last measured time.
def progress_order():
    truth = ["truth"] if config["truth"]["source"] == "fsi" else []
    return truth + list(PIPELINE_STAGES)


def mpi_launch(wildcards, resources):
    """The launcher of a stage that runs on MPI ranks: "<mpi> -n <tasks>" when a profile gives the
    rule an `mpi` resource and more than one task (profiles/slurm: mpi="srun"; Snakemake 8's SLURM
    executor reads the same two names), else nothing: one process."""
    mpi = resources.get("mpi", "") if hasattr(resources, "get") else getattr(resources, "mpi", "")
    tasks = int(resources.get("tasks", 1) if hasattr(resources, "get") else getattr(resources, "tasks", 1))
    mpi = str(mpi).strip().strip("'\"")  # a value given on the command line keeps its quotes
    return f"{mpi} -n {tasks}" if mpi and tasks > 1 else ""


# The rules whose command runs "<mpi> -n <tasks>" (mpi_launch above).
MPI_RULES = ("loads", "fsi", "truth_fsi")


def check_mpi_resources(overwrite):
    """Issue 48's bad input: a profile (--set-resources) that gives a rule several MPI tasks must give
    it a launcher, and only the MPI_RULES run on ranks; else the tasks would idle beside one
    process. One line naming what to change, exit 2, before any job starts."""
    for rule, res in sorted(overwrite.items()):
        if "tasks" not in res:
            continue
        tasks = str(res["tasks"]).strip().strip("'\"")
        if not tasks.isdigit() or int(tasks) < 1:
            fail = f"{rule}:tasks={tasks}, expected a whole number >= 1"
        elif int(tasks) > 1 and rule not in MPI_RULES:
            fail = (f"{rule}:tasks={tasks}, but rule {rule} is not launched on MPI ranks"
                    f" (only {', '.join(MPI_RULES)} are); set {rule}:tasks=1")
        elif int(tasks) > 1 and not str(res.get("mpi", "")).strip().strip("'\""):
            fail = f"{rule}:tasks={tasks} without a launcher; add {rule}:mpi=\"srun\" (or mpirun) to set-resources"
        else:
            continue
        sys.stderr.write(f"finverse: error: profile resources: {fail}\n")
        sys.stderr.flush()
        os._exit(2)  # (Snakemake turns SystemExit into a traceback and exit 1; nothing is locked yet)


def stage_shell(stage, command):
    """command, then the stage's progress line (not printed when the command fails)."""
    expected = ",".join(f"{k}={v}" for k, v in sorted(config["progress"]["expected_minutes"].items()))
    times = f"results/{config['case']}/benchmarks/stage_times.json"
    return (
        "_stage_start=$(date +%s.%N); " + command + f"; /usr/bin/python3 {SCRIPTS}/stage_progress.py"
        f" --times {times} --stage {stage} --order {','.join(progress_order())}"
        + (f" --expected {expected}" if expected else "") + " --start $_stage_start"
    )


def validation_targets():
    """The cases of `snakemake validation` and of results/validation/index.txt: config
    validation.cases, or every registered case when that list is empty."""
    wanted = config["validation"]["cases"] or sorted(VALIDATION_CASES)
    unknown = [c for c in wanted if c not in VALIDATION_CASES]
    if unknown:
        raise ValueError(f"config validation.cases: unknown case(s) {unknown}; defined: {sorted(VALIDATION_CASES)}")
    return [f"results/validation/{c}/summary.json" for c in wanted]


def bench_targets():
    """The benchmarks of `snakemake bench` and of results/bench/index.txt: config bench.names,
    or every registered benchmark when that list is empty."""
    wanted = config["bench"]["names"] or sorted(BENCHMARKS)
    unknown = [b for b in wanted if b not in BENCHMARKS]
    if unknown:
        raise ValueError(f"config bench.names: unknown benchmark(s) {unknown}; defined: {sorted(BENCHMARKS)}")
    return [f"results/bench/{b}.json" for b in wanted]
