"""A damaged checkpoint (src/run/README.md, "Restart"): truncated, bytes flipped in the state, or left
incomplete, it is refused with a message naming the file and what is wrong, and the
previous checkpoint (.chk.prev.h5) is used instead, with a message saying so; the run
then completes identical to the uninterrupted one. With both damaged: exit 4 and a
message naming both. A restart from a file that is not a checkpoint: exit 4. An output
with a stack shorter than the checkpoint's snapshots: exit 4, the output unchanged and
no copy left beside it. An output with a dataset whose header is damaged: the restart
recreates it, NaN in the rows kept, and says so."""
import os

import h5py
import numpy as np

from common import Checks, parse_args
from restart_common import (checkpoint_attrs, checkpoint_of, copy_run, lost_rows_explained,
                            panoptic, previous_of, rows, snapshot_differences, y_offset)

SCENE = "params/tests/restart.toml"
BASE = []


def flip(path, offset, n=4):
    with open(path, "r+b") as f:
        f.seek(offset)
        b = bytearray(f.read(n))
        f.seek(offset)
        f.write(bytes(x ^ 0xA5 for x in b))


def truncate(path):
    os.truncate(path, os.path.getsize(path) // 2)


def unflag(path):
    with h5py.File(path, "r+") as f:
        del f.attrs["complete"]


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir

    # The uninterrupted run, and the same run stopped at snapshot 20 (a shorter list of
    # snapshot times) with checkpoints every 6 snapshots: .chk.h5 at 20, .prev at 18.
    ts = [float(t) for t in np.geomspace(100.0, 1e6, 30)]
    full_sets = BASE + [f"output.times_yr=[{','.join(repr(t) for t in ts)}]",
                        f"output.t_end_yr={ts[-1]!r}"]
    cut_sets = BASE + ["checkpoint.every_snapshots=6",
                       f"output.times_yr=[{','.join(repr(t) for t in ts[:20])}]",
                       f"output.t_end_yr={ts[19]!r}"]
    ref = f"{w}/reference.h5"
    panoptic(args.exe, SCENE, "-o", ref, "--overwrite", sets=full_sets)
    base = f"{w}/stopped.h5"
    panoptic(args.exe, SCENE, "-o", base, "--overwrite", sets=cut_sets)
    k_chk = checkpoint_attrs(checkpoint_of(base))["snapshot_index"]
    k_prev = checkpoint_attrs(previous_of(base))["snapshot_index"]
    c.check((k_chk, k_prev) == (20, 18), f"checkpoints at snapshots {k_chk} and {k_prev}")

    damages = {
        "truncated": (truncate, "truncated"),
        "flipped bytes in the state": (lambda p: flip(p, y_offset(p) + 800), "checksum"),
        "incomplete": (unflag, "incomplete"),
    }
    for name, (damage, word) in damages.items():
        out = f"{w}/{name.split()[0]}.h5"
        copy_run(base, out)
        damage(checkpoint_of(out))
        p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(out), "-o", out,
                     sets=full_sets)
        c.check(checkpoint_of(out) in p.stderr and word in p.stderr,
                f"{name}: the message names the checkpoint and says '{word}'")
        c.check(previous_of(out) in p.stderr and "previous checkpoint" in p.stderr,
                f"{name}: it says the previous checkpoint is used: "
                f"{p.stderr.strip().splitlines()[-1]!r}")
        diffs = snapshot_differences(ref, out)
        c.check(not diffs and rows(out) == rows(ref),
                f"{name}: restarted from snapshot {k_prev}, the run completes identical "
                f"to the uninterrupted run {diffs if diffs else ''}")
        # The damaged checkpoint was not promoted: the good one at snapshot 18 is kept
        # as the fallback, the new .chk.h5 is the final one.
        c.check(checkpoint_attrs(previous_of(out))["snapshot_index"] == k_prev,
                f"{name}: the damaged checkpoint did not replace the good fallback")

    out = f"{w}/both.h5"
    copy_run(base, out)
    truncate(checkpoint_of(out))
    flip(previous_of(out), y_offset(previous_of(out)) + 80)
    p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(out), "-o", out,
                 sets=full_sets, expect=4)
    c.check(checkpoint_of(out) in p.stderr and previous_of(out) in p.stderr
            and "without --restart" in p.stderr,
            "both damaged: exit 4, the message names both files and the fix")
    c.check(rows(out) == 21, "both damaged: the output is left as it was")

    # an output damaged in a way only the set-up of the continued copy sees (a stack
    # shorter than the checkpoint's snapshots): exit 4 naming it, the output left byte
    # for byte as it was and no copy beside it (the restart sets up <out>.restart.tmp and
    # renames it over the output only once set up)
    out = f"{w}/short.h5"
    copy_run(base, out)
    with h5py.File(out, "r+") as f:
        st = f["snapshots/St"]
        st.resize((5, st.shape[1]))
    with open(out, "rb") as f:
        before = f.read()
    p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(out), "-o", out,
                 sets=full_sets, expect=4)
    with open(out, "rb") as f:
        after = f.read()
    c.check("/snapshots/St has fewer rows" in p.stderr and after == before
            and not os.path.exists(out + ".restart.tmp"),
            f"a short stack: exit 4 ({p.stderr.strip().splitlines()[-1]!r}), the output "
            "unchanged, no copy left beside it")

    # an output whose /snapshots/St header is damaged (as a SIGKILL in the middle of its
    # write can leave it: the kernel stops a write at a page boundary; seen once in
    # regression.test_restart_killed, where the restart's copy then hung in HDF5's SWMR
    # read retries): the restart's copy leaves St out, the restart recreates it with NaN
    # in the kept rows, says so, and the run completes; every other dataset is
    # bit-identical to the run never stopped
    out = f"{w}/torn.h5"
    copy_run(base, out)
    with h5py.File(out, "r") as f:
        g = f["snapshots"]
        addr = g.id.links.get_info(b"St").u
    flip(out, addr + 24, 8)
    p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(out), "-o", out,
                 sets=full_sets)
    explained = lost_rows_explained(ref, out)
    c.check("/snapshots/St rows 0-20" in p.stderr and "/snapshots/St rows" in explained
            and rows(out) == rows(ref),
            f"a torn dataset header: the restart completes, St's kept rows NaN and named "
            f"({explained[:60]}...), every other dataset as the run never stopped")

    # the wrong file, not a damaged one: bad input, naming the checkpoint to give (it was
    # exit 4 with the advice to start the run again without --restart)
    p = panoptic(args.exe, SCENE, "--restart", ref, "-o", out, sets=full_sets, expect=2)
    c.check("the output of a run, not its checkpoint" in p.stderr
            and "restart from " + checkpoint_of(ref) in p.stderr
            and "without --restart" not in p.stderr,
            "an output file given as checkpoint: exit 2, names its checkpoint")
    c.finish()


if __name__ == "__main__":
    main()
