#!/usr/bin/env python3
"""Mass resolution of a porous size distribution in one cell: the same scene run at
several bins per decade, compared at fixed masses (tests/bench/results/porosity_split.md,
"Mass resolution in one cell"). Per run and time: the filling factor phi at each mass,
interpolated in ln m between the bins that hold more than 1e-6 of the cell's dust (blank
outside them), the exponential of the mass-weighted mean ln m, and the mass-weighted mean
mass. For every three successive runs, the observed order of convergence of each column,
ln(|x1 - x2| / |x2 - x3|) / ln(h1 / h2) in ln x, with h the grid's ln m spacing (runs
ordered from coarse to fine, each refining the last by the same factor).
Usage: porous_cell_resolution.py [--cell I] [--times-yr 300,1000] [--masses-g 1e-9,...]
RUN.h5 RUN2.h5 ..."""
import argparse

import numpy as np

from porous_mmsn import open_run  # readable while its run still writes it (SWMR)


def cell_columns(path, cell, t_yr, masses):
    """ln of (phi at each mass, exp of the mean ln m, mean mass) of one cell at the
    snapshot nearest t_yr, the snapshot's time [yr] and the grid's ln m spacing."""
    with open_run(path) as f:
        m = f["grid/m_bins"][:]
        t = f["snapshots/time"][:]
        k = int(np.argmin(np.abs(t - t_yr)))
        sigma = f["snapshots/sigma"][k].reshape(-1, len(m))[cell]
        phi = f["snapshots/phi_bins"][k].reshape(-1, len(m))[cell]
    ln_m = np.log(m)
    held = sigma > 1e-6 * sigma.sum()
    cols = []
    for mass in masses:
        inside = ln_m[held].min() <= np.log(mass) <= ln_m[held].max()
        cols.append(np.interp(np.log(mass), ln_m[held], np.log(phi[held])) if inside
                    else np.nan)
    w = sigma / sigma.sum()
    cols += [(w * ln_m).sum(), np.log((w * m).sum())]
    return np.array(cols), t[k], ln_m[1] - ln_m[0]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("runs", nargs="+")
    p.add_argument("--cell", type=int, default=0)
    p.add_argument("--times-yr", default="300,1000")
    p.add_argument("--masses-g", default="1e-9,1e-7,1e-5,1e-3,1e-1")
    a = p.parse_args()
    masses = [float(x) for x in a.masses_g.split(",")]
    heads = [f"phi@{x:.0e}" for x in masses] + ["exp<ln m>", "<m> [g]"]
    for t_yr in (float(x) for x in a.times_yr.split(",")):
        rows = [cell_columns(r, a.cell, t_yr, masses) for r in a.runs]
        print(f"\ncell {a.cell}, t = {rows[0][1]:g} yr")
        print(f"{'run':>24} {'ln m step':>9} " + " ".join(f"{h:>10}" for h in heads))
        for r, (x, _, h) in zip(a.runs, rows):
            print(f"{r[-24:]:>24} {h:9.4f} " + " ".join(f"{v:10.4g}" for v in np.exp(x)))
        for i in range(len(rows) - 2):
            (x1, _, h1), (x2, _, h2), (x3, _, _) = rows[i:i + 3]
            with np.errstate(divide="ignore", invalid="ignore"):
                order = np.log(np.abs(x1 - x2) / np.abs(x2 - x3)) / np.log(h1 / h2)
            print(f"{'order, runs ' + str(i + 1) + '-' + str(i + 3):>24} {'':9} "
                  + " ".join(f"{v:10.2f}" for v in order))


if __name__ == "__main__":
    main()
