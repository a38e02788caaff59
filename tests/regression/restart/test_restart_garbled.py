"""Garbled rows are found on restart (src/run/README.md, "Restart"): a writer killed while HDF5
flushed the output can leave the chunk-index entries of rows it had flushed long before
pointing at other data, so that a row reads back whole but wrong. A checkpoint keeps the
digest of every row written up to it, and the restart verifies the rows it keeps: a row
that differs is said aloud, written as NaN and recorded, never continued silently.

Here the output of a run cut after snapshot 8 (its final checkpoint there) is garbled by
hand, one row of /snapshots/sigma_d and one of /timeseries/mass_budget overwritten with
the values of another row, as such an index entry would show them. The restart with the
full list of output times must name both rows, write them as NaN, and leave every other
snapshot identical, bit for bit, to the run never stopped; a second restart from the
checkpoint it ends with must find nothing more (the NaN rows are what it now keeps)."""
import h5py
import numpy as np

from postprocess.reader import open_output  # noqa: E402

from common import Checks, parse_args
from restart_common import checkpoint_attrs, checkpoint_of, panoptic, snapshot_differences

SCENE = "params/tests/restart.toml"  # transport alone: short runs
TIMES = [float(t) for t in np.geomspace(100.0, 1e6, 13)]
CUT = 8  # the cut run ends at snapshot CUT, with its final checkpoint there
SNAP_ROW, SNAP_FROM = 3, 5  # /snapshots/sigma_d row SNAP_ROW := row SNAP_FROM
SERIES_ROW, SERIES_FROM = 1, 2  # /timeseries/mass_budget likewise


def times_set(ts):
    return [f"output.times_yr=[{','.join(repr(t) for t in ts)}]",
            f"output.t_end_yr={ts[-1]!r}"]


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir

    ref = f"{w}/reference.h5"
    panoptic(args.exe, SCENE, "-o", ref, "--overwrite", sets=times_set(TIMES))

    out = f"{w}/cut.h5"
    panoptic(args.exe, SCENE, "-o", out, "--overwrite", sets=times_set(TIMES[:CUT]))
    c.check(checkpoint_attrs(checkpoint_of(out))["snapshot_index"] == CUT,
            f"the cut run's final checkpoint is at snapshot {CUT}")
    with h5py.File(out, "r+") as f:
        s = f["snapshots/sigma_d"]
        s[SNAP_ROW] = s[SNAP_FROM]
        m = f["timeseries/mass_budget"]
        c.check(m.shape[0] > SERIES_FROM, f"the cut run sampled {m.shape[0]} rows of "
                                          f"/timeseries (more than {SERIES_FROM})")
        m[SERIES_ROW] = m[SERIES_FROM]
        series_before = {k: f["timeseries"][k][()] for k in f["timeseries"]}

    p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(out), sets=times_set(TIMES))
    named = [f"/snapshots/sigma_d row {SNAP_ROW}", f"/timeseries/mass_budget row {SERIES_ROW}"]
    c.check(all(n in p.stderr for n in named) and "garbled" in p.stderr,
            f"the restart names the garbled rows: {p.stderr.strip()!r}")
    with open_output(out) as f:
        note = f.attrs["restarts"]
        note = note.decode() if isinstance(note, bytes) else str(note)
        c.check(all(n in note.split("lost rows")[-1] for n in named),
                "the root attribute restarts records them")
        sd = f["snapshots/sigma_d"][()]
        c.check(np.isnan(sd[SNAP_ROW]).all(), f"/snapshots/sigma_d row {SNAP_ROW} is NaN")
        mb = f["timeseries/mass_budget"][()]
        c.check(np.isnan(mb[SERIES_ROW]).all(),
                f"/timeseries/mass_budget row {SERIES_ROW} is NaN")
        kept = {k: f["timeseries"][k][()] for k in f["timeseries"]}
    # Every other kept row of /timeseries as it was (the restart continues after them).
    same = True
    for k, before in series_before.items():
        n = len(before) - 1  # the cut run's end-of-run sample is not kept
        rows = [i for i in range(n) if not (k == "mass_budget" and i == SERIES_ROW)]
        same &= np.array_equal(kept[k][rows].view(np.uint64), before[rows].view(np.uint64))
    c.check(same, "every other kept /timeseries row is unchanged")
    with open_output(ref) as f:
        ref_sd = f["snapshots/sigma_d"][()]
    others = [i for i in range(len(ref_sd)) if i != SNAP_ROW]
    diffs = [d for d in snapshot_differences(ref, out) if not d.startswith("snapshots/sigma_d")]
    c.check(not diffs and sd.shape == ref_sd.shape and
            np.array_equal(sd[others].view(np.uint64), ref_sd[others].view(np.uint64)),
            f"every other snapshot is identical to the uninterrupted run's {diffs}")

    # The final checkpoint carries the digests of the rows as they now are (NaN rows
    # included): restarting from it to a later time finds nothing lost.
    p2 = panoptic(args.exe, SCENE, "--restart", checkpoint_of(out),
                  sets=times_set(TIMES + [2e6]))
    c.check("lost" not in p2.stderr and "garbled" not in p2.stderr,
            f"a second restart finds nothing more: {p2.stderr.strip()!r}")
    c.finish()


if __name__ == "__main__":
    main()
