#!/usr/bin/python3
"""The bad-input suite (issue 46): every executable given something a careless user would give it.

Each case runs one command and asserts
  - the exit code (2: bad input),
  - exactly one error line, the project's own ("<tool>: error: ..." or "[<tool> ...] error: ..."),
    naming the flag, key or file (`names`), its numbers as a person writes them (no 309-digit
    bound, no "4.000000"), and no line from a library,
  - that none of the case's outputs exists afterwards (nothing under a final name).
The stages that run longer than a second are also killed (SIGKILL) half way: none of their
outputs may exist afterwards.
Placeholders in a command: {bin} the executables, {fix} the tiny case's golden mesh.h5 and
motion.h5 (tests/regression/mesh/tiny_case), {repo} the repository, {w} the case's own scratch
folder. Cases needing a bad file write it with `make` (a function of the scratch folder).

  /usr/bin/python3 tests/bad_input/run_bad_inputs.py --bin build/bin --repo . --work /tmp/bad_input [--only fin-mesh]
"""
import argparse
import math
import json
import os
import re
import shutil
import subprocess
import sys

MESH = "{fix}/mesh.h5"
MOTION = "{fix}/motion.h5"
MATERIALS = "{repo}/data/cases/trout_fin_materials.json"
CFD_CASE = "{repo}/data/cases/cfd/cylinder_channel_2d.yaml"


def case(tool, args, names, outputs=(), rc=2, make=None, label=None):
    return {"tool": tool, "args": args, "names": names, "outputs": list(outputs), "rc": rc, "make": make,
            "label": label or f"{tool} {args}"}


def edited(source, pattern, replacement, name):
    """A `make` that writes a copy of `source` with one regex replacement."""
    def make(w, fmt):
        text = open(fmt(source)).read()
        new = re.sub(pattern, replacement, text, count=1)
        assert new != text, f"{name}: pattern {pattern!r} not found"
        with open(os.path.join(w, name), "w") as f:
            f.write(new)
    return make


def written(name, text):
    def make(w, fmt):
        with open(os.path.join(w, name), "w") as f:
            f.write(text)
    return make


def flag_cases(tool, base, out, flags):
    """One case per (flag, value): base command + the flag, the flag named in the error."""
    return [case(tool, f"{base} {flag} {value}", flag, [out]) for flag, value in flags]


