# The front of the pipeline on the case's fin (DESIGN.md section 1): fin-synth renders the virtual
# experiment, fin-track (rules/vision.smk) reconstructs its motion, fin-mesh builds the structural
# and IBM meshes and carries the reconstructed motion (kinematics.h5) onto the mesh nodes; truth.h5
# is only scored against.
#
#   snakemake -c2 results/<case>/motion.h5
#
# The truth's motion (config truth.source, issue 33): fsi runs fin-fsi fin on its own truth mesh
# (results/<case>/truth/mesh.h5, the case's template) with the known materials (truth.materials)
# and the root drive truth.root_drive (St and A from fin:), and fin-synth renders that motion and
# records the materials and drive in truth.h5; prescribed renders the prescribed kinematics.
# truth.effects (issue 34): candidate effects planted in the truth structure (truth_effects).
#
# Default case: one flapping period. f = St U / A with U = Re nu / c = 0.1 m/s (water;
# core/flow_scales.hpp) and A = 1.0 c, the trailing edge's peak-to-peak excursion
# (fin.strouhal_excursion_over_chord; the root heaves 0.44 c half amplitude), gives f = 4.4 Hz, so
# T = 0.2273 s = 113.6 frames at 500 fps (114 recorded), three 512 x 512 views.
# fin.periods (if the schema has it) records more periods.

import json

_FIN = config["fin"]
_CASE = config["case"]
_OUT = f"results/{_CASE}"
_PERIODS = _FIN["periods"]

# Flags that define the fin, shared by fin-synth and fin-mesh so both build the same template.
_TEMPLATE_FLAGS = (
    f"--chord {_FIN['chord_m']} --height-over-chord {_FIN['height_over_chord']} --rays {_FIN['rays']}"
)


_TRUTH = config["truth"]
_TRUTH_OUT = f"{_OUT}/truth"
_TRUTH_FSI = _TRUTH["source"] == "fsi"
# Planted candidate effects (issue 34, tools/fem/effects): the truth FSI's structure runs with
# them and truth.h5 records them (fin-synth reads them back from fsi.h5). The prescribed
# kinematics has no structure for them to act on, and fin-synth binds the truth surface to the
# flat rest mesh, so a rest-shape effect cannot be rendered yet: both are refused here, not ignored.
_TRUTH_EFFECTS = _TRUTH.get("effects", [])
if _TRUTH_EFFECTS and not _TRUTH_FSI:
    raise ValueError("config truth.effects: planted effects need truth.source fsi (the prescribed kinematics has no structure)")
if any(e.get("name") == "cupped_rest_shape" for e in _TRUTH_EFFECTS):
    raise ValueError("config truth.effects: cupped_rest_shape changes the truth's rest shape, which fin-synth cannot render yet")


rule truth_mesh:
    input:
        exe=EXE("fin-mesh"),
    output:
        mesh=f"{_TRUTH_OUT}/mesh.h5",
        vtu=f"{_TRUTH_OUT}/mesh.vtu",
    log:
        f"results/logs/{_CASE}/truth_mesh.log",
    threads: 1
    resources:
        mem_mb=500,
    params:
        flags=_TEMPLATE_FLAGS,
    shell:
        "{input.exe} {params.flags} --mesh {output.mesh} --vtu {output.vtu} --threads {threads} 2> {log}"


def _truth_drive():
    """drive.json of the truth FSI (fem/io/root_drive_file.hpp): truth.root_drive, St and A from fin."""
    d = dict(_TRUTH["root_drive"])
    d["strouhal"] = _FIN["strouhal"]
    d["excursion_over_chord"] = _FIN["strouhal_excursion_over_chord"]
    return d


rule truth_drive:
    output:
        f"{_TRUTH_OUT}/drive.json",
    params:
        drive=_truth_drive(),
    run:
        with open(output[0] + ".tmp", "w") as f:
            json.dump(params.drive, f, indent=2, sort_keys=True)
            f.write("\n")
        os.replace(output[0] + ".tmp", output[0])


rule truth_effects:
    """effects.json of the truth FSI, checked by fin-fem (unknown name or range: one line, exit 2)."""
    input:
        exe=EXE("fin-fem"),
    output:
        f"{_TRUTH_OUT}/effects.json",
    log:
        f"results/logs/{_CASE}/truth_effects.log",
    params:
        effects=_TRUTH_EFFECTS,
    run:
        with open(output[0] + ".tmp", "w") as f:
            json.dump(params.effects, f, indent=2, sort_keys=True)
            f.write("\n")
        shell("{input.exe} effects --check {output}.tmp > /dev/null 2> {log}")
        os.replace(output[0] + ".tmp", output[0])


