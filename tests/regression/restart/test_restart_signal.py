"""Stopping to restart (src/run/README.md, "Restart"): SIGINT, SIGTERM and --max-wall stop a run
with exit code 75 after checkpointing its last snapshot, say where the checkpoint is and
print the command that continues the run; that command completes the run, and the output
then equals, bit for bit, that of a run never stopped: no snapshot missing or twice."""
import os
import resource
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


def children_cpu():
    """CPU seconds (user + system) of the waited-for child processes so far."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def wait_for_file(path, proc, timeout):
    """Waits until `path` exists; False if the process ended or the time ran out first."""
    deadline = time.time() + timeout
    while time.time() < deadline and proc.poll() is None:
        if os.path.exists(path):
            return True
        time.sleep(0.001)
    return False


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
    t0, cpu0 = time.time(), children_cpu()
    panoptic(args.exe, SCENE, "-o", ref, "--overwrite", sets=SETS)
    wall, cpu = time.time() - t0, children_cpu() - cpu0
    print(f"uninterrupted run: {rows(ref)} snapshots in {wall:.2f} s ({cpu:.2f} CPU s)")

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
    # The limit is a fraction of the reference's CPU time, not of its wall time: the run
    # cannot finish in less wall time than that CPU time, however the machine's load
    # changes (with 0.3 x the reference's wall, a reference slowed by other processes
    # gave a limit the stopped run, on a freer machine, finished within: exit 0).
    out = f"{w}/max_wall.h5"
    limit = max(0.3, 0.3 * cpu)
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
    # -o: the checkpoint names the reference as its output, which a restart would continue
    cmd = [args.exe, "run", os.path.join(REPO, SCENE), "--restart", checkpoint_of(setup),
           "-o", setup]
    for s in SETS[:-1] + ["output.t_end_yr=2e7"]:
        cmd += ["--set", s]
    copy = setup + ".restart.tmp"
    if os.path.exists(copy):  # left by a killed run: it would be taken for this one's
        os.remove(copy)
    t0 = time.time()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # Sent while the restart copies its output (src/io/run_output.cpp: the copy is written
    # beside it as OUTPUT.restart.tmp, by a child process), i.e. surely in the set-up and
    # after the process has started: a fixed 0.25 s after the start came, on a loaded
    # machine, before the executable was even loaded (killed: exit -15).
    copying = wait_for_file(copy, proc, timeout=60)
    t_signal = time.time() - t0
    header = []  # when the header, printed once the set-up is done, came
    reader = threading.Thread(target=lambda: header.extend(
        (time.time() - t0, ln) for ln in proc.stdout))
    reader.start()
    proc.send_signal(signal.SIGTERM)
    proc.wait()
    reader.join()
    err = proc.stderr.read()
    time.sleep(0.5)  # a copying child left running would still be writing
    c.check(not os.path.exists(copy) and "could not rebuild" not in err,
            f"the restart waited for its copy and continues it, leaving no {copy} "
            f"(the stop signal broke off the wait: 'no process for the copy', the output "
            f"continued in place and the copy left behind) {err.strip()!r}")
    t_header = next((t for t, ln in header if ln.startswith("panoptic ")), None)
    when = (f"while it copied its output, at {t_signal:.2f} s; the set-up " +
            ("never ended: killed" if t_header is None else f"ended at {t_header:.2f} s"))
    c.check(copying, f"the restart was seen copying its output ({when})")
    c.check(proc.returncode == EXIT_STOPPED and rows(setup) == rows(ref) and
            checkpoint_attrs(checkpoint_of(setup))["snapshot_index"] == rows(ref) - 1,
            f"SIGTERM during a restart's set-up ({when}): exit {proc.returncode}, output "
            f"and checkpoint as before")

    p = panoptic(args.exe, SCENE, "-o", f"{w}/bad.h5", "--overwrite", "--max-wall", "90x",
                 sets=SETS, expect=2)
    c.check("90x" in p.stderr and "1h30m" in p.stderr,
            "--max-wall 90x: exit 2, the message shows the accepted forms")
    c.finish()


if __name__ == "__main__":
    main()