def cases():
    c = []
    # fin-mesh: sizes, signs, NaN, ranges, the template's limits, config files.
    c += flag_cases("fin-mesh", "--mesh {w}/mesh.h5", "{w}/mesh.h5", [
        ("--max-edge", "-1"), ("--max-edge", "0"), ("--max-edge", "nan"), ("--max-edge", "inf"),
        ("--max-edge", "1e-6"), ("--chord", "0"), ("--chord", "-0.01"), ("--height-over-chord", "nan"),
        ("--membrane-thickness", "-1"), ("--rays", "1"), ("--rays", "-3"), ("--ray-points", "0"),
        ("--ray-points", "1"), ("--min-angle", "-5"), ("--threads", "-1"), ("--max-edge", "abc"),
        ("--edge-ray-thickness", "inf"), ("--tip-thickness-ratio", "-0.2"), ("--ray-width-ratio", "0"),
        ("--root-band", "-1"), ("--ibm-thickness", "nan")])
    c += [case("fin-mesh", "--mesh {w}/mesh.h5 --rays 100000", "--rays", ["{w}/mesh.h5"]),
          case("fin-mesh", "--mesh {w}/mesh.h5 --ray-points 100000000", "--ray-points", ["{w}/mesh.h5"]),
          case("fin-mesh", "--mesh {w}/mesh.h5 --min-angle 40", "--min-angle", ["{w}/mesh.h5"]),
          case("fin-mesh", "--mesh {w}/mesh.h5 --config {w}/c.toml", "bogus-key", ["{w}/mesh.h5"],
               make=written("c.toml", "max-edge = 0.1\nbogus-key = 3\n")),
          case("fin-mesh", "--mesh {w}/mesh.h5 --config {w}/c.toml", "--max-edge", ["{w}/mesh.h5"],
               make=written("c.toml", "max-edge = -0.1\n")),
          case("fin-mesh", "--mesh {w}/mesh.h5 --motion-source {w}/missing.h5 --motion {w}/motion.h5",
               "missing.h5", ["{w}/mesh.h5", "{w}/motion.h5"]),
          case("fin-mesh", "--mesh {w}/mesh.h5 --template {w}/missing.json", "missing.json", ["{w}/mesh.h5"])]

    # fin-synth: image sizes against the machine, signs and ranges; nothing created.
    c += flag_cases("fin-synth", "--out-dir {w}/synth", "{w}/synth", [
        ("--width", "0"), ("--height", "-1"), ("--fps", "0"), ("--fps", "nan"), ("--periods", "-1"),
        ("--noise-sigma", "-1"), ("--supersample", "0"), ("--blur-samples", "0"), ("--vignetting", "2"),
        ("--exposure", "-0.5"), ("--chord", "0"), ("--reynolds", "-10"), ("--viscosity", "0"),
        ("--strouhal", "nan"), ("--gain", "-1"), ("--threads", "-4"), ("--rays", "0"),
        ("--debris", "-3"), ("--field-chords", "inf")])
    c += [case("fin-synth", "--out-dir {w}/synth --width 1000000", "--width", ["{w}/synth"]),
          case("fin-synth", "--out-dir {w}/synth --width 100000 --height 100000", "--width", ["{w}/synth"]),
          case("fin-synth", "--out-dir {w}/synth --jpeg-quality 101", "--jpeg-quality", ["{w}/synth"]),
          case("fin-synth", "--out-dir {w}/synth --views side,top", "top", ["{w}/synth"]),
          # issue 47: the deep body's pectoral fins.
          case("fin-synth", "--out-dir {w}/synth --pectoral-length 1", "--pectoral-length", ["{w}/synth"]),
          case("fin-synth", "--out-dir {w}/synth --body --pectoral-station 0.3", "--pectoral-station", ["{w}/synth"]),
          case("fin-synth", "--out-dir {w}/synth --body --pectoral-length -1", "--pectoral-length", ["{w}/synth"]),
          case("fin-synth", "--out-dir {w}/synth --body --pectoral-length 1 --pectoral-open 80,10", "--pectoral-open",
               ["{w}/synth"]),
          case("fin-synth", "--out-dir {w}/synth --body --pectoral-length 1 --pectoral-station 1.5",
               "--pectoral-station", ["{w}/synth"])]

    # fin-fit: optimiser sizes, increments and times.
    fit = f"run --mesh {MESH} --motion {MOTION} --loads {MOTION} --materials {MATERIALS} --out {{w}}/m.h5"
    c += flag_cases("fin-fit", fit, "{w}/m.h5", [
        ("--population", "-1"), ("--generations", "-2"), ("--runs", "0"), ("--polish-evaluations", "-5"),
        ("--instant-count", "0"), ("--dt", "-1"), ("--dt", "nan"), ("--substeps", "0"), ("--periods", "-1"),
        ("--ramp", "-0.1"), ("--threads", "-2"), ("--instants", "nan")])
    c += [case("fin-fit", f"run --mesh {{w}}/missing.h5 --motion {MOTION} --materials {MATERIALS} --out {{w}}/m.h5",
               "missing.h5", ["{w}/m.h5"]),
          case("fin-fit", f"run --mesh {MESH} --motion {MOTION} --materials {{w}}/missing.json --out {{w}}/m.h5",
               "missing.json", ["{w}/m.h5"])]
    c += flag_cases("fin-fit", f"evaluate --mesh {MESH} --motion {MOTION} --materials {MATERIALS}", "{w}/none", [
        ("--instant-count", "-1"), ("--dt", "inf"), ("--substeps", "-1")])

    # fin-loop: residual and trace flags.
    res = f"residual --mesh {MESH} --reconstruction {MOTION} --prediction {MOTION} --out {{w}}/r.h5"
    c += flag_cases("fin-loop", res, "{w}/r.h5", [
        ("--period", "-1"), ("--period", "nan"), ("--harmonics", "-1"), ("--modes", "-2")])
    tr = f"trace --mesh {MESH} --motion {MOTION} --materials {MATERIALS} --out {{w}}/l.h5"
    c += flag_cases("fin-loop", tr, "{w}/l.h5", [
        ("--lm-evaluations", "-1"), ("--alpha", "2"), ("--alpha", "nan"), ("--max-effects", "-1"),
        ("--fit-drive", "-1"), ("--fit-drive", "50"), ("--drive-harmonics", "-1"), ("--relative-step", "-0.1"),
        ("--frequency", "-4.4"), ("--substeps", "0"), ("--spectral-radius", "inf"), ("--ramp", "-1")])

    # fin-cfd fin: flow flags; sizes against the machine.
    cfd = f"fin --mesh {MESH} --motion {MOTION} --out {{w}}/loads.h5"
    c += flag_cases("fin-cfd", cfd, "{w}/loads.h5", [
        ("--speed", "-0.1"), ("--cfl", "0"), ("--cfl", "nan"), ("--periods", "-1"), ("--reynolds", "-5"),
        ("--viscosity", "-1e-6"), ("--rho", "-1000"), ("--cells-per-chord", "-8"), ("--chord", "-1"),
        ("--checkpoint-every", "-1"), ("--threads", "-1")])
    c += [case("fin-cfd", cfd + " --cells-per-chord 1e6", "--cells-per-chord", ["{w}/loads.h5"])]
    # fin-cfd run: the case file's keys.
    for name, pattern, repl, names in [
            ("rho", r"rho: 1\}", "rho: -1}", "fluid.rho"), ("force_every", r"force_every: 10", "force_every: -1",
                                                                "outputs.force_every"),
            ("h", r"h: 0.003125 ", "h: 5.0e-9 ", "grid.h"), ("inverted", r"x: \[0, 2.2\]", "x: [2.2, 0]", "domain.x"),
            ("nu_nan", r"nu: 1.0e-3", "nu: .nan", "fluid.nu"), ("inlet_nan", r"velocity: \[0.3, 0, 0\]",
                                                              "velocity: [.nan, 0, 0]", "boundaries.x_lo.velocity"),
            ("nu_neg", r"nu: 1.0e-3", "nu: -1.0e-3", "fluid.nu"), ("cfl", r"cfl: 0.5", "cfl: 0", "time.cfl"),
            ("t_end", r"t_end: 8 ", "t_end: -8 ", "time.t_end"), ("radius", r"radius: 0.05", "radius: -0.05", "radius"),
            ("stretch", r"stretch_ratio: 1.05", "stretch_ratio: 0.5", "grid.stretch_ratio"),
            ("unknown_key", r"cfl: 0.5", "cfl: 0.5\n  cfll: 0.4", "cfll"),
            ("ramp", r"ramp_time: 1", "ramp_time: -1", "ramp_time"),
            ("rtol", r"poisson_rtol: 1.0e-9", "poisson_rtol: 0", "solver.poisson_rtol")]:
        c.append(case("fin-cfd", f"--out-dir {{w}}/out run {{w}}/case_{name}.yaml", names, ["{w}/out"],
                      make=edited(CFD_CASE, pattern, repl, f"case_{name}.yaml")))
    c += [case("fin-cfd", "--out-dir {w}/out run {w}/missing.yaml", "missing.yaml", ["{w}/out"])]

    # fin-fem run and loads.
    fem = f"run --mesh {MESH} --materials {MATERIALS} --out {{w}}/model.h5"
    c += flag_cases("fin-fem", fem, "{w}/model.h5", [
        ("--substeps", "0"), ("--max-iterations", "-1"), ("--ramp", "-1"), ("--periods", "nan"),
        ("--frames-per-period", "0"), ("--rho-inf", "-0.5"), ("--ramp-steps", "-2")])
    c += flag_cases("fin-fem", f"loads --mesh {MESH} --root-drive {{w}}/none.json --out {{w}}/loads.h5",
                    "{w}/loads.h5", [("--periods", "-2"), ("--frames-per-period", "0"), ("--reynolds", "nan"),
                                     ("--density", "-1000"), ("--drag-coefficient", "-2"), ("--start-periods", "-1")])

    # A materials file for another fin: ray 99 on a 20-ray mesh.
    ray99 = edited(MATERIALS, r'"ray"\s*:\s*\{', '"ray": {"99": {"E": 1e9, "nu": 0.3, "density": 1100}, ',
                   "m99.json")
    c += [case("fin-fem", f"run --mesh {MESH} --materials {{w}}/m99.json --motion {MOTION} --out {{w}}/model.h5",
               "m99.json", ["{w}/model.h5"], make=ray99),
          case("fin-fit", f"run --mesh {MESH} --materials {{w}}/m99.json --motion {MOTION} --out {{w}}/m.h5",
               "m99.json", ["{w}/m.h5"], make=ray99)]

    # JSON inputs with unknown keys or out-of-range values, and subcommand keys in a --config file.
    drive = '{"heave_over_chord": 0.44, "frequency_hz": 4.4, "ramp_periods": 0.5'
    for name, text, names in [("drive_key", drive + ', "bogus": 1}', "bogus"),
                              ("drive_heave", drive.replace("0.44", "-0.44") + "}", "heave_over_chord"),
                              ("drive_freq", drive.replace("4.4", "-4.4") + "}", "frequency_hz"),
                              ("drive_nan", drive.replace("0.44", "NaN") + "}", "drive_nan.json")]:
        c.append(case("fin-fem", f"loads --mesh {MESH} --root-drive {{w}}/{name}.json --out {{w}}/loads.h5", names,
                      ["{w}/loads.h5"], make=written(f"{name}.json", text)))
    c += [case("fin-fem", "effects --check {w}/e.json", "bogus", [],
               make=written("e.json", '[{"name": "active_stiffening", "amplitude": 0.3, "bogus": 2}]')),
          case("fin-fem", "effects --check {w}/e.json", "no_such_effect", [],
               make=written("e.json", '[{"name": "no_such_effect"}]')),
          case("fin-fit", f"--config {{w}}/f.toml {fit}", "run.populationn", ["{w}/m.h5"],
               make=written("f.toml", "[run]\npopulationn = 4\n")),
          case("fin-fit", f"--config {{w}}/f.toml {fit}", "--population", ["{w}/m.h5"],
               make=written("f.toml", "[run]\npopulation = -1\n"))]

    # fin-calibrate's importers and recordings, fin-report's inputs of the wrong schema.
    c += [case("fin-calibrate", "dlt --coefficients {w}/dlt.csv --views side back --image-size 512x512 512x512 "
               "--out {w}/c.yml", "dlt.csv", ["{w}/c.yml"], make=written("dlt.csv", "garbage\n1 2 3\n")),
          case("fin-calibrate", "anipose --calibration {w}/a.toml --out {w}/c.yml", "a.toml", ["{w}/c.yml"],
               make=written("a.toml", '[cam_0]\nname = "side"\nsize = [512, 512]\nmatrix = [[1, 0, 0], [0, 1, 0]]\n')),
          case("fin-calibrate", "anipose --calibration {w}/a.toml --out {w}/c.yml", "a.toml", ["{w}/c.yml"],
               make=written("a.toml", "not toml ][")),
          case("fin-calibrate", "checkerboard --view side={w}/none --view back={w}/none --out {w}/c.yml",
               "--square-mm", ["{w}/c.yml"]),
          case("fin-calibrate", "checkerboard --view side={w}/none --view back={w}/none --square-mm 10 --out {w}/c.yml",
               "none", ["{w}/c.yml"]),
          case("fin-report", f"--case x --out-dir {{w}}/rep --mesh {MESH} --motion {MESH}", "mesh.h5", ["{w}/rep"]),
          case("fin-report", f"--case x --out-dir {{w}}/rep --mesh {MOTION}", "motion.h5", ["{w}/rep"])]

    # fin-track: flags, and the cameras file (a NaN focal length once crashed it).
    trk = "--frames {w} --cameras {w}/cameras.yml --out {w}/k.h5"
    c += [case("fin-track", f"{trk} {flag} {value}", flag, ["{w}/k.h5"])
          for flag, value in [("--fps", "0"), ("--fps", "-1"), ("--fps", "nan"), ("--segments", "0"), ("--iterations", "-1"),
                              ("--min-views", "0"), ("--min-iou", "1.5"), ("--coverage-weight", "-1"),
                              ("--temporal-sigma", "-1"), ("--rays", "0"), ("--chord", "-1"),
                              ("--period", "-0.2"), ("--tolerance", "nan")]]

    # fin-fsi fin, fin-calibrate, fin-report, fin-diff: flags.
    fsi = f"fin --mesh {MESH} --materials {MATERIALS} --out {{w}}/fsi.h5"
    c += flag_cases("fin-fsi", fsi, "{w}/fsi.h5", [
        ("--speed", "-1"), ("--cells-per-chord", "nan"), ("--reynolds", "-1"), ("--rho", "-1"), ("--viscosity", "0"),
        ("--periods", "-1"), ("--substeps", "0"), ("--cfl", "-0.5")])
    # fin-fsi fin: a fin too soft for the coupled run (the fit's soft corner) is refused before any step.
    soft = ('{"membrane": {"E": 1e5, "nu": 0.4, "density": 1050}, '
            '"rays": {"E": 1e7, "nu": 0.4, "density": 1100}}')

    def soft_fin(w, fmt):
        written("soft.json", soft)(w, fmt)
        written("drive.json", DRIVE)(w, fmt)
    c.append(case("fin-fsi", f"fin --mesh {MESH} --materials {{w}}/soft.json --root-drive {{w}}/drive.json "
                  "--min-frequency-ratio 4 --out {w}/fsi.h5", "{w}/soft.json: the fin's first natural frequency",
                  ["{w}/fsi.h5"], make=soft_fin, label="fin-fsi fin: materials too soft for the coupled run"))
    c += flag_cases("fin-calibrate", "simulate --cameras {w}/cameras.yml --out-dir {w}/cal", "{w}/cal", [
        ("--poses", "-1"), ("--supersample", "0"), ("--noise-sigma", "-1"), ("--marker-fraction", "1.5"),
        ("--board-fraction", "-0.45")])
    c += flag_cases("fin-diff", "{fix} {fix}", "{w}/none", [("--atol", "-1"), ("--rtol", "nan"), ("--atol", "inf")])
    c += flag_cases("fin-report", "--case x --out-dir {w}/rep", "{w}/rep", [("--chord", "-0.01"), ("--chord", "nan")])
    return c


