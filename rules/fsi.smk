# Validation cases of the coupled flow-structure interaction (DESIGN.md section 5.3, issue 32), run
# by fin-fsi: the Turek-Hron FSI benchmarks with the implicit partitioned coupling.
#
#   snakemake -c2 results/validation/fsi_turek_hron_fsi1/summary.json
#   snakemake -c2 results/validation/fsi_turek_hron_fsi3/summary.json
#
# Each writes summary.json and fsi.h5 (schema finverse/fsi) into results/validation/<case>/. A
# missed metric is recorded in summary.json and makes fin-fsi exit 1, a result and not a failed
# job (METRIC_MISSED_IS_A_RESULT, rules/common.smk). Costs and numbers: docs/studies/fsi_turek_hron.md.

_FSI_REFERENCE = os.path.join(REPO, "data", "reference", "turek_hron.json")

# case -> (description, flags of the full case, flags of the coarse one). The coarse FSI2 / FSI3
# runs cover only the start of the inflow ramp (no full period: `missing_periods` misses); they check
# that the coupled run goes and converges, in under a minute. The full ones run on one core for
# about 5 min of CPU (FSI1, D/16 box + D/32 core), 30 min (FSI3, D/16, 10 s) and 10 min (FSI2,
# D/16, 15 s). FSI2 and FSI3 need dt = 0.3 h / U_max at D/16: at 0.5 the flow blows up (FSI3 at
# t = 1.77 s, with the flag rigid too; FSI2 at 2.48 s; docs/studies/fsi_turek_hron.md).
_FSI_CASES = {
    "fsi_turek_hron_fsi1": ("Turek-Hron FSI1: steady flag deflection at Re 20, coupled",
                            "--case FSI1 --cells-per-diameter 16 --core-cells-per-diameter 32"
                            " --wall-stretch-ratio 0.98 --t-end 8 --output-every 20",
                            "--case FSI1 --cells-per-diameter 16 --t-end 3 --output-every 20"),
    "fsi_turek_hron_fsi2": ("Turek-Hron FSI2: flag flapping at Re 100, rho_s/rho_f = 10, coupled",
                            "--case FSI2 --cells-per-diameter 16 --cfl 0.3 --t-end 15 --output-every 10",
                            "--case FSI2 --cells-per-diameter 16 --cfl 0.3 --t-end 0.5 --output-every 10"),
    "fsi_turek_hron_fsi3": ("Turek-Hron FSI3: flag flapping at Re 200, rho_s/rho_f = 1, coupled",
                            "--case FSI3 --cells-per-diameter 16 --cfl 0.3 --t-end 10 --output-every 10",
                            "--case FSI3 --cells-per-diameter 16 --cfl 0.3 --t-end 0.3 --output-every 10"),
    # The flag's wet surface as a zero-thickness sheet beside the ghost-cell cylinder (issue 44,
    # goal 6, D/20; docs/studies/thin_surface.md, "Goal 6"): 4.5 min (FSI2) and 6 min (FSI3) of CPU;
    # the closed flag at D/20 takes 15 and 27 min. Measured there: the sheet is the better flag for
    # FSI2, the closed one for FSI3.
    "fsi_turek_hron_fsi2_sheet": ("Turek-Hron FSI2 with the flag as a sheet (no cell changes kind), coupled",
                                  "--case FSI2 --surface sheet --cells-per-diameter 20 --cfl 0.3 --t-end 15"
                                  " --output-every 10",
                                  "--case FSI2 --surface sheet --cells-per-diameter 16 --cfl 0.3 --t-end 0.5"
                                  " --output-every 10"),
    "fsi_turek_hron_fsi3_sheet": ("Turek-Hron FSI3 with the flag as a sheet (no cell changes kind), coupled",
                                  "--case FSI3 --surface sheet --cells-per-diameter 20 --cfl 0.3 --t-end 10"
                                  " --output-every 10",
                                  "--case FSI3 --surface sheet --cells-per-diameter 16 --cfl 0.3 --t-end 0.3"
                                  " --output-every 10"),
}

for _case, (_description, _full, _coarse) in _FSI_CASES.items():
    register_validation(_case, _description)


