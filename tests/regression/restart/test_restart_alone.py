"""Restart from the checkpoint alone (src/run/README.md, Restart): `panoptic run --restart
CHK` with no scene file takes the scene (its --set options included), the output file and
the run's label from the checkpoint, and continues the run bit for bit:
  * a run stopped by --max-wall, written to its default output out/<label>.h5 (run from
    the work directory), continued by the command it printed for the checkpoint alone:
    /snapshots, /timeseries and /summary identical to the uninterrupted run's;
  * a completed shorter run (output.times_yr cut after snapshot 5) carried on with
    `--restart CHK --set output.times_yr=[...]` alone: the grid of its own --set kept;
  * a --set that the checkpoint's run cannot continue (grid.n_cells) is refused (exit 2),
    and `panoptic run` with neither a scene nor --restart says what to give (exit 2)."""
import os
import shlex
import subprocess

import numpy as np

from common import REPO, Checks, parse_args
from restart_common import (EXIT_STOPPED, checkpoint_of, panoptic, previous_of,
                            snapshot_differences, solver_attrs)

FIDUCIAL = "params/fiducial.toml"
SETS = ["grid.n_cells=64", "grid.stretch=0", "output.t_end_yr=1e5"]
LABEL = "fiducial+grid.n_cells=64+grid.stretch=0+output.t_end_yr=1e5"
SCENE = "params/tests/restart.toml"
TIMES = [float(t) for t in np.geomspace(100.0, 1e6, 13)]


def times_set(ts):
    return [f"output.times_yr=[{','.join(repr(t) for t in ts)}]", f"output.t_end_yr={ts[-1]!r}"]


def in_dir(cwd, *cmd):
    return subprocess.run(list(cmd), capture_output=True, text=True, cwd=cwd)


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    exe = os.path.abspath(args.exe)
    groups = ("snapshots", "timeseries", "summary")

    ref = f"{w}/reference.h5"
    panoptic(exe, FIDUCIAL, "-o", ref, "--overwrite", sets=SETS)
    out = f"{w}/out/{LABEL}.h5"
    for stale in (out, checkpoint_of(out), previous_of(out)):  # an earlier test's
        if os.path.exists(stale):
            os.remove(stale)
    sets = [a for s in SETS for a in ("--set", s)]
    p = in_dir(w, exe, "run", os.path.join(REPO, FIDUCIAL), *sets, "--max-wall", "0.2s")
    alone = next((ln.split(": ", 1)[1] for ln in p.stdout.splitlines()
                  if ln.startswith("or, from the checkpoint alone: ")), "")
    c.check(p.returncode == EXIT_STOPPED and
            shlex.split(alone) == [exe, "run", "--restart", f"out/{LABEL}.chk.h5"],
            f"stopped by --max-wall (exit {p.returncode}), the command for the "
            f"checkpoint alone printed: {alone!r} {p.stderr.strip()[:200]}")
    if not alone:
        c.finish()
    p = in_dir(w, *shlex.split(alone))
    c.check(p.returncode == 0 and "(stored in the checkpoint)" in p.stdout,
            f"restarted from the checkpoint alone: exit {p.returncode}, "
            f"{p.stdout.splitlines()[0] if p.stdout else p.stderr.strip()}")
    diffs = snapshot_differences(ref, out, groups)
    c.check(diffs == [], f"the default output continued bit for bit, {groups} "
            f"identical to the uninterrupted run's {diffs}")
    s, r = solver_attrs(out), solver_attrs(ref)
    c.check(all(s[k] == r[k] for k in ("nst", "nfe", "nje")),
            f"the same solver statistics ({s['nst']} steps)")

    # A completed run cut after snapshot 5, carried on with the times alone
    ref2, cut = f"{w}/reference2.h5", f"{w}/cut.h5"
    panoptic(exe, SCENE, "-o", ref2, "--overwrite", sets=["grid.n_cells=120"] + times_set(TIMES))
    panoptic(exe, SCENE, "-o", cut, "--overwrite", sets=["grid.n_cells=120"] +
             times_set(TIMES[:5]))
    cmd = [exe, "run", "--restart", checkpoint_of(cut)]
    for s in times_set(TIMES):
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    diffs = snapshot_differences(ref2, cut)
    c.check(p.returncode == 0 and diffs == [],
            f"a completed run carried on from its checkpoint alone with later times: exit "
            f"{p.returncode}, /snapshots identical {diffs} {p.stderr.strip()[:200]}")

    # Refusals
    p = subprocess.run([exe, "run", "--restart", checkpoint_of(cut), "--set",
                        "grid.n_cells=100"], capture_output=True, text=True)
    c.check(p.returncode == 2 and "grid.n_cells = 100" in p.stderr and
            "the checkpoint has 120" in p.stderr,
            f"an incompatible --set: exit {p.returncode}, {p.stderr.strip()[:200]}")
    p = subprocess.run([exe, "run"], capture_output=True, text=True)
    c.check(p.returncode == 2 and "a scene file is required" in p.stderr and
            "--restart" in p.stderr, f"neither scene nor --restart: exit {p.returncode}, "
            f"{p.stderr.strip()}")
    c.finish()


if __name__ == "__main__":
    main()
