"""Helpers of the restart tests (tests/regression/restart/test_restart*.py): run panoptic with
any arguments, compare the /snapshots of two output files bit for bit, and find the
checkpoint files next to an output."""
import os
import shutil
import subprocess

# Read files while panoptic writes them: HDF5's file lock would refuse us.
os.environ["HDF5_USE_FILE_LOCKING"] = "FALSE"

import numpy as np  # noqa: E402

from postprocess.reader import open_output  # noqa: E402

from common import REPO, run_checked  # noqa: E402

EXIT_STOPPED = 75  # panoptic's exit code for "stopped, restart from the checkpoint"


def panoptic(exe, scene, *args, sets=(), expect=0):
    """Runs `panoptic run scene args --set ...`; returns the CompletedProcess. Raises
    SystemExit, printing the command and its output, when the exit code is not `expect`
    (None: any)."""
    cmd = [exe, "run", os.path.join(REPO, scene), *args]
    for s in sets:
        cmd += ["--set", s]
    return run_checked(cmd, expect)


def checkpoint_of(out):
    """out/x.h5 -> out/x.chk.h5"""
    return os.path.splitext(out)[0] + ".chk.h5"


def previous_of(out):
    """out/x.h5 -> out/x.chk.prev.h5"""
    return os.path.splitext(out)[0] + ".chk.prev.h5"


def copy_run(out, dest, files=("output", "chk", "prev")):
    """Copies an output and its checkpoints to the output name `dest`."""
    pairs = {"output": (out, dest), "chk": (checkpoint_of(out), checkpoint_of(dest)),
             "prev": (previous_of(out), previous_of(dest))}
    for key in files:
        src, dst = pairs[key]
        shutil.copyfile(src, dst)


def snapshot_differences(a, b, groups=("snapshots",)):
    """Names of the datasets of `groups` (default /snapshots) that differ between files a
    and b in shape or in any bit (NaN = NaN), plus those present in only one; [] when
    identical."""
    diffs = []
    with open_output(a) as fa, open_output(b) as fb:
        for group in groups:
            if group not in fa and group not in fb:
                continue
            ga, gb = fa.get(group, {}), fb.get(group, {})
            for name in sorted(set(ga) | set(gb)):
                if name not in ga or name not in gb:
                    diffs.append(f"{group}/{name} (missing)")
                    continue
                x, y = ga[name][()], gb[name][()]
                if x.shape != y.shape or not np.array_equal(x.view(np.uint64),
                                                            y.view(np.uint64)):
                    diffs.append(f"{group}/{name} {x.shape} vs {y.shape}")
    return diffs


def restarted_from_prev(c, exe, workdir, scene, sets, name, what, groups):
    """Runs `scene` with `sets` (a checkpoint.every_snapshots among them) to
    workdir/name.h5, restarts a copy from its mid-run .chk.prev.h5 and checks with `c`
    that the copy ends identical to the run never stopped in `groups`, with as many
    snapshots. Returns (the run, the restarted copy, the checkpoint's snapshot index)."""
    full = f"{workdir}/{name}.h5"
    panoptic(exe, scene, "-o", full, "--overwrite", sets=sets)
    again = f"{workdir}/{name}_restarted.h5"
    copy_run(full, again, files=("output", "prev"))
    k = checkpoint_attrs(previous_of(again))["snapshot_index"]
    panoptic(exe, scene, "--restart", previous_of(again), "-o", again, sets=sets)
    diffs = snapshot_differences(full, again, groups)
    c.check(not diffs and rows(again) == rows(full),
            f"{what} restarted from snapshot {k} of {rows(full) - 1}: identical "
            f"{diffs if diffs else ''}")
    return full, again, k


def lost_rows_explained(ref, out, groups=("snapshots",)):
    """Whether every difference between `ref` and `out` in `groups` is a row the restart
    found lost in the file (its chunk gone after a writer was killed while HDF5 flushed
    the file), wrote as NaN and named in the root attribute `restarts`: "" if not, else
    the names of those rows."""
    with open_output(ref) as fa, open_output(out) as fb:
        note = fb.attrs.get("restarts", b"")
        note = note.decode() if isinstance(note, bytes) else str(note)
        named = []
        for group in groups:
            if group not in fa or group not in fb:
                continue
            for name in sorted(set(fa[group]) | set(fb[group])):
                if name not in fa[group] or name not in fb[group]:
                    return ""
                x, y = fa[group][name][()], fb[group][name][()]
                if x.shape != y.shape:
                    return ""
                xr, yr = x.reshape(len(x), -1), y.reshape(len(y), -1)
                bad = [i for i in range(len(x)) if not np.array_equal(
                    xr[i].view(np.uint64), yr[i].view(np.uint64))]
                if not bad:
                    continue
                if not all(np.isnan(yr[i]).all() for i in bad) or \
                        f"/{group}/{name} row" not in note.split("lost rows")[-1]:
                    return ""
                named.append(f"/{group}/{name} rows {bad}")
    return "; ".join(named)


def h5diff_snapshots(a, b):
    """h5diff of the two /snapshots groups when Debian's hdf5-tools is installed: True
    when identical, None when h5diff is missing."""
    if shutil.which("h5diff") is None:
        return None
    p = subprocess.run(["h5diff", "-q", a, b, "/snapshots", "/snapshots"],
                       capture_output=True, text=True)
    return p.returncode == 0


def rows(path):
    with open_output(path) as f:
        return f["snapshots/time"].shape[0]


def times(path):
    with open_output(path) as f:
        return f["snapshots/time"][()]


def checkpoint_attrs(path):
    with open_output(path) as f:
        return {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}


def row_digests(path):
    """A checkpoint's row digests: {"snapshots:St": [digest of row 0, ...], ...}."""
    with open_output(path) as f:
        if "row_digests" not in f:
            return {}
        return {k: [int(x) for x in v[()]] for k, v in f["row_digests"].items()}


def solver_attrs(path):
    with open_output(path) as f:
        if "solver" not in f:
            return {}
        return {k: (v.decode() if isinstance(v, bytes) else v)
                for k, v in f["solver"].attrs.items()}


def y_offset(path):
    """Byte offset of the state vector /y in a checkpoint file."""
    with open_output(path) as f:
        return f["y"].id.get_offset()
