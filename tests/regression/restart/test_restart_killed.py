"""SIGKILL at a random moment, then restart (src/run/README.md, "Restart"): the run cannot react, but
the last checkpoint on disk is whole (written to a temporary file, fsynced, renamed), no
snapshot written before it is lost, and the run restarted from it completes with
/snapshots identical, bit for bit, to those of a run never killed: none missing, none
twice. Killed several times at random moments (the seed is printed); once the last
checkpoint is the one of a run that was itself restarted."""
import os
import random
import signal
import subprocess
import time

import numpy as np

from common import REPO, Checks, parse_args
from restart_common import (checkpoint_attrs, checkpoint_of, lost_rows_explained,
                            panoptic, previous_of, rows, snapshot_differences, times)

SCENE = "params/tests/restart.toml"
# Compared bit for bit with the uninterrupted run (a restart continues all three).
GROUPS = ("snapshots", "timeseries", "summary")
SETS = ["grid.n_cells=2000", "solver.rtol=1e-9", "output.n_snapshots=200",
        "output.t_end_yr=1e7", "checkpoint.every_snapshots=10"]


def launch(exe, out, restart=None):
    cmd = [exe, "run", os.path.join(REPO, SCENE), "-o", out]
    cmd += ["--restart", restart] if restart else ["--overwrite"]
    for s in SETS:
        cmd += ["--set", s]
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True)


def kill_at_random(proc, chk, rng, wall, frac=0.5):
    """Waits for a first checkpoint, then SIGKILLs at a random moment within frac * wall;
    returns whether the process was still running when killed."""
    deadline = time.time() + 60
    while proc.poll() is None and not os.path.exists(chk) and time.time() < deadline:
        time.sleep(0.01)
    time.sleep(rng.uniform(0.0, frac * wall))
    running = proc.poll() is None
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    return running


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    seed = int(os.environ.get("PANOPTIC_TEST_SEED", time.time_ns() % 2**32))
    rng = random.Random(seed)
    print(f"seed {seed} (set PANOPTIC_TEST_SEED to repeat)")

    ref = f"{w}/reference.h5"
    t0 = time.time()
    panoptic(args.exe, SCENE, "-o", ref, "--overwrite", sets=SETS)
    wall = time.time() - t0
    ref_times = times(ref)

    for trial in range(2):
        out = f"{w}/killed{trial}.h5"
        chk = checkpoint_of(out)
        # The reference's wall time can overstate the run's on a machine whose load
        # changes: a run that finished before its kill did not test a kill, so it is
        # tried again with a shorter delay.
        for attempt in range(3):
            for stale in (out, chk, previous_of(out)):
                if os.path.exists(stale):
                    os.remove(stale)
            running = kill_at_random(launch(args.exe, out), chk, rng, wall,
                                     frac=0.5 / 2**attempt)
            if running:
                break
        restart_from = chk
        finished = False  # the restart of trial 1 ran to the end before its kill came
        if trial == 1:
            # Kill the restarted run too: its checkpoints continue the first run's. When
            # the first kill came late, the restart may finish before its own kill: then
            # its output is compared as it is (there is nothing left to restart).
            proc = launch(args.exe, out, restart=chk)
            finished = not kill_at_random(proc, chk, rng, wall)
            if finished and proc.returncode != 0:
                # It did not finish: it stopped. A restart refuses an output file that
                # a kill damaged beyond repair (src/run/README.md, "Restart"), with a message.
                c.check(False, f"trial {trial}: the restart before the second kill "
                               f"exited {proc.returncode}: {proc.stderr.read().strip()}")
                continue
        n_file = rows(out)
        k = checkpoint_attrs(chk)["snapshot_index"]
        print(f"trial {trial}: killed with {n_file} snapshots in the file, last checkpoint "
              f"at snapshot {k}")
        c.check(running, f"trial {trial}: the run was going when killed")
        c.check(k <= n_file - 1 and np.array_equal(times(out)[:k + 1], ref_times[:k + 1]),
                f"trial {trial}: every snapshot up to the checkpoint ({k}) is in the file")
        if finished:
            print(f"trial {trial}: the restarted run finished before it was killed")
            p = None
        else:
            p = panoptic(args.exe, SCENE, "--restart", restart_from, "-o", out, sets=SETS)
        diffs = snapshot_differences(ref, out, GROUPS)
        # A writer killed while HDF5 flushed the file can lose rows it had flushed before
        # (the chunk index is not journaled): the restart must then say so, write them as
        # NaN and record them; anything else that differs is a failure.
        lost = lost_rows_explained(ref, out, GROUPS) if diffs else ""
        t = times(out)
        c.check((not diffs or lost) and len(t) == len(ref_times) and np.all(np.diff(t) > 0),
                f"trial {trial}: "
                + ("the restart ran to the end" if finished else f"restarted from snapshot {k}")
                + f": {len(t)} snapshots, none "
                f"missing or twice; /snapshots, /timeseries, /summary identical to the "
                f"uninterrupted run"
                + (f", except rows the file had lost, found, written as NaN and recorded "
                   f"by the restart: {lost}" if lost else "")
                + f" {diffs if diffs and not lost else ''} {p.stderr.strip() if p else ''}")
    c.finish()


if __name__ == "__main__":
    main()
