# Validation cases of the incompressible Navier-Stokes solver (DESIGN.md sections 5.1 and 6), run by
# fin-cfd:
#
#   snakemake -c2 results/validation/taylor_green/summary.json
#   snakemake -c2 results/validation/channel/summary.json
#
# A missed metric is recorded in summary.json and makes fin-cfd exit 1, which the rules accept
# (`|| [ $? -eq 1 ]`); only real errors (exit 2) fail a rule. validation.coarse selects the CI
# variants (coarser grids, fewer time steps). OpenMP threads wait passively: on a shared, busy
# machine spinning threads steal the cores that do the work (measured: 128^2 Taylor-Green, 2
# threads at load 12, 7.0 s wall spinning vs 1.1 s passive).

if have("fin-cfd"):
    register_validation("taylor_green", "2-D Taylor-Green vortex: observed order of accuracy in space and time")
    register_validation("channel", "inlet/outlet channel: developed Poiseuille profile and pressure gradient")

    rule validation_taylor_green:
        input:
            exe=EXE("fin-cfd"),
        output:
            "results/validation/taylor_green/summary.json",
        log:
            "results/logs/validation/taylor_green.log",
        threads: THREADS
        resources:
            mem_mb=300,
        params:
            flags="--coarse" if COARSE else "",
        shell:
            "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} --out-dir results/validation {params.flags}"
            " taylor_green > {log} 2>&1 || [ $? -eq 1 ]"

    rule validation_channel:
        input:
            exe=EXE("fin-cfd"),
        output:
            summary="results/validation/channel/summary.json",
            checkpoint="results/validation/channel/checkpoint.h5",
            pvd="results/validation/channel/flow.pvd",
        log:
            "results/logs/validation/channel.log",
        threads: THREADS
        resources:
            mem_mb=300,
        params:
            flags="--coarse" if COARSE else "",
        shell:
            "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads {threads} --out-dir results/validation {params.flags}"
            " channel --checkpoint-every 100 --vtk > {log} 2>&1 || [ $? -eq 1 ]"
