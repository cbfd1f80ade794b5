#!/usr/bin/env python3
"""CalculiX (ccx, Debian calculix-ccx) reference for the hybrid plate (data/cases/hybrid_plate.json).

Builds the plate with quadratic shells (S8R) and the three rays with quadratic beams (B32R)
sharing the plate's nodes on a structured mesh, runs the geometrically nonlinear static
(pressure, NLGEOM) case and the dynamic (leading-edge heave) case, and writes the beam-tip
displacements and CalculiX's wall time as JSON:

    calculix_hybrid_plate.py --case data/cases/hybrid_plate.json --nx 16 --nz 16 --out ccx.json

The benchmark and the FEM validation run it at two or more meshes to show that CalculiX's own
answer is converged before it is used as a reference. The validation reference
(data/reference/hybrid_plate_calculix.json: finest meshes, mesh study, ccx version, command,
date) is written with --reference-out, from fresh runs or, with --merge, from earlier outputs:

    calculix_hybrid_plate.py --case data/cases/hybrid_plate.json --nx 8 --nx 16 --nx 32 \
        --analysis static --out runs.json --reference-out data/reference/hybrid_plate_calculix.json

Dynamic reference (--analysis dynamic, default --dynamic-method modal): ccx's eigenmodes of the
plate clamped at the leading edge (*FREQUENCY, --modes of them), superposed analytically for the
heave y_LE = A (1 - cos 2 pi f t) (modal_history: exact in time, undamped). It is linear, so the
dynamic case is data/cases/hybrid_plate_small_heave.json (A = 0.001, a tenth of the plate
thickness), where fin-fem's NLGEOM answer is linear to 1e-4 of the deflection range. Checked
against a direct NLGEOM run of the plate alone (4x4, no beams, where ccx converges): deflection
range within 0.07 %, largest history difference 3 % of the range (the direct run's time step).

Why not ccx's *DYNAMIC (NLGEOM, --dynamic-method direct): with the B32R beams on the S8R nodes it
diverges between 0.003 and 0.29 s on every variant tried (4x4 mesh, 800 increments of 0.005 s): NLGEOM or
linear, ALPHA 0 or -0.3, automatic or fixed (DIRECT, 0.001) increments, beam moduli / 100,
isotropic or nu = 0 beams, leading-edge rotations free. The plate alone and the beams alone both
run to 4 s, so the cause is ccx's nonlinear beam/shell "knots" in direct integration. Modelling
the rays as orthotropic shell strips (--beam-model strip: no knots) runs, but ccx 2.20 is wrong
for strips narrower than about 0.1 here: a one-element-wide S8R strip gives "opposite normals"
and nonpositive Jacobians below 8 plate thicknesses, and S8 strips of width 0.02-0.06 clamped at
one end are 4-31 times too stiff against beam theory (0.1 wide: within 0.3 %), so that option is
kept only for the record. At A = 0.1 (data/cases/hybrid_plate.json) the plate's membrane
stiffening changes fin-fem's deflection range by 40 % against the linear answer, so no NLGEOM
dynamic reference exists for that amplitude.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time



REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def portable(arg):
    """A path as the stored reference should show it: relative to the repository when inside it,
    else only its file name (scratch outputs), so no machine's directories end up in data/."""
    if not arg.startswith("/"):
        return arg
    full = os.path.abspath(arg)
    if full.startswith(REPO + os.sep):
        return os.path.relpath(full, REPO)
    return os.path.basename(full)

def node_id(i, k, nz2):
    return 1 + i * (nz2 + 1) + k


def strip_bounds(case, width):
    """Spanwise interval of each beam's shell strip: centred on the beam axis, so that the
    strips of the edge beams reach half their width beyond the plate edge."""
    return [(b["z"] - 0.5 * width, b["z"] + 0.5 * width) for b in case["beams"]]


