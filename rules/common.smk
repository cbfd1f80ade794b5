# Helpers shared by every rule file: where executables live, and the registry of validation
# cases and benchmarks that the default target and the summary index draw from.
import os

REPO = workflow.basedir
# A relative build_dir is relative to the repository, so the workflow can run in another
# working directory (snakemake -d DIR), as the workflow test does.
BUILD = config["build_dir"] if os.path.isabs(config["build_dir"]) else os.path.join(REPO, config["build_dir"])
SCRIPTS = os.path.join(REPO, "tools", "scripts")
THREADS = config["threads"]
COARSE = config["validation"]["coarse"]

# name -> description; each rules/<area>.smk registers the cases it defines.
VALIDATION_CASES = {}
BENCHMARKS = {}
# Final outputs of the pipeline stages that exist (each rules/<area>.smk adds its own).
STAGE_OUTPUTS = []


def EXE(name):
    """Path of an executable in the build; rules list it as an input."""
    return os.path.join(BUILD, "bin", name)


def have(name):
    return os.path.exists(EXE(name))


def register_validation(name, description):
    VALIDATION_CASES[name] = description


def register_stage_output(path):
    STAGE_OUTPUTS.append(path)


def register_bench(name, description):
    BENCHMARKS[name] = description


def validation_targets():
    wanted = config["validation"]["cases"] or sorted(VALIDATION_CASES)
    unknown = [c for c in wanted if c not in VALIDATION_CASES]
    if unknown:
        raise ValueError(f"config validation.cases: unknown case(s) {unknown}; defined: {sorted(VALIDATION_CASES)}")
    return [f"results/validation/{c}/summary.json" for c in wanted]


def bench_targets():
    wanted = config["bench"]["names"]
    unknown = [b for b in wanted if b not in BENCHMARKS]
    if unknown:
        raise ValueError(f"config bench.names: unknown benchmark(s) {unknown}; defined: {sorted(BENCHMARKS)}")
    return [f"results/bench/{b}.json" for b in wanted]
