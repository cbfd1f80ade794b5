#!/usr/bin/python3
"""How much of a fin run's load noise the output-interval mean removes, from a loads.h5 written
with one output per step (docs/studies/fin_load_noise.md, sections 2 and 3).

    tools/scripts/loads_noise.py window loads.h5 [N]      last period as N outputs: sampled vs mean
    tools/scripts/loads_noise.py band loads.h5 M W SKIP   in-band noise of a short record

window: the record holds one period of S steps (fin-cfd fin ... --output-interval <dt>
--output-periods 1 --sample-loads); it forms N outputs (m = S/N steps apart) both as one step
each and as the centred box mean over m steps (tools/cfd/io/loads_window.hpp), and prints the
smoothness measures of tools/cfd/validation/load_smoothness.cpp for both.
band: a short, not periodic record; the box mean over M steps (what an output mean keeps) less
a running cubic over W steps, after SKIP steps: the rms of what remains, and the same without the
mean (the per-step noise).
"""
import sys

import h5py
import numpy as np

K = 10  # harmonics in the smooth part (issue 30)


def window(path, n_out):
    f = h5py.File(path, "r")
    ct, cl = f["coefficients/thrust"][:], f["coefficients/lateral"][:]
    nodal = f["nodal_force"][:].reshape(len(ct), -1)
    jump = f["pressure_jump"][:]
    steps = len(ct)
    m = steps // n_out
    if m * n_out != steps:
        sys.exit(f"{path}: {steps} steps are not {n_out} outputs")

    def box(x):  # output k at step k m (1-based), periodic record
        xx = np.concatenate([x, x, x])
        out = []
        for k in range(1, n_out + 1):
            s = k * m - 1 + steps
            if m % 2:
                idx, w = range(s - (m - 1) // 2, s + (m - 1) // 2 + 1), np.ones(m)
            else:
                idx, w = range(s - m // 2, s + m // 2 + 1), np.ones(m + 1)
                w[0] = w[-1] = 0.5
            out.append(np.tensordot(w, xx[list(idx)], axes=1) / w.sum())
        return np.array(out)

    def sample(x):
        return x[m - 1::m]

    def smooth(x):
        X = np.fft.rfft(x, axis=0)
        X[K + 1:] = 0
        return np.fft.irfft(X, len(x), axis=0)

    def energy_fraction(x):
        X = np.abs(np.fft.rfft(x - x.mean())) ** 2
        X[1:len(x) // 2] *= 2
        return X[K + 1:].sum() / X[1:].sum()

    def rms_ratio(x):
        s = smooth(x)
        return np.sqrt(((x - s) ** 2).sum() / (s ** 2).sum())

    def increment_ratio(x):
        s = smooth(x)
        return np.sqrt((np.diff(x, axis=0) ** 2).sum() / (np.diff(s, axis=0) ** 2).sum())

    for name, op in (("sampled", sample), ("mean", box)):
        a, b, n, p = op(ct), op(cl), op(nodal), op(jump)
        print(f"{name:8s} N={n_out} m={m}: energy>10 C_T {energy_fraction(a):.4f} C_L {energy_fraction(b):.4f} | "
              f"rms ratio nodal {rms_ratio(n):.4f} jump {rms_ratio(p):.4f} | increment ratio nodal "
              f"{increment_ratio(n):.3f} C_T {increment_ratio(a):.3f} | C_T mean {a.mean():+.4f} max {a.max():+.3f} "
              f"max|C_L| {np.abs(b).max():.3f}")


def band(path, m, w, skip):
    f = h5py.File(path, "r")

    def running_cubic(x):
        h, out = w // 2, np.empty(len(x))
        for i in range(len(x)):
            a, b = max(0, i - h), min(len(x), i + h + 1)
            out[i] = np.polyfit(np.arange(a, b) - i, x[a:b], 3)[-1]
        return out

    for key in ("thrust", "lateral"):
        x = f["coefficients/" + key][skip:]
        y = np.convolve(x, np.ones(m) / m, "valid")
        inner = slice(w // 2, -(w // 2))
        print(f"{key}: in-band noise rms {np.std((y - running_cubic(y))[inner]):.4f}  per-step noise rms "
              f"{np.std((x - running_cubic(x))[inner]):.4f}  rms(C) {np.sqrt((x ** 2).mean()):.3f}")


if __name__ == "__main__":
    if len(sys.argv) >= 3 and sys.argv[1] == "window":
        window(sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 100)
    elif len(sys.argv) == 6 and sys.argv[1] == "band":
        band(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]))
    else:
        sys.exit(__doc__)