def surface_cases():
    """fin-cfd run on the STL sphere case with a broken surface file beside it."""
    source = "{repo}/data/cases/cfd/sphere_re100_stl.yaml"
    # A closed tetrahedron in ASCII STL, one coordinate of its first vertex replaced by `x`.
    corners = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]

    def tetrahedron(x):
        out = ["solid tet"]
        for f in faces:
            out += [" facet normal 0 0 0", "  outer loop"]
            for v in f:
                c = [str(a) for a in corners[v]]
                if v == 0:
                    c[0] = x
                out.append("   vertex " + " ".join(c))
            out += ["  endloop", " endfacet"]
        return "\n".join(out + ["endsolid tet", ""])

    def with_surface(text):
        def make(w, fmt):
            with open(os.path.join(w, "case.yaml"), "w") as f:
                f.write(re.sub(r"surface: sphere\.stl", "surface: bad.stl", open(fmt(source)).read()))
            with open(os.path.join(w, "bad.stl"), "w") as f:
                f.write(text)
        return make
    broken = "solid broken\n facet normal 0 0 1\n  outer loop\n   vertex 0 0\n"
    return [case("fin-cfd", "--out-dir {w}/out run {w}/case.yaml", "bad.stl", ["{w}/out"], make=with_surface(t),
                 label=f"fin-cfd run: surface file {name}")
            for name, t in (("nan vertex", tetrahedron("nan")), ("broken", broken))]