def span_grid(case, nz, strip_width):
    """Element edges along the span. beams: nz equal cells (beams on element edges). strips:
    each beam becomes one element of width strip_width centred on its axis, and the plate
    between strips gets about nz cells over the whole span, split in proportion to length."""
    span = case["plate"]["span"]
    z0 = -0.5 * span
    if not strip_width:
        return [z0 + span * k / nz for k in range(nz + 1)]
    strips = sorted(strip_bounds(case, strip_width))
    edges = [strips[0][0]]
    for (a0, a1), (b0, _) in zip(strips, strips[1:]):
        if b0 <= a1:
            raise SystemExit("calculix_hybrid_plate: beam strips overlap; use a smaller --strip-width")
        edges.append(a1)
        n = max(1, round(nz * (b0 - a1) / span))
        edges += [a1 + (b0 - a1) * j / n for j in range(1, n + 1)]
    edges.append(strips[-1][1])
    if strips[0][0] > z0 or strips[-1][1] < z0 + span:
        raise SystemExit("calculix_hybrid_plate: --beam-model strip needs beams at both plate edges")
    return edges


def build_mesh(case, nx, nz, strip_width=0.0):
    """Nodes and S8R/B32R connectivity on a (2nx+1) x (2nz'+1) node grid (quad centres unused).
    With strip_width > 0 the beams are shell strips (elements listed per beam in `strips`) and
    no B32R is generated; the tip is the mid-side node of the strip's trailing edge, on the
    beam axis."""
    chord = case["plate"]["chord"]
    zc = span_grid(case, nz, strip_width)
    nze = len(zc) - 1
    nx2, nz2 = 2 * nx, 2 * nze
    zq = []
    for k in range(nze):
        zq += [zc[k], 0.5 * (zc[k] + zc[k + 1])]
    zq.append(zc[-1])
    nodes = {}
    for i in range(nx2 + 1):
        for k in range(nz2 + 1):
            if i % 2 and k % 2:
                continue
            nodes[node_id(i, k, nz2)] = (chord * i / nx2, 0.0, zq[k])
    shells = []
    owner = []  # None: plate; else the beam whose strip holds the element
    strips = strip_bounds(case, strip_width) if strip_width else []
    for ex in range(nx):
        for ez in range(nze):
            i, k = 2 * ex, 2 * ez
            c = [(i, k), (i + 2, k), (i + 2, k + 2), (i, k + 2), (i + 1, k), (i + 2, k + 1), (i + 1, k + 2), (i, k + 1)]
            shells.append([node_id(a, b, nz2) for a, b in c])
            zm = 0.5 * (zc[ez] + zc[ez + 1])
            owner.append(next((b["name"] for b, (a0, a1) in zip(case["beams"], strips) if a0 < zm < a1), None))
    beams = {}
    tips = {}
    for b in case["beams"]:
        kb = min(range(nz2 + 1), key=lambda k: abs(zq[k] - b["z"]))
        if abs(zq[kb] - b["z"]) > 1e-12 or (not strip_width and kb % 2):
            raise SystemExit(f"calculix_hybrid_plate: beam {b['name']} at z={b['z']} is not on an element edge of nz={nz}")
        if not strip_width:
            beams[b["name"]] = [[node_id(i, kb, nz2), node_id(i + 1, kb, nz2), node_id(i + 2, kb, nz2)]
                                for i in range(0, nx2, 2)]
        tips[b["name"]] = node_id(nx2, kb, nz2)
    leading = [node_id(0, k, nz2) for k in range(nz2 + 1)]
    return nodes, shells, owner, beams, leading, tips, zc


def torsion_constant(a, c):
    """Saint-Venant torsion constant of an a x c rectangle (the approximation finverse's
    tools/fem/beam_section.cpp uses)."""
    a, c = max(a, c), min(a, c)
    r = c / a
    return a * c ** 3 * (1.0 / 3.0 - 0.21 * r * (1.0 - r ** 4 / 12.0))


