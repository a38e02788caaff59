"""The model error of a run against a reference run of the same scene: what the
single-size model gets wrong, measured against the size distribution (issue 35; spec §15,
"so that a distribution run and a single-size run of the same scene are compared field
by field").

    profiles, outcomes = panoptic.compare_runs("single.h5", "distribution.h5")
    panoptic-model-error single.h5 distribution.h5 [--times-yr 1e4,1e5] [--csv PREFIX]
    python3 -m postprocess.model_error ...          (the same, from the repository root)

Both runs must share the radial grid; scene keys other than [model], [solver], [output]
and [meta] that differ are warned about, since their differences are then not the model's
alone. Per common snapshot time (`profiles`, one row each):
- sigma_d_l1: the fraction of the reference's dust mass that sits elsewhere,
  sum |Sigma_d - Sigma_d,ref| A / sum Sigma_d,ref A (A: annulus areas), over the cells
  chosen (r_au; default the whole grid);
- for sigma_d and each of St, m, phi (the mass-dominating particle; both runs write
  them): the median ratio run / reference over the dusty cells (Sigma_d,ref above
  `floor` times its largest value, and the run's too), and the worst factor
  exp(max |ln ratio|); against a size distribution also its mass-weighted mean mass
  m_mean, which a single size's m stands for (spec §4.1), as m_mean_median and
  m_mean_worst;
- m_dust, m_out_inner, m_pl (coagulation + SI): the run's minus the reference's, in
  units of the reference's initial dust mass.
`outcomes`: the /summary values both runs have (planetesimal masses and zone edges,
pebble masses, dust left; the earliest planetesimal formation), the run's, the
reference's, their difference and ratio.
"""
import argparse
import sys
import warnings

import numpy as np
import pandas as pd

from .reader import as_run

# scene tables whose keys may differ between the two runs: the model itself and how it is
# integrated and written
MODEL_TABLES = ("model", "solver", "output", "meta")
# keys outside those tables that choose the model too: how a size distribution carries
# porosity (physics/coagulation/porosity_track.hpp)
MODEL_KEYS = ("porosity.bins",)
# mass-dominating-particle fields compared as ratios, when both runs write them
RATIO_FIELDS = ("St", "m", "phi")
# /summary scalars compared (a run writes those its scene has)
OUTCOMES = ("m_pl_coag", "r_min_pl_coag", "r_max_pl_coag", "m_pl_si", "r_min_pl_si",
            "r_max_pl_si", "m_peb_snowline", "m_peb_r_in", "m_dust_final")


def compare_runs(run, reference, times_yr=None, floor=1e-6, r_au=None):
    """(profiles, outcomes) pandas DataFrames of `run` against `reference` (Run objects or
    paths): see the module's docstring. times_yr: the snapshot times to compare (each
    the nearest common one), default every common snapshot; r_au: (lo, hi) [au], the
    profiles over the cells whose centres lie within, default all. ValueError when the
    grids differ, the runs share no snapshot time or no cell lies within r_au."""
    run, reference = as_run(run), as_run(reference)
    _check_grids(run, reference)
    _warn_scene_differences(run, reference)
    pairs = _common_snapshots(run, reference, times_yr)
    m0 = float(reference.dust_mass()[0])
    cells = np.ones(len(reference.r_c), bool)
    if r_au is not None:
        cells = (reference.r_c >= r_au[0]) & (reference.r_c <= r_au[1])
        if not cells.any():
            raise ValueError(f"no cell centre lies within {r_au[0]:g}-{r_au[1]:g} au (the "
                             f"grid's: {reference.r_c[0]:g}-{reference.r_c[-1]:g} au)")
    rows = [_profile_row(run, reference, i, j, m0, floor, cells) for i, j in pairs]
    return pd.DataFrame(rows), _outcomes(run, reference)