def pipe_cases():
    """fin-cfd run on the pipe case (fluid inside a wall): an open pipe surface, an inlet disc off the
    pipe's cross-section, a ball that sticks through the wall."""
    source = "{repo}/data/cases/cfd/pipe_flow.yaml"

    def open_tube(w, fmt):
        # A tube of 16 segments without end caps: not closed.
        n, r, pts = 16, 0.01095, []
        ring = [(r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n)) for k in range(n)]
        out = ["solid tube"]
        for k in range(n):
            (x0, y0), (x1, y1) = ring[k], ring[(k + 1) % n]
            for tri in (((x0, y0, -0.004), (x1, y1, -0.004), (x1, y1, 0.1)),
                        ((x0, y0, -0.004), (x1, y1, 0.1), (x0, y0, 0.1))):
                out += [" facet normal 0 0 0", "  outer loop"]
                out += [f"   vertex {a} {b} {c}" for a, b, c in tri]
                out += ["  endloop", " endfacet"]
        with open(os.path.join(w, "tube.stl"), "w") as f:
            f.write("\n".join(out + ["endsolid tube", ""]))
        text = open(fmt(source)).read()
        new = re.sub(r"shape: cylinder .*\n(    .*\n){4}", "surface: tube.stl\n", text, count=1)
        assert new != text
        with open(os.path.join(w, "case_open.yaml"), "w") as f:
            f.write(new)
    c = [case("fin-cfd", "--out-dir {w}/out run {w}/case_open.yaml", "tube.stl", ["{w}/out"], make=open_tube,
              label="fin-cfd run: pipe surface not closed")]
    for name, pattern, repl, names in [
            ("inlet_off", r"centre: \[0, 0, 0\], radius", "centre: [0.003, 0, 0], radius", "boundaries.z_lo.pipes[0]"),
            ("through_wall", r"radius: 0.004", "radius: 0.012", "bodies[1]")]:
        c.append(case("fin-cfd", f"--out-dir {{w}}/out run {{w}}/case_{name}.yaml", names, ["{w}/out"],
                      make=edited(source, pattern, repl, f"case_{name}.yaml"), label=f"fin-cfd run: pipe {name}"))
    return c