def strip_material(case, b, strip_width):
    """Orthotropic shell strip of the plate's thickness standing for beam b (global axes: 1 = x
    along the beam, 2 = y the plate normal, 3 = z along the span). Same thickness as the plate,
    so ccx expands strip and plate alike and generates no knot where they meet (beam/shell knots
    make ccx's *DYNAMIC diverge, see the module comment). E1 gives the strip the beam's bending
    stiffness E I about z, the shear moduli its torsional stiffness G J; E2 = E3 = E_plate keeps
    the plate's spanwise bending across the strip; the density holds the beam's mass plus the
    plate's mass that the strip replaces, so that mass per length is that of plate + beam."""
    p = case["plate"]
    t = p["thickness"]
    w = strip_width
    i_b = b["width"] * b["thickness"] ** 3 / 12.0
    i_s = w * t ** 3 / 12.0
    e1 = b["E"] * i_b / i_s
    g_b = b["E"] / (2 * (1 + b["nu"]))
    g = g_b * torsion_constant(b["width"], b["thickness"]) / torsion_constant(w, t)
    a0, a1 = b["z"] - 0.5 * w, b["z"] + 0.5 * w
    overlap = max(0.0, min(a1, 0.5 * p["span"]) - max(a0, -0.5 * p["span"]))
    rho = (b["density"] * b["width"] * b["thickness"] + p["density"] * t * overlap) / (w * t)
    return e1, p["E"], g, rho


