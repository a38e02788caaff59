"""Restart bit for bit (src/run/README.md, "Restart"): a run continued from a checkpoint writes
/snapshots identical in every bit to those of the run that was never stopped, whichever
snapshot the checkpoint is at, and ends with the same solver statistics.

The checkpoints are those at the end of shorter runs of the same scene (output.times_yr
cut after snapshot j, so output.t_end_yr = its last time: a compatible change), restarted
with the full list; plus the mid-run .chk.prev.h5 of the default log-spaced scene, and a
scene with an evolving gas disk (another layout: sigma_d, sigma_g per cell)."""
import re

import h5py
import numpy as np

from postprocess.reader import open_output  # noqa: E402

from common import Checks, parse_args
from restart_common import (EXIT_STOPPED, checkpoint_attrs, checkpoint_of, copy_run,
                            h5diff_snapshots, lost_rows_explained, panoptic, previous_of,
                            restarted_from_prev, row_digests, rows, snapshot_differences,
                            solver_attrs)

YR = 3.156e7  # s, src/core/units.hpp
SCENE = "params/tests/restart.toml"  # transport alone: short runs
FIDUCIAL = "params/fiducial.toml"
BASE = []
TIMES = [float(t) for t in np.geomspace(100.0, 1e6, 13)]
# A restart also continues /timeseries and rewrites /summary identically, from a mid-run
# checkpoint and from the final one of a run cut at a snapshot (its last /timeseries
# sample is at that snapshot, as in the uninterrupted run). SCENE has no /timeseries;
# the growth model's cut run below checks it.
MID_RUN_GROUPS = ("snapshots", "timeseries", "summary")