def flap_cases():
    """fin-fsi flap (the Hessenthaler Phase I run in 3-D): a flow case with a sheet among its bodies,
    an MRI centreline with a bad row, a modulus of zero, a flow factor of zero, a flap too wide for
    the junction (it sticks through the outlet pipe's wall)."""
    flow = "{repo}/data/cases/cfd/pipe_flow.yaml"
    base = ("--threads 1 flap --reference {repo}/data/reference/hessenthaler2017.json --out-dir {w}/out "
            "--centreline {repo}/data/reference/hessenthaler2017/phaseI_centreline.csv")

    def bad_centreline(w, fmt):
        with open(os.path.join(w, "c.csv"), "w") as f:
            f.write("# MRI\nx_mm,y_mm,z_mm\n0,0,0.977\n0,one,6.8\n")
    sheet = edited(flow, r"  - name: ball\n    shape: sphere",
                   "  - name: ball\n    shape: plate\n    leading_edge: [0, 0, 0.02]\n    chord: 0.005\n"
                   "    span: 0.005\n    incidence: 0\n  - name: ball2\n    shape: sphere", "sheet.yaml")
    return [
        case("fin-fsi", base + " --flow {w}/sheet.yaml --youngs-modulus 1.8e5", "sheet.yaml: body ball:",
             ["{w}/out"], make=sheet, label="fin-fsi flap: a sheet in the flow case"),
        case("fin-fsi", base.replace("--centreline {repo}/data/reference/hessenthaler2017/phaseI_centreline.csv",
                                     "--centreline {w}/c.csv") + f" --flow {flow} --youngs-modulus 1.8e5",
             "c.csv:4:", ["{w}/out"], make=bad_centreline, label="fin-fsi flap: a bad MRI row"),
        case("fin-fsi", base + f" --flow {flow} --youngs-modulus 0", "--youngs-modulus", ["{w}/out"],
             label="fin-fsi flap: modulus 0"),
        case("fin-fsi", base + f" --flow {flow} --youngs-modulus 1.8e5 --viscosity-factor 0", "--viscosity-factor",
             ["{w}/out"], label="fin-fsi flap: viscosity factor 0"),
        case("fin-fsi", base.replace("{repo}/data/reference/hessenthaler2017.json", "{w}/wide.json")
             + " --flow {repo}/data/cases/cfd/hessenthaler/junction_flow.yaml --h 0.004 --youngs-modulus 1.8e5",
             "wide.json: the flap (65 x 74 mm) sticks through", ["{w}/out"],
             make=edited("{repo}/data/reference/hessenthaler2017.json", r'"width": 11.0', '"width": 74.0', "wide.json"),
             label="fin-fsi flap: a flap through the junction's wall"),
    ] + flap_loop_cases()