def write_input(path, case, nx, nz, analysis, beam_model="beam", strip_width=0.0):
    sw = strip_width if beam_model == "strip" else 0.0
    nodes, shells, owner, beams, leading, tips, _ = build_mesh(case, nx, nz, sw)
    p = case["plate"]
    out = ["** finverse hybrid plate, CalculiX reference, " + analysis + ", beams as " + beam_model,
           "*NODE, NSET=NALL"]
    out += [f"{n},{x:.15g},{y:.15g},{z:.15g}" for n, (x, y, z) in sorted(nodes.items())]
    eid = 0
    for name in [None] + [b["name"] for b in case["beams"]]:
        ids = [e for e, o in enumerate(owner) if o == name]
        if not ids:
            continue
        # Strips as S8 (full integration): ccx 2.20 rejects S8R strips narrower than about 8 shell
        # thicknesses ("opposite normals are defined" in gen3dnor, then nonpositive Jacobians).
        out.append(f"*ELEMENT, TYPE=S8R, ELSET=PLATE" if name is None else f"*ELEMENT, TYPE=S8, ELSET=STRIP_{name.upper()}")
        for e in ids:
            eid += 1
            out.append(f"{eid}," + ",".join(map(str, shells[e])))
    for name, conn in beams.items():
        out.append(f"*ELEMENT, TYPE=B32R, ELSET=BEAM_{name.upper()}")
        for c in conn:
            eid += 1
            out.append(f"{eid}," + ",".join(map(str, c)))
    out.append("*NSET, NSET=LE")
    out += [",".join(map(str, leading[i:i + 12])) for i in range(0, len(leading), 12)]
    out.append("*NSET, NSET=TIPS")
    out.append(",".join(str(tips[b["name"]]) for b in case["beams"]))
    out += ["*MATERIAL, NAME=PLATE", "*ELASTIC", f"{p['E']:.10g},{p['nu']:.10g}", "*DENSITY", f"{p['density']:.10g}",
            "*SHELL SECTION, ELSET=PLATE, MATERIAL=PLATE", f"{p['thickness']:.10g}"]
    for b in case["beams"]:
        n = b["name"].upper()
        if sw:
            e1, e23, g, rho = strip_material(case, b, sw)
            out += [f"*MATERIAL, NAME=M_{n}", "*ELASTIC, TYPE=ENGINEERING CONSTANTS",
                    f"{e1:.10g},{e23:.10g},{e23:.10g},0,0,0,{g:.10g},{g:.10g}", f"{g:.10g}",
                    "*DENSITY", f"{rho:.10g}",
                    f"*SHELL SECTION, ELSET=STRIP_{n}, MATERIAL=M_{n}", f"{p['thickness']:.10g}"]
            continue
        # RECT a,b: a along the first section direction (given: z, in the plate plane), b along
        # tangent x first direction (here -y, the plate normal).
        # Engineering constants E, nu = 0, G = E / (2 (1 + nu)): ccx expands a B32R into C3D20R
        # bricks, and where a beam shares its nodes with the shell every node becomes a rigid
        # "knot" that keeps the section from contracting laterally; with the isotropic nu = 0.3
        # the fibres then act with the constrained modulus E (1 - nu) / ((1 + nu)(1 - 2 nu)) =
        # 1.35 E (measured: linear tips 26-35 % stiffer than finverse's). A beam's response depends
        # on E and G only, so nu = 0 with G kept is the same Euler-Bernoulli/Timoshenko beam as
        # finverse's and removes the artefact.
        g = b["E"] / (2 * (1 + b["nu"]))
        out += [f"*MATERIAL, NAME=M_{n}", "*ELASTIC, TYPE=ENGINEERING CONSTANTS",
                f"{b['E']:.10g},{b['E']:.10g},{b['E']:.10g},0,0,0,{g:.10g},{g:.10g}", f"{g:.10g}",
                "*DENSITY", f"{b['density']:.10g}",
                f"*BEAM SECTION, ELSET=BEAM_{n}, MATERIAL=M_{n}, SECTION=RECT", f"{b['width']:.10g},{b['thickness']:.10g}",
                "0.,0.,1."]
    if analysis == "modal":
        # Eigenmodes of the plate clamped at the leading edge (linear: ccx's *FREQUENCY has no
        # NLGEOM); the heave response is superposed from them in modal_history().
        out += ["*BOUNDARY", "LE,1,6", "*STEP", "*FREQUENCY", str(case.get("_ccx_modes", 60))]
    elif analysis == "static":
        s = case["static"]
        # Dead load, as in finverse (nodal loads keep their direction): ccx's *DLOAD P is a
        # follower pressure under NLGEOM, so the pressure enters as the consistent nodal forces
        # of the S8R serendipity interpolation on each rectangular element, -1/12 of p A at a
        # corner and 1/3 at a mid-side node, all along -y.
        out += ["*BOUNDARY", "LE,1,6", f"*STEP, NLGEOM, INC=1000", "*STATIC", f"{1.0 / s['load_steps']:.10g},1.0",
                "*CLOAD"]
        force = {}
        # A strip reaching beyond the plate edge carries the pressure on its part inside the
        # plate only (spread as if uniform over the element).
        half = 0.5 * p["span"]
        for c in shells:
            xs = [nodes[n][0] for n in c[:4]]
            zs = [nodes[n][2] for n in c[:4]]
            area = (max(xs) - min(xs)) * max(0.0, min(max(zs), half) - max(min(zs), -half))
            for j, n in enumerate(c):
                force[n] = force.get(n, 0.0) + (-1.0 / 12.0 if j < 4 else 1.0 / 3.0) * s["pressure"] * area
        out += [f"{n},2,{-f:.15g}" for n, f in sorted(force.items()) if f != 0.0]
    else:
        d = case["dynamic"]
        f, a = d["frequency"], d["heave_amplitude"]
        t_end = d["periods"] / f
        dt = d["time_step"]
        # ALPHA = 0: ccx's alpha method reduces to the trapezoidal rule (finverse: generalized-alpha
        # with rho_inf = 1). The increment is the case's time step, cut by ccx's automatic
        # incrementation only where its Newton iteration does not converge (a fixed DIRECT
        # increment diverges there); the output times are then not all on the case's grid.
        # Tabulated y_LE(t) = A (1 - cos 2 pi f t) / A; ccx interpolates linearly, so sample finely.
        samples = int(round(t_end / (dt / 4))) + 1
        amp = []
        for j in range(samples):
            t = t_end * j / (samples - 1)
            amp.append(f"{t:.10g},{1 - math.cos(2 * math.pi * f * t):.12g}")
        out += ["*AMPLITUDE, NAME=HEAVE"] + [",".join(amp[i:i + 4]) for i in range(0, len(amp), 4)]
        out += ["*BOUNDARY", "LE,1,1", "LE,3,6", "*STEP, NLGEOM, INC=100000", f"*DYNAMIC, ALPHA={case.get('_ccx_alpha', 0.0):.6g}",
                f"{dt:.10g},{t_end:.10g},{dt / 64:.10g},{dt:.10g}", "*BOUNDARY, AMPLITUDE=HEAVE", f"LE,2,2,{a:.10g}"]
    out += ["*NODE PRINT, NSET=TIPS", "U", "*END STEP"]
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")
    return tips, len(shells), eid - len(shells), len(nodes)