def _check_grids(run, reference):
    """ValueError unless both runs have the same cell faces (to 1e-12 relative)."""
    a, b = run.r_f, reference.r_f
    if a.shape != b.shape or not np.allclose(a, b, rtol=1e-12, atol=0.0):
        raise ValueError(
            f"the radial grids differ: {run.path} has {len(a) - 1} cells over "
            f"{a[0]:g}-{a[-1]:g} au, {reference.path} {len(b) - 1} over {b[0]:g}-{b[-1]:g} au; "
            f"a model error compares cell by cell: run both with the same [grid] keys")


def _flatten(table, prefix=""):
    """{"grid.n_cells": 100, ...} of a nested scene dict."""
    out = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(_flatten(value, name + "."))
        else:
            out[name] = value
    return out


def _warn_scene_differences(run, reference):
    """Warn about scene keys outside MODEL_TABLES and MODEL_KEYS whose values differ."""
    a, b = _flatten(run.config), _flatten(reference.config)
    differ = sorted(k for k in set(a) | set(b)
                    if k.split(".")[0] not in MODEL_TABLES and k not in MODEL_KEYS
                    and a.get(k) != b.get(k))
    if differ:
        listed = ", ".join(f"{k} = {a.get(k)!r} / {b.get(k)!r}" for k in differ[:8])
        more = f" and {len(differ) - 8} more" if len(differ) > 8 else ""
        warnings.warn(f"{run.path} and {reference.path} differ in scene keys beyond the "
                      f"model ({listed}{more}): the differences below are not the model's "
                      f"alone", stacklevel=3)


def _common_snapshots(run, reference, times_yr):
    """[(i, j)]: snapshot i of run and j of reference at the same time (1e-9 relative)."""
    pairs = []
    for i, t in enumerate(run.time):
        j = int(np.argmin(np.abs(reference.time - t)))
        if abs(reference.time[j] - t) <= 1e-9 * max(abs(t), 1.0):
            pairs.append((i, j))
    if not pairs:
        raise ValueError(f"{run.path} and {reference.path} share no snapshot time "
                         f"(run the same scene's [output] times)")
    if times_yr is None:
        return pairs
    chosen = []
    for t in times_yr:
        k = int(np.argmin([abs(run.time[i] - t) for i, _ in pairs]))
        if abs(run.time[pairs[k][0]] - t) > 0.1 * abs(t):
            warnings.warn(f"no common snapshot near t = {t:g} yr; the nearest is at "
                          f"{run.time[pairs[k][0]]:g} yr", stacklevel=3)
        if pairs[k] not in chosen:
            chosen.append(pairs[k])
    return chosen


def _ratios(value, ref, dusty):
    """(median ratio, worst factor) of value / ref over the dusty cells; NaN if none."""
    ok = dusty & (value > 0) & (ref > 0)
    if not ok.any():
        return np.nan, np.nan
    log_ratio = np.log(value[ok] / ref[ok])
    return float(np.exp(np.median(log_ratio))), float(np.exp(np.abs(log_ratio).max()))


def _planetesimal_mass(run, i):
    """Planetesimal mass of snapshot i, both channels [g] (0 where the scene has none)."""
    return sum(float(run.snapshots[n][i]) for n in ("m_pl_coag", "m_pl_si") if n in run.snapshots)


def _profile_row(run, reference, i, j, m0, floor, cells):
    """The profiles' row of snapshot i of run against snapshot j of reference, over the
    cells selected by the mask `cells` (the mass columns: the whole grid)."""
    s, r = run.snapshots, reference.snapshots
    sd, sd_ref = s["sigma_d"][i], r["sigma_d"][j]
    dusty = cells & (sd_ref > floor * sd_ref.max()) & (sd > floor * sd.max())
    area = np.where(cells, reference.area, 0.0)
    held = float(sd_ref @ area)  # 0 once the reference's dust has left the cells: NaN
    row = {"t_yr": float(run.time[i]),
           "sigma_d_l1": float(np.abs(sd - sd_ref) @ area) / held if held > 0 else np.nan,
           "dusty_cells": int(dusty.sum())}
    row["sigma_d_median"], row["sigma_d_worst"] = _ratios(sd, sd_ref, dusty)
    for name in RATIO_FIELDS:
        if name in s and name in r:
            row[f"{name}_median"], row[f"{name}_worst"] = _ratios(s[name][i], r[name][j], dusty)
    if "m_mean" in r:  # a single size's m stands for the distribution's mean mass
        mine = s["m_mean"] if "m_mean" in s else s["m"]
        row["m_mean_median"], row["m_mean_worst"] = _ratios(mine[i], r["m_mean"][j], dusty)
    for name in ("m_dust", "m_out_inner"):
        if name in s and name in r:
            row[name] = (float(s[name][i]) - float(r[name][j])) / m0
    row["m_pl"] = (_planetesimal_mass(run, i) - _planetesimal_mass(reference, j)) / m0
    return row


