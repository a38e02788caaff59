"""Edge cases of `panoptic scan` met on clusters:

- --force after a change of output.t_end_yr: the runs start again from t = 0 and equal, bit
  for bit, the runs of a new scan of the changed file (they were continued from the
  final checkpoints of the old end time: other snapshot times, a restart on record)."""
import glob
import os
import shutil

import h5py
import numpy as np

from common import Checks, parse_args
from scan_common import scan, summary, write_scan

SETS = ["grid.n_cells=16", "output.t_first_yr=10.0", "output.n_snapshots=3"]
MASS = 'key = "star.mass_msun"\nvalues = [0.6, 1.3]'


def snapshots(h5):
    with h5py.File(h5, "r") as f:
        return {k: ds[()] for k, ds in f["snapshots"].items()}, "restarts" in f.attrs


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    for d in glob.glob(f"{w}/*"):
        shutil.rmtree(d) if os.path.isdir(d) else os.remove(d)

    # 1 --force with a later end time: rerun from the start, as a new scan runs them
    sf = write_scan(f"{w}/short.toml", [MASS], sets=SETS + ["output.t_end_yr=100.0"])
    scan(args.exe, sf, f"{w}/forced")
    sf = write_scan(f"{w}/short.toml", [MASS], sets=SETS + ["output.t_end_yr=300.0"])
    p = scan(args.exe, sf, f"{w}/forced", "--force")
    scan(args.exe, sf, f"{w}/fresh")
    c.check("0 complete (checked), 2 to run" in p.stdout and
            (summary(f"{w}/forced")["runs/status"] == "completed").all(),
            "--force with t_end_yr 100 -> 300: both runs run again and complete")
    for name in ("run_00000", "run_00001"):
        a, restarted = snapshots(f"{w}/forced/runs/{name}.h5")
        b, _ = snapshots(f"{w}/fresh/runs/{name}.h5")
        same = sorted(a) == sorted(b) and all(
            a[k].shape == b[k].shape and np.array_equal(a[k], b[k], equal_nan=True) for k in b)
        c.check(same and not restarted,
                f"{name}: snapshot times {a['time']} (a new scan: {b['time']}), "
                f"every /snapshots dataset equal: {same}, continued from a checkpoint: "
                f"{restarted}")

    c.finish()


main()
