# Issue 34, validation 2: the silicone flap of Hessenthaler et al. (2017), measured data
# (data/reference/hessenthaler2017.json; docs/studies/hessenthaler_flap.md).
#   (i)  fin-fit flap: Young's modulus from the buoyancy-only tip deflection (29.50 mm), its 95 %
#        interval from the MRI voxel, a beam and shell-strip mesh study, the model checks at the
#        others' mu (61 kPa) and the uniaxial mu (96.9 kPa -> 21.7 mm). About 1 min; coarse 7 s.
#   (ii) the Phase I flow prediction (16.41 mm) is not run yet: the summary carries the graded
#        metric phase_I_prediction_missing, so the case reads FAIL until it is.
#
#   snakemake -c2 results/validation/loop_hessenthaler/summary.json
_FLAP_REFERENCE = os.path.join(REPO, "data", "reference", "hessenthaler2017.json")
register_validation("loop_hessenthaler", "Hessenthaler 2017 flap: E from the buoyancy-only deflection (mu vs "
                    "61 kPa within 5 %), model checks; Phase I flow prediction still missing")


rule validation_loop_hessenthaler:
    input:
        exe=EXE("fin-fit"),
        reference=_FLAP_REFERENCE,
    output:
        "results/validation/loop_hessenthaler/summary.json",
    log:
        "results/logs/validation/loop_hessenthaler.log",
    threads: 1
    params:
        coarse="--coarse" if COARSE else "",
    shell:
        "OMP_WAIT_POLICY=PASSIVE {input.exe} --threads 1 flap --reference {input.reference} {params.coarse}"
        " --out-dir results/validation --name loop_hessenthaler 2> {log} " + METRIC_MISSED_IS_A_RESULT