def flap_loop_cases():
    """fin-loop flap with the 3-D Phase I frame: a loads file that is not there, no MRI centreline,
    a perturbed run without the base run."""
    fit = written("fit.json", json.dumps({
        "schema": "finverse/summary", "schema_version": 1, "kind": "validation", "name": "fit", "description": "fit",
        "pass": True, "timing": {"wall_s": 1.0, "threads": 1}, "metrics": [{"name": "youngs_modulus", "value": 1.83e5, "units": "Pa", "kind": "info",
                                   "reference": None, "source": "", "error": None, "tolerance": None, "pass": None}]}))
    base = ("--threads 1 flap --reference {repo}/data/reference/hessenthaler2017.json --fit {w}/fit.json "
            "--out-dir {w}/out --name loop")
    mri = " --centreline {repo}/data/reference/hessenthaler2017/phaseI_centreline.csv"
    return [
        case("fin-loop", base + " --phase1 {w}/none.h5" + mri, "none.h5", ["{w}/out"], make=fit,
             label="fin-loop flap: a missing 3-D loads file"),
        case("fin-loop", base + " --phase1 {w}/none.h5", "--centreline", ["{w}/out"], make=fit,
             label="fin-loop flap: --phase1 without --centreline"),
        case("fin-loop", base + " --phase1-viscosity {w}/none.h5" + mri, "--phase1", ["{w}/out"], make=fit,
             label="fin-loop flap: a perturbed run without the base run"),
    ]


def contract_cases():
    """fin-contract check on a mesh.h5 whose triangle names a vertex past the end."""
    def make(w, fmt):
        import h5py
        shutil.copy(fmt(MESH), os.path.join(w, "mesh.h5"))
        with h5py.File(os.path.join(w, "mesh.h5"), "r+") as f:
            t = f["triangles"][...]
            t[3, 1] = 999999
            f["triangles"][...] = t
    return [case("fin-contract", "check {w}/mesh.h5", "/triangles", [], make=make, label="fin-contract: index 999999")]


DRIVE = ('{"heave_over_chord": 0.44, "pitch_center_deg": 12, "pitch_edge_deg": 22, "pitch_phase_deg": -90, '
         '"pitch_phase_w_deg": -20, "frequency_hz": 4.4, "ramp_periods": 0.5}')