def parse_dat(path, tips):
    """Time series of the tip displacements from the .dat file."""
    by_node = {v: k for k, v in tips.items()}
    series = []
    block = re.compile(r"displacements \(vx,vy,vz\) for set TIPS and time\s+(\S+)")
    current = None
    with open(path) as fh:
        for line in fh:
            m = block.search(line)
            if m:
                current = {"time": float(m.group(1)), "u": {}}
                series.append(current)
                continue
            parts = line.split()
            if current is not None and len(parts) == 4 and parts[0].isdigit() and int(parts[0]) in by_node:
                current["u"][by_node[int(parts[0])]] = [float(x) for x in parts[1:]]
    return [s for s in series if len(s["u"]) == len(tips)]


def parse_modes(path, tips):
    """Eigenvalues, participation factors along y and effective modal masses along y of a
    *FREQUENCY step, and the tip y displacements of each mode (ccx normalises the modes to unit
    modal mass)."""
    omega2, gamma_y, mass_y = [], [], []
    table = None
    with open(path) as fh:
        for line in fh:
            if "E I G E N V A L U E   O U T P U T" in line:
                table = "eig"
            elif "P A R T I C I P A T I O N   F A C T O R S" in line:
                table = "part"
            elif "E F F E C T I V E   M O D A L   M A S S" in line:
                table = "mass"
            elif "T O T A L   E F F E C T I V E   M A S S" in line or "displacements" in line:
                table = None
            parts = line.split()
            if table and len(parts) >= 5 and parts[0].isdigit():
                if table == "eig":
                    omega2.append(float(parts[1]))
                elif table == "part":
                    gamma_y.append(float(parts[2]))
                elif table == "mass":
                    mass_y.append(float(parts[2]))
    shapes = parse_dat(path, tips)
    if not omega2 or len(gamma_y) != len(omega2) or len(shapes) != len(omega2) or len(mass_y) != len(omega2):
        raise SystemExit(f"calculix_hybrid_plate: cannot read the modes in {path}")
    # ccx's knots (rotations fixed on expanded shell nodes) can give a few spurious negative
    # eigenvalues; they are dropped when they carry no mass in y (the heave cannot excite them).
    # Likewise a few modes print tip displacements of 1e8 and more although normalised to unit
    # modal mass (a node carrying mass moves by at most about 1/sqrt(its mass), here ~ 30): they
    # are spurious too and dropped under the same condition.
    keep = []
    total = sum(mass_y)
    for i, w2 in enumerate(omega2):
        spurious = w2 <= 0 or max(abs(v[1]) for v in shapes[i]["u"].values()) > 1e3
        if not spurious:
            keep.append(i)
        elif abs(mass_y[i]) > 1e-6 * total:
            raise SystemExit(f"calculix_hybrid_plate: spurious mode {i + 1} in {path} (eigenvalue {w2}) "
                             f"has effective mass {mass_y[i]} in y")
    pick = lambda v: [v[i] for i in keep]
    return (pick(omega2), pick(gamma_y), pick(mass_y),
            pick([{k: u[1] for k, u in m["u"].items()} for m in shapes]))


