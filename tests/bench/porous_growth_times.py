#!/usr/bin/env python3
"""Growth times of one cell of a porous run, for the mass-resolution study of
tests/bench/results/porous_mmsn.md (local growth, transport off): when the cell's
mass-weighted mean mass <m> = sum_k sigma_k m_k / sum_k sigma_k (a size distribution) or
its particle mass m (the single size) first reaches 1e-9, 1e-6, ..., 1e12 g (interpolated
in ln <m> between snapshots), and between which snapshots its mass-dominating St first
reaches 10.
Usage: porous_growth_times.py [--cell I] RUN.h5 [RUN2.h5 ...]."""
import argparse

import h5py
import numpy as np

MASSES_G = [1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9, 1e12]


def open_run(path):
    """The file, readable while its run still writes it (SWMR)."""
    try:
        return h5py.File(path, "r", swmr=True, libver="latest")
    except OSError:
        return h5py.File(path, "r")


def mean_mass(f, cell):
    s = f["snapshots"]
    n_t = len(s["time"])
    if "sigma" in s and "m_bins" in f["grid"]:
        m = f["grid/m_bins"][:]
        sigma = s["sigma"][:].reshape(n_t, -1, len(m))[:, cell, :]
        return (sigma * m).sum(axis=1) / sigma.sum(axis=1)
    return s["m"][:, cell]


def first_time(t, x, level):
    """When x first reaches level, interpolated in ln x; None when it never does."""
    hit = np.nonzero(x >= level)[0]
    if len(hit) == 0:
        return None
    i = hit[0]
    if i == 0:
        return float(t[0])
    w = np.log(level / x[i - 1]) / np.log(x[i] / x[i - 1])
    return float(t[i - 1] + w * (t[i] - t[i - 1]))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("runs", nargs="+")
    p.add_argument("--cell", type=int, default=0)
    a = p.parse_args()
    print("run | " + " | ".join(f"<m> {m:g} g [yr]" for m in MASSES_G) +
          " | St >= 10 between [yr] | last snapshot [yr]")
    for path in a.runs:
        with open_run(path) as f:
            t = f["snapshots/time"][:]
            m = mean_mass(f, a.cell)
            st = f["snapshots/St"][:, a.cell]
            times = [first_time(t, m, level) for level in MASSES_G]
            hit = np.nonzero(st >= 10.0)[0]
            onset = "-" if len(hit) == 0 else f"{t[max(hit[0] - 1, 0)]:.0f}-{t[hit[0]]:.0f}"
            cols = ["-" if x is None else f"{x:.0f}" for x in times]
            print(f"{path} | " + " | ".join(cols) + f" | {onset} | {t[-1]:.0f}")


if __name__ == "__main__":
    main()
