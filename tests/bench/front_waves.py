"""Travelling waves at the growth front of the fiducial scene (issue 7;
tests/bench/results/performance_log.md): runs params/fiducial.toml to 1000 yr with
snapshots every 5 yr from 850 yr, for each grid given, and prints the RMS of Sigma_d(t)
about a quadratic trend in time, relative to its mean, averaged over the cells between 1.4
and 1.9 au. A smooth front gives ~0.3 %; the waves of coarse log-spaced grids give tens
of per cent. Run on demand.

    /usr/bin/python3 tests/bench/front_waves.py --exe build/panoptic --workdir DIR \\
        [--grids 125:0 250:0 500:0 1000:0 350:0.5] [--rtol 1e-6]
(each grid is n_cells:stretch)"""
import argparse
import os
import subprocess
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, REPO)
from postprocess.reader import load_run  # noqa: E402

T_OUT = np.arange(850.0, 1000.0, 5.0)


def wave_amplitude(run, r_lo=1.4, r_hi=1.9):
    r = run.r_c
    cells = np.where((r > r_lo) & (r < r_hi))[0]
    k = np.where(run.time >= T_OUT[0] - 1e-9)[0]
    t = run.time[k]
    amp = []
    for c in cells:
        s = run.snapshots["sigma_d"][k, c]
        trend = np.polyval(np.polyfit(t, s, 2), t)
        amp.append(np.std(s - trend) / np.mean(s))
    return float(np.mean(amp))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--grids", nargs="+", default=["125:0", "250:0", "500:0", "1000:0",
                                                   "350:0.5"])
    ap.add_argument("--rtol", type=float, default=1e-6)
    args = ap.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    times = "[" + ",".join(f"{t:g}" for t in T_OUT) + "]"
    print("| cells | stretch | steps to 1000 yr | wave amplitude |\n|---|---|---|---|")
    for g in args.grids:
        n, stretch = g.split(":")
        out = os.path.join(args.workdir, f"front_N{n}_s{stretch}.h5")
        subprocess.run([args.exe, "run", os.path.join(REPO, "params", "fiducial.toml"),
                        "-o", out, "--overwrite", "--set", f"grid.n_cells={n}",
                        "--set", f"grid.stretch={stretch}", "--set",
                        f"solver.rtol={args.rtol:g}", "--set", "output.t_end_yr=1000",
                        "--set", f"output.times_yr={times}",
                        "--set", "checkpoint.every_wall_s=0"],
                       check=True, stdout=subprocess.DEVNULL)
        run = load_run(out)
        print(f"| {n} | {stretch} | {int(run.solver['nst'])} | "
              f"{100 * wave_amplitude(run):.1f} % |", flush=True)


if __name__ == "__main__":
    main()