def kill_cases():
    """Stages killed (SIGKILL) after `after` seconds of a run that takes longer: nothing of theirs
    may be left under a final name."""
    def run_first(*commands):
        def make(w, fmt):
            with open(os.path.join(w, "drive.json"), "w") as f:
                f.write(DRIVE)
            for c in commands:
                subprocess.run([fmt("{bin}/" + c.split()[0])] + fmt(" ".join(c.split()[1:])).split(), cwd=w,
                               check=True, capture_output=True, timeout=120)
        return make
    small_synth = "fin-synth --out-dir {w}/s --width 160 --height 160 --fps 100 --periods 1 --vtk false --threads 1"
    loads = f"fin-fem loads --mesh {MESH} --root-drive {{w}}/drive.json --out {{w}}/loads.h5 --periods 1"
    return [
        dict(tool="fin-synth", args="--out-dir {w}/synth --vtk false --threads 1", after=3.0,
             outputs=["{w}/synth/frames", "{w}/synth/truth.h5", "{w}/synth/cameras.yml"], make=None),
        # 2.6 s alone on a fast core (0.8 s at --max-edge 0.008 ended before the kill).
        dict(tool="fin-mesh", args=f"--threads 1 --mesh {{w}}/mesh.h5 --max-edge 0.005", after=1.0,
             outputs=["{w}/mesh.h5"], make=None),
        dict(tool="fin-fem", args=f"--threads 1 run --mesh {MESH} --materials {MATERIALS} --motion {MOTION} "
             "--out {w}/fem.h5", after=2.0, outputs=["{w}/fem.h5"], make=None),
        dict(tool="fin-cfd", args=f"--threads 1 fin --mesh {MESH} --motion {MOTION} --out {{w}}/loads.h5 "
             "--summary {w}/loads.json", after=3.0, outputs=["{w}/loads.h5", "{w}/loads.json"], make=None),
        dict(tool="fin-fsi", args=f"--threads 1 fin --mesh {MESH} --materials {MATERIALS} --root-drive {{w}}/drive.json "
             "--out {w}/fsi.h5", after=3.0, outputs=["{w}/fsi.h5"], make=run_first()),
        dict(tool="fin-track", args="--threads 1 --frames {w}/s/frames --cameras {w}/s/cameras.yml --out {w}/k.h5",
             after=1.5, outputs=["{w}/k.h5"], make=run_first(small_synth)),
        dict(tool="fin-fit", args=f"--threads 1 run --mesh {MESH} --motion {MOTION} --loads {{w}}/loads.h5 "
             f"--materials {MATERIALS} --out {{w}}/m.h5 --summary {{w}}/m.json", after=3.0,
             outputs=["{w}/m.h5", "{w}/m.json"], make=run_first(loads)),
        dict(tool="fin-loop", args=f"--threads 1 trace --mesh {MESH} --motion {MOTION} --loads {{w}}/loads.h5 "
             f"--materials {MATERIALS} --out {{w}}/l.h5 --summary {{w}}/l.json", after=3.0,
             outputs=["{w}/l.h5", "{w}/l.json"], make=run_first(loads)),
    ]


