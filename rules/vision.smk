# fin-track in the DAG (DESIGN.md section 1): frames + cameras.yml -> kinematics.h5, which
# fin-mesh then carries onto the mesh (rules/mesh.smk). truth.h5 is used only to score.
#
#   snakemake -c2 results/<case>/kinematics.h5
#   snakemake -c2 results/validation/tracking/summary.json    accuracy against truth.h5
#   snakemake -c2 results/bench/track.json                     speed (fin-track, fin-mesh)
#
# The validation renders its own frames with the issue's sensor model (noise sigma = 2 grey
# levels, about 1 px of motion blur: 3 sub-frames over 15 % of the frame interval), tracks them
# with all views, with one view removed and with every principal point moved by 0.5 px, and
# scores all three against truth.h5 (the last two reported only). The silhouette IoU that is graded
# is the fitted surface's against the true surface's, both as area-coverage silhouettes at the
# image resolution (tools/vision/silhouette_coverage.hpp); fit and truth against the segmentation
# are reported beside it. COARSE: 3 frames.

_VFIN = config["fin"]
_VCASE = config["case"]
_VOUT = f"results/{_VCASE}"
_VTEMPLATE = (
    f"--chord {_VFIN['chord_m']} --height-over-chord {_VFIN['height_over_chord']} --rays {_VFIN['rays']}"
)
# The motion's period, stored as the kinematics' T attribute only when the record covers whole
# periods: fin-track computes it from the flow scales as fin-synth does (core/flow_scales.hpp).
_V_PERIOD = (
    f"--reynolds {_VFIN['reynolds']} --strouhal {_VFIN['strouhal']}"
    f" --excursion-over-chord {_VFIN['strouhal_excursion_over_chord']}"
    if float(_VFIN["periods"]).is_integer()
    else ""
)
_V_NOISY = "--blur-samples 3 --exposure 0.15 --noise-sigma 2"

rule track:
    input:
        exe=EXE("fin-track"),
        frames=f"{_VOUT}/frames",
        cameras=f"{_VOUT}/cameras.yml",
    output:
        kinematics=f"{_VOUT}/kinematics.h5",
    log:
        f"results/logs/{_VCASE}/track.log",
    benchmark:
        stage_benchmark("track"),
    threads: THREADS
    resources:
        mem_mb=1000,
    params:
        flags=f"{_VTEMPLATE} --fps {_VFIN['fps']} {_V_PERIOD}",
    shell:
        stage_shell(
            "track",
            "{input.exe} {params.flags} --frames {input.frames} --cameras {input.cameras} --out {output.kinematics}"
            " --threads {threads} 2> {log}",
        )

register_stage_output(f"{_VOUT}/kinematics.h5")

_VT = "results/validation/tracking"
_VT_PERIODS = 0.03 if COARSE else _VFIN["periods"]

register_validation(
    "tracking",
    "fin-track on noisy, blurred synthetic frames vs truth.h5: vertex error <= 1/2/4 % c, IoU >= 0.97, TE amplitude 2 %",
)

rule validation_tracking_synth:
    input:
        exe=EXE("fin-synth"),
    output:
        truth=f"{_VT}/synth/truth.h5",
        cameras=f"{_VT}/synth/cameras.yml",
        frames=directory(f"{_VT}/synth/frames"),
    log:
        "results/logs/validation/tracking_synth.log",
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        flags=f"{_VTEMPLATE} --fps {_VFIN['fps']} --periods {_VT_PERIODS} --seed {config['seed']} {_V_NOISY} --vtk false",
        out=f"{_VT}/synth",
    shell:
        "{input.exe} --out-dir {params.out} {params.flags} --threads {threads} 2> {log}"

rule validation_tracking:
    input:
        exe=EXE("fin-track"),
        truth=f"{_VT}/synth/truth.h5",
        cameras=f"{_VT}/synth/cameras.yml",
        frames=f"{_VT}/synth/frames",
    output:
        summary=f"{_VT}/summary.json",
        kinematics=f"{_VT}/kinematics.h5",
        one_view_removed=f"{_VT}/kinematics_without_ventral.h5",
        perturbed=f"{_VT}/kinematics_calibration_0p5px.h5",
    log:
        "results/logs/validation/tracking.log",
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        flags=f"{_VTEMPLATE} --fps {_VFIN['fps']}",
    shell:
        "({input.exe} {params.flags} --frames {input.frames} --cameras {input.cameras} --ignore-view ventral"
        "  --out {output.one_view_removed} --threads {threads}"
        " && {input.exe} {params.flags} --frames {input.frames} --cameras {input.cameras}"
        "  --perturb-calibration-px 0.5 --seed {config[seed]} --out {output.perturbed} --threads {threads}"
        " && ({input.exe} {params.flags} --frames {input.frames} --cameras {input.cameras} --out {output.kinematics}"
        "  --truth {input.truth} --summary {output.summary} --also-score without_ventral={output.one_view_removed}"
        "  --also-score calibration_0p5px={output.perturbed} --threads {threads} " + METRIC_MISSED_IS_A_RESULT + ")) 2> {log}"

_BT = "results/bench/track"
register_bench("track", "fin-track seconds per frame set (all views, default resolution) and fin-mesh wall time")

rule bench_track:
    input:
        synth=EXE("fin-synth"),
        track=EXE("fin-track"),
        mesh=EXE("fin-mesh"),
    output:
        json="results/bench/track.json",
    log:
        "results/logs/bench/track.log",
    threads: THREADS
    resources:
        mem_mb=1500,
    params:
        flags=_VTEMPLATE,
        periods=0.03 if COARSE else 0.1,
        noisy=_V_NOISY,
        work=_BT,
    shell:
        "({input.synth} --out-dir {params.work} {params.flags} --periods {params.periods} {params.noisy} --vtk false"
        "  --threads {threads}"
        " && ({input.mesh} {params.flags} --mesh {params.work}/mesh.h5 --summary {params.work}/mesh_summary.json"
        "  --threads {threads} " + METRIC_MISSED_IS_A_RESULT + ")"
        " && ({input.track} {params.flags} --frames {params.work}/frames --cameras {params.work}/cameras.yml"
        "  --out {params.work}/kinematics.h5 --bench-json {output.json}"
        "  --bench-mesh-summary {params.work}/mesh_summary.json --threads {threads} " + METRIC_MISSED_IS_A_RESULT + ")) 2> {log}"
