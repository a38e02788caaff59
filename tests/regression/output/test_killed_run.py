"""A run killed with SIGKILL in the middle leaves an HDF5 file that the reader opens, with
complete snapshots only (every dataset has as many rows as /snapshots/time), and the
snapshots it holds equal those of an uninterrupted run."""
import os
import signal
import subprocess
import time

# Read the file while panoptic writes it: HDF5's file lock would refuse us.
os.environ["HDF5_USE_FILE_LOCKING"] = "FALSE"

import numpy as np  # noqa: E402

from postprocess.reader import open_output  # noqa: E402

from common import REPO, Checks, load_run, parse_args, run  # noqa: E402

# Slow enough to be caught mid-run: many cells, tight tolerance, many snapshots.
# Transport alone (growth off) keeps the reference run short.
SETS = ["growth.enabled=false", "porosity.enabled=false", "planetesimals.coagulation=false",
        'planetesimals.si="none"', "grid.n_cells=3000",
        "solver.rtol=1e-10", "output.n_snapshots=400", "output.t_end_yr=1e7",
        "transport.St=0.05"]


def main():
    args = parse_args()
    c = Checks()
    out = f"{args.workdir}/killed.h5"
    cmd = [args.exe, "run", os.path.join(REPO, "params/fiducial.toml"), "-o", out, "--overwrite"]
    for s in SETS:
        cmd += ["--set", s]
    if os.path.exists(out):
        os.remove(out)
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    # wait until a few snapshots are on disk, then kill at once
    deadline = time.time() + 60
    rows = 0
    while time.time() < deadline and proc.poll() is None:
        time.sleep(0.05)
        try:
            with open_output(out) as f:
                rows = f["snapshots/time"].shape[0]
        except Exception:  # noqa: BLE001 - a file being written can fail to read in
            rows = 0           # many ways (OSError, KeyError, RuntimeError): not yet
        if rows >= 5:
            break
    time.sleep(0.137)  # a moment that is not aligned with a snapshot
    still_running = proc.poll() is None
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    c.check(still_running, f"the run was still going when killed ({rows} snapshots seen)")
    r = load_run(out)
    n = r.n_snapshots
    print(f"killed run: {n} complete snapshots, last at t = {r.time[-1]:.4g} yr")
    c.check(n >= 5, "the killed file opens and holds the snapshots written before the kill")
    with open_output(out) as f:
        lengths = {k: f["snapshots"][k].shape[0] for k in f["snapshots"]}
    c.check(min(lengths.values()) >= n, f"every snapshot dataset has the rows of time ({lengths['time']})")
    c.check(r.solver.get("status") in (None, ""), "no completion status: the file says the run did not finish")

    # The same scene run without interruption to the same snapshot times: CVODE meets the
    # same stop times in the same order, so the snapshots must be identical.
    ref = f"{args.workdir}/reference.h5"
    times = "[" + ",".join(repr(float(t)) for t in r.time[1:n]) + "]"
    run(args.exe, "params/fiducial.toml", ref,
        SETS + [f"output.t_end_yr={float(r.time[n - 1])!r}", f"output.times_yr={times}"])
    rr = load_run(ref)
    diff = np.max(np.abs(rr.snapshots["sigma_d"][:n] - r.snapshots["sigma_d"][:n]))
    print(f"uninterrupted run to the same times: max |difference| of sigma_d {diff:.2e}")
    c.check(np.array_equal(rr.time[:n], r.time[:n]), "same snapshot times")
    c.check(np.array_equal(rr.snapshots["sigma_d"][:n], r.snapshots["sigma_d"][:n]),
            "the killed file's snapshots are identical to an uninterrupted run's")
    c.finish()


if __name__ == "__main__":
    main()
