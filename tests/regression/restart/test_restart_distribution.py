"""Restart bit for bit of the size-distribution mode (src/run/README.md, "Restart"; issue 35
item 5): params/tests/distribution_small.toml (12 cells, 50 bins, coagulation with
fragmentation, drift, diffusion, the viscous gas) run once straight and once restarted from
its mid-run checkpoint (.chk.prev.h5, checkpoint.every_snapshots = 2) writes /snapshots
(sigma(r, m) included), /timeseries and /summary identical in every bit (h5py and h5diff),
with the same solver statistics; compact (by GMRES, the default, and by the block
solver), with the snow line (silicate and icy cells, sublimation booked), with porous bins
(psi_k per bin: phi_bins) and with porosity on the track (porosity.bins = "track", with
the snow line). And a compact run
stopped by --max-wall (exit 75, at its first step) continued from its checkpoint.
With planetesimals per bin (direct coagulation and the d16 streaming instability, their
thresholds lowered as in test_bin_planetesimals; 6 cells), compact and porous: both
channels book mass before the checkpoint and after it. With erosion (halt, v_eros =
0.3 m/s under v_frag = 1 m/s: the unequal pairs erode, spec §5.1, §15.2): the mass-weighted
mean mass of the inner cells ends below a tenth of the compact run's (erosion off). With
a mass grid that ends at 1e-2 g: the largest fraction of a cell's dust in the top bin,
reached at the checkpoint's snapshot, is /summary/top_bin_fraction_max after the restart
too (src/run/diagnostics.cpp reads it back)."""
import numpy as np

from common import Checks, parse_args
from postprocess.reader import open_output
from restart_common import (EXIT_STOPPED, checkpoint_of, h5diff_snapshots, panoptic,
                            restarted_from_prev, rows, snapshot_differences, solver_attrs)

SCENE = "params/tests/distribution_small.toml"
GROUPS = ("snapshots", "timeseries", "summary")
EVERY = "checkpoint.every_snapshots=2"  # the one before the end: snapshot 2 of 4
# both channels per bin at thresholds the grains of 1 000 yr reach (St ~1e-5), 6 cells
PLANETESIMALS = ("grid.n_cells=6", "planetesimals.coagulation=true", "planetesimals.St_pl=1e-5",
                 'planetesimals.si="d16"', "planetesimals.St_si_min=1e-5",
                 "planetesimals.eps_crit=5e-3")
CASES = (
    ("compact", [EVERY]),
    # the block solver, by name since GMRES is solver.linear = "auto"'s choice
    ("compact_block", [EVERY, 'solver.linear="block"']),
    ("snowline", [EVERY, "snowline.enabled=true"]),
    # porous bins cost ~10x: a shorter run (snapshots at 10, 31, 97, 300 yr)
    ("porous", [EVERY, "porosity.enabled=true", "output.t_end_yr=300.0",
                "output.t_first_yr=10.0"]),
    # porosity on the track (no psi; phi_bins from the gas at each refresh), with the
    # snow line: silicate and icy cells have their own tracks
    ("porous_track", [EVERY, "porosity.enabled=true", 'porosity.bins="track"',
                      "snowline.enabled=true"]),
    ("planetesimals", [EVERY, *PLANETESIMALS, "output.t_end_yr=1e3"]),
    ("planetesimals_porous", [EVERY, *PLANETESIMALS, "porosity.enabled=true",
                              "output.t_end_yr=300.0", "output.t_first_yr=10.0"]),
    ("erosion", [EVERY, "erosion.model=halt", "erosion.v_eros_m_s=0.3"]),
    # a mass grid that ends at 1e-2 g: the top bin holds up to 0.118 of a cell's dust,
    # most at snapshot 2, the checkpoint's, so the restart must read it back
    ("top_bin", [EVERY, "model.m_max_g=1e-2"]),
)
INNER = 6  # the cells inside ~10 au, where the pairs collide above v_eros


def snapshots(path, *names):
    with open_output(path) as f:
        return [f[f"snapshots/{name}"][()] for name in names]


def mean_mass(path):
    """Mass-weighted mean mass [g] of the bins of each cell at the last snapshot."""
    with open_output(path) as f:
        m_bins = f["grid/m_bins"][()]
        sigma = f["snapshots/sigma"][-1].reshape(-1, m_bins.size)
    return (sigma * m_bins).sum(axis=1) / sigma.sum(axis=1)


def planetesimals_formed(c, name, full, k):
    """Both channels book mass by the checkpoint (snapshot k) and more after it."""
    for channel in ("coag", "si"):
        m, m_dust = snapshots(full, f"m_pl_{channel}", "m_dust")
        c.check(m[k] > 0 and m[-1] > m[k],
                f"{name}: planetesimals by {channel} {m[k] / m_dust[0]:.2e} of the dust "
                f"at the checkpoint, {m[-1] / m_dust[0]:.2e} at the end")


def eroded(c, full, compact):
    m_eros, m_compact = mean_mass(full)[:INNER], mean_mass(compact)[:INNER]
    ratio = m_eros / m_compact
    c.check(np.all(ratio < 0.1), f"erosion: mean mass of the inner {INNER} cells "
            f"{np.array2string(ratio, precision=3)} of the compact run's (< 0.1)")


def top_bin_kept(c, full, k):
    """/summary/top_bin_fraction_max is the largest of /snapshots/top_bin_fraction, here
    reached at or before the checkpoint's snapshot k (so that the restarted run, which
    never computes that snapshot again, has it from the file), and above the warning's
    1e-3."""
    fraction, = snapshots(full, "top_bin_fraction")
    with open_output(full) as f:
        summary = f["summary/top_bin_fraction_max"][()]
    peak = int(np.argmax(fraction.max(axis=1)))
    c.check(summary.shape == (1,) and summary[0] == fraction.max() and 1e-3 < summary[0]
            and 0 < peak <= k, f"top_bin: /summary/top_bin_fraction_max {summary[0]:.4g} "
            f"is the snapshots' largest, at snapshot {peak} (checkpoint: {k})")


def main():
    args = parse_args()
    c = Checks()
    outputs = {}
    for name, sets in CASES:
        full, again, k = restarted_from_prev(c, args.exe, args.workdir, SCENE, sets,
                                             f"distribution_{name}",
                                             f"size distribution, {name},", GROUPS)
        outputs[name] = full
        if name.startswith("planetesimals"):
            planetesimals_formed(c, name, full, k)
        if name == "erosion":
            eroded(c, full, outputs["compact"])
        if name == "top_bin":
            top_bin_kept(c, full, k)
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
