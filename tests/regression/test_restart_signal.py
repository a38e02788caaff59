"""Stopping to restart (README "Restart"): SIGINT, SIGTERM and --max-wall stop a run
with exit code 75 after checkpointing its last snapshot, say where the checkpoint is and
print the command that continues the run; that command completes the run, and the output
then equals, bit for bit, that of a run never stopped: no snapshot missing or twice."""
import os
import shlex
import signal
import subprocess
import threading
import time

import numpy as np

from common import REPO, Checks, parse_args
from restart_common import (EXIT_STOPPED, checkpoint_attrs, checkpoint_of, copy_run, panoptic,
                            rows, snapshot_differences, solver_attrs, times)

SCENE = "params/tests/restart.toml"
# Compared bit for bit with the uninterrupted run (a restart continues all three).
GROUPS = ("snapshots", "timeseries", "summary")
# Slow enough (~2 s) to be stopped mid-run, with many snapshots.
SETS = ["grid.n_cells=2000", "solver.rtol=1e-9", "output.n_snapshots=200",
        "output.t_end_yr=1e7"]


def start(exe, out, extra=()):
    # A file left by an earlier test run would be seen as this run's progress.
    for stale in (out, checkpoint_of(out)):
        if os.path.exists(stale):
            os.remove(stale)
    cmd = [exe, "run", os.path.join(REPO, SCENE), "-o", out, "--overwrite", *extra]
    for s in SETS:
        cmd += ["--set", s]
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for_rows(out, n, proc, timeout=60):
    """Waits until `out` holds n snapshots (or the process ended)."""
    deadline = time.time() + timeout
    while time.time() < deadline and proc.poll() is None:
        try:
            if rows(out) >= n:
                return True
        except (OSError, KeyError):
            pass
        time.sleep(0.02)
    return False


def check_stopped_run(c, name, proc, out, reference):
    stdout, stderr = proc.communicate()
    c.check(proc.returncode == EXIT_STOPPED,
            f"{name}: exit code {proc.returncode} (expected {EXIT_STOPPED})")
    chk = checkpoint_of(out)
    c.check(chk in stdout and "restart with:" in stdout,
            f"{name}: the message names the checkpoint and the restart command")
    attrs = checkpoint_attrs(chk)
    n_file = rows(out)
    c.check(attrs["snapshot_index"] == n_file - 1,
            f"{name}: the checkpoint holds the last snapshot written "
            f"({attrs['snapshot_index']} of {n_file - 1})")
    c.check(solver_attrs(out).get("status", "").startswith("stopped by"),
            f"{name}: /solver status says stopped: {solver_attrs(out).get('status')!r}")
    line = next(ln for ln in stdout.splitlines() if ln.startswith("restart with: "))
    cmd = shlex.split(line[len("restart with: "):])
    p = subprocess.run(cmd, capture_output=True, text=True)
    c.check(p.returncode == 0, f"{name}: the printed restart command completes the run "
                               f"(exit {p.returncode}) {p.stderr.strip()}")
    diffs = snapshot_differences(reference, out, GROUPS)
    t = times(out)
    c.check(not diffs and rows(out) == rows(reference) and np.all(np.diff(t) > 0),
            f"{name}: {rows(out)} snapshots, strictly increasing times, every dataset of "
            f"/snapshots, /timeseries, /summary identical to the uninterrupted run's "
            f"{diffs if diffs else ''}")
    c.check(solver_attrs(out)["nst"] == solver_attrs(reference)["nst"],
            f"{name}: same total step count as the uninterrupted run "
            f"({solver_attrs(out)['nst']})")


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir

    ref = f"{w}/reference.h5"
    t0 = time.time()
    panoptic(args.exe, SCENE, "-o", ref, "--overwrite", sets=SETS)
    wall = time.time() - t0
    print(f"uninterrupted run: {rows(ref)} snapshots in {wall:.2f} s")

    for sig, name in ((signal.SIGINT, "SIGINT"), (signal.SIGTERM, "SIGTERM")):
        out = f"{w}/{name.lower()}.h5"
        proc = start(args.exe, out)
        seen = wait_for_rows(out, 40, proc)
        time.sleep(0.05)  # between two snapshots
        running = proc.poll() is None
        proc.send_signal(sig)
        c.check(seen and running, f"{name}: sent while the run was going")
        check_stopped_run(c, name, proc, out, ref)

    # --max-wall: stops before the limit with a checkpoint, like a batch queue's limit.
    out = f"{w}/max_wall.h5"
    limit = max(0.3, 0.3 * wall)
    proc = start(args.exe, out, ["--max-wall", f"{limit:.2f}s"])
    t0 = time.time()
    proc.wait()
    took = time.time() - t0
    c.check(took < limit + 1.0, f"--max-wall {limit:.2f}s: stopped after {took:.2f} s")
    check_stopped_run(c, "--max-wall", proc, out, ref)

    # SIGTERM while a restart still sets up (it copies the 16 MB output first, ~0.8 s
    # here): the handlers are in place from the start of `panoptic run`, so the run
    # stops at its first step with the checkpoint and exit 75 (it was killed with 143)
    setup = f"{w}/setup.h5"
    copy_run(ref, setup, files=("output", "chk"))
    cmd = [args.exe, "run", os.path.join(REPO, SCENE), "--restart", checkpoint_of(setup)]
    for s in SETS[:-1] + ["output.t_end_yr=2e7"]:
        cmd += ["--set", s]
    t0 = time.time()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    header = []  # when the header, printed once the set-up is done, came
    reader = threading.Thread(target=lambda: header.extend(
        (time.time() - t0, ln) for ln in proc.stdout))
    reader.start()
    time.sleep(0.25)
    proc.send_signal(signal.SIGTERM)
    proc.wait()
    reader.join()
    t_header = next((t for t, ln in header if ln.startswith("panoptic ")), None)
    when = ("during its set-up, which never ended: killed" if t_header is None else
            f"during its set-up, which ended at {t_header:.2f} s" if t_header > 0.25 else
            "after its set-up: inconclusive")
    c.check(proc.returncode == EXIT_STOPPED and rows(setup) == rows(ref) and
            checkpoint_attrs(checkpoint_of(setup))["snapshot_index"] == rows(ref) - 1,
            f"SIGTERM 0.25 s into a restart ({when}): exit {proc.returncode}, output and "
            f"checkpoint as before")

    p = panoptic(args.exe, SCENE, "-o", f"{w}/bad.h5", "--overwrite", "--max-wall", "90x",
                 sets=SETS, expect=2)
    c.check("90x" in p.stderr and "1h30m" in p.stderr,
            "--max-wall 90x: exit 2, the message shows the accepted forms")
    c.finish()


if __name__ == "__main__":
    main()
