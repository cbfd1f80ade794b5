# Issue 34, validation 1: the loop on virtual fish with an undeclared effect. One dataset per
# config/loop/loop_<name>.yaml (truth.effects: the planted effects, possibly none); every dataset
# runs the same command, which never depends on what was planted:
#
#   snakemake -c2 results/validation/loop_<name>/summary.json
#
# truth (structure only, not the 25-min FSI): fin-fem run quasi-static (truth.analysis: dynamic,
# a dynamic run: see below) on the case's fin under the analytic root drive and the quasi-steady loads of fin-fem loads (resistive + added mass,
# tools/fem/io/quasi_steady_loads.hpp), with the planted effects, over 2 periods after a one-period
# ramp -> fin-synth --motion-source fem renders 2 periods at 20 frames per period with the tracking
# validation's sensor (noise sigma 2, 3 blur sub-frames over the same 0.3 ms shutter) -> fin-track
# -> fin-mesh -> fin-loop trace on the reconstruction, given the same load model on its own mesh
# as its "measured loads". The grader (tools/scripts/loop_scores.py) alone reads truth.h5.
# A dynamic dataset's truth and trace both run fin-fem's dynamic analysis at 8 sub-steps per frame
# (generalized-alpha, rho_inf 0.5), and both carry the fin tissue's Kelvin-Voigt damping that
# data/cases/loop_start_materials.json declares ("rayleigh"): the trace's model runs are dynamic
# where the data are (issue 45, deliverable 2). Below about 4 % of critical at the beat the
# undamped fin's generalized-alpha run blows up at 8 sub-steps (docs/studies/fin_dynamic_run.md).
# Study: docs/studies/loop_virtual_fish.md. Hours of CPU in all: not in the coarse (tiny) set.

import glob
import json
import re

import yaml

_LFIN = config["fin"]
_LOOP_DIR = os.path.join(REPO, "config", "loop")
_LOOP_CASES = sorted(os.path.basename(p)[:-5] for p in glob.glob(os.path.join(_LOOP_DIR, "loop_*.yaml")))
_L_TEMPLATE = f"--chord {_LFIN['chord_m']} --height-over-chord {_LFIN['height_over_chord']} --rays {_LFIN['rays']}"
# f = St U / (A c), U = Re nu / c (water), as fin-synth and fin-fsi compute it.
_L_SPEED = _LFIN["reynolds"] * 1e-6 / _LFIN["chord_m"]
_L_FREQ = _LFIN["strouhal"] * _L_SPEED / (_LFIN["strouhal_excursion_over_chord"] * _LFIN["chord_m"])
_L_FPP = 32  # frames per period (camera, loads and truth): at 16 fin-track lost the fin between frames
_L_PERIODS = 2  # periods of truth and loads; the camera records 2.02 (65 frames: the trace holds the last cycle out)
# The structural mesh at c/12.5 edges (523 nodes, not fin-mesh's default c/25 with 1241): a
# quasi-static model run of the 65 frames costs ~16 s CPU, and the trace makes ~60 of them.
_L_MESH = "--max-edge 0.08"
# Quasi-steady loads 4x the strip-theory estimate: peak lateral force 7 mN, the FSI truth's order
# (C_L ~ 8 on the default motion, docs/studies/fin_kinematics_and_force_size.md).
_L_LOADS = f"--periods {_L_PERIODS} --frames-per-period {_L_FPP} --reynolds {_LFIN['reynolds']} --scale 4"
_L_FPS = _L_FPP * _L_FREQ
# The tracking validation's sensor (rules/vision.smk): sigma 2, 3 blur sub-frames over 15 % of a
# 500 fps frame interval = 0.3 ms, here the same shutter time at the lower frame rate.
_L_NOISY = f"--blur-samples 3 --exposure {0.15 * _L_FPS / 500:.6g} --noise-sigma 2"
# The fit: membrane and the two edge rays (the stiffest, whose bending carries the edges), from
# data/cases/loop_start_materials.json; the candidates of config/loop/candidates.json.
_L_PARAMETERS = "E_membrane,E_ray1,E_ray20"
# Root rotations per ray from the reconstruction (the drive pitches each ray's root): with one
# fitted rotation the model missed the control's truth by 4 % c RMS at the trailing edge, per ray by 0.85 % c.
# The drive is read through 2 harmonics of the beat, which drops the tracking's frame-to-frame noise
# from the root tangents: the control's refitted trailing edge 83 -> 68 um, nothing added; refitting
# the drive itself soaked up the planted root curvature (docs/studies/loop_virtual_fish.md, session 40).
_L_TRACE = (f"--parameters {_L_PARAMETERS} --frequency {_L_FREQ:.9g} --period {1 / _L_FREQ:.9g} --lm-evaluations 12"
            " --root-rotation per_ray --drive-harmonics 2")
_L_DYNAMIC = "--substeps 8 --rho-inf 0.5"  # fin-fem run's flags of a dynamic truth; the trace's below
_L_TRACE_DYNAMIC = "--analysis dynamic --substeps 8 --spectral-radius 0.5"
_L_START_MATERIALS = os.path.join(REPO, "data", "cases", "loop_start_materials.json")

