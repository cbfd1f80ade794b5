# fin-calibrate in the DAG (issue 35 item 2): the validation of a lab's own rig calibration.
#
#   snakemake -c2 results/validation/footage_calibration/summary.json
#
# fin-synth's rig (the cameras its frames are rendered through, written with one frame) is the
# truth. fin-calibrate simulate renders a checkerboard recording through it (board poses aimed at
# every camera, every pair and the whole rig; seeded noise), fin-calibrate checkerboard calibrates
# the rig back from the images alone, and fin-calibrate score compares it with the truth
# (reprojection <= 0.2 px, camera centre <= 0.5 mm, rotation <= 0.1 deg) and checks that the rig
# written as DLTdv coefficients and as Anipose's calibration.toml imports to the same cameras.
# COARSE: fewer poses, 2x2 instead of 4x4 anti-aliasing rays per pixel.

_CFIN = config["fin"]
_CV = "results/validation/footage_calibration"
_C_VIEWS = "side,back,ventral"
_C_POSES = 28 if COARSE else 63
_C_SUPERSAMPLE = 2 if COARSE else 4

register_validation(
    "footage_calibration",
    "fin-calibrate on a checkerboard recording simulated through fin-synth's rig: <= 0.2 px, 0.5 mm, 0.1 deg; DLTdv/Anipose imports",
)


rule validation_footage_calibration_rig:
    input:
        exe=EXE("fin-synth"),
    output:
        cameras=f"{_CV}/rig/cameras.yml",
    log:
        "results/logs/validation/footage_calibration_rig.log",
    threads: 1
    resources:
        mem_mb=500,
    params:
        # One frame is enough: only the rig's cameras.yml is used.
        flags=f"--chord {_CFIN['chord_m']} --height-over-chord {_CFIN['height_over_chord']} --rays {_CFIN['rays']}"
        f" --views {_C_VIEWS} --fps {_CFIN['fps']} --periods 0.02 --vtk false",
        out=f"{_CV}/rig",
    shell:
        "{input.exe} --out-dir {params.out} {params.flags} --threads {threads} 2> {log}"


rule validation_footage_calibration:
    input:
        exe=EXE("fin-calibrate"),
        rig=f"{_CV}/rig/cameras.yml",
    output:
        summary=f"{_CV}/summary.json",
        cameras=f"{_CV}/calibrated/cameras.yml",
        report=f"{_CV}/calibrated/report.json",
    log:
        "results/logs/validation/footage_calibration.log",
    threads: 1
    resources:
        mem_mb=1500,
    params:
        rec=f"{_CV}/recording",
        sim=f"--poses {_C_POSES} --supersample {_C_SUPERSAMPLE} --max-tilt-deg 50 --board-fraction 0.6 --seed {config['seed']}",
        views=" ".join(f"--view {v}={_CV}/recording/{v}" for v in _C_VIEWS.split(",")),
    shell:
        "({input.exe} simulate --cameras {input.rig} --out-dir {params.rec} {params.sim}"
        " && {input.exe} checkerboard {params.views} --board-file {params.rec}/board.json"
        "  --out {output.cameras} --report {output.report}"
        " && ({input.exe} score --truth {input.rig} --cameras {output.cameras} --report {output.report}"
        "  --summary {output.summary} " + METRIC_MISSED_IS_A_RESULT + ")) 2> {log}"