def modal_history(case, omega2, gamma_y, shapes):
    """Tip histories of the leading-edge heave by exact modal superposition. With the leading
    edge clamped, the deflection relative to the heaved base, w = u - r y_LE (r: unit y
    translation), obeys M w'' + K w = -M r y_LE''; per mass-normalised mode i
    q_i'' + w_i^2 q_i = -Gamma_i y_LE'' with Gamma_i = phi_i^T M r (ccx's participation factor).
    For y_LE = A (1 - cos W t), y_LE'' = A W^2 cos W t, and from rest
    q_i = -Gamma_i A W^2 / (w_i^2 - W^2) (cos W t - cos w_i t): exact in time, undamped.
    The tips' absolute y displacements u = w + y_LE are returned on the case's time grid."""
    d = case["dynamic"]
    a, big_w = d["heave_amplitude"], 2 * math.pi * d["frequency"]
    dt, t_end = d["time_step"], d["periods"] / d["frequency"]
    steps = int(round(t_end / dt))
    series = []
    for k in range(1, steps + 1):
        t = k * dt
        heave = a * (1 - math.cos(big_w * t))
        u = {name: [0.0, heave, 0.0] for name in shapes[0]}
        for w2, g, phi in zip(omega2, gamma_y, shapes):
            wi = math.sqrt(w2)
            q = -g * a * big_w ** 2 / (w2 - big_w ** 2) * (math.cos(big_w * t) - math.cos(wi * t))
            for name in u:
                u[name][1] += phi[name] * q
        series.append({"time": t, "u": u})
    return series


