# Performance benchmarks against peers measured in the same run (results/bench/<name>.json).
# Peers come from Debian packages installed by tools/scripts/install-deps.sh --peers; a
# benchmark whose peer executable is not built is absent from the DAG.

MPIRUN = "mpirun --oversubscribe --allow-run-as-root" if os.geteuid() == 0 else "mpirun --oversubscribe"

if have("fin-poisson-hypre"):
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
            " {input.ours} {params.sizes} --threads {threads} --peer {output.peer} --json {output.json}"
            " || [ $? -eq 1 ]) > {log} 2>&1"
