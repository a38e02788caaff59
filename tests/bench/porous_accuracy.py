#!/usr/bin/env python3
"""The accuracy of size-distribution runs of one scene against a reference run of it,
bin by bin: at every snapshot, over the (cell, bin) pairs whose reference sigma_k exceeds
FLOOR times the snapshot's largest, |ratio - 1| of sigma_k and of the filling factor
phi_k; printed are the largest over all snapshots, the largest of the snapshots'
medians, the largest |ratio - 1| of Sigma_d, and two measures of what a cell's dust
does: the mass-weighted mean of |ratio - 1| of sigma_k in the worst cell (weights: the
reference's sigma_k over the bins above the floor) and |ratio - 1| of the
mass-dominating St in the worst cell; with each run's solver counts.
Usage: porous_accuracy.py REFERENCE.h5 RUN.h5 [RUN2.h5 ...] [--floor 1e-6]
(tests/bench/results/porous_cost.md)."""
import argparse

import h5py
import numpy as np


def solver_line(f):
    a = f["solver"].attrs
    return (f"{int(a['nst'])} steps, {int(a['nfe'])} RHS, {int(a['nje'])} Jacobians, "
            f"{int(a['nncf'])} Newton failures")


def errors(ref, run, floor):
    """(worst sigma, median sigma, worst phi, median phi, worst Sigma_d, worst
    mass-weighted sigma of a cell, worst mass-dominating St) over the snapshots; the
    bins are those significant in the reference."""
    worst = np.zeros(7)
    medians = [[], []]
    n_cells = ref["snapshots/sigma_d"].shape[1]
    for k in range(ref["snapshots/time"].shape[0]):
        s0, s1 = ref["snapshots/sigma"][k], run["snapshots/sigma"][k]
        keep = s0 > floor * s0.max()
        r = np.where(keep, np.abs(s1 / np.where(keep, s0, 1.0) - 1.0), 0.0)
        rs = r[keep]
        worst[0] = max(worst[0], rs.max())
        medians[0].append(np.median(rs))
        if "phi_bins" in ref["snapshots"]:
            p0, p1 = ref["snapshots/phi_bins"][k], run["snapshots/phi_bins"][k]
            rp = np.abs(p1[keep] / p0[keep] - 1.0)
            worst[2] = max(worst[2], rp.max())
            medians[1].append(np.median(rp))
        d0, d1 = ref["snapshots/sigma_d"][k], run["snapshots/sigma_d"][k]
        worst[4] = max(worst[4], np.max(np.abs(d1 / d0 - 1.0)))
        w = np.where(keep, s0, 0.0).reshape(n_cells, -1)
        held = w.sum(axis=1) > 0.0  # cells with a bin above the floor
        cell = (w * r.reshape(n_cells, -1)).sum(axis=1)[held] / w.sum(axis=1)[held]
        worst[5] = max(worst[5], cell.max())
        st0, st1 = ref["snapshots/St"][k], run["snapshots/St"][k]
        worst[6] = max(worst[6], np.max(np.abs(st1 / st0 - 1.0)))
    worst[1] = max(medians[0])
    worst[3] = max(medians[1]) if medians[1] else 0.0
    return worst


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("reference")
    p.add_argument("runs", nargs="+")
    p.add_argument("--floor", type=float, default=1e-6)
    a = p.parse_args()
    with h5py.File(a.reference, "r") as ref:
        print(f"reference {a.reference}: {solver_line(ref)}")
        print("| run | solver | sigma_k worst | sigma_k median | phi_k worst | "
              "phi_k median | Sigma_d worst | sigma_k of a cell, mass-weighted | "
              "St of the mass-dominating bin |")
        print("|---|---|---|---|---|---|---|---|---|")
        for path in a.runs:
            with h5py.File(path, "r") as run:
                n = ref["snapshots/time"].shape[0]
                if run["snapshots/time"].shape[0] < n or not np.allclose(
                        run["snapshots/time"][:n], ref["snapshots/time"][:], rtol=1e-12):
                    raise SystemExit(f"{path}: snapshot times differ from the reference")
                e = errors(ref, run, a.floor)
                print(f"| {path} | {solver_line(run)} | " +
                      " | ".join(f"{x:.1e}" for x in e) + " |")


if __name__ == "__main__":
    main()
