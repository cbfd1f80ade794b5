# The front of the pipeline on the case's fin (DESIGN.md section 1): fin-synth renders the virtual
# experiment, fin-track (rules/vision.smk) reconstructs its motion, fin-mesh builds the structural
# and IBM meshes and carries the reconstructed motion (kinematics.h5) onto the mesh nodes; truth.h5
# is only scored against.
#
#   snakemake -c2 results/<case>/motion.h5
#
# Default case: one flapping period. f = St U / A with U = Re nu / c = 0.1 m/s (water;
# core/flow_scales.hpp) and A = 1.0 c, the trailing edge's peak-to-peak excursion
# (fin.strouhal_excursion_over_chord; the root heaves 0.44 c half amplitude), gives f = 4.4 Hz, so
# T = 0.2273 s = 113.6 frames at 500 fps (114 recorded), three 512 x 512 views.
# fin.periods (if the schema has it) records more periods.

_FIN = config["fin"]
_CASE = config["case"]
_OUT = f"results/{_CASE}"
_PERIODS = _FIN["periods"]

# Flags that define the fin, shared by fin-synth and fin-mesh so both build the same template.
_TEMPLATE_FLAGS = (
    f"--chord {_FIN['chord_m']} --height-over-chord {_FIN['height_over_chord']} --rays {_FIN['rays']}"
)


rule synth:
    input:
        exe=EXE("fin-synth"),
    output:
        truth=f"{_OUT}/truth.h5",
        cameras=f"{_OUT}/cameras.yml",
        template=f"{_OUT}/template.json",
        frames=directory(f"{_OUT}/frames"),
    log:
        f"results/logs/{_CASE}/synth.log",
    benchmark:
        stage_benchmark("synth"),
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        flags=(
            f"{_TEMPLATE_FLAGS} --reynolds {_FIN['reynolds']} --strouhal {_FIN['strouhal']}"
            f" --heave-over-chord {_FIN['heave_amplitude_over_chord']}"
            f" --excursion-over-chord {_FIN['strouhal_excursion_over_chord']} --fps {_FIN['fps']}"
            f" --periods {_PERIODS} --views {','.join(_FIN['views'])} --seed {config['seed']}"
        ),
        out=_OUT,
    shell:
        "{input.exe} --out-dir {params.out} {params.flags} --threads {threads} 2> {log}"


rule mesh:
    input:
        exe=EXE("fin-mesh"),
        # The reconstructed motion (rules/vision.smk).
        motion_source=f"{_OUT}/kinematics.h5",
    output:
        mesh=f"{_OUT}/mesh.h5",
        vtu=f"{_OUT}/mesh.vtu",
        motion=f"{_OUT}/motion.h5",
        pvd=f"{_OUT}/motion.pvd",
    log:
        f"results/logs/{_CASE}/mesh.log",
    benchmark:
        stage_benchmark("mesh"),
    threads: THREADS
    resources:
        mem_mb=1000,
    params:
        flags=_TEMPLATE_FLAGS,
    shell:
        "{input.exe} {params.flags} --mesh {output.mesh} --vtu {output.vtu}"
        " --motion-source {input.motion_source} --motion {output.motion} --motion-pvd {output.pvd}"
        " --threads {threads} 2> {log}"

register_stage_output(f"{_OUT}/motion.h5")

register_validation(
    "fin_mesh_quality",
    "fin-mesh on the case's fin: min angle >= 25 deg, area, closed IBM body, <= 5 s",
)

rule validation_fin_mesh_quality:
    input:
        exe=EXE("fin-mesh"),
    output:
        summary="results/validation/fin_mesh_quality/summary.json",
        mesh="results/validation/fin_mesh_quality/mesh.h5",
    log:
        "results/logs/validation/fin_mesh_quality.log",
    threads: 1
    resources:
        mem_mb=500,
    params:
        flags=_TEMPLATE_FLAGS,
    shell:
        "{input.exe} {params.flags} --mesh {output.mesh} --summary {output.summary} --threads {threads} 2> {log}"
