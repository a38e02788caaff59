"""Outcomes of a parameter scan against its axes, from the scan's summary table.

    panoptic-plot-scan DIR [-o OUTDIR] [--axes KEY[,KEY]] [--outcomes A,B,...] [--log KEY]
                       [--format png|pdf|svg] [--title T] [--size column|page|INCHES]
    (in the repository: python3 -m postprocess.plot_scan DIR ...)

reads DIR/summary.h5 (written by `panoptic scan ... -o DIR`) and writes into OUTDIR
(default DIR/plots/), printing the path of each figure:
  - one axis (or --axes KEY): lines_<KEY>.png, one panel per outcome against the axis;
    with a second axis of at most 8 values, one line per value of it; points are joined
    only where every other axis is fixed (else, e.g. Latin hypercube, drawn alone);
  - two axes: map_<outcome>.png per outcome: a colour map over the two axes when the runs
    form a full grid (sampling = "grid"), else a scatter coloured by the outcome
    (Latin-hypercube scans).
Axes of log spacing (and lists of positive numbers that span two decades or more) get
log scales, and so does every axis named by --log (e.g. 850, 1700, 3400); a map of two
axes of a scan of more says which axes it leaves out; positive outcomes that span more than two decades get
a logarithmic colour scale (values more than 1e6 below the largest get its lowest colour).
Runs that did not complete are drawn as black crosses (along the bottom of a line panel:
they have no value), completed runs without a value of the outcome (NaN, e.g.
t_first_pl_min where no planetesimal formed) as open grey circles. Outcomes (default: those present
of m_pl_coag, m_pl_si, m_peb_snowline, m_peb_r_in, m_dust_final, t_first_pl_min) are the
/summary scalars of the runs (src/io/README.md, Output; units M_earth, au, yr).
"""
import os
import sys

import matplotlib.ticker
import numpy as np
from matplotlib import colors, patheffects

from . import style
from .scan import load_summary  # noqa: F401 (plot_scan.load_summary, as before)

DEFAULT_OUTCOMES = ("m_pl_coag", "m_pl_si", "m_peb_snowline", "m_peb_r_in", "m_dust_final",
                    "t_first_pl_min")
UNITS = {"m_pl_coag": "M_earth", "m_pl_si": "M_earth", "m_peb_snowline": "M_earth",
         "m_peb_r_in": "M_earth", "m_dust_final": "M_earth", "t_first_pl_min": "yr",
         "r_min_pl_coag": "au", "r_max_pl_coag": "au", "r_min_pl_si": "au",
         "r_max_pl_si": "au"}


# Typeset names of the scene keys scans most often vary and of the outcomes (mathtext);
# any other key is labelled by its name with the unit its suffix gives.
KEY_LABELS = {
    "star.mass_msun": r"$M_\star$ [M$_\odot$]",
    "star.luminosity_lsun": r"$L_\star$ [L$_\odot$]",
    "disk.alpha": r"$\alpha$",
    "disk.m_disk_msun": r"$M_{\rm disk}$ [M$_\odot$]",
    "disk.r_c_au": r"$r_{\rm c}$ [au]",
    "disk.sigma_1au": r"$\Sigma_{\rm g}$(1 au) [g cm$^{-2}$]",
    "disk.T_1au": r"$T$(1 au) [K]",
    "disk.p": r"$p$ ($\Sigma_{\rm g} \propto r^{-p}$)",
    "disk.q": r"$q$ ($T \propto r^{-q}$)",
    "dust.dust_to_gas": r"$Z$ (dust-to-gas)",
    "erosion.v_eros_m_s": r"$v_{\rm eros}$ [m s$^{-1}$]",
    "fragmentation.v_frag_ice_m_s": r"$v_{\rm frag,ice}$ [m s$^{-1}$]",
    "fragmentation.v_frag_sil_m_s": r"$v_{\rm frag,sil}$ [m s$^{-1}$]",
    "growth.f_grow": r"$f_{\rm grow}$",
    "porosity.s_hs": r"$s_{\rm hs}$",
    "grid.n_cells": r"$N$ (cells)",
    "solver.rtol": "rtol",
}
OUTCOME_LABELS = {
    "m_pl_coag": r"$M_{\rm pl}$, coagulation",
    "m_pl_si": r"$M_{\rm pl}$, streaming instability",
    "m_peb_snowline": "pebbles through the snow line",
    "m_peb_r_in": r"pebbles through $r_{\rm in}$",
    "m_dust_final": "dust left on the grid",
    "t_first_pl_min": "first planetesimals",
    "r_min_pl_coag": r"inner edge, coagulation zone",
    "r_max_pl_coag": r"outer edge, coagulation zone",
    "r_min_pl_si": r"inner edge, SI zone",
    "r_max_pl_si": r"outer edge, SI zone",
}
UNIT_TEX = {"M_earth": r"M$_\oplus$", "au": "au", "yr": "yr", "M_sun": r"M$_\odot$"}
_SUFFIX_UNITS = (("_msun", r"M$_\odot$"), ("_lsun", r"L$_\odot$"), ("_au", "au"),
                 ("_yr", "yr"), ("_m_s", r"m s$^{-1}$"), ("_um", r"$\mu$m"))