def _truth_fsi_inputs(wildcards):
    inputs = {
        "exe": EXE("fin-fsi"),
        "mesh": f"{_TRUTH_OUT}/mesh.h5",
        "drive": f"{_TRUTH_OUT}/drive.json",
        "materials": os.path.join(REPO, _TRUTH["materials"]),
    }
    if _TRUTH_EFFECTS:  # without effects the rule stays as it was (no rerun of a 25-min truth)
        inputs["effects"] = f"{_TRUTH_OUT}/effects.json"
    return inputs


rule truth_fsi:
    input:
        unpack(_truth_fsi_inputs),
    output:
        fsi=f"{_TRUTH_OUT}/fsi.h5",
        summary=f"{_TRUTH_OUT}/fsi_summary.json",
    log:
        f"results/logs/{_CASE}/truth_fsi.log",
    benchmark:
        stage_benchmark("truth"),
    threads: THREADS
    resources:
        mem_mb=2000,
    params:
        # A checkpoint every 50 steps beside fsi.h5 (fsi.checkpoint.h5): a stopped truth continues with
        # fin-fsi fin ... --restart results/<case>/truth/fsi.checkpoint.h5 (tools/fsi/coupled_run.hpp).
        flags=f"--reynolds {_FIN['reynolds']} {_TRUTH['flags']}"
        + (f" --effects {_TRUTH_OUT}/effects.json" if _TRUTH_EFFECTS else ""),
        launch=mpi_launch,  # the flow's solves on MPI ranks where the profile says (as the fsi stage)
    shell:
        # A short spin before the threads sleep: the structure's serial work between the flow's
        # parallel loops made the sleeping threads' wake-ups cost the truth 26 % (default_case.md).
        stage_shell(
            "truth",
            "OMP_WAIT_POLICY=PASSIVE GOMP_SPINCOUNT=10000 {params.launch} {input.exe} --threads {threads} fin --mesh {input.mesh} --materials {input.materials}"
            " --root-drive {input.drive} --out {output.fsi} --summary {output.summary} --checkpoint-every 50"
            " {params.flags} 2> {log}",
        )


def _synth_inputs(wildcards):
    inputs = {"exe": EXE("fin-synth")}
    if _TRUTH_FSI:
        inputs.update(
            fsi=f"{_TRUTH_OUT}/fsi.h5",
            fsi_mesh=f"{_TRUTH_OUT}/mesh.h5",
            drive=f"{_TRUTH_OUT}/drive.json",
            materials=os.path.join(REPO, _TRUTH["materials"]),
        )
    return inputs


# The motion's flags: the FSI truth's files, or the prescribed kinematics' own.
_SYNTH_MOTION_FLAGS = (
    "--motion-source fsi --fsi {input.fsi} --fsi-mesh {input.fsi_mesh} --materials {input.materials}"
    " --root-drive {input.drive}"
    if _TRUTH_FSI
    else f"--motion-source prescribed --strouhal {_FIN['strouhal']} --heave-over-chord {_FIN['heave_amplitude_over_chord']}"
    f" --excursion-over-chord {_FIN['strouhal_excursion_over_chord']}"
)


rule synth:
    input:
        unpack(_synth_inputs),
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
            f"{_TEMPLATE_FLAGS} --reynolds {_FIN['reynolds']} --fps {_FIN['fps']}"
            f" --periods {_PERIODS} --views {','.join(_FIN['views'])} --seed {config['seed']}"
        ),
        out=_OUT,
    shell:
        stage_shell(
            "synth",
            "{input.exe} --out-dir {params.out} {params.flags} " + _SYNTH_MOTION_FLAGS + " --threads {threads} 2> {log}",
        )


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
        flags=_TEMPLATE_FLAGS + (" " + config["mesh"]["flags"] if config["mesh"]["flags"] else ""),
    shell:
        stage_shell(
            "mesh",
            "{input.exe} {params.flags} --mesh {output.mesh} --vtu {output.vtu}"
            " --motion-source {input.motion_source} --motion {output.motion} --motion-pvd {output.pvd}"
            " --threads {threads} 2> {log}",
        )

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