if not COARSE:
    for _name in _LOOP_CASES:
        register_validation(_name, "fin-loop on a virtual fish (config/loop/" + _name + ".yaml): planted effect "
                            "ranked first and added, TE residual cut >= 5x, refitted moduli within 5 %; control: none added")


def _loop_truth(name):
    path = os.path.join(_LOOP_DIR, name + ".yaml")
    with open(path) as f:
        case = yaml.safe_load(f) or {}
    return path, case.get("truth") or {}


def _loop_case(name):
    path, truth = _loop_truth(name)
    effects = truth.get("effects") or []
    if not isinstance(effects, list):
        raise ValueError(f"{path}: truth.effects: expected a list of effect specs")
    return effects


def _loop_dynamic(name):
    """True for a dataset whose truth.analysis is dynamic (default quasi_static)."""
    path, truth = _loop_truth(name)
    analysis = truth.get("analysis", "quasi_static")
    if analysis not in ("quasi_static", "dynamic"):
        raise ValueError(f"{path}: truth.analysis: expected quasi_static or dynamic, got {analysis!r}")
    return analysis == "dynamic"


def _loop_truth_materials(name):
    """The truth's materials: the case's, plus for a dynamic dataset the tissue damping that the
    trace's start materials declare (the fit knows it; a planted damping comes on top of it)."""
    with open(os.path.join(REPO, config["truth"]["materials"])) as f:
        materials = json.load(f)
    if _loop_dynamic(name):
        with open(_L_START_MATERIALS) as f:
            materials["rayleigh"] = json.load(f)["rayleigh"]
    return materials


# Only the datasets of config/loop/ (results/validation/loop_hessenthaler is rules/flap.smk's).
wildcard_constraints:
    loop="|".join(re.escape(n) for n in _LOOP_CASES) or "no_loop_dataset",


rule loop_truth_inputs:
    """drive.json (frequency given: a structural run has no flow speed) and the planted effects, checked by fin-fem."""
    input:
        exe=EXE("fin-fem"),
        case=os.path.join(_LOOP_DIR, "{loop}.yaml"),
        materials=os.path.join(REPO, config["truth"]["materials"]),
        start=_L_START_MATERIALS,
    output:
        drive="results/validation/{loop}/truth/drive.json",
        effects="results/validation/{loop}/truth/effects.json",
        materials="results/validation/{loop}/truth/materials.json",
    log:
        "results/logs/validation/{loop}/truth_inputs.log",
    run:
        drive = dict(config["truth"]["root_drive"], frequency_hz=_L_FREQ, ramp_periods=1)
        materials = _loop_truth_materials(wildcards.loop)
        for path, data in ((output.drive, drive), (output.effects, _loop_case(wildcards.loop)),
                           (output.materials, materials)):
            with open(path + ".tmp", "w") as f:
                json.dump(data, f, indent=2, sort_keys=True)
                f.write("\n")
        shell("{input.exe} effects --check {output.effects}.tmp > /dev/null 2> {log}")
        os.replace(output.drive + ".tmp", output.drive)
        os.replace(output.effects + ".tmp", output.effects)
        os.replace(output.materials + ".tmp", output.materials)


rule loop_truth:
    input:
        mesher=EXE("fin-mesh"),
        fem=EXE("fin-fem"),
        drive="results/validation/{loop}/truth/drive.json",
        effects="results/validation/{loop}/truth/effects.json",
        materials="results/validation/{loop}/truth/materials.json",
    output:
        mesh="results/validation/{loop}/truth/mesh.h5",
        loads="results/validation/{loop}/truth/loads.h5",
        motion="results/validation/{loop}/truth/motion.h5",
    log:
        "results/logs/validation/{loop}/truth.log",
    threads: 1
    resources:
        mem_mb=1500,
    params:
        template=f"{_L_TEMPLATE} {_L_MESH}",
        times=_L_LOADS,
        analysis=lambda w: f"dynamic {_L_DYNAMIC}" if _loop_dynamic(w.loop) else "quasi_static",
    shell:
        "({input.mesher} {params.template} --mesh {output.mesh} --threads 1"
        " && {input.fem} loads --mesh {output.mesh} --root-drive {input.drive} --start-periods 1 {params.times}"
        "  --out {output.loads}"
        " && {input.fem} --threads {threads} run --analysis {params.analysis} --mesh {output.mesh} --materials {input.materials}"
        "  --root-drive {input.drive} --loads {output.loads} --effects {input.effects} --out {output.motion}) 2> {log}"