def key_label(key):
    """Axis label of a scene key: its typeset name and unit (KEY_LABELS), else the key
    with the unit of its suffix (`_au`, `_msun`, ...)."""
    if key in KEY_LABELS:
        return KEY_LABELS[key]
    for suffix, unit in _SUFFIX_UNITS:
        if key.endswith(suffix):
            return f"{key} [{unit}]"
    return key


def grid_map(x, y, z):
    """The runs as a full grid: (xs, ys, Z) with Z[j, i] the value at (xs[i], ys[j]), or
    None when the points do not form a full grid (each pair exactly once)."""
    xs, ys = np.unique(x), np.unique(y)
    if len(xs) * len(ys) != len(x):
        return None
    Z = np.full((len(ys), len(xs)), np.nan)
    seen = np.zeros(Z.shape, bool)
    for xv, yv, zv in zip(x, y, z):
        i, j = np.searchsorted(xs, xv), np.searchsorted(ys, yv)
        if seen[j, i]:
            return None
        seen[j, i] = True
        Z[j, i] = zv
    return xs, ys, Z


def edges(v, log):
    """Cell edges around sorted centres v (midpoints; in log10 for a log axis)."""
    t = np.log10(v) if log else np.asarray(v, float)
    if len(t) == 1:
        e = np.array([t[0] - 0.5, t[0] + 0.5])
    else:
        mid = 0.5 * (t[1:] + t[:-1])
        e = np.concatenate([[2 * t[0] - mid[0]], mid, [2 * t[-1] - mid[-1]]])
    return 10 ** e if log else e


def norm_for(z):
    """A log colour scale for positive values over more than two decades (the lowest
    1e-6 of the largest), else None (linear)."""
    good = z[np.isfinite(z)]
    pos = good[good > 0]
    if len(pos) and good.min() >= 0:
        hi = pos.max()
        lo = max(pos.min(), hi * 1e-6)
        if hi / lo > 100:
            return colors.LogNorm(vmin=lo, vmax=hi, clip=True)
    return None


def label(name, s):
    """Axis label with the outcome's units: the summary's `units` attribute (summaries
    written before it was filled in have "": then the table above)."""
    units = s.get("units", {}).get(name) or UNITS.get(name, "")
    text = OUTCOME_LABELS.get(name, name)
    return f"{text} [{UNIT_TEX.get(units, units)}]" if units else text


def sampled_ticks(ax, which, values, log):
    """Ticks at the sampled values of an axis of at most 10 of them (labels %.4g), so
    that every run's value can be read off."""
    v = np.unique(values)
    if len(v) > 10:
        return
    axis = ax.xaxis if which == "x" else ax.yaxis
    axis.set_ticks(v, labels=[f"{x:.4g}" for x in v])
    axis.set_minor_locator(matplotlib.ticker.NullLocator())


def fixed_elsewhere(s, key, sel):
    """True when the runs sel (bool mask) differ only in axis `key` (every other axis
    has one value among them): then their outcomes form a curve against `key`."""
    return all(len(np.unique(v[sel])) <= 1 for k, (v, _) in s["axes"].items() if k != key)


def mark_missing(ax, x, y, bad, nan, label_runs):
    """Runs that did not complete (bad, black crosses) and completed runs without a value
    of the outcome (nan, NaN: e.g. t_first_pl_min where none formed; open grey circles).
    y None: along the bottom of a line panel (axes coordinates: no value is implied), else
    at the runs' (x, y) of a map."""
    transform = ax.get_xaxis_transform() if y is None else ax.transData
    for mask, marker, label in ((bad, {"marker": "x", "color": "k", "ms": 7},
                                 "not completed"),
                                (nan, {"marker": "o", "mfc": "none", "mec": "0.45", "ms": 6},
                                 "completed, no value (NaN)")):
        if mask.any():
            ys = np.full(mask.sum(), 0.03) if y is None else y[mask]
            ax.plot(x[mask], ys, ls="none", transform=transform, clip_on=False,
                    label=label if label_runs else None, **marker)


