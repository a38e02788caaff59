"""What a restart may change (src/run/README.md, "Restart"): a scene that differs from the
checkpoint's in a key that defines the state (grid, disk, processes, dust) is refused
with exit 2 and a message naming the key, both values and the fix, before the output is
touched; the output times, the solver settings and checkpoint.* may change. A later
output.t_end_yr continues a finished run: the earlier snapshots stay as they were and the
new ones follow."""
import numpy as np

from postprocess.reader import open_output  # noqa: E402

from common import Checks, parse_args
from restart_common import checkpoint_of, copy_run, panoptic, rows, times

SCENE = "params/tests/restart.toml"
BASE = ["grid.n_cells=200", "output.t_end_yr=1e5", "output.n_snapshots=20"]


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir

    done = f"{w}/done.h5"
    panoptic(args.exe, SCENE, "-o", done, "--overwrite", sets=BASE)
    n_done = rows(done)

    refused = {
        "grid.n_cells=250": "grid.n_cells",
        "growth.enabled=true": "growth.enabled",  # also another state layout
        "snowline.enabled=false": "snowline.enabled",  # one global variable fewer
        "grid.r_out_au=200.0": "grid.r_out_au",
        "disk.alpha=1e-4": "disk.alpha",
        "gas.evolve=true": "gas.evolve",  # also another state layout
        "transport.diffusion=false": "transport.diffusion",
        "dust.dust_to_gas=0.02": "dust.dust_to_gas",
    }
    for change, key in refused.items():
        out = f"{w}/refused.h5"
        copy_run(done, out, files=("output", "chk"))
        p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(out), "-o", out,
                     sets=BASE + [change, "output.t_end_yr=1e6"], expect=2)
        c.check(f"{key} = " in p.stderr and "the checkpoint has" in p.stderr
                and f"--set {key}=" in p.stderr and checkpoint_of(out) in p.stderr,
                f"{change}: refused with exit 2, naming {key}, both values and the fix")
        value = change.split("=")[1]
        # the error, not a warning about a key the change leaves unused (transport.St
        # with growth.enabled = true)
        error = "\n".join(l for l in p.stderr.splitlines()
                          if not l.startswith("panoptic: warning: "))
        shown = error.split(f"{key} = ")[1].split(" ")[0]
        same = shown == value or (value[0].isdigit() and float(shown) == float(value))
        c.check(same, f"{change}: the message shows the new value ({shown})")
        c.check(rows(out) == n_done, f"{change}: the output is untouched")
    print("for example:\n" + p.stderr)

    # The same scene from the final checkpoint: nothing to do, and the message says so.
    p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(done), "-o", done, sets=BASE,
                 expect=2)
    c.check("output.t_end_yr" in p.stderr and "raise" in p.stderr,
            "restart at t_end: exit 2, the message says to raise output.t_end_yr")

    # A later end, a tighter tolerance, other checkpoint settings: accepted.
    later = f"{w}/later.h5"
    copy_run(done, later, files=("output", "chk"))
    p = panoptic(args.exe, SCENE, "--restart", checkpoint_of(later), "-o", later,
                 sets=BASE + ["output.t_end_yr=1e6", "solver.rtol=1e-7",
                              "checkpoint.every_snapshots=5", "checkpoint.every_wall_s=0"])
    t = times(later)
    c.check(len(t) > n_done and np.all(np.diff(t) > 0) and t[-1] == 1e6,
            f"later output.t_end_yr: {len(t) - n_done} more snapshots to t = {t[-1]:.3g} yr, "
            f"times strictly increasing")
    with open_output(done) as a, open_output(later) as b:
        same = all(np.array_equal(a["snapshots"][k][()].view(np.uint64),
                                  b["snapshots"][k][:n_done].view(np.uint64))
                   for k in a["snapshots"])
        note = b.attrs["restarts"]
        note = note.decode() if isinstance(note, bytes) else note
    c.check(same, f"later output.t_end_yr: the {n_done} earlier snapshots are kept, bit for "
                  f"bit, in every /snapshots dataset")
    c.check("output.t_end_yr" in note and "solver.rtol" in note,
            f"the output records the restart and the changed keys: {note!r}")
    c.finish()


if __name__ == "__main__":
    main()
