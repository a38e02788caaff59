"""A run killed at any moment leaves an output that opens and holds only rows equal to
those of the run never killed, or (killed in its set-up, before the first snapshot) no
output at all: never an unreadable file, never a row of zeros or of other data. A
restart killed at any moment leaves the output with at least the rows it had, and a
second restart from the checkpoint gives the output of a restart never killed.

The CI caught the failure this test pins down (regression.test_killed_run, once): a
SIGKILL in the middle of HDF5's flush of a snapshot left /snapshots/sigma_d with a row
of zeros at a valid time. Killed at every 7th of its 543 writes, a 40-cell run of 6
snapshots written as before (HDF5 1.8 format, plain flushes) left an unreadable file at
16 of the 80 kill points (8 in the set-up; 8 in flushes, "addr overflow": metadata
written in place pointed past the end of file that the superblock recorded) and a row
of zeros at 1. The output is now written in HDF5's SWMR mode (RunOutput::
start_appending), which orders its metadata writes so that the file on disk is
consistent after every write.

The shim (kill_after_writes.c, LD_PRELOAD) kills panoptic with SIGKILL just before its
(N+1)-th write to a file whose path begins with the output's (the output, and the
copies it is set up and finished in); a write that returned is in the page cache, so
N = 0, 1, 2, ... goes through every state a SIGKILL can leave the files in. Every N is
tried, up to the run's last write."""
import os
import shutil
import subprocess
import warnings

import numpy as np

from common import REPO, Checks, load_run, parse_args, run

SETS = ["grid.n_cells=16", "output.n_snapshots=2"]
T_END, T_RESTART_END = 100, 300


def same_rows(r, ref):
    """Names of the /snapshots and /timeseries datasets of run `r` whose rows differ
    from the first rows of `ref` (NaN equal to NaN: t_first_pl before formation)."""
    k, m = r.n_snapshots, len(r.timeseries.get("time", []))
    bad = [name for name, a in r.snapshots.items()
           if not np.array_equal(a[:k], ref.snapshots[name][:k], equal_nan=True)]
    bad += ["timeseries/" + name for name, a in r.timeseries.items()
            if not np.array_equal(a[:m], ref.timeseries[name][:m], equal_nan=True)]
    if k > ref.n_snapshots or m > len(ref.timeseries["time"]):
        bad.append(f"more rows than the run never killed ({k}, {m})")
    return bad


def read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return load_run(path)


