#!/usr/bin/env python3
"""The accuracy of runs of one scene against a reference run of it and against DustPy's
profiles (../shared/anchors/dustpy_default_profiles.csv): at each of the anchor's times,
the largest |ratio - 1| of Sigma_d and of the mass-dominating St over the grid cells in
[r_min, r_max] au (against the reference run: cell by cell on the common grid; against
DustPy: interpolated in ln r onto DustPy's radii in that range, as dustpy_anchor.py).
Usage: solver_accuracy.py REFERENCE.h5 RUN.h5 [RUN2.h5 ...] [--r-min 1.5] [--r-max 30]
(tests/bench/results/implicit_euler.md)."""
import argparse

import h5py
import numpy as np

from dustpy_anchor import DEFAULT_ANCHOR, load_anchor, snapshot


def worst(x):
    return float(np.max(np.abs(x - 1.0)))


def solver_line(path):
    with h5py.File(path, "r") as f:
        a = f["solver"].attrs
        return f"{int(a['nst'])} steps, {int(a['nfe'])} RHS, {int(a['nje'])} Jacobians"


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("reference")
    p.add_argument("runs", nargs="+")
    p.add_argument("--anchor", default=DEFAULT_ANCHOR)
    p.add_argument("--r-min", type=float, default=1.5)
    p.add_argument("--r-max", type=float, default=30.0)
    a = p.parse_args()
    anchor = load_anchor(a.anchor)
    for t in sorted(set(anchor["t_yr"])):
        ref = snapshot(a.reference, t)
        if ref is None:
            continue
        dp = anchor[(anchor["t_yr"] == t) & (anchor["r_au"] >= a.r_min)
                    & (anchor["r_au"] <= a.r_max)]
        r_au = ref["r"]  # /grid/r_c is in au
        cells = (r_au >= a.r_min) & (r_au <= a.r_max)
        print(f"t = {t:.0e} yr, {cells.sum()} cells and {len(dp)} DustPy radii in "
              f"[{a.r_min}, {a.r_max}] au: largest |ratio - 1|")
        print(f"{'run':<40} {'Sigma_d/ref':>11} {'St/ref':>8} {'Sigma_d/DP':>10} "
              f"{'St/DP':>8}  solver")
        for path in [a.reference, *a.runs]:
            s = snapshot(path, t)
            if s is None:
                continue
            lr, lrs = np.log(dp["r_au"]), np.log(s["r"])
            sd_dp = np.interp(lr, lrs, s["sigma_d"]) / dp["sigma_dust"]
            st_dp = np.exp(np.interp(lr, lrs, np.log(s["St"]))) / dp["St_rep"]
            print(f"{path:<40} {worst(s['sigma_d'][cells] / ref['sigma_d'][cells]):11.3g} "
                  f"{worst(s['St'][cells] / ref['St'][cells]):8.3g} {worst(sd_dp):10.3g} "
                  f"{worst(st_dp):8.3g}  {solver_line(path)}")


if __name__ == "__main__":
    main()
