# finverse workflow (DESIGN.md section 1): frames -> kinematics -> mesh -> loads -> materials
# -> coupled FSI -> report, plus the validation cases and benchmarks of every stage.
#
#   snakemake -c2                                   default case (config/config.yaml)
#   snakemake -c2 --configfile config/cases/tiny.yaml
#   snakemake -c2 -R <rule>                         rerun one stage (and what depends on it)
#   snakemake -c2 results/validation/<case>/summary.json
#   snakemake -n                                    show what would run
#
# A stage appears in the DAG only once its executable exists in the build; no rule stands in
# for a computation that is not implemented. Every rule lists its executable as an input, so a
# rebuilt tool reruns its stage.
import os

from snakemake.utils import validate

configfile: os.path.join(workflow.basedir, "config", "config.yaml")
validate(config, "config/config.schema.yaml")

include: "rules/common.smk"
for _area in ["fem", "cfd", "mesh", "vision", "fit", "fsi"]:
    if os.path.exists(os.path.join(workflow.basedir, "rules", _area + ".smk")):
        include: os.path.join("rules", _area + ".smk")
include: "rules/bench.smk"
include: "rules/report.smk"


rule all:
    input:
        STAGE_OUTPUTS,
        validation_targets(),
        bench_targets(),
        "results/validation/index.txt" if validation_targets() else [],
    default_target: True
