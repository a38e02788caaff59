"""A run killed at any moment leaves an output that opens and holds only rows equal to
those of the run never killed, or (killed in its set-up, before the first snapshot) no
output at all: never an unreadable file, never a row of zeros or of other data.

The CI caught the failure this test pins down (regression.test_killed_run, once): a
SIGKILL in the middle of HDF5's flush of a snapshot left /snapshots/sigma_d with a row
of zeros at a valid time. Killed at every 7th of its 543 writes, a 40-cell run of 6
snapshots written as before (HDF5 1.8 format, plain flushes) left an unreadable file at
16 of the 80 kill points (8 in the set-up; 8 in flushes, "addr overflow": metadata
written in place pointed past the end of file that the superblock recorded) and a row
of zeros at 1. The
output is now written in HDF5's SWMR mode (RunOutput::start_appending), which orders
its metadata writes so that the file on disk is consistent after every write.

The shim (kill_after_writes.c, LD_PRELOAD) kills panoptic with SIGKILL just before its
(N+1)-th write to the output; a write that returned is in the page cache, so N = 0, 1,
2, ... goes through every state a SIGKILL can leave the file in. Every N is tried, up
to the run's last write."""
import os
import subprocess
import warnings

import numpy as np

from common import REPO, Checks, load_run, parse_args, run

SETS = ["grid.n_cells=16", "output.n_snapshots=2", "output.t_end_yr=100"]


def main():
    args = parse_args()
    c = Checks()
    shim = os.environ.get("PANOPTIC_KILL_SHIM", "")
    if not os.path.exists(shim):
        raise SystemExit(f"the LD_PRELOAD shim is missing: PANOPTIC_KILL_SHIM={shim!r}")
    ref_path = os.path.join(args.workdir, "reference.h5")
    run(args.exe, "params/fiducial.toml", ref_path, SETS)
    ref = load_run(ref_path)

    out = os.path.join(args.workdir, "killed.h5")
    cmd = [args.exe, "run", os.path.join(REPO, "params/fiducial.toml"), "-o", out]
    for s in SETS:
        cmd += ["--set", s]
    env = dict(os.environ, LD_PRELOAD=shim, PANOPTIC_KILL_PATH=out)
    n, tried, absent, unreadable, wrong, snapshots_seen = 0, 0, [], [], [], set()
    first_file = None
    while True:
        for p in os.listdir(args.workdir):
            if p.startswith("killed."):
                os.remove(os.path.join(args.workdir, p))
        env["PANOPTIC_KILL_AFTER_WRITES"] = str(n)
        p = subprocess.run(cmd, env=env, capture_output=True)
        if p.returncode == 0:
            break  # the run made fewer than n + 1 writes: every kill point is tried
        if p.returncode != -9:
            raise SystemExit(f"kill after {n} writes: exit {p.returncode}, not SIGKILL:\n"
                             f"{p.stderr.decode()}")
        tried += 1
        if not os.path.exists(out):
            absent.append(n)
        else:
            first_file = n if first_file is None else first_file
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    r = load_run(out)
            except Exception as e:  # noqa: BLE001 - any failure to read is the defect
                unreadable.append((n, f"{type(e).__name__}: {e}"[:160]))
                n += 1
                continue
            k = r.n_snapshots
            snapshots_seen.add(k)
            bad = [name for name, a in r.snapshots.items()  # NaN: t_first_pl not yet
                   if not np.array_equal(a[:k], ref.snapshots[name][:k], equal_nan=True)]
            m = len(r.timeseries.get("time", []))
            bad += ["timeseries/" + name for name, a in r.timeseries.items()
                    if not np.array_equal(a[:m], ref.timeseries[name][:m], equal_nan=True)]
            if k > ref.n_snapshots or m > len(ref.timeseries["time"]) or bad:
                wrong.append((n, k, m, bad[:4]))
        n += 1
    print(f"{n} writes to the output; killed before each: {tried} runs; no output at "
          f"{len(absent)} (writes 0-{max(absent) if absent else '-'}), unreadable at "
          f"{len(unreadable)}, rows unlike the uninterrupted run's at {len(wrong)}; "
          f"snapshot counts seen {sorted(snapshots_seen)}")
    for u in unreadable[:5]:
        print("  unreadable", u)
    for w in wrong[:5]:
        print("  wrong rows", w)
    c.check(tried == n and n > 100, f"every kill point tried ({tried} of {n} writes)")
    c.check(not unreadable, "the output opens after a kill at every write")
    c.check(not wrong, "every row the killed output holds equals the uninterrupted run's")
    c.check(first_file is not None and all(a < first_file for a in absent),
            "no output only when killed in the set-up (before it is renamed into place)")
    c.check(set(range(ref.n_snapshots + 1)) - {0} <= snapshots_seen | {ref.n_snapshots},
            "kills between snapshots leave every snapshot count (1 .. all but the last)")
    c.finish()


if __name__ == "__main__":
    main()