rule validation_fsi:
    input:
        exe=EXE("fin-fsi"),
        reference=_FSI_REFERENCE,
    output:
        summary="results/validation/{case}/summary.json",
        fsi="results/validation/{case}/fsi.h5",
    wildcard_constraints:
        case="|".join(_FSI_CASES),
    log:
        "results/logs/validation/{case}.log",
    threads: 1
    resources:
        mem_mb=500,
    params:
        flags=lambda wildcards: _FSI_CASES[wildcards.case][2 if COARSE else 1],
    shell:
        "{input.exe} --threads {threads} turek_hron {params.flags} --acceleration iqn-ils"
        " --reference {input.reference} --summary {output.summary} --out {output.fsi}"
        " > {log} 2>&1 " + METRIC_MISSED_IS_A_RESULT


# The 3-D flexible plate pitching about its leading edge (seed paper sec. 3.2; issue 32, validation
# 3): every K in one run and one summary.json (A/L, phase, stiff limit, resonance against the modal
# estimate). Full: L/16, 100 steps per period, 4 periods, about 4 min of one core per K (7 runs with
# the rigid one); coarse (CI): L/8, 24 steps per period, 2 periods, three K, well under a minute.
# Numbers: docs/studies/fsi_pitching_plate.md.
register_validation("fsi_pitching_plate", "Flexible plate pitching in a stream, K = 0.5..50, coupled 3-D")

rule validation_fsi_pitching_plate:
    input:
        exe=EXE("fin-fsi"),
    output:
        summary="results/validation/fsi_pitching_plate/summary.json",
    log:
        "results/logs/validation/fsi_pitching_plate.log",
    threads: 1
    resources:
        mem_mb=1000,
    params:
        flags=("--K 0.5,2,50 --cells-per-chord 8 --steps-per-period 24 --periods 2 --downstream 1.5"
               " --half-height 1 --half-width 1.5" if COARSE
               else "--K 0.5,1,2,4,10,50 --periods 4"),
    shell:
        "{input.exe} --threads {threads} pitching_plate {params.flags} --rigid"
        " --summary {output.summary} > {log} 2>&1 " + METRIC_MISSED_IS_A_RESULT


# The pipeline's FSI stage (issue 33): the fin coupled with the FITTED materials (materials.h5 over
# the base materials fin-fit started from), driven at the root by the RECONSTRUCTED motion
# (motion.h5, each ray's root rotation fitted per ray), so fin-report grades FSI against the
# reconstruction. Flags: config fsi.flags (grid, periods; docs/studies/fin_fsi.md sizes them).
_FSI_STAGE = config["fsi"]
_FSI_OUT = f"results/{config['case']}"


rule fsi:
    input:
        exe=EXE("fin-fsi"),
        mesh=f"{_FSI_OUT}/mesh.h5",
        motion=f"{_FSI_OUT}/motion.h5",
        materials=f"{_FSI_OUT}/materials.h5",
        base=os.path.join(REPO, config["fit"]["materials"]),
    output:
        fsi=f"{_FSI_OUT}/fsi.h5",
        summary=f"{_FSI_OUT}/fsi_summary.json",
    log:
        f"results/logs/{config['case']}/fsi.log",
    benchmark:
        stage_benchmark("fsi"),
    threads: THREADS
    resources:
        mem_mb=2000,
    params:
        flags=_FSI_STAGE["flags"],
        launch=mpi_launch,  # the flow's pressure and momentum solves on MPI ranks where the profile says
    shell:
        # A short spin before the threads sleep: the structure's serial work between the flow's
        # parallel loops made the sleeping threads' wake-ups cost the truth 26 % (default_case.md).
        stage_shell(
            "fsi",
            "OMP_WAIT_POLICY=PASSIVE GOMP_SPINCOUNT=10000 {params.launch} {input.exe} --threads {threads} fin --mesh {input.mesh} --motion {input.motion}"
            " --materials {input.materials} --base-materials {input.base} --out {output.fsi}"
            " --summary {output.summary} --checkpoint-every 50 {params.flags} 2> {log}",
        )

register_stage_output(f"{_FSI_OUT}/fsi.h5")