def line_figure(s, key, outcomes, path=None, ax=None):
    """One panel per outcome against axis `key`; returns the figure (also saved to path,
    if given). Points are joined only where the other axes are fixed (one line per value
    of a second axis of at most 8 values); else (more axes, Latin hypercube) they are
    drawn alone. ax: the axes to draw into, one per outcome (default: a new figure)."""
    x, spacing = s["axes"][key]
    others = [k for k in s["axes"] if k != key and s["axes"][k][0].dtype.kind == "f"]
    groups = [(None, np.ones(len(x), bool))]
    if others:
        vals = np.unique(s["axes"][others[0]][0])
        if len(vals) <= 8 and len(vals) < len(x):    # values shared by runs (not LHS)
            groups = [(f"{key_label(others[0]).split(' [')[0]} = {v:.4g}",
                       s["axes"][others[0]][0] == v) for v in vals]
    joined = [fixed_elsewhere(s, key, sel) for _, sel in groups]
    ok = s["status"] == "completed"
    n = len(outcomes)
    cols = min(n, 3)
    rows = (n + cols - 1) // cols
    given = None if ax is None else (list(ax) if np.iterable(ax) else [ax])
    if given is not None and len(given) != n:
        raise ValueError(f"line_figure: {len(given)} axes for {n} outcomes")
    fig = style.new_figure(4.2 * cols, 3.3 * rows) if given is None else given[0].figure
    for k, o in enumerate(outcomes):
        ax = fig.add_subplot(rows, cols, k + 1) if given is None else given[k]
        z = s["outcome"][o]
        for (lab, sel), line in zip(groups, joined):
            m = sel & ok & np.isfinite(z)
            order = np.argsort(x[m])
            # lines of equal values would hide each other: drawn see-through, later
            # ones thinner
            ax.plot(x[m][order], z[m][order], "o-" if line else "o", ms=3, label=lab,
                    alpha=0.8, lw=max(0.8, 2.2 - 0.2 * len(ax.lines)))
        bad, nan = ~ok, ok & ~np.isfinite(z)
        mark_missing(ax, x, None, bad, nan, label_runs=True)
        if spacing == "log":
            ax.set_xscale("log")
        sampled_ticks(ax, "x", x, spacing == "log")
        norm = norm_for(z)
        if norm is not None:
            ax.set_yscale("log")
            ax.set_ylim(norm.vmin / 2, norm.vmax * 2)
        ax.set_xlabel(key_label(key))
        ax.set_ylabel(label(o, s))
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    if not all(joined):
        other = ", ".join(k for k in s["axes"] if k != key)
        fig.suptitle(f"points not joined: the other axes ({other}) vary between them",
                     fontsize=9)
    elif given is None and style.options()["title"]:
        fig.suptitle(style.options()["title"])
    if path is not None:
        style.savefig(fig, path, dpi=150)
    return fig


def map_figure(s, kx, ky, o, path=None, ax=None):
    """Colour map (full grid) or scatter of outcome o over axes kx, ky; returns the figure
    (also saved to path, if given). The axes of the scan the map leaves out are named
    under it (their runs overlap on the map). Into `ax` if given."""
    x, sx = s["axes"][kx]
    y, sy = s["axes"][ky]
    z = np.where(s["status"] == "completed", s["outcome"][o], np.nan)
    own = ax is None
    fig = style.new_figure(5.6, 4.4) if own else ax.figure
    ax = fig.add_subplot() if own else ax
    norm = norm_for(z)
    g = grid_map(x, y, z) if s["sampling"] == "grid" else None
    if g is not None:
        xs, ys, Z = g
        im = ax.pcolormesh(edges(xs, sx == "log"), edges(ys, sy == "log"),
                           np.ma.masked_invalid(Z), norm=norm, shading="flat")
        if Z.size <= 64:  # the value of each run, readable on its cell
            for j, yv in enumerate(ys):
                for i, xv in enumerate(xs):
                    if np.isfinite(Z[j, i]):
                        ax.text(xv, yv, f"{Z[j, i]:.3g}", ha="center", va="center",
                                fontsize=7, color="w",
                                path_effects=[patheffects.withStroke(linewidth=1.5,
                                                                     foreground="k")])

    else:
        m = np.isfinite(z)
        im = ax.scatter(x[m], y[m], c=z[m], norm=norm, s=28, edgecolors="none")
    bad = s["status"] != "completed"
    mark_missing(ax, x, y, bad, ~bad & ~np.isfinite(z), label_runs=True)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7, loc="upper right")
    if sx == "log":
        ax.set_xscale("log")
    if sy == "log":
        ax.set_yscale("log")
    # after the scales, which reset the tick locators; a scatter's too (a grid scan with
    # an axis left out), where at most 10 values are sampled
    sampled_ticks(ax, "x", x if g is None else g[0], sx == "log")
    sampled_ticks(ax, "y", y if g is None else g[1], sy == "log")
    ax.set_xlabel(key_label(kx))
    ax.set_ylabel(key_label(ky))
    heading = f"{OUTCOME_LABELS.get(o, o)} ({s.get('scene') or 'scan'}, {len(z)} runs)"
    left_out = left_out_note(s, (kx, ky))
    ax.set_title(style.title(heading + (f"\n{left_out}" if left_out else "")), fontsize=9)
    fig.colorbar(im, ax=ax, label=label(o, s))
    if path is not None:
        style.savefig(fig, path, dpi=150)
    return fig


