# finverse workflow (DESIGN.md section 1): frames -> kinematics -> mesh -> loads -> materials
# -> coupled FSI -> report, plus the validation cases and benchmarks of every stage.
#
#   snakemake -c2                 the pipeline on the default case (config/config.yaml):
#                                 fin-synth -> fin-track -> fin-mesh -> fin-cfd fin, to results/<case>/
#                                 -> fin-fit run -> fin-report (results/<case>/report/index.html,
#                                 rules/report.smk: the scores and the paper's figures)
#                                 (the loads take about 50 min: docs/studies/cfd_run_cost.md)
#   snakemake -c2 validation      every validation case (hours on 2 cores) and results/validation/index.txt
#   snakemake -c2 bench           every benchmark and results/bench/index.txt (needs the peers:
#                                 tools/scripts/install-deps.sh --peers; run it on an idle machine)
#   snakemake -c2 --configfile config/cases/tiny.yaml
#                                 the tiny case (what CI runs, tests/workflow): the pipeline on a tenth
#                                 of a period and the coarse variant of every validation case
#   snakemake -c2 results/validation/<case>/summary.json      one validation case
#   snakemake -c2 -R <rule>       rerun one stage (and what depends on it)
#   snakemake -n                  show what would run (add -p for the commands)
#
# Every rule is in the DAG whether or not its executable is built: a missing one is the output of
# rule missing_executable (rules/common.smk), which fails with one line saying how to build it.
# Every rule lists its executable as an input, so a rebuilt tool reruns its stage.
import os

from snakemake.utils import validate

configfile: os.path.join(workflow.basedir, "config", "config.yaml")
validate(config, "config/config.schema.yaml")

include: "rules/common.smk"
include: "rules/vision.smk"
include: "rules/mesh.smk"
include: "rules/cfd.smk"
include: "rules/fem.smk"
include: "rules/fit.smk"
include: "rules/fsi.smk"
include: "rules/bench.smk"
include: "rules/report.smk"
include: "rules/trout.smk"
include: "rules/calibrate.smk"
include: "rules/footage.smk"
include: "rules/flap.smk"
include: "rules/loop.smk"

# A profile's MPI tasks without a launcher, or on a rule that does not run on ranks: one line, exit 2.
check_mpi_resources(workflow.overwrite_resources)


# A new run of the main job: its progress lines count from here (rules/common.smk, stage_shell).
onstart:
    shell(f"/usr/bin/python3 {SCRIPTS}/stage_progress.py --begin --times results/{config['case']}/benchmarks/stage_times.json")


# The default target: the pipeline on the case, and its validation cases when the case asks for
# them (config validation.in_default_target; the tiny case does).
rule all:
    input:
        STAGE_OUTPUTS,
        validation_targets() + ["results/validation/index.txt"] if config["validation"]["in_default_target"] else [],
    default_target: True


rule validation:
    input:
        validation_targets(),
        "results/validation/index.txt",


rule bench:
    input:
        bench_targets(),
        "results/bench/index.txt",