def run_kill_case(i, k, args):
    import signal
    import time
    w = os.path.join(args.work, f"kill{i:02d}")
    shutil.rmtree(w, ignore_errors=True)
    os.makedirs(w)

    def fmt(s):
        return s.format(bin=args.bin, fix=args.fix, repo=args.repo, w=w)
    if k["make"]:
        k["make"](w, fmt)
    p = subprocess.Popen([os.path.join(args.bin, k["tool"])] + fmt(k["args"]).split(), cwd=w,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(k["after"])
    if p.poll() is not None:
        return f"ended (exit {p.returncode}) before the kill at {k['after']} s: {p.stderr.read()[-200:]!r}"
    os.kill(p.pid, signal.SIGKILL)
    p.wait()
    left = [o for o in map(fmt, k["outputs"]) if os.path.exists(o)]
    return f"left behind: {left}" if left else ""


CAMERAS_SOURCE = "{repo}/tests/bad_input/cameras.yml"


def frame_cases():
    """fin-track on frame folders holding broken PNG and JPEG files: the decoders' own warnings
    must not reach the user, only our line naming the file."""
    def frames(content, ext):
        def make(w, fmt):
            for view in ("side", "back", "ventral"):
                os.makedirs(os.path.join(w, "f", view))
                for k in (1, 2):
                    with open(os.path.join(w, "f", view, f"{k:06d}.{ext}"), "wb") as f:
                        f.write(content)
        return make
    def clips(content):
        def make(w, fmt):
            for view in ("side", "back", "ventral"):
                with open(os.path.join(w, f"{view}.avi"), "wb") as f:
                    f.write(content)
        return make
    clip_cases = [case("fin-track", "--frames side={w}/side.avi back={w}/back.avi ventral={w}/ventral.avi "
                       "--cameras {w}/cameras.yml --out {w}/k.h5", "side.avi", ["{w}/k.h5"], make=clips(content),
                       label=f"fin-track: clip {name}")
                  for name, content in (("garbage", bytes(range(256)) * 20), ("RIFF header only", b"RIFF\0\0\0\0AVI LIST"))]
    png_garbage = b"\x89PNG\r\n\x1a\n garbage"
    png_truncated = b"\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x00"
    jpeg_truncated = b"\xff\xd8\xff\xe0\x00\x10JFIF\x00"
    return [case("fin-track", "--frames {w}/f --cameras {w}/cameras.yml --out {w}/k.h5", "000001." + ext, ["{w}/k.h5"],
                 make=frames(content, ext), label=f"fin-track: {name}")
            for name, content, ext in (("PNG garbage", png_garbage, "png"), ("PNG truncated", png_truncated, "png"),
                                       ("JPEG truncated", jpeg_truncated, "jpg"))] + clip_cases


def camera_cases():
    out = []
    for name, repl, names in [("nan", ".nan", "camera_matrix"), ("neg", "-5.", "focal"), ("inf", ".inf", "camera_matrix")]:
        out.append(case("fin-track", f"--frames {{w}} --cameras {{w}}/cam_{name}.yml --out {{w}}/k.h5", names,
                        ["{w}/k.h5"], make=edited(CAMERAS_SOURCE, r"2\.7927272727272725e\+03", repl,
                                                  f"cam_{name}.yml")))
    return out


def run_case(i, k, args):
    w = os.path.join(args.work, f"{i:03d}")
    shutil.rmtree(w, ignore_errors=True)
    os.makedirs(w)
    shutil.copy(args.repo + "/tests/bad_input/cameras.yml", os.path.join(w, "cameras.yml"))

    def fmt(s):
        return s.format(bin=args.bin, fix=args.fix, repo=args.repo, w=w)
    if k["make"]:
        k["make"](w, fmt)
    argv = [os.path.join(args.bin, k["tool"])] + fmt(k["args"]).split()
    try:
        p = subprocess.run(argv, capture_output=True, text=True, timeout=60, cwd=w)
    except subprocess.TimeoutExpired:
        return "ran over 60 s (unbounded?)"
    problems = []
    if p.returncode != k["rc"]:
        problems.append(f"exit {p.returncode}, expected {k['rc']}")
    tool = k["tool"]
    lines = [l for l in p.stderr.splitlines() if l.strip()]
    own = re.compile(r"^(\[" + re.escape(tool) + r" [^\]]*\] |" + re.escape(tool) + r": )")
    foreign = [l for l in lines if not own.match(l)]
    errors = [l for l in lines if own.match(l) and re.search(r"\berror\b", l)]
    if foreign:
        problems.append(f"{len(foreign)} line(s) not the project's own, e.g. {foreign[0][:120]!r}")
    if len(errors) != 1:
        problems.append(f"{len(errors)} error lines, expected 1")
    elif fmt(k["names"]) not in errors[0]:
        problems.append(f"the error line does not name {fmt(k['names'])!r}: {errors[0][:160]!r}")
    elif re.search(r"\d{16,}|\d\.0{6}\b", errors[0]):
        problems.append(f"a number not as a person writes it: {errors[0][:160]!r}")
    left = [o for o in map(fmt, k["outputs"]) if os.path.exists(o)]
    if left:
        problems.append(f"left behind: {left}")
    return "; ".join(problems)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", required=True)
    ap.add_argument("--repo", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--only", help="run only this executable's cases")
    args = ap.parse_args()
    args.bin, args.repo, args.work = map(os.path.abspath, (args.bin, args.repo, args.work))
    args.fix = os.path.join(args.repo, "tests", "regression", "mesh", "tiny_case")
    all_cases = cases() + camera_cases() + frame_cases() + surface_cases() + pipe_cases() + flap_cases() + contract_cases()
    selected = [(i, k) for i, k in enumerate(all_cases) if not args.only or k["tool"] == args.only]
    kills = [(i, k) for i, k in enumerate(kill_cases()) if not args.only or k["tool"] == args.only]
    failed = 0
    for i, k in selected:
        why = run_case(i, k, args)
        if why:
            failed += 1
            print(f"FAIL {k['label']}: {why}")
    for i, k in kills:
        why = run_kill_case(i, k, args)
        if why:
            failed += 1
            print(f"FAIL kill -9 {k['tool']} after {k['after']} s: {why}")
    total = len(selected) + len(kills)
    print(f"bad-input suite: {total - failed} of {total} cases pass ({len(kills)} of them killed mid-run)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
