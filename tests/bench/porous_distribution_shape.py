#!/usr/bin/env python3
"""The shape of one cell's size distribution over time, for comparing a size-distribution
run with the single-size run of the same scene (tests/bench/results/porous_mmsn.md, "Why
the distribution grows unlike the single size"). Per snapshot: the mass-weighted mean
mass <m> = sum_k sigma_k m_k / sum_k sigma_k, the mass-dominating bin (largest sigma_k)
with its St and filling factor, the mass-weighted spread of log10 m and of ln St, and the
mass fraction in the tail, the bins whose St exceeds 10x the mass-dominating bin's.
A single-size run prints its particle's m, St and phi.
Usage: porous_distribution_shape.py [--cell I] [--every N] RUN.h5 [RUN2.h5 ...]."""
import argparse

import numpy as np

from porous_growth_times import open_run


def spread(w, x):
    """Standard deviation of x under the weights w (sum 1)."""
    mean = (w * x).sum()
    return float(np.sqrt((w * (x - mean) ** 2).sum()))


def distribution_rows(f, cell, every):
    s = f["snapshots"]
    t = s["time"][:]
    m = f["grid/m_bins"][:]
    n_t, n_b = len(t), len(m)
    sigma = s["sigma"][:].reshape(n_t, -1, n_b)[:, cell, :]
    st = s["st_bins"][:].reshape(n_t, -1, n_b)[:, cell, :]
    # compact runs write no phi_bins: every bin is compact
    phi = (s["phi_bins"][:].reshape(n_t, -1, n_b)[:, cell, :] if "phi_bins" in s
           else np.ones_like(sigma))
    print("t [yr] | <m> [g] | dominating m [g] | its St | its phi | "
          "sd log10 m | sd ln St | mass in St > 10 St_dom")
    for i in range(0, n_t, every):
        total = sigma[i].sum()
        if total <= 0.0:
            continue
        w = np.clip(sigma[i], 0.0, None) / total
        k = int(np.argmax(sigma[i]))
        tail = w[st[i] > 10.0 * st[i, k]].sum()
        print(f"{t[i]:.0f} | {(w * m).sum():.3g} | {m[k]:.3g} | {st[i, k]:.3g} | "
              f"{phi[i, k]:.3g} | {spread(w, np.log10(m)):.2f} | "
              f"{spread(w, np.log(st[i])):.2f} | {tail:.2f}")


def single_rows(f, cell, every):
    s = f["snapshots"]
    t = s["time"][:]
    print("t [yr] | m [g] | St | phi")
    for i in range(0, len(t), every):
        phi = s["phi"][i, cell] if "phi" in s else 1.0
        print(f"{t[i]:.0f} | {s['m'][i, cell]:.3g} | {s['St'][i, cell]:.3g} | {phi:.3g}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("runs", nargs="+")
    p.add_argument("--cell", type=int, default=0)
    p.add_argument("--every", type=int, default=4, help="print every N-th snapshot")
    a = p.parse_args()
    for path in a.runs:
        print(f"## {path}, cell {a.cell}")
        with open_run(path) as f:
            if "sigma" in f["snapshots"] and "m_bins" in f["grid"]:
                distribution_rows(f, a.cell, a.every)
            else:
                single_rows(f, a.cell, a.every)


if __name__ == "__main__":
    main()
