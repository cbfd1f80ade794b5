# The table of every validation summary in the run (tools/scripts/summary.py prints it).


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