def left_out_note(s, shown):
    """'not shown: disk.T_1au (150-300); runs differing only in it overlap' for the axes
    of scan s outside `shown`; "" when the map shows every axis."""
    parts = []
    for k, (v, _) in s["axes"].items():
        if k in shown:
            continue
        if v.dtype.kind == "f":
            parts.append(f"{k} ({np.min(v):.3g}$-${np.max(v):.3g})")
        else:
            parts.append(f"{k} ({len(np.unique(v))} values)")
    if not parts:
        return ""
    return "not shown: " + ", ".join(parts) + " (runs that differ only there overlap)"


def main(argv=None):
    """Command line: the figures of DIR/summary.h5 into OUTDIR; returns the exit status."""
    ap = style.cli_parser(__doc__, "scan_dir", None, None)
    ap.add_argument("--axes", help="one or two axis keys, comma-separated (default: the "
                                   "first two numeric axes)")
    ap.add_argument("--outcomes", help="comma-separated /summary names")
    ap.add_argument("--log", action="append", default=[], metavar="KEY",
                    help="draw axis KEY on a log scale (repeat, or comma-separate)")
    return style.run_cli(ap, argv, _main)


def _main(a):
    """main() inside the style options of the command line."""
    try:
        s = load_summary(a.scan_dir)
    except FileNotFoundError as err:
        sys.exit(f"plot_scan: {err}")
    outdir = a.outdir or os.path.join(a.scan_dir, "plots")
    os.makedirs(outdir, exist_ok=True)
    numeric = [k for k, (v, _) in s["axes"].items() if v.dtype.kind == "f"]
    for k in (k for arg in a.log for k in arg.split(",") if k):
        if k not in numeric:
            sys.exit(f"plot_scan: --log {k}: not a numeric axis of this scan; axes: "
                     f"{', '.join(numeric)}")
        values = s["axes"][k][0]
        if not np.all(values > 0):
            sys.exit(f"plot_scan: --log {k}: the axis has values <= 0")
        s["axes"][k] = (values, "log")
    keys = a.axes.split(",") if a.axes else numeric[:2]
    for k in keys:
        if k not in numeric:
            sys.exit(f"plot_scan: {k}: not a numeric axis of this scan; axes: {', '.join(numeric)}")
    if not keys or len(keys) > 2:
        sys.exit("plot_scan: give one or two axes with --axes")
    outcomes = (a.outcomes.split(",") if a.outcomes
                else [o for o in DEFAULT_OUTCOMES if o in s["outcome"]])
    for o in outcomes:
        if o not in s["outcome"]:
            sys.exit(f"plot_scan: {o}: not an outcome of this scan; outcomes: "
                     f"{', '.join(sorted(s['outcome']))}")
    if not outcomes:
        sys.exit("plot_scan: no completed run has a /summary yet")
    paths = []
    if len(keys) == 1:
        p = os.path.join(outdir, style.file_name(f"lines_{keys[0]}.png"))
        line_figure(s, keys[0], outcomes, p)
        paths.append(p)
    else:
        for o in outcomes:
            p = os.path.join(outdir, style.file_name(f"map_{o}.png"))
            map_figure(s, keys[0], keys[1], o, p)
            paths.append(p)
    for p in paths:
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