def kill_at_every_write(cmd, out, shim, prepare, check):
    """Runs `cmd` killed before its N-th write to `out`* for N = 0, 1, ... until it
    completes; `prepare()` before each, `check(n)` after each kill. Returns the count."""
    env = dict(os.environ, LD_PRELOAD=shim, PANOPTIC_KILL_PATH=out)
    n = 0
    while True:
        prepare()
        env["PANOPTIC_KILL_AFTER_WRITES"] = str(n)
        p = subprocess.run(cmd, env=env, capture_output=True)
        if p.returncode == 0:
            return n  # fewer than n + 1 writes: every kill point was tried
        if p.returncode != -9:
            raise SystemExit(f"{' '.join(cmd)}\nkill after {n} writes: exit "
                             f"{p.returncode}, not SIGKILL:\n{p.stderr.decode()}")
        check(n)
        n += 1


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    shim = os.environ.get("PANOPTIC_KILL_SHIM", "")
    if not os.path.exists(shim):
        raise SystemExit(f"the LD_PRELOAD shim is missing: PANOPTIC_KILL_SHIM={shim!r}")
    scene = os.path.join(REPO, "params/fiducial.toml")
    sets = SETS + [f"output.t_end_yr={T_END}"]
    ref_path = os.path.join(w, "reference.h5")
    run(args.exe, "params/fiducial.toml", ref_path, sets)
    ref = read(ref_path)

    # 1. a new run
    out = os.path.join(w, "killed.h5")
    cmd = [args.exe, "run", scene, "-o", out]
    for s in sets:
        cmd += ["--set", s]
    absent, unreadable, wrong, counts = [], [], [], set()

    def clean():
        for p in os.listdir(w):
            if p.startswith("killed."):
                os.remove(os.path.join(w, p))

    def check_new(n):
        if not os.path.exists(out):
            absent.append(n)
            return
        try:
            r = read(out)
        except Exception as e:  # noqa: BLE001 - any failure to read is the defect
            unreadable.append((n, f"{type(e).__name__}: {e}"[:160]))
            return
        counts.add(r.n_snapshots)
        if bad := same_rows(r, ref):
            wrong.append((n, bad[:4]))

    n = kill_at_every_write(cmd, out, shim, clean, check_new)
    print(f"new run: {n} writes to the output, killed before each; no output at "
          f"{len(absent)} (writes 0-{max(absent) if absent else '-'}), unreadable at "
          f"{len(unreadable)}, rows unlike the uninterrupted run's at {len(wrong)}; "
          f"snapshot counts seen {sorted(counts)}")
    for x in unreadable[:5] + wrong[:5]:
        print("  ", x)
    c.check(n > 100, f"every kill point of the new run tried ({n})")
    c.check(not unreadable, "the output opens after a kill at every write")
    c.check(not wrong, "every row the killed output holds equals the uninterrupted run's")
    c.check(absent == list(range(len(absent))) and ref.n_snapshots in counts | {0},
            "no output only when killed in the set-up (before it is renamed into place)")

    # 2. a restart of a finished run to a later end, killed at every write; then
    # restarted again from its checkpoint, without a kill
    base = os.path.join(w, "base.h5")
    run(args.exe, "params/fiducial.toml", base, sets)
    later = ["--set", f"output.t_end_yr={T_RESTART_END}"]
    for s in SETS:
        later += ["--set", s]
    restarted = os.path.join(w, "restarted.h5")  # the restart never killed
    shutil.copy(base, restarted)
    shutil.copy(os.path.join(w, "base.chk.h5"), os.path.join(w, "restarted.chk.h5"))
    subprocess.run([args.exe, "run", scene, "--restart", os.path.join(w, "restarted.chk.h5"),
                    "-o", restarted] + later, capture_output=True, check=True)
    whole = read(restarted)
    n_base = read(base).n_snapshots
    chk = os.path.join(w, "killed.chk.h5")
    cmd = [args.exe, "run", scene, "--restart", chk, "-o", out] + later
    unreadable, wrong, lost, recovered, finished, counts = [], [], [], [], 0, set()

    def prepare_restart():
        clean()
        shutil.copy(base, out)
        shutil.copy(os.path.join(w, "base.chk.h5"), chk)

    def check_restart(n):
        nonlocal finished
        try:
            r = read(out)
        except Exception as e:  # noqa: BLE001
            unreadable.append((n, f"{type(e).__name__}: {e}"[:160]))
            return
        counts.add(r.n_snapshots)
        if r.n_snapshots < n_base:
            lost.append((n, r.n_snapshots))
        if bad := same_rows(r, whole):
            wrong.append((n, bad[:4]))
        p = subprocess.run([args.exe, "run", scene, "--restart", chk, "-o", out] + later,
                           capture_output=True, text=True)
        if p.returncode == 2 and "at or after the end of this run" in p.stderr:
            finished += 1  # killed after its last checkpoint: nothing left to run
            return
        again = read(out) if p.returncode == 0 else None
        if again is None or same_rows(again, whole) or again.n_snapshots != whole.n_snapshots \
                or again.summary.keys() != whole.summary.keys() \
                or any(not np.array_equal(again.summary[k], whole.summary[k], equal_nan=True)
                       for k in whole.summary):
            recovered.append((n, p.returncode, p.stderr.strip()[-200:]))

    n = kill_at_every_write(cmd, out, shim, prepare_restart, check_restart)
    print(f"restart: {n} writes to the output, killed before each; unreadable at "
          f"{len(unreadable)}, fewer rows than before the restart at {len(lost)}, rows "
          f"unlike the restart never killed at {len(wrong)}; restarted again: "
          f"{n - finished - len(recovered)} equal to the restart never killed, "
          f"{len(recovered)} not, {finished} killed after the last checkpoint; snapshot "
          f"counts seen {sorted(counts)}")
    for x in unreadable[:5] + lost[:5] + wrong[:5] + recovered[:5]:
        print("  ", x)
    c.check(n > 100, f"every kill point of the restart tried ({n})")
    c.check(not unreadable, "the output opens after a restart killed at every write")
    c.check(not lost, "a killed restart leaves at least the rows the output had")
    c.check(not wrong, "every row equals the restart never killed's")
    c.check(not recovered, "restarted again, the output is the restart never killed's "
            "(snapshots, /timeseries, /summary)")
    c.finish()


if __name__ == "__main__":
    main()