def _outcomes(run, reference):
    """The /summary comparison, one row per outcome both runs have."""
    rows = []
    for name in OUTCOMES:
        if name in run.summary and name in reference.summary:
            rows.append((name, float(run.summary[name]), float(reference.summary[name])))
    t_first = [np.asarray(x.summary.get("t_first_pl", [np.nan]), float) for x in (run, reference)]
    if all(np.isfinite(t).any() for t in t_first):
        rows.append(("t_first_pl_earliest", *(float(np.nanmin(t)) for t in t_first)))
    table = pd.DataFrame(rows, columns=["outcome", "run", "reference"])
    table["unit"] = [_outcome_unit(name) for name in table["outcome"]]
    table["difference"] = table["run"] - table["reference"]
    with np.errstate(divide="ignore", invalid="ignore"):
        table["ratio"] = table["run"] / table["reference"]
    return table


def _outcome_unit(name):
    """The unit of a compared /summary value (src/io/README.md, Output)."""
    if name.startswith("r_"):
        return "au"
    return "yr" if name.startswith("t_") else "M_earth"


def main(argv=None):
    """Command line: print the two tables (and write them as CSV with --csv)."""
    parser = argparse.ArgumentParser(
        prog="panoptic-model-error",
        description="The model error of RUN against REFERENCE (two runs of one scene, e.g. "
                    "single size against size distribution): profiles per common snapshot "
                    "and /summary outcomes.")
    parser.add_argument("run", help="the run to measure (HDF5 output)")
    parser.add_argument("reference", help="the reference run of the same scene (HDF5 output)")
    parser.add_argument("--times-yr", help="snapshot times [yr], comma-separated (default all)")
    parser.add_argument("--r-au", help="LO,HI: the profiles over the cells within [au] "
                        "(default all)")
    parser.add_argument("--floor", type=float, default=1e-6,
                        help="dusty cells: Sigma_d above this times its largest value (1e-6)")
    parser.add_argument("--csv", metavar="PREFIX",
                        help="also write PREFIX_profiles.csv and PREFIX_outcomes.csv")
    args = parser.parse_args(argv)
    times = [float(x) for x in args.times_yr.split(",")] if args.times_yr else None
    if not args.floor > 0:
        parser.error(f"--floor {args.floor:g}: must be > 0 (a fraction of the largest Sigma_d)")
    r_au = [float(x) for x in args.r_au.split(",")] if args.r_au else None
    if r_au is not None and (len(r_au) != 2 or not 0 < r_au[0] < r_au[1]):
        parser.error(f"--r-au {args.r_au}: give LO,HI with 0 < LO < HI [au], e.g. 1.5,30")
    try:
        profiles, outcomes = compare_runs(args.run, args.reference, times, args.floor, r_au)
    except (ValueError, KeyError, OSError) as err:
        print(f"model_error: {err}", file=sys.stderr)
        return 1
    with pd.option_context("display.width", 200, "display.max_columns", None,
                           "display.float_format", "{:.4g}".format):
        print(f"{args.run} against {args.reference}\n\nprofiles (masses: fractions of the "
              f"reference's initial dust; ratios: run / reference)\n{profiles.to_string(index=False)}"
              f"\n\noutcomes\n{outcomes.to_string(index=False)}")
    if args.csv:
        profiles.to_csv(f"{args.csv}_profiles.csv", index=False)
        outcomes.to_csv(f"{args.csv}_outcomes.csv", index=False)
    return 0


if __name__ == "__main__":
    sys.exit(main())
