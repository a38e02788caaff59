"""Scan benchmark (not a test, not run by ctest): the 200-run scan params/scans/
bench_200.toml with N local workers (default 2). Prints runs per minute, the busy time of
each worker (sum of its runs' wall times) and the load balance: max busy / mean busy, and
the idle fraction of the workers over the scan's wall time.

    /usr/bin/python3 tests/bench/bench_scan.py --exe build/panoptic [-j 2] [--out DIR]
        [--mpi N]   (mpirun --oversubscribe -n N instead of -j)
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(REPO, "build/panoptic"))
    ap.add_argument("-j", type=int, default=2)
    ap.add_argument("--mpi", type=int, default=0)
    ap.add_argument("--scan", default=os.path.join(REPO, "params/scans/bench_200.toml"))
    ap.add_argument("--out", default=os.path.join(REPO, "out/bench_scan"))
    a = ap.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    cmd = [a.exe, "scan", a.scan, "-o", a.out]
    if a.mpi:
        cmd = ["mpirun", "--oversubscribe", "-n", str(a.mpi)] + cmd
        os.environ.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"})
    else:
        cmd += ["-j", str(a.j)]
    t0 = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL)
    wall = time.monotonic() - t0
    with h5py.File(os.path.join(a.out, "summary.h5"), "r") as f:
        status = np.array([s.decode() for s in f["runs/status"][()]])
        worker = np.array([s.decode() for s in f["runs/worker"][()]])
        run_wall = f["runs/wall_s"][()]
        steps = f["runs/steps"][()]
    n = len(status)
    print(f"command: {' '.join(cmd)}  (exit {p.returncode})")
    print(f"{n} runs, {np.count_nonzero(status == 'completed')} completed, wall {wall:.1f} s: "
          f"{60 * n / wall:.1f} runs/min")
    print(f"run wall time: median {np.median(run_wall):.2f} s, min {run_wall.min():.2f}, "
          f"max {run_wall.max():.2f}; CVODE steps: median {np.median(steps):.0f}, "
          f"min {steps.min():.0f}, max {steps.max():.0f}")
    busy = {w: run_wall[worker == w].sum() for w in sorted(set(worker))}
    for w, b in busy.items():
        print(f"  worker {w}: {np.count_nonzero(worker == w)} runs, busy {b:.1f} s "
              f"({100 * b / wall:.0f}% of the scan's wall time)")
    b = np.array(list(busy.values()))
    print(f"load balance: max/mean busy = {b.max() / b.mean():.3f}; "
          f"idle fraction = {1 - b.sum() / (len(b) * wall):.3f}")
    sys.exit(p.returncode)


main()
