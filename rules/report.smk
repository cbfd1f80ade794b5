# The report of the case (issue 33 "Deliver" 3): fin-report grades the scores its stage files
# allow and writes the figure data; tools/scripts/report_figures.py draws the paper's figures and
# index.html (opens from disk). fsi.h5 is read when the pipeline has a stage that writes it;
# without it the FSI scores say "not available".
#
#   snakemake -c2 results/<case>/report/index.html
#
# And the table of every validation summary in the run (tools/scripts/summary.py prints it).

import shlex

_REPORT_OUT = f"results/{config['case']}"


def _report_stage_inputs(wildcards):
    stages = {s: f"{_REPORT_OUT}/{s}.h5" for s in ("truth", "kinematics", "mesh", "motion", "loads", "materials")}
    if f"{_REPORT_OUT}/fsi.h5" in STAGE_OUTPUTS:
        stages["fsi"] = f"{_REPORT_OUT}/fsi.h5"
    return stages


rule report:
    input:
        unpack(_report_stage_inputs),
        exe=EXE("fin-report"),
        script=os.path.join(SCRIPTS, "report_figures.py"),
        # Used only when truth.h5 records no materials (a prescribed truth): the case's intended truth.
        truth_materials=os.path.join(REPO, config["truth"]["materials"]),
    output:
        index=f"{_REPORT_OUT}/report/index.html",
        summary=f"{_REPORT_OUT}/report/summary.json",
        figures=f"{_REPORT_OUT}/report/figures.json",
    log:
        f"results/logs/{config['case']}/report.log",
    benchmark:
        stage_benchmark("report"),
    threads: 1
    resources:
        mem_mb=1000,
    params:
        out=f"{_REPORT_OUT}/report",
        fsi=lambda wildcards, input: f"--fsi {input.fsi}" if "fsi" in input.keys() else "",
        # What the case's scores can test (config report.scope), quoted for the shell.
        scope=(lambda s: f"--scope {shlex.quote(s)}" if s else "")(config.get("report", {}).get("scope", "")),
    shell:
        stage_shell(
            "report",
            "{input.exe} --case {config[case]} --truth {input.truth} --kinematics {input.kinematics}"
            " --mesh {input.mesh} --motion {input.motion} --loads {input.loads} --materials {input.materials}"
            " --truth-materials {input.truth_materials} {params.fsi} {params.scope} --out-dir {params.out} 2> {log}"
            " && /usr/bin/python3 {input.script} {params.out} 2>> {log}",
        )

register_stage_output(f"{_REPORT_OUT}/report/index.html")



rule validation_index:
    input:
        summaries=validation_targets(),
        script=os.path.join(SCRIPTS, "summary.py"),
    output:
        "results/validation/index.txt",
    log:
        "results/logs/validation_index.log",
    threads: 1
    resources:
        mem_mb=200,
    shell:
        "python3 {input.script} --no-fail {input.summaries} > {output}.tmp 2> {log} && mv {output}.tmp {output}"


rule bench_index:
    input:
        summaries=bench_targets(),
        script=os.path.join(SCRIPTS, "summary.py"),
    output:
        "results/bench/index.txt",
    log:
        "results/logs/bench_index.log",
    threads: 1
    resources:
        mem_mb=200,
    shell:
        "python3 {input.script} --no-fail {input.summaries} > {output}.tmp 2> {log} && mv {output}.tmp {output}"
