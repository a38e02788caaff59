"""Restart bit for bit of the size-distribution mode (src/run/README.md, "Restart"; issue 35
item 5): params/tests/distribution_small.toml (12 cells, 50 bins, coagulation with
fragmentation, drift, diffusion, the viscous gas) run once straight and once restarted from
its mid-run checkpoint (.chk.prev.h5, checkpoint.every_snapshots = 2) writes /snapshots
(sigma(r, m) included), /timeseries and /summary identical in every bit (h5py and h5diff),
with the same solver statistics; compact, with the snow line (silicate and icy cells,
sublimation booked) and with porous bins (psi_k per bin: phi_bins). And a compact run
stopped by --max-wall (exit 75, at its first step) continued from its checkpoint."""
from common import Checks, parse_args
from restart_common import (EXIT_STOPPED, checkpoint_of, h5diff_snapshots, panoptic,
                            restarted_from_prev, rows, snapshot_differences, solver_attrs)

SCENE = "params/tests/distribution_small.toml"
GROUPS = ("snapshots", "timeseries", "summary")
EVERY = "checkpoint.every_snapshots=2"  # the one before the end: snapshot 2 of 4
CASES = (
    ("compact", [EVERY]),
    ("snowline", [EVERY, "snowline.enabled=true"]),
    # porous bins cost ~10x: a shorter run (snapshots at 10, 31, 97, 300 yr)
    ("porous", [EVERY, "porosity.enabled=true", "output.t_end_yr=300.0",
                "output.t_first_yr=10.0"]),
)


def main():
    args = parse_args()
    c = Checks()
    for name, sets in CASES:
        full, again, k = restarted_from_prev(c, args.exe, args.workdir, SCENE, sets,
                                             f"distribution_{name}",
                                             f"size distribution, {name},", GROUPS)
        c.check(0 < k < rows(full) - 1, f"{name}: the checkpoint is mid-run (snapshot {k} "
                f"of {rows(full) - 1})")
        same = h5diff_snapshots(full, again)
        if same is not None:
            c.check(same, f"{name}: h5diff finds no difference in /snapshots")
        s, r = solver_attrs(again), solver_attrs(full)
        keys = ("nst", "nfe", "nje", "nreinit")
        stats = ", ".join(f"{key} {s[key]}" for key in keys)
        c.check(all(s[key] == r[key] for key in keys),
                f"{name}: the same solver statistics ({stats})")
        if name != "compact":
            continue
        stopped = f"{args.workdir}/distribution_stopped.h5"
        p = panoptic(args.exe, SCENE, "-o", stopped, "--overwrite", "--max-wall",
                     "0.000001s", sets=sets, expect=EXIT_STOPPED)
        panoptic(args.exe, SCENE, "--restart", checkpoint_of(stopped), sets=sets)
        diffs = snapshot_differences(full, stopped, GROUPS)
        c.check("--restart" in p.stdout and not diffs and rows(stopped) == rows(full),
                f"compact, stopped by --max-wall and restarted: identical "
                f"{diffs if diffs else ''}")
    c.finish()


if __name__ == "__main__":
    main()
