#!/usr/bin/python3
"""Grid convergence of the fin's loads (issue 30 item 5, docs/studies/fin_load_grid_convergence.md).

    tools/scripts/loads_convergence.py H1:loads1.h5 H2:loads2.h5 H3:loads3.h5 ...

Each argument is a cell size (in chords, e.g. 0.0625 for c/16) and the loads.h5 of the default
fin run at that resolution (same mesh.h5 and motion, so the nodal forces are on the same nodes).
Over the last period (every output of the file): mean and peak C_T, the C_Y (lateral)
fundamental's amplitude and phase, and the nodal-force field; for every consecutive triple the
observed order p of each scalar from the three-level Richardson relation (non-uniform ratios,
solved by fixed-point iteration), and the field's relative rms difference to the finest run.
"""
import sys

import h5py
import numpy as np


def load(path):
    f = h5py.File(path, "r")
    t = f["time"][:]
    ct, cy = f["coefficients/thrust"][:], f["coefficients/lateral"][:]
    nodal = f["nodal_force"][:]
    period = float(f.attrs["T"]) if "T" in f.attrs else t[-1] - t[0]
    keep = t >= t[-1] - period * (1 - 0.5 / len(t))
    t, ct, cy, nodal = t[keep], ct[keep], cy[keep], nodal[keep]
    w = 2 * np.pi / period
    c1 = 2 * np.mean(cy * np.exp(-1j * w * t))
    return {"CT_mean": ct.mean(), "CT_max": ct.max(), "CY_amp": abs(c1), "CY_phase_deg": np.degrees(np.angle(c1)),
            "nodal": nodal, "n": len(t)}


def order(h, f):
    """Observed order from three levels h1 > h2 > h3 (f1, f2, f3), or nan when not monotone."""
    (h1, h2, h3), (f1, f2, f3) = h, f
    e21, e32 = f2 - f1, f3 - f2
    if e21 == 0 or e32 == 0 or np.sign(e21) != np.sign(e32):
        return float("nan")
    r21, r32 = h1 / h2, h2 / h3
    p = abs(np.log(abs(e21 / e32))) / np.log(r21)
    for _ in range(100):  # Celik et al. 2008: p = |ln|e21/e32| + q(p)| / ln r21
        q = np.log((r21**p - 1) / (r32**p - 1))
        p = abs(np.log(abs(e21 / e32)) + q) / np.log(r21)
    return p


def main(args):
    runs = []
    for a in args:
        h, path = a.split(":", 1)
        runs.append((float(h), path, load(path)))
    runs.sort(key=lambda r: -r[0])
    fine = runs[-1][2]["nodal"]
    keys = ["CT_mean", "CT_max", "CY_amp", "CY_phase_deg"]
    print("h/c      " + "  ".join(f"{k:>12}" for k in keys) + "  nodal_rms_diff_to_finest")
    for h, path, r in runs:
        n = min(len(r["nodal"]), len(fine))
        diff = np.sqrt(np.mean((r["nodal"][:n] - fine[:n]) ** 2)) / np.sqrt(np.mean(fine[:n] ** 2))
        print(f"{h:<8.4f} " + "  ".join(f"{r[k]:12.4f}" for k in keys) + f"  {diff:.4f}")
    for i in range(len(runs) - 2):
        tri = runs[i:i + 3]
        hs = [t[0] for t in tri]
        print(f"observed order, h/c = {hs[0]:.4f}, {hs[1]:.4f}, {hs[2]:.4f}: " +
              ", ".join(f"{k} {order(hs, [t[2][k] for t in tri]):.2f}" for k in keys))


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1:])