rule loop_synth:
    input:
        exe=EXE("fin-synth"),
        mesh="results/validation/{loop}/truth/mesh.h5",
        motion="results/validation/{loop}/truth/motion.h5",
        drive="results/validation/{loop}/truth/drive.json",
        materials="results/validation/{loop}/truth/materials.json",
    output:
        truth="results/validation/{loop}/synth/truth.h5",
        cameras="results/validation/{loop}/synth/cameras.yml",
        frames=directory("results/validation/{loop}/synth/frames"),
    log:
        "results/logs/validation/{loop}/synth.log",
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        flags=f"{_L_TEMPLATE} --reynolds {_LFIN['reynolds']} --fps {_L_FPS:.9g} --periods {_L_PERIODS + 0.02}"
        f" --seed {config['seed']} {_L_NOISY} --vtk false",
        out="results/validation/{loop}/synth",
    shell:
        "{input.exe} --out-dir {params.out} {params.flags} --motion-source fem --fem {input.motion}"
        " --fsi-mesh {input.mesh} --materials {input.materials} --root-drive {input.drive} --threads {threads} 2> {log}"


rule loop_reconstruct:
    input:
        track=EXE("fin-track"),
        mesher=EXE("fin-mesh"),
        fem=EXE("fin-fem"),
        frames="results/validation/{loop}/synth/frames",
        cameras="results/validation/{loop}/synth/cameras.yml",
        drive="results/validation/{loop}/truth/drive.json",
    output:
        kinematics="results/validation/{loop}/kinematics.h5",
        mesh="results/validation/{loop}/mesh.h5",
        motion="results/validation/{loop}/motion.h5",
        loads="results/validation/{loop}/loads.h5",
    log:
        "results/logs/validation/{loop}/reconstruct.log",
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        template=_L_TEMPLATE,
        mesh=_L_MESH,
        fps=f"{_L_FPS:.9g}",
        times=_L_LOADS,
        vtu="results/validation/{loop}/mesh.vtu",
        pvd="results/validation/{loop}/motion.pvd",
    shell:
        "({input.track} {params.template} --fps {params.fps} --frames {input.frames} --cameras {input.cameras}"
        "  --out {output.kinematics} --threads {threads}"
        " && {input.mesher} {params.template} {params.mesh} --mesh {output.mesh} --vtu {params.vtu}"
        "  --motion-source {output.kinematics} --motion {output.motion} --motion-pvd {params.pvd} --threads {threads}"
        " && {input.fem} loads --mesh {output.mesh} --root-drive {input.drive} --start-periods 0 {params.times}"
        "  --out {output.loads}) 2> {log}"


rule loop_trace:
    input:
        exe=EXE("fin-loop"),
        mesh="results/validation/{loop}/mesh.h5",
        motion="results/validation/{loop}/motion.h5",
        loads="results/validation/{loop}/loads.h5",
        materials=_L_START_MATERIALS,
        candidates=os.path.join(_LOOP_DIR, "candidates.json"),
    output:
        base="results/validation/{loop}/base.json",
        loop="results/validation/{loop}/loop.h5",
        summary="results/validation/{loop}/loop.json",
    log:
        "results/logs/validation/{loop}/trace.log",
    threads: THREADS
    resources:
        mem_mb=2000,
    params:
        flags=lambda w: f"{_L_TRACE} {_L_TRACE_DYNAMIC}" if _loop_dynamic(w.loop) else _L_TRACE,
        base_h5="results/validation/{loop}/base.h5",
    shell:
        "({input.exe} --threads {threads} trace --mesh {input.mesh} --motion {input.motion} --loads {input.loads}"
        "  --materials {input.materials} {params.flags} --max-effects 0 --out {params.base_h5} --summary {output.base}"
        " && {input.exe} --threads {threads} trace --mesh {input.mesh} --motion {input.motion} --loads {input.loads}"
        "  --materials {input.materials} --candidates {input.candidates} {params.flags}"
        "  --out {output.loop} --summary {output.summary}) 2> {log}"


rule loop_report:
    """fin-report's Closing the loop section (residual maps, decision trail) for the dataset."""
    input:
        exe=EXE("fin-report"),
        script=os.path.join(SCRIPTS, "report_figures.py"),
        mesh="results/validation/{loop}/mesh.h5",
        loop="results/validation/{loop}/loop.h5",
    output:
        "results/validation/{loop}/report/index.html",
    log:
        "results/logs/validation/{loop}/report.log",
    params:
        out="results/validation/{loop}/report",
    shell:
        "({input.exe} --case {wildcards.loop} --mesh {input.mesh} --loop {input.loop} --out-dir {params.out}"
        " && /usr/bin/python3 {input.script} {params.out}) 2> {log}"


rule validation_loop:
    input:
        report="results/validation/{loop}/report/index.html",
        base="results/validation/{loop}/base.json",
        loop="results/validation/{loop}/loop.json",
        truth="results/validation/{loop}/synth/truth.h5",
        script=os.path.join(SCRIPTS, "loop_scores.py"),
    output:
        summary="results/validation/{loop}/summary.json",
    log:
        "results/logs/validation/{loop}/scores.log",
    params:
        parameters=_L_PARAMETERS,
    shell:
        "(/usr/bin/python3 {input.script} --name {wildcards.loop} --loop {input.loop} --base {input.base}"
        " --truth {input.truth} --parameters {params.parameters} --out {output.summary} "
        + METRIC_MISSED_IS_A_RESULT + ") 2> {log}"