def run(case, nx, nz, analysis, keep_dir=None, beam_model="beam", strip_width=0.0):
    ccx = shutil.which("ccx")
    if not ccx:
        raise SystemExit("calculix_hybrid_plate: ccx not found (install with tools/scripts/install-deps.sh --peers)")
    work = keep_dir or tempfile.mkdtemp(prefix="finverse_ccx_")
    os.makedirs(work, exist_ok=True)
    modal = analysis == "dynamic" and case.get("_ccx_method", "modal") == "modal"
    step = "modal" if modal else analysis
    job = os.path.join(work, f"hybrid_{step}_{beam_model}_{nx}x{nz}")
    tips, nshell, nbeam, nnode = write_input(job + ".inp", case, nx, nz, step, beam_model, strip_width)
    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "2"),
               CCX_NPROC_EQUATION_SOLVER=os.environ.get("OMP_NUM_THREADS", "2"))
    t0 = time.perf_counter()
    proc = subprocess.run([ccx, "-i", os.path.basename(job)], cwd=work, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0 or "*ERROR" in proc.stdout:
        tail = "\n".join(proc.stdout.splitlines()[-15:])
        raise SystemExit(f"calculix_hybrid_plate: ccx failed on {job}.inp:\n{tail}")
    if modal:
        omega2, gamma_y, mass_y, shapes = parse_modes(job + ".dat", tips)
        series = modal_history(case, omega2, gamma_y, shapes)
    else:
        series = parse_dat(job + ".dat", tips)
    if not series:
        raise SystemExit(f"calculix_hybrid_plate: no tip displacements in {job}.dat")
    if keep_dir is None:
        shutil.rmtree(work, ignore_errors=True)
    out = {"case": case.get("_path"), "nx": nx, "nz": nz, "shell_elements": nshell, "beam_elements": nbeam,
           "nodes": nnode, "wall_s": wall, "beam_model": beam_model, "series": series}
    if beam_model == "strip":
        out["strip_width"] = strip_width
    if analysis == "dynamic":
        out["_dynamic"] = {k: case["dynamic"][k] for k in ("heave_amplitude", "frequency")}
        out["time_step"] = case["dynamic"]["time_step"]
        out["method"] = "modal" if modal else "direct"
        if modal:
            out["modes"] = len(omega2)
            out["frequencies"] = [math.sqrt(max(w2, 0.0)) / (2 * math.pi) for w2 in omega2[:10]]
            out["effective_mass_y"] = sum(mass_y)
        else:
            out["alpha"] = case.get("_ccx_alpha", 0.0)
    return out


def tips_y(series_entry):
    return {name: u[1] for name, u in series_entry["u"].items()}


def relative_change(a, b):
    """Static: largest relative change of the tip y displacements between two runs. Dynamic:
    largest change over the history of a tip's y displacement relative to the range (max - min)
    of its deflection w = u_y - y_LE in the finer run (both runs on the case's time grid)."""
    if a.get("time_step") is None:
        ya, yb = tips_y(a["series"][-1]), tips_y(b["series"][-1])
        return max(abs(yb[k] - ya[k]) / abs(yb[k]) for k in yb)
    if [s["time"] for s in a["series"]] != [s["time"] for s in b["series"]]:
        raise SystemExit("calculix_hybrid_plate: dynamic runs of a mesh study need the same output times")
    change = 0.0
    for k in b["series"][0]["u"]:
        ua = [s["u"][k][1] for s in a["series"]]
        ub = [s["u"][k][1] for s in b["series"]]
        heave = [s["u"][k][1] - w for s, w in zip(b["series"], deflection(b, k))]
        wb = [u - h for u, h in zip(ub, heave)]
        change = max(change, max(abs(x - y) for x, y in zip(ua, ub)) / (max(wb) - min(wb)))
    return change


def deflection(run_result, tip):
    """w = u_y - y_LE of one tip over a dynamic run."""
    d = run_result["_dynamic"]
    big_w = 2 * math.pi * d["frequency"]
    return [s["u"][tip][1] - d["heave_amplitude"] * (1 - math.cos(big_w * s["time"])) for s in run_result["series"]]


def build_reference(result, tolerance):
    """The reference file for tools/fem/validation/hybrid_plate.cpp: the finest static and
    dynamic runs, with the mesh study (successive relative changes of the final tip values)."""
    ref = {k: result[k] for k in ("peer", "case", "command", "date", "omp_threads", "sources") if k in result}
    ref["schema"] = "finverse/calculix_hybrid_plate"
    ref["mesh_study_tolerance"] = tolerance
    ref["mesh_study"] = []
    for analysis in ("static", "dynamic"):
        runs = sorted((r for r in result["runs"] if r["analysis"] == analysis), key=lambda r: r["nx"] * r["nz"])
        if not runs:
            continue
        for prev, r in zip([None] + runs[:-1], runs):
            row = {"analysis": analysis, "nx": r["nx"], "nz": r["nz"], "nodes": r["nodes"], "wall_s": r["wall_s"],
                   "final_time": r["series"][-1]["time"], "tips_y": tips_y(r["series"][-1])}
            if prev is not None:
                row["relative_change"] = relative_change(prev, r)
            ref["mesh_study"].append(row)
        fine = runs[-1]
        entry = {"case": fine.get("case", result.get("case")), "nx": fine["nx"], "nz": fine["nz"],
                 "wall_s": fine["wall_s"], "converged": len(runs) > 1 and relative_change(runs[-2], fine) < tolerance}
        if analysis == "static":
            entry["tips_y"] = tips_y(fine["series"][-1])
        else:
            for key in ("method", "modes", "frequencies", "effective_mass_y", "time_step", "alpha"):
                if key in fine:
                    entry[key] = fine[key]
            entry.update(fine["_dynamic"])
            entry["time"] = [s["time"] for s in fine["series"]]
            entry["tips_y"] = {k: [s["u"][k][1] for s in fine["series"]] for k in fine["series"][0]["u"]}
        ref[analysis] = entry
    return ref


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", required=True)
    ap.add_argument("--nx", type=int, action="append", help="elements along the chord (repeatable: mesh study)")
    ap.add_argument("--nz", type=int, action="append", help="elements along the span (same count as --nx)")
    ap.add_argument("--analysis", choices=["static", "dynamic", "both"], default="both")
    ap.add_argument("--out", required=True)
    ap.add_argument("--reference-out", help="also write the validation reference (finest meshes + mesh study) here")
    ap.add_argument("--study-tolerance", type=float, default=0.005,
                    help="mesh study: converged when the finest two meshes differ by less than this")
    ap.add_argument("--merge", nargs="+", metavar="RUNS_JSON",
                    help="run nothing: merge the runs of earlier outputs of this script (each keeps its command and date)")
    ap.add_argument("--keep", help="keep CalculiX's files in this directory")
    ap.add_argument("--beam-model", choices=["beam", "strip"], default="beam",
                    help="rays as B32R beams on the shell's nodes, or as orthotropic S8R strips of the plate's "
                         "thickness (no beam/shell knots: the only model whose *DYNAMIC converges in ccx 2.20)")
    ap.add_argument("--strip-width", type=float, default=0.02, help="width of a ray's strip (--beam-model strip)")
    ap.add_argument("--time-step", type=float, help="dynamic: ccx increment instead of the case's time step")
    ap.add_argument("--dynamic-method", choices=["modal", "direct"], default="modal",
                    help="modal: ccx *FREQUENCY + exact modal superposition of the heave (linear); "
                         "direct: ccx *DYNAMIC NLGEOM (diverges with beams on shell nodes in ccx 2.20)")
    ap.add_argument("--modes", type=int, default=60, help="eigenmodes kept (--dynamic-method modal)")
    ap.add_argument("--alpha", type=float, default=0.0,
                    help="ccx *DYNAMIC ALPHA in [-1/3, 0] (0: trapezoidal rule, as finverse's rho_inf = 1)")
    args = ap.parse_args()
    with open(args.case) as fh:
        case = json.load(fh)
    case["_path"] = portable(args.case)
    case["_ccx_alpha"] = args.alpha
    case["_ccx_method"] = args.dynamic_method
    case["_ccx_modes"] = args.modes
    if args.time_step:
        case["dynamic"]["time_step"] = args.time_step
    nxs = args.nx or [8, 16]
    nzs = args.nz or nxs
    if len(nxs) != len(nzs):
        raise SystemExit("calculix_hybrid_plate: give as many --nz as --nx")
    version = subprocess.run(["ccx", "-v"], capture_output=True, text=True).stdout.strip().splitlines()
    result = {"peer": "CalculiX " + (version[-1].split()[-1] if version else "?"), "case": portable(args.case),
              "command": " ".join([os.path.basename(sys.argv[0])] + [portable(a) for a in sys.argv[1:]]),
              "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
              "omp_threads": int(os.environ.get("OMP_NUM_THREADS", "2")), "runs": []}
    analyses = ["static", "dynamic"] if args.analysis == "both" else [args.analysis]
    if args.merge:
        analyses = []
        result["sources"] = []
        for path in args.merge:
            with open(path) as fh:
                earlier = json.load(fh)
            result["peer"] = earlier["peer"]
            result["sources"].append({k: earlier.get(k) for k in ("command", "date", "omp_threads")})
            for r in earlier["runs"]:
                r.setdefault("case", earlier.get("case"))
            result["runs"] += earlier["runs"]
        for r in result["runs"]:
            if r.get("analysis") == "dynamic" and "_dynamic" not in r:
                r["_dynamic"] = {k: case["dynamic"][k] for k in ("heave_amplitude", "frequency")}
    for analysis in analyses:
        for nx, nz in zip(nxs, nzs):
            r = run(case, nx, nz, analysis, args.keep, args.beam_model, args.strip_width)
            r["analysis"] = analysis
            final = r["series"][-1]["u"]
            print(f"{analysis:7s} {nx:3d}x{nz:<3d} {r['wall_s']:7.2f} s  tips " +
                  "  ".join(f"{k}: {v[1]:+.5f}" for k, v in final.items()), file=sys.stderr)
            result["runs"].append(r)
    outputs = [(args.out, result)]
    if args.reference_out:
        outputs.append((args.reference_out, build_reference(result, args.study_tolerance)))
    for path, data in outputs:
        tmp = path + ".tmp"
        with open(tmp, "w") as fh:
            json.dump(data, fh, indent=1)
        os.replace(tmp, path)


if __name__ == "__main__":
    main()
