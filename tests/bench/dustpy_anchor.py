#!/usr/bin/env python3
"""Compare panoptic runs of the DustPy default disk with DustPy's profiles
(../shared/anchors/dustpy_default_profiles.csv): Sigma_d and the mass-dominating St (and
a) at the anchor's times, at radii 1.5-30 au, interpolated in ln r onto the anchor's
radii. Usage: dustpy_anchor.py RUN.h5 [RUN2.h5 ...] [--anchor CSV] [--radii 1.5,3,...].
Prints one table per time: r, DustPy's values, then each run's value and its ratio."""
import argparse
import os

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
# ../shared/anchors beside the repository (a worktree may lie one level deeper)
CANDIDATES = [os.path.join(HERE, *[".."] * up, "shared", "anchors",
                           "dustpy_default_profiles.csv") for up in (3, 4)]
DEFAULT_ANCHOR = next((c for c in CANDIDATES if os.path.exists(c)), CANDIDATES[0])


def load_anchor(path):
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    return np.genfromtxt(lines, delimiter=",", names=True)


def snapshot(path, t_yr):
    with h5py.File(path, "r") as f:
        s = f["snapshots"]
        times = s["time"][:]
        k = int(np.argmin(np.abs(np.log(np.maximum(times, 1e-30) / t_yr))))
        if abs(times[k] / t_yr - 1.0) > 1e-6:
            return None
        r = f["grid/r_c"][:]
        out = {"r": r, "t": times[k]}
        for name in ("sigma_d", "St", "a", "sigma_g"):
            if name in s:
                out[name] = s[name][k]
        return out


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("runs", nargs="+")
    p.add_argument("--anchor", default=DEFAULT_ANCHOR)
    p.add_argument("--radii", default="1.5,2,3,5,7,10,15,20,30")
    a = p.parse_args()
    anchor = load_anchor(a.anchor)
    radii = [float(x) for x in a.radii.split(",")]
    for t in sorted(set(anchor["t_yr"])):
        ref = anchor[anchor["t_yr"] == t]
        snaps = [snapshot(run, t) for run in a.runs]
        if all(s is None for s in snaps):
            continue
        print(f"\nt = {t:.0e} yr")
        head = f"{'r [au]':>7} {'DP sig_d':>9} {'DP St':>9} {'DP a':>9}"
        for i, s in enumerate(snaps):
            if s is not None:
                head += f" | run{i} sig_d  ratio   St        ratio   a         ratio"
        print(head)
        for r in radii:
            lr = np.log(r)
            ref_sd = np.interp(lr, np.log(ref["r_au"]), ref["sigma_dust"])
            ref_st = np.exp(np.interp(lr, np.log(ref["r_au"]), np.log(ref["St_rep"])))
            ref_a = np.exp(np.interp(lr, np.log(ref["r_au"]), np.log(ref["a_rep"])))
            line = f"{r:7.2f} {ref_sd:9.3e} {ref_st:9.3e} {ref_a:9.3e}"
            for s in snaps:
                if s is None:
                    continue
                lrs = np.log(s["r"])
                sd = np.interp(lr, lrs, s["sigma_d"])
                st = np.exp(np.interp(lr, lrs, np.log(s["St"])))
                ar = np.exp(np.interp(lr, lrs, np.log(s["a"]))) if "a" in s else np.nan
                line += (f" | {sd:9.3e} {sd / ref_sd:6.3f} {st:9.3e} {st / ref_st:6.3f}"
                         f" {ar:9.3e} {ar / ref_a:6.3f}")
            print(line)


if __name__ == "__main__":
    main()
