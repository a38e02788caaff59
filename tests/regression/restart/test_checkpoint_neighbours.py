"""The files a new run replaces next to its output (src/run/README.md, "Restart"): a run writing
out/x.h5 keeps its checkpoints in out/x.chk.h5 and out/x.chk.prev.h5, and a new run there
removes those of the run it replaces. It must remove nothing else:
  * a file at either path that panoptic did not write as a checkpoint (a text file, or
    the output of another run named x.chk.h5) stops the run with exit 4 and a message
    naming it, with or without --overwrite, and is left byte for byte as it was, and no
    output is created;
  * a real checkpoint without --overwrite stops the run with exit 4 and is kept (with
    the advice to --restart from it, or, when its output is gone, that only
    --overwrite can help); with --overwrite it is removed and the run completes, also
    when it is damaged (truncated, or empty) as a scan's rerun needs.
And a restart that changes a key a restart may change (here output.t_end_yr, as a
restart without the stopped run's --set options does) says so on stderr, with both
values, and records them in the output's `restarts` attribute."""
import os


from postprocess.reader import open_output  # noqa: E402

from common import Checks, parse_args, text
from restart_common import checkpoint_of, panoptic, previous_of

SCENE = "params/tests/restart.toml"
SHORT = ["output.t_end_yr=1e3", "output.n_snapshots=5", "grid.n_cells=50"]


def read(path):
    with open(path, "rb") as f:
        return f.read()


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    for name in os.listdir(w):
        os.remove(os.path.join(w, name))

    # another run's output, named like a checkpoint
    other = f"{w}/other.chk.h5"
    panoptic(args.exe, SCENE, "-o", other, sets=SHORT)
    os.remove(checkpoint_of(other))  # its own checkpoint, other.chk.chk.h5
    notes = f"{w}/notes.chk.prev.h5"
    with open(notes, "w") as f:
        f.write("my notes\n")
    for out, victim in ((f"{w}/other.h5", other), (f"{w}/notes.h5", notes)):
        before = read(victim)
        for flags in ([], ["--overwrite"]):
            p = panoptic(args.exe, SCENE, "-o", out, *flags, sets=SHORT, expect=None)
            label = f"-o {os.path.basename(out)} {' '.join(flags)}".rstrip()
            c.check(p.returncode == 4, f"{label}: exit {p.returncode} (4) with "
                    f"{os.path.basename(victim)} in the way")
            c.check(os.path.basename(victim) in p.stderr
                    and "not a panoptic checkpoint" in p.stderr,
                    f"{label}: the message names the file: {p.stderr.strip()[:160]}")
            c.check(read(victim) == before, f"{label}: {os.path.basename(victim)} "
                    "left byte for byte as it was")
            c.check(not os.path.exists(out), f"{label}: no output created")

    # a real checkpoint whose output is gone
    run = f"{w}/run.h5"
    panoptic(args.exe, SCENE, "-o", run, sets=SHORT)
    chk = checkpoint_of(run)
    c.check(os.path.exists(chk), "a finished run leaves its checkpoint")
    # a new run to an output whose run left a checkpoint: refused without --overwrite
    # (the output is there: continue it with --restart), the checkpoint kept
    before, out_before = read(chk), read(run)
    p = panoptic(args.exe, SCENE, "-o", run, sets=SHORT, expect=None)
    c.check(p.returncode == 4 and "--overwrite" in p.stderr,
            f"existing output and checkpoint, no --overwrite: exit {p.returncode} (4): "
            f"{p.stderr.strip()[:160]}")
    c.check(read(chk) == before and read(run) == out_before,
            "the checkpoint and the output kept")
    p = panoptic(args.exe, SCENE, "-o", run, "--overwrite", sets=SHORT, expect=None)
    c.check(p.returncode == 0 and "removed" in p.stdout,
            f"with --overwrite: exit {p.returncode} (0), the old checkpoint removed")
    with open_output(run) as f:
        new_id = text(f.attrs["run_id"])
    with open_output(chk) as f:
        chk_id = text(f.attrs["run_id"])
    c.check(not os.path.exists(previous_of(run)) and chk_id == new_id,
            f"the checkpoint is the new run's (run_id {chk_id} = {new_id}), no .prev")

    # a damaged checkpoint (truncated: HDF5 cannot open it) is still the earlier run's
    # and --overwrite replaces it (a scan reruns a run this way); an empty one too
    for label, damage in (("truncated", lambda p: os.truncate(p, 2000)),
                          ("empty", lambda p: os.truncate(p, 0))):
        damage(chk)
        p = panoptic(args.exe, SCENE, "-o", run, "--overwrite", sets=SHORT, expect=None)
        c.check(p.returncode == 0 and "HDF5-DIAG" not in p.stderr,
                f"{label} checkpoint with --overwrite: exit {p.returncode} (0), replaced "
                f"{p.stderr.strip()[:120]}")
    # the advice when the checkpoint's output is gone: only --overwrite can help
    os.remove(run)
    p = panoptic(args.exe, SCENE, "-o", run, sets=SHORT, expect=None)
    c.check(p.returncode == 4 and "output is gone" in p.stderr
            and "--restart" not in p.stderr,
            f"checkpoint whose output is gone: {p.stderr.strip()[:160]}")
    panoptic(args.exe, SCENE, "-o", run, "--overwrite", sets=SHORT)

    # a restart that changes output.t_end_yr
    p = panoptic(args.exe, SCENE, "--restart", chk, "-o", run,
                 sets=["output.t_end_yr=2e3", "output.n_snapshots=5", "grid.n_cells=50"])
    c.check("changes output.t_end_yr = 2000" in p.stderr and "(was 1000" in p.stderr,
            f"the restart's note: {p.stderr.strip()[:200]}")
    with open_output(run) as f:
        restarts = text(f.attrs["restarts"])
    c.check("changed: output.t_end_yr = 2000" in restarts and "(was 1000" in restarts,
            f"recorded: {restarts[-120:]}")
    c.finish()


if __name__ == "__main__":
    main()