def times_set(ts):
    return [f"output.times_yr=[{','.join(repr(t) for t in ts)}]", f"output.t_end_yr={ts[-1]!r}"]


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir

    ref = f"{w}/reference.h5"
    panoptic(args.exe, SCENE, "-o", ref, "--overwrite", sets=BASE + times_set(TIMES))
    ref_solver = solver_attrs(ref)
    print(f"uninterrupted run: {rows(ref)} snapshots, {ref_solver['nst']} steps, "
          f"{ref_solver['nreinit']} reinitialisations")

    for j in (1, 4, 8, 12):
        out = f"{w}/cut{j}.h5"
        panoptic(args.exe, SCENE, "-o", out, "--overwrite", sets=BASE + times_set(TIMES[:j]))
        chk = checkpoint_attrs(checkpoint_of(out))
        c.check(chk["snapshot_index"] == j and chk["complete"] == 1,
                f"run cut after snapshot {j}: its final checkpoint is at snapshot "
                f"{chk['snapshot_index']}")
        cut_nst = solver_attrs(out)["nst"]
        p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(out),
                     sets=BASE + times_set(TIMES))
        diffs = snapshot_differences(ref, out)
        c.check(not diffs, f"restart from snapshot {j}: every /snapshots dataset identical "
                           f"to the uninterrupted run's {diffs if diffs else ''}")
        same = h5diff_snapshots(ref, out)
        if same is not None:
            c.check(same, f"restart from snapshot {j}: h5diff finds no difference")
        s = solver_attrs(out)
        c.check(all(s[k] == ref_solver[k] for k in ("nst", "nfe", "nje", "nreinit")),
                f"restart from snapshot {j}: same solver statistics (steps {s['nst']})")
        # the restarted process itself integrated only from the checkpoint on (a
        # "restart" that integrated again from t = 0 would give the same bits)
        own = re.search(r"this process: (\d+) steps", p.stdout)
        c.check("restart from" in p.stdout and own is not None and
                int(own.group(1)) == ref_solver["nst"] - cut_nst and int(own.group(1)) > 0,
                f"the restarted process took the {ref_solver['nst'] - cut_nst} steps after "
                f"the checkpoint ({own.group(0) if own else 'no step count printed'})")

    # The default log-spaced scene: restart from the checkpoint before the last one.
    full = f"{w}/full.h5"
    panoptic(args.exe, SCENE, "-o", full, "--overwrite",
             sets=BASE + ["checkpoint.every_snapshots=7"])
    again = f"{w}/from_prev.h5"
    copy_run(full, again, files=("output", "prev"))
    k = checkpoint_attrs(previous_of(again))["snapshot_index"]
    c.check(0 < k < rows(full) - 1, f"the previous checkpoint is mid-run (snapshot {k})")
    # -o: the copy is continued, not the file the checkpoint names
    panoptic(args.exe, SCENE, "--restart", previous_of(again), "-o", again,
             sets=BASE + ["checkpoint.every_snapshots=7"])
    c.check("restarted from" in checkpoint_attrs(again).get("restarts", ""),
            "the continued output records the restart (root attribute restarts)")
    diffs = snapshot_differences(full, again, MID_RUN_GROUPS)
    c.check(not diffs and rows(again) == rows(full),
            f"log-spaced scene restarted from .chk.prev.h5 (snapshot {k}): /snapshots, "
            f"/timeseries, /summary identical, {rows(again)} snapshots "
            f"{diffs if diffs else ''}")

    # A restart stopped before its first snapshot (--max-wall, due at the first step)
    # checkpoints again the snapshot it restarted from: the same rows, so the same row
    # digests, those of /timeseries included (a later restart verifies the rows it keeps
    # against them).
    stopped = f"{w}/stopped_at_once.h5"
    copy_run(full, stopped, files=("output", "prev"))
    before = row_digests(previous_of(stopped))
    panoptic(args.exe, SCENE, "--restart", previous_of(stopped), "-o", stopped,
             "--max-wall", "0.000001s", sets=BASE + ["checkpoint.every_snapshots=7"],
             expect=EXIT_STOPPED)
    after = row_digests(checkpoint_of(stopped))
    series = sorted(key for key in before if key.startswith("timeseries:"))
    c.check(checkpoint_attrs(checkpoint_of(stopped))["snapshot_index"] == k and series and
            after == before,
            f"a restart stopped at once checkpoints snapshot {k} again with the same row "
            f"digests ({len(before)} datasets, {len(series)} of /timeseries; now "
            f"{len(after)}, missing: {sorted(set(before) - set(after))})")

    # A restart killed while it cut the file (SIGKILL, test_restart_killed) can leave the
    # /timeseries rows after its checkpoint read back as zeros, the fill value. The next
    # restart from that checkpoint must drop them with the rest, not keep them as samples.
    debris = f"{w}/debris.h5"
    copy_run(full, debris, files=("output", "prev"))
    t_k = checkpoint_attrs(previous_of(debris))["t"] / YR
    with h5py.File(debris, "r+") as f:
        g = f["timeseries"]
        first = int(np.searchsorted(g["time"][:], t_k, side="right"))  # rows rise in t
        for name in g:
            g[name][first:] = np.zeros((g[name].shape[0] - first,) + g[name].shape[1:])
        n_zero = g["time"].shape[0] - first
    panoptic(args.exe, SCENE, "--restart", previous_of(debris), "-o", debris,
             sets=BASE + ["checkpoint.every_snapshots=7"])
    diffs = snapshot_differences(full, debris, MID_RUN_GROUPS)
    c.check(n_zero > 0 and not diffs,
            f"restart over {n_zero} zeroed /timeseries rows after the checkpoint "
            f"(snapshot {k}): /snapshots, /timeseries, /summary identical "
            f"{diffs if diffs else ''}")

    # A writer killed while HDF5 flushed the file can lose the chunk of a row it had
    # flushed long before (seen in test_restart_killed: /snapshots/St row 51 read back as
    # zeros). The restart must find it, write it as NaN, say so and record it.
    holed = f"{w}/holed.h5"
    copy_run(full, holed, files=("output", "prev"))
    j = k // 2  # a row well before the checkpoint
    with h5py.File(holed, "r+") as f:
        g = f["snapshots"]
        old = g["sigma_d"]
        data, attrs, chunks = old[()], dict(old.attrs), old.chunks
        del g["sigma_d"]
        new = g.create_dataset("sigma_d", shape=data.shape, maxshape=(None, data.shape[1]),
                               chunks=chunks, dtype=data.dtype, fillvalue=0.0)
        for i in range(len(data)):
            if i != j:  # row j's chunk is never written: gone, as after such a kill
                new[i] = data[i]
        for name, value in attrs.items():
            new.attrs[name] = value
    p = panoptic(args.exe, SCENE, "--restart", previous_of(holed), "-o", holed,
                 sets=BASE + ["checkpoint.every_snapshots=7"])
    lost = lost_rows_explained(full, holed, MID_RUN_GROUPS)
    c.check(lost == f"/snapshots/sigma_d rows [{j}]" and
            f"/snapshots/sigma_d row {j}" in p.stderr,
            f"a row lost from the file before the checkpoint (/snapshots/sigma_d row {j}) "
            f"is found, written as NaN, named on stderr and in the root attribute "
            f"restarts; every other row identical ({lost or 'not so'})")

    def from_prev(scene, sets, name, what):
        restarted_from_prev(c, args.exe, w, scene, sets, name, what, MID_RUN_GROUPS)

    # Evolving gas: two variables per cell and one more booked mass.
    from_prev("params/tests/lbp_viscous.toml",
              ["grid.n_cells=100", "output.times_yr=[1e3, 3e3, 1e4, 3e4, 1e5]",
               "checkpoint.every_snapshots=2"],
              "gas", "evolving gas (sigma_d, sigma_g per cell)")
    # The full model of params/fiducial.toml: growth and porosity (sigma_d, q_m, q_phi per
    # cell), snow-line sublimation, planetesimals, /timeseries.
    growth_sets = ["grid.n_cells=40", "output.t_end_yr=1e3", "output.t_first_yr=10.0",
                   "output.n_snapshots=8", "checkpoint.every_snapshots=3"]
    from_prev(FIDUCIAL, growth_sets, "growth", "growth model")
    # ... on evolving gas: the particle laws' eta and v_g are set from the gas at every
    # snapshot (Simulation::refresh_local_gas); the restart sets them from the
    # checkpoint's state, as the run never stopped did at that snapshot
    from_prev(FIDUCIAL,
              growth_sets[:1] + ["gas.evolve=true", "output.t_end_yr=3e4"] +
              growth_sets[2:],
              "growth_gas", "growth model on evolving gas")
    # ... and a run of it cut at a snapshot, then continued to the end: /timeseries and
    # /summary as well as /snapshots equal the uninterrupted run's
    g_times = [float(t) for t in np.geomspace(10.0, 1e3, 8)]
    g_sets = ["grid.n_cells=40", "output.t_first_yr=10.0"]
    g_full = f"{w}/growth_times.h5"
    panoptic(args.exe, FIDUCIAL, "-o", g_full, "--overwrite", sets=g_sets + times_set(g_times))
    g_cut = f"{w}/growth_cut.h5"
    panoptic(args.exe, FIDUCIAL, "-o", g_cut, "--overwrite",
             sets=g_sets + times_set(g_times[:5]))
    panoptic(args.exe, FIDUCIAL, "--restart", checkpoint_of(g_cut),
             sets=g_sets + times_set(g_times))
    diffs = snapshot_differences(g_full, g_cut, MID_RUN_GROUPS)
    with open_output(g_full) as f:
        n_series = len(f["timeseries/time"])
    c.check(not diffs and rows(g_cut) == rows(g_full),
            f"growth model cut at snapshot 4 and continued: /snapshots, /timeseries "
            f"({n_series} rows), /summary identical {diffs if diffs else ''}")
    c.finish()


if __name__ == "__main__":
    main()
