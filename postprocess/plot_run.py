"""Every diagnostic figure of one run, with one command.

    panoptic-plot RUN.h5 [-o OUTDIR] [--format png|pdf|svg] [--no-footer] [--title T]
                  [--size column|page|INCHES]
    (in the repository: python3 -m postprocess.plot_run RUN.h5 ...)

writes into OUTDIR (default: RUN_plots/ next to RUN.h5) and prints the path of each:
    sigma_d.png, dust_to_gas.png  Sigma_d(r) and Sigma_d/Sigma_g(r) at up to 12 times
                                  (postprocess.plot)
    rt_St.png, rt_a.png,          r-t maps (log r [au], log t [yr]) of the Stokes number,
    rt_phi.png,                   the particle radius [cm], the filling factor (grey:
    rt_dust_to_gas.png            no dust left) and Sigma_d/Sigma_g (diverging colours,
                                  white = the initial ratio), with the snow line, the
                                  planetesimal-forming zone (hatched, outlined) and
                                  t_first_pl(r)
    pebble_flux.png               inward pebble flux [M_earth Myr^-1] and cumulative mass
                                  [M_earth] through every monitored radius vs time
    sigma_pl.png                  Sigma_pl(r) [g cm^-2] by channel at the last snapshot
    mass_budget.png               where the dust went [M_earth] vs time, and the relative
                                  error of the budget
A figure whose data the file lacks (transport-only runs have no a, phi or planetesimal
fields; older files no /timeseries, whose figures then use the snapshots) is skipped with
a note on stderr; an unfinished (killed) run is marked in the titles. Exit status 0 when
every figure that could be made was written, 1 otherwise. Every plot_* function returns
its Figure, draws into a given `ax=` (then the caller's figure keeps its size, title and
footer), and writes nothing when out_path is None.
"""
import os
import sys
import traceback

import numpy as np
from matplotlib import colormaps, colors, patheffects
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from . import plot, style
from .reader import BUILT_IN_BUDGET_TERMS, M_EARTH, MYR

FORMED_FRACTION = 1e-6        # Sigma_pl > this x the largest initial Sigma_d: formed
                              # (src/run/diagnostics.cpp; /summary/formed_threshold)
NO_DUST_FRACTION = 1e-6       # Sigma_d < this x initial Sigma_d: cell counted as dust-free
ZONE_MARGIN = 4.0             # Sigma_pl figure: r range = planetesimal zone widened x4
DEPLETION_DECADES = 4         # dust-to-gas map: colours resolve this far below the initial
LINE_DECADES = 6              # y range of the time-series panels
BUDGET_DECADES = 10           # y range of the mass-budget panel, below the initial mass
OUTLINE = [patheffects.withStroke(linewidth=2.6, foreground="k")]
SNOW_STYLE = {"color": "w", "ls": (0, (5, 3)), "lw": 1.3, "path_effects": OUTLINE}
# t_first_pl(r): a thin red line with a thin black edge, visible on every colour map
# (a wide white halo merged into a white band where t_first_pl is flat); drawn and
# put in the legend with the same style
T_FIRST_STYLE = {"color": "#ff3030", "lw": 1.3, "zorder": 3,
                 "path_effects": [patheffects.withStroke(linewidth=2.3, foreground="k")]}
ZONE_HATCH, ZONE_HATCH_COLOR = "//", "0.9"    # planetesimal-forming zone: sparse hatch,
ZONE_EDGE_STYLE = {"colors": "w", "linewidths": 1.0,     # outlined along the cell edges
                   "path_effects": [patheffects.withStroke(linewidth=2.4, foreground="k")]}
NO_DUST_LABEL = (rf"no dust ($\Sigma_\mathrm{{d}} < 10^{{{np.log10(NO_DUST_FRACTION):.0f}}}"
                 r"\,\Sigma_\mathrm{d,0}$)")
FORMED_TEX = (rf"10^{{{np.log10(FORMED_FRACTION):.0f}}}\,"
              r"\max\,\Sigma_\mathrm{d,0}")
ZONE_LABEL = rf"planetesimals ($\Sigma_\mathrm{{pl}} > {FORMED_TEX}$)"
NO_DUST_COLOR = "0.82"
CHANNELS = (("coag", "direct coagulation", "tab:green"),
            ("si", "streaming instability", "tab:purple"))
MONITOR_COLORS = ("k", "tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple",
                  "tab:brown", "tab:pink", "tab:olive", "tab:cyan")   # by increasing radius
# label and colour of each built-in budget term; a term added by a new process is drawn
# under its dataset name in the next colour of the cycle
BUDGET_STYLE = {"m_dust": ("dust on grid", "tab:blue"),
                "m_pl_coag": ("planetesimals (coag.)", "tab:green"),
                "m_pl_si": ("planetesimals (SI)", "tab:purple"),
                "m_out_inner": ("through $r_\\mathrm{in}$", "tab:red"),
                "m_sublimated": ("sublimated", "tab:orange")}

# r-t maps: output file and the keyword arguments of plot_map
MAPS = (("rt_St.png", {"field": "St", "quantity": "Stokes number St", "cmap": "viridis",
                       "decades": 8}),
        ("rt_a.png", {"field": "a", "quantity": "particle radius $a$", "cmap": "plasma",
                      "decades": 8}),
        ("rt_phi.png", {"field": "phi", "quantity": r"filling factor $\phi$",
                        "cmap": "cividis", "decades": 6, "vmax": 1.0}),
        ("rt_dust_to_gas.png", {"field": None,
                                "quantity": r"$\Sigma_\mathrm{d}\,/\,\Sigma_\mathrm{g}$",
                                "cmap": "RdBu_r", "decades": 6, "diverging": True,
                                "mask_no_dust": False, "hatch_color": "0.2"}))


class Skip(Exception):
    """The run lacks the data of a figure; the message says what is missing."""


# --- helpers ---------------------------------------------------------------------------

def unit_tex(unit):
    """'g cm^-2' -> 'g cm$^{-2}$' (matplotlib mathtext); '' stays ''."""
    words = []
    for word in unit.split():
        base, _, power = word.partition("^")
        words.append(f"{base}$^{{{power}}}$" if power else base)
    return " ".join(words)


def axis_label(quantity, unit):
    """'quantity [unit]', or just the quantity when dimensionless."""
    return f"{quantity} [{unit_tex(unit)}]" if unit else quantity


def new_figure(nrows=1, height=4.6, sharex=True, ax=None):
    """Agg-backed figure with nrows axes stacked vertically (log x), and the axes; given
    `ax` (one axes or a sequence of nrows), their figure and them."""
    if ax is not None:
        axes = list(ax) if np.iterable(ax) else [ax]
        fig = axes[0].figure
    else:
        fig = style.new_figure(6.4, height)
        axes = fig.subplots(nrows, 1, sharex=sharex, squeeze=False)[:, 0]
    for ax in axes:
        ax.set_xscale("log")
        ax.grid(True, which="major", color="0.88", lw=0.6)
        ax.set_axisbelow(True)
    return fig, list(axes)


def title(run, what):
    """Figure title: scene, what is shown, and a warning for an unfinished run (or the
    --title given)."""
    text = f"{run.scene or 'run'}: {what}"
    if not run.finished:
        text += f"  [unfinished, last snapshot {plot.format_years(run.time[-1])}]"
    return style.title(text)


def suptitle(fig, own, text):
    """The figure's title, on a figure made here (own) only."""
    if own and text:
        fig.suptitle(text, fontsize="large")


def save(fig, run, out_path):
    """Provenance footer (unless --no-footer), and savefig unless out_path is None (in a
    notebook: every plot_* function returns its Figure)."""
    style.footer(fig, plot._provenance(run))
    if out_path is not None:
        style.savefig(fig, out_path)


def done(fig, run, out_path, own):
    """save() a figure made here (own); a figure given through ax= only saved to
    out_path if given (its footer is the caller's)."""
    if own:
        save(fig, run, out_path)
    elif out_path is not None:
        style.savefig(fig, out_path)


def legend_above(ax, own, ncol, **kwargs):
    """The legend in a band above the axes of a figure made here (own), in ncol columns
    (one on a figure narrower than 5 in: the labels are long); inside the axes of a caller's figure
    (ax=), whose layout is the caller's."""
    if not own:
        return ax.legend(loc="best", fontsize="x-small", framealpha=0.8, **kwargs)
    if style.narrow():
        ncol = 1
    return ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.01, 1.0, 0.1), mode="expand",
                     ncol=ncol, fontsize=7.5, title_fontsize=7.5, frameon=False,
                     borderaxespad=0.0, **kwargs)


def note(ax, text, y=0.5):
    """Grey explanatory text centred in the axes."""
    ax.text(0.5, y, text, transform=ax.transAxes, ha="center", va="center", fontsize=9,
            color="0.35", wrap=True,
            bbox={"boxstyle": "round", "fc": "w", "ec": "0.8", "alpha": 0.9})


def plural(n, word):
    """'1 cell', '3 cells'."""
    return f"{n} {word}" + ("" if n == 1 else "s")


def initial_dust(run):
    """Initial Sigma_d (N,) [g cm^-2]: the first snapshot."""
    return run.snapshots["sigma_d"][0]


def formed_threshold(run):
    """Sigma_pl [g cm^-2] above which a cell counts as having formed planetesimals: the
    run's /summary/formed_threshold (FORMED_FRACTION of the largest initial Sigma_d, the
    threshold of /summary's r_min_pl_*, r_max_pl_* and t_first_pl), else (a file without
    it: killed or older) the same computed from the first snapshot."""
    value = run.summary.get("formed_threshold")
    if value is not None and np.isfinite(value) and value > 0:
        return float(value)
    return FORMED_FRACTION * float(np.max(initial_dust(run)))


def sigma_pl_total(run):
    """Sigma_pl (nt, N) [g cm^-2] of all channels; None without planetesimal fields."""
    snaps = run.snapshots
    if "sigma_pl" in snaps:
        return snaps["sigma_pl"]
    parts = [snaps[f"sigma_pl_{c}"] for c, _, _ in CHANNELS if f"sigma_pl_{c}" in snaps]
    return sum(parts) if parts else None


def t_first_pl(run):
    """Time of first planetesimal formation per cell (N,) [yr], NaN = never; from
    /summary, else the last snapshot (unfinished run); None without planetesimals."""
    if "t_first_pl" in run.summary:
        return np.atleast_1d(np.asarray(run.summary["t_first_pl"], dtype=float))
    if "t_first_pl" in run.snapshots:
        return run.snapshots["t_first_pl"][-1]
    return None


def log_limits(values, decades, vmax=None):
    """(vmin, vmax, extend) of a log colour scale for the positive finite values.

    vmax: the 99.5th percentile (or the given bound), vmin: the 0.5th percentile but at
    most `decades` decades below vmax; extend says which ends clip data. None if no
    positive values.
    """
    v = values[np.isfinite(values) & (values > 0)]
    if v.size == 0:
        return None
    hi = float(np.percentile(v, 99.5)) if vmax is None else vmax
    lo = max(float(np.percentile(v, 0.5)), hi * 10.0 ** -decades)
    if not lo < hi:     # a constant field: one decade below it
        lo = hi / 10.0
    extend = {(False, False): "neither", (True, False): "min", (False, True): "max",
              (True, True): "both"}[(bool(v.min() < lo * 0.999), bool(v.max() > hi * 1.001))]
    return lo, hi, extend


def time_edges(t):
    """Cell edges [yr] around positive, increasing times t: log midpoints, the ends
    mirrored (half a decade each side for a single time)."""
    log_t = np.log10(t)
    if len(t) == 1:
        return 10.0 ** np.array([log_t[0] - 0.5, log_t[0] + 0.5])
    mid = 0.5 * (log_t[1:] + log_t[:-1])
    return 10.0 ** np.concatenate([[2 * log_t[0] - mid[0]], mid, [2 * log_t[-1] - mid[-1]]])


def mask_rectangles(mask, x_edges, y_edges):
    """Rectangles (list of 4 vertices) covering the True cells of mask (ny, nx), one
    per run of adjacent True cells in a row."""
    boxes = []
    for j, row in enumerate(mask):
        padded = np.concatenate([[False], row, [False]]).astype(np.int8)
        starts = np.flatnonzero(np.diff(padded) == 1)
        ends = np.flatnonzero(np.diff(padded) == -1)
        for i0, i1 in zip(starts, ends):
            x0, x1, y0, y1 = x_edges[i0], x_edges[i1], y_edges[j], y_edges[j + 1]
            boxes.append([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
    return boxes


def mask_outline(mask, x_edges, y_edges):
    """Segments [(x0, y0), (x1, y1)] of the cell edges between True and False cells of
    mask (ny, nx) (the border of the True region, including the array's border)."""
    padded = np.pad(mask, 1, constant_values=False)
    segments = []
    jj, ii = np.nonzero(padded[1:, 1:-1] != padded[:-1, 1:-1])    # horizontal edges
    segments += [[(x_edges[i], y_edges[j]), (x_edges[i + 1], y_edges[j])] for j, i in zip(jj, ii)]
    jj, ii = np.nonzero(padded[1:-1, 1:] != padded[1:-1, :-1])    # vertical edges
    segments += [[(x_edges[i], y_edges[j]), (x_edges[i], y_edges[j + 1])] for j, i in zip(jj, ii)]
    return segments


label_minor_log_ticks = plot.label_minor_log_ticks


def mark_snow_line(ax, run, view=None, **style):
    """Vertical dashed line at the snow line if inside view (r range [au], default the
    grid); its legend handle or None."""
    r_snow = run.r_snow_au
    lo, hi = view or (run.r_f[0], run.r_f[-1])
    if np.isfinite(r_snow) and lo <= r_snow <= hi:
        return ax.axvline(r_snow, label=f"snow line ({r_snow:.3g} au)", **(style or SNOW_STYLE))
    return None


# --- r-t maps --------------------------------------------------------------------------

def plot_map(run, out_path=None, field="St", quantity="Stokes number St", cmap="viridis",
             decades=8, vmax=None, mask_no_dust=True, diverging=False,
             hatch_color=ZONE_HATCH_COLOR, ax=None):
    """r-t map of a snapshot field (nt, N) (field None: Sigma_d/Sigma_g), log colours.

    x: r [au] (cell faces), y: snapshot times [yr] > 0 (log midpoints as edges). The
    colour scale spans at most `decades` decades (log_limits), up to vmax if given;
    diverging: centred on the initial dust-to-gas ratio (dust_to_gas_reference), at least
    a decade each side. Cells with Sigma_d < NO_DUST_FRACTION x initial Sigma_d are grey
    when mask_no_dust. Overlays: snow line, planetesimal-forming zone (Sigma_pl >
    formed_threshold, hatched in hatch_color and outlined) and
    t_first_pl(r). MAPS holds the arguments of the four maps plot_run writes. Into `ax`
    if given; returns the Figure.
    """
    snaps = run.snapshots
    if field is None:
        values, unit = dust_to_gas(run), ""
    elif field in snaps:
        values, unit = snaps[field], run.units.get(f"snapshots/{field}", "")
    else:
        raise Skip(f"no /snapshots/{field} (growth off?)")
    keep = np.flatnonzero(run.time > 0)
    if keep.size == 0:
        raise Skip("no snapshot at t > 0")
    t = run.time[keep]
    values = plot.masked_log(values[keep])
    dust_free = np.zeros(values.shape, dtype=bool)
    if mask_no_dust:
        dust_free = snaps["sigma_d"][keep] < NO_DUST_FRACTION * initial_dust(run)[None, :]
        values = np.where(dust_free, np.nan, values)

    own = ax is None
    fig, (ax,) = new_figure(height=4.9, ax=ax)
    ax.set_yscale("log")
    ax.grid(False)
    limits = log_limits(values, decades, vmax)
    colour_map = colormaps[cmap].with_extremes(bad=NO_DUST_COLOR)
    handles = []
    if limits is None:
        note(ax, "no positive values")
    elif diverging:
        draw_diverging(fig, ax, run, t, values, limits, colour_map, quantity)
    else:
        lo, hi, extend = limits
        mesh = ax.pcolormesh(run.r_f, time_edges(t), values, cmap=colour_map,
                             norm=colors.LogNorm(lo, hi), rasterized=True)
        bar = fig.colorbar(mesh, ax=ax, extend=extend, pad=0.02)
        bar.set_label(axis_label(quantity, unit))
        if lo * 10 >= hi and np.nanmax(values) <= hi * 1.001 and np.nanmin(values) >= hi / 1.001:
            note(ax, f"{quantity} = {hi:.3g} everywhere", y=0.9)
    if dust_free.any():
        handles.append(Patch(fc=NO_DUST_COLOR, ec="0.6", lw=0.5, label=NO_DUST_LABEL))
    elif limits is not None and np.isnan(values).any():
        n_bad = plural(int(np.isnan(values).sum()), "cell")
        handles.append(Patch(fc=NO_DUST_COLOR, ec="0.6", lw=0.5,
                             label=f"{quantity} $\\leq 0$ ({n_bad})"))
    snow = mark_snow_line(ax, run)
    if snow is not None:
        handles.append(snow)
    handles += overlay_planetesimals(ax, run, keep, t, hatch_color)
    ax.set_xlim(run.r_f[0], run.r_f[-1])
    ax.set_ylim(time_edges(t)[0], time_edges(t)[-1])
    label_minor_log_ticks(ax.xaxis, run.r_f[0], run.r_f[-1])
    label_minor_log_ticks(ax.yaxis, time_edges(t)[0], time_edges(t)[-1])
    ax.set_xlabel(r"$r$ [au]")
    ax.set_ylabel(r"$t$ [yr]")
    if handles:
        legend_above(ax, own, 2, handles=handles, handlelength=2.2)
    suptitle(fig, own, title(run, f"{quantity}(r, t)"))
    done(fig, run, out_path, own)
    return fig


def dust_to_gas(run):
    """Sigma_d / Sigma_g (nt, N), NaN where Sigma_g <= 0."""
    sigma_g = run.snapshots["sigma_g"]
    return np.divide(run.snapshots["sigma_d"], sigma_g, out=np.full(sigma_g.shape, np.nan),
                     where=sigma_g > 0)


def dust_to_gas_reference(run):
    """The initial dust-to-gas ratio: dust.dust_to_gas of the scene when the dust starts
    as that fraction of the gas, else the dust-mass-weighted median of the first
    snapshot's Sigma_d / Sigma_g."""
    dust = run.config.get("dust", {})
    if dust.get("init", "dust_to_gas") == "dust_to_gas" and dust.get("dust_to_gas", 0) > 0:
        return float(dust["dust_to_gas"])
    ratio, mass = dust_to_gas(run)[0], run.snapshots["sigma_d"][0] * run.area
    ok = np.isfinite(ratio) & (ratio > 0) & (mass > 0)
    if not ok.any():
        return np.nan
    order = np.argsort(ratio[ok])
    cumulative = np.cumsum(mass[ok][order])
    return float(ratio[ok][order][np.searchsorted(cumulative, 0.5 * cumulative[-1])])


def draw_diverging(fig, ax, run, t, values, limits, colour_map, quantity):
    """pcolormesh of log10(values) with a two-slope norm centred on the initial
    dust-to-gas ratio (dust_to_gas_reference; the middle of the range when it has none):
    one to DEPLETION_DECADES decades below it (deeper depletion saturates), a decade or
    more above; colour bar labelled in powers of 10."""
    lo, hi, _ = limits
    centre = dust_to_gas_reference(run)
    initial = bool(np.isfinite(centre) and centre > 0)
    if initial:
        # white stays the initial ratio even when the largest ratios (gas drained at an
        # edge) lie many decades above it: the lower end from the data, not from `hi`
        positive = values[np.isfinite(values) & (values > 0)]
        lo = float(np.percentile(positive, 0.5))
    else:
        centre = np.sqrt(lo * hi)
    word = "initial" if initial else "middle"
    lo = min(max(lo, centre * 10.0 ** -DEPLETION_DECADES), centre / 10.0)
    hi = max(hi, centre * 10.0)
    log_values = np.log10(values)
    norm = colors.TwoSlopeNorm(vcenter=np.log10(centre), vmin=np.log10(lo), vmax=np.log10(hi))
    mesh = ax.pcolormesh(run.r_f, time_edges(t), log_values, cmap=colour_map, norm=norm,
                         rasterized=True)
    finite = values[np.isfinite(values)]
    extend = {(False, False): "neither", (True, False): "min", (False, True): "max",
              (True, True): "both"}[(bool(finite.min() < lo * 0.999),
                                     bool(finite.max() > hi * 1.001))]
    bar = fig.colorbar(mesh, ax=ax, extend=extend, pad=0.02)
    decades = np.arange(np.ceil(np.log10(lo)), np.floor(np.log10(hi)) + 1)
    ticks = np.union1d(decades, [np.log10(centre)])
    bar.set_ticks(ticks)
    bar.set_ticklabels([f"{10 ** x:.3g}\n({word})" if x == np.log10(centre) and
                        x not in decades else f"$10^{{{x:.0f}}}$" for x in ticks])
    bar.set_label(f"{quantity}   (white: {word} {centre:.3g})")


def overlay_planetesimals(ax, run, keep, t, hatch_color=ZONE_HATCH_COLOR):
    """Hatch the snapshot cells keep (times t [yr]) where Sigma_pl > formed_threshold,
    draw t_first_pl(r) [yr]; returns the legend handles."""
    handles = []
    sigma_pl = sigma_pl_total(run)
    if sigma_pl is not None:
        formed = sigma_pl[keep] > formed_threshold(run)
        if formed.any():
            x_edges, y_edges = run.r_f, time_edges(t)
            ax.add_collection(PolyCollection(mask_rectangles(formed, x_edges, y_edges),
                                             facecolors="none", edgecolors=hatch_color,
                                             hatch=ZONE_HATCH, lw=0.0, zorder=2))
            ax.add_collection(LineCollection(mask_outline(formed, x_edges, y_edges),
                                             zorder=2.1, **ZONE_EDGE_STYLE))
            handles.append(Patch(fc="0.6", ec="k", lw=1.0, hatch=ZONE_HATCH,
                                 label=ZONE_LABEL))
    t_first = t_first_pl(run)
    if t_first is not None and np.isfinite(t_first).any():
        bottom = time_edges(t)[0]    # the axis starts below the first snapshot t[0]
        early = np.isfinite(t_first) & (t_first < bottom)
        label = r"$t_\mathrm{first\,pl}(r)$"
        if early.any():
            label += (f" ({plural(early.sum(), 'cell')} before {plot.format_years(bottom)},"
                      " off the axis)")
        ax.plot(run.r_c, t_first, **T_FIRST_STYLE)
        handles.append(Line2D([], [], label=label, **T_FIRST_STYLE))
    return handles


# --- pebble flux -----------------------------------------------------------------------

def pebble_series(run):
    """(time [yr], flux [M_earth Myr^-1], m_through [M_earth], source) per monitor:
    /timeseries, else the snapshots (converted from g s^-1 and g)."""
    ts, snaps = run.timeseries, run.snapshots
    if "pebble_flux" in ts and "m_through" in ts and len(ts["time"]):
        return ts["time"], ts["pebble_flux"], ts["m_through"], "/timeseries"
    if "pebble_flux" in snaps and "m_through" in snaps:
        return (run.time, snaps["pebble_flux"] / (M_EARTH / MYR), snaps["m_through"] / M_EARTH,
                "snapshots")
    raise Skip("no pebble-flux data (/timeseries or /snapshots/pebble_flux)")


def monitor_label(name, r_au, snow_line=True):
    """'snow line (2.73 au)'; a name that already is the radius ('10 au') alone. With
    snow_line False (snowline.enabled = false) the monitor panoptic names "snow line" is
    only where T = T_sub, and labelled so."""
    plain = f"{r_au:.3g} au"
    pretty = {"r_in": r"$r_\mathrm{in}$", "r_out": r"$r_\mathrm{out}$"}.get(name, name)
    if name == "snow line" and not snow_line:
        pretty = r"$T = T_\mathrm{sub}$, snow line off"
    return name if name == plain else f"{pretty} ({plain})"


def plot_pebble_flux(run, out_path=None, ax=None):
    """Inward pebble flux [M_earth Myr^-1] and cumulative mass through [M_earth] at
    every monitored radius vs t [yr]; log-log, legend with names and radii. ax: one axes
    (the flux only) or two (flux, mass); returns the Figure."""
    time, flux, mass, source = pebble_series(run)
    r_au = run.monitor_r_au
    if not np.any(time > 0):
        raise Skip("no pebble-flux sample at t > 0")
    if flux.ndim != 2 or flux.shape[1] == 0 or flux.shape[1] != len(r_au):
        raise Skip("no pebble monitors on the grid")
    names = run.pebble_names or [f"{r:.3g} au" for r in r_au]
    order = np.argsort(r_au)
    own = ax is None
    fig, axes = new_figure(2, height=6.6, ax=ax)
    ax_f, ax_m = (axes + [None])[:2]
    positive = time > 0
    outward = False
    for n, k in enumerate(order):
        final = mass[-1, k] if len(mass) else np.nan
        # inner monitors drawn wider, so that coinciding curves stay visible
        width = 1.2 + 1.0 * (len(order) - 1 - n) / max(len(order) - 1, 1)
        snow_line = bool(np.isfinite(run.r_snow_au))
        line_style = {"color": MONITOR_COLORS[n % len(MONITOR_COLORS)], "lw": width,
                 "ls": "--" if names[k] == "snow line" and snow_line else "-"}
        ax_f.plot(time[positive], plot.masked_log(flux[positive, k]),
                  label=f"{monitor_label(names[k], r_au[k], snow_line)}: {final:.3g} "
                        + r"$M_\oplus$",
                  **line_style)
        if ax_m is not None:
            ax_m.plot(time[positive], plot.masked_log(mass[positive, k]), **line_style)
        outward |= bool(np.any(flux[positive, k] < 0))
    for ax, values in ((ax_f, flux), (ax_m, mass)):
        if ax is not None:
            ax.set_yscale("log")
            set_decades_ylim(ax, values[positive], LINE_DECADES)
    ax_f.set_ylabel(r"inward pebble flux [$M_\oplus$ Myr$^{-1}$]")
    bottom = ax_f if ax_m is None else ax_m
    if ax_m is not None:
        ax_m.set_ylabel(r"cumulative mass through [$M_\oplus$]")
    bottom.set_xlabel(r"$t$ [yr]")
    if np.any(positive):
        bottom.set_xlim(time[positive].min(), time[positive].max())
        label_minor_log_ticks(bottom.xaxis, time[positive].min(), time[positive].max())
    columns = 3 if np.isfinite(run.r_snow_au) else 2     # room for the T_sub label
    legend_above(ax_f, own, min(columns, len(order)),
                 title=f"monitor: total mass through by {plot.format_years(time[-1])}")
    if outward:
        ax_f.text(0.99, 0.02, "gaps: net outward flow (not shown)", transform=ax_f.transAxes,
                  ha="right", va="bottom", fontsize=7, color="0.4")
    suptitle(fig, own, title(run, "pebble flux through the monitored radii"))
    source_note(fig, own, source)
    done(fig, run, out_path, own)
    return fig


def source_note(fig, own, source):
    """'from the snapshots (no /timeseries)' in the bottom left of a figure made here."""
    if own and source != "/timeseries":
        fig.text(0.005, 0.002, f"from the {source} (no /timeseries)", fontsize=6, color="0.5",
                 va="bottom")


def set_decades_ylim(ax, values, decades):
    """Log y range of the positive values: from the largest down at most `decades`
    decades, at least one decade wide (centred on the values)."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    if v.size == 0:
        note(ax, "no positive values")
        return
    top = v.max()
    bottom = max(v.min(), top * 10.0 ** -decades)
    half_span = np.sqrt(max(top / bottom, 10.0))
    centre = np.sqrt(top * bottom)
    ax.set_ylim(centre / half_span / 1.5, centre * half_span * 1.5)
    label_minor_log_ticks(ax.yaxis, *ax.get_ylim())


# --- planetesimal surface density ------------------------------------------------------

def plot_sigma_pl(run, out_path=None, ax=None):
    """Sigma_pl(r) [g cm^-2] by channel and in total at the last snapshot, with Sigma_g
    and the initial Sigma_d for scale and the formation threshold (formed_threshold).
    Into `ax` if given; returns the Figure."""
    snaps = run.snapshots
    total = sigma_pl_total(run)
    if total is None:
        raise Skip("no planetesimal fields (planetesimal formation off)")
    last = -1
    own = ax is None
    fig, (ax,) = new_figure(height=4.6, ax=ax)
    ax.set_yscale("log")
    ax.grid(True, which="minor", axis="x", color="0.95", lw=0.4)
    sigma_d0 = initial_dust(run)
    ax.plot(run.r_c, plot.masked_log(snaps["sigma_g"][last]), color="0.45", ls="--", lw=1.3,
            label=rf"$\Sigma_\mathrm{{g}}$ at {plot.format_years(run.time[last])}")
    ax.plot(run.r_c, plot.masked_log(sigma_d0), color="tab:brown", ls=":", lw=1.4,
            label=rf"$\Sigma_\mathrm{{d}}$ at {plot.format_years(run.time[0])}")
    ax.plot(run.r_c, plot.masked_log(snaps["sigma_d"][last]), color="tab:brown", lw=1.0,
            alpha=0.6, label=rf"$\Sigma_\mathrm{{d}}$ at {plot.format_years(run.time[last])}")
    threshold = np.full(run.r_c.shape, formed_threshold(run))
    ax.plot(run.r_c, threshold, color="0.6", lw=0.8, ls="-.",
            label=rf"threshold ${FORMED_TEX}$")
    shown = [snaps["sigma_g"][last], sigma_d0, threshold]
    formed_any = False
    for channel, what, colour in CHANNELS:
        name = f"sigma_pl_{channel}"
        if name not in snaps:
            continue
        sigma = snaps[name][last]
        m = run.summary.get(f"m_pl_{channel}")
        mass = f", {m:.3g} " + r"$M_\oplus$" if m is not None and np.isfinite(m) else ""
        if not np.any(sigma > threshold):
            mass += " (nowhere above threshold)"
        ax.plot(run.r_c, plot.masked_log(np.where(sigma > 1e-3 * threshold, sigma, 0.0)),
                color=colour, lw=1.5, label=f"{what}{mass}")
        formed_any |= bool(np.any(sigma > threshold))
    total_last = total[last]
    visible = np.where(total_last > 1e-3 * threshold, total_last, 0.0)
    ax.plot(run.r_c, plot.masked_log(visible), color="k", lw=2.4, alpha=0.35, zorder=1.5,
            label=r"total $\Sigma_\mathrm{pl}$")
    shown.append(visible)
    x_lo, x_hi = zone_view(run, total_last > threshold)
    mark_snow_line(ax, run, (x_lo, x_hi), **plot.SNOW_STYLE)
    ax.set_xlim(x_lo, x_hi)
    label_minor_log_ticks(ax.xaxis, x_lo, x_hi)
    in_view = (run.r_c >= x_lo) & (run.r_c <= x_hi)
    values = np.concatenate([plot.masked_log(a[in_view]) for a in shown])
    values = values[np.isfinite(values)]
    top = values.max() if values.size else 1.0
    bottom = values.min() if values.size else 1e-10
    ax.set_ylim(bottom / 3.0, top * 3.0)
    if not formed_any:
        note(ax, f"no planetesimals formed by {plot.format_years(run.time[last])}\n"
                 rf"($\Sigma_\mathrm{{pl}} \leq {FORMED_TEX}$ everywhere)", y=0.2)
    if (x_lo, x_hi) != (run.r_f[0], run.r_f[-1]):
        ax.plot([], [], ls="none", label=f"($r$ zoomed to the planetesimals;\n grid "
                f"{run.r_f[0]:.3g}$-${run.r_f[-1]:.4g} au)")
    ax.set_xlabel(r"$r$ [au]")
    ax.set_ylabel(r"$\Sigma$ [g cm$^{-2}$]")
    legend_above(ax, own, 2)
    suptitle(fig, own, title(run, f"planetesimals at {plot.format_years(run.time[last])}"))
    done(fig, run, out_path, own)
    return fig


def zone_view(run, formed):
    """x range [au] of the Sigma_pl figure: the cells where formed (N,) is True, widened
    by ZONE_MARGIN each side (the whole grid if none, or if that is nearly all of it)."""
    if not formed.any():
        return run.r_f[0], run.r_f[-1]
    cells = np.flatnonzero(formed)
    lo = max(run.r_f[0], run.r_f[cells[0]] / ZONE_MARGIN)
    hi = min(run.r_f[-1], run.r_f[cells[-1] + 1] * ZONE_MARGIN)
    if np.log(hi / lo) > 0.7 * np.log(run.r_f[-1] / run.r_f[0]):
        return run.r_f[0], run.r_f[-1]
    return lo, hi


# --- mass budget -----------------------------------------------------------------------

BUDGET_TERMS = BUILT_IN_BUDGET_TERMS


def budget_series(run):
    """(time [yr], columns (ns, n_terms) [M_earth], error (ns,) [M_earth], initial
    [M_earth], term names, source): /timeseries/mass_budget, else the snapshot totals
    (g -> M_earth). The terms are the file's (mass_budget_columns, budget_terms), or the
    five built-in ones of a file written before those attributes."""
    ts, snaps = run.timeseries, run.snapshots
    initial = None
    if run.time.size and run.time[0] <= 0 and "m_dust" in snaps:
        initial = snaps["m_dust"][0] / M_EARTH
    if "mass_budget" in ts and len(ts["time"]):
        budget = ts["mass_budget"]
        names = run.budget_columns[:-1] or list(BUDGET_TERMS)
        if len(names) + 1 != budget.shape[1]:
            raise Skip(f"/timeseries/mass_budget has {budget.shape[1]} columns, its names "
                       f"{len(names) + 1}")
        columns, error = budget[:, :-1], budget[:, -1]
        if initial is None:
            initial = columns[0].sum()
        return ts["time"], columns, error, initial, names, "/timeseries"
    if "m_dust" not in snaps:
        raise Skip("no /timeseries/mass_budget and no /snapshots/m_dust")
    names = run.budget_terms or list(BUDGET_TERMS)
    zero = np.zeros_like(snaps["m_dust"])
    columns = np.stack([snaps.get(name, zero) for name in names], axis=1) / M_EARTH
    initial = columns[0].sum() if initial is None else initial
    return (run.time, columns, np.abs(columns.sum(axis=1) - initial), initial, names,
            "snapshots")


def plot_mass_budget(run, out_path=None, ax=None):
    """Dust on the grid, planetesimals (each channel), mass through r_in and sublimated
    [M_earth] vs t [yr]; below, |sum - initial| / initial. ax: one axes (the masses
    only) or two (masses, error); returns the Figure."""
    time, columns, error, initial, names, source = budget_series(run)
    positive = time > 0
    if not positive.any():
        raise Skip("no mass-budget sample at t > 0")
    own = ax is None
    fig, axes = new_figure(2, height=6.4, ax=ax)
    ax, ax_e = (axes + [None])[:2]
    if own:
        fig.get_layout_engine().set(h_pad=0.04)
    ax.set_yscale("log")
    ax.axhline(initial, color="k", ls="--", lw=1.0,
               label=f"initial dust: {initial:.4g} " + r"$M_\oplus$")
    absent = []
    floor = initial * 10.0 ** -BUDGET_DECADES
    extra = iter(("tab:brown", "tab:pink", "tab:olive", "tab:cyan", "tab:gray"))
    for k, name in enumerate(names):
        label, colour = BUDGET_STYLE.get(name, (name, None))
        colour = colour or next(extra, "k")
        column = columns[positive, k]
        if not np.any(column > 0):
            absent.append(label)
            continue
        final = columns[-1, k]
        below = "  (below the axis)" if column.max() <= floor else ""
        ax.plot(time[positive], plot.masked_log(column), color=colour, lw=1.5,
                label=f"{label}: {final:.3g} " + r"$M_\oplus$" + below)
    shown = columns[positive][columns[positive] > floor]
    ax.set_ylim(max(shown.min() if shown.size else floor, floor) / 2.0, initial * 3.0)
    ax.set_ylabel(r"dust mass [$M_\oplus$]")
    legend_above(ax, own, 2, title=f"mass at {plot.format_years(time[-1])}")
    if absent:
        ax.text(0.01, 0.02, "zero throughout: " + ", ".join(absent), transform=ax.transAxes,
                fontsize=7, color="0.4", va="bottom")

    if ax_e is None:
        ax.set_xlabel(r"$t$ [yr]")
        ax.set_xlim(time[positive].min(), time[positive].max())
        suptitle(fig, own, title(run, "dust mass budget"))
        done(fig, run, out_path, own)
        return fig
    relative = plot.masked_log(error[positive] / initial) if initial > 0 else np.full(
        positive.sum(), np.nan)
    ax_e.set_yscale("log")
    ax_e.plot(time[positive], relative, color="k", lw=1.0, marker=".", ms=2.0,
              label=r"|sum $-\ M_0$| / $M_0$  ($M_0$: initial dust)")
    eps = np.finfo(float).eps
    ax_e.axhline(eps, color="0.5", ls=":", lw=1.0, label=r"machine $\epsilon$")
    finite = relative[np.isfinite(relative)]
    if 0 < finite.size < relative.size:
        ax_e.text(0.99, 0.02, "gaps: error exactly 0", transform=ax_e.transAxes, ha="right",
                  va="bottom", fontsize=7, color="0.4")
    if finite.size:
        ax_e.set_ylim(min(finite.min(), eps) / 3.0, max(finite.max(), 100 * eps) * 3.0)
    else:
        note(ax_e, "budget closes exactly (error 0 at every sample)")
    final_error = run.summary.get("budget_error")
    ax_e.legend(fontsize=7.5, frameon=False, loc="upper left",
                title=(f"final: {final_error:.2g}" if final_error is not None else None),
                title_fontsize=7.5)
    ax_e.set_ylabel("relative budget error")
    ax_e.set_xlabel(r"$t$ [yr]")
    if np.any(positive):
        ax_e.set_xlim(time[positive].min(), time[positive].max())
        label_minor_log_ticks(ax_e.xaxis, time[positive].min(), time[positive].max())
    suptitle(fig, own, title(run, "dust mass budget"))
    source_note(fig, own, source)
    done(fig, run, out_path, own)
    return fig


# --- command line ----------------------------------------------------------------------

def figures(run):
    """(file name, function(out_path)) of every figure, in output order."""
    indices = plot.select_snapshots(run.time)
    jobs = [("sigma_d.png", lambda p: plot.plot_sigma_d(run, indices, p)),
            ("dust_to_gas.png", lambda p: plot.plot_dust_to_gas(run, indices, p))]
    for name, spec in MAPS:
        jobs.append((name, lambda p, spec=spec: plot_map(run, p, **spec)))
    jobs += [("pebble_flux.png", lambda p: plot_pebble_flux(run, p)),
             ("sigma_pl.png", lambda p: plot_sigma_pl(run, p)),
             ("mass_budget.png", lambda p: plot_mass_budget(run, p))]
    return jobs


def main(argv=None):
    """Command-line entry point; returns the exit status."""
    return style.run_cli(plot.run_cli_parser(__doc__), argv, _main)


def _main(args):
    """main() inside the style options of the command line."""
    run = plot.load_run_to_plot(args.run)
    if run is None:
        return 1
    outdir = args.outdir or plot.default_outdir(args.run)
    os.makedirs(outdir, exist_ok=True)
    status = 0
    for name, make in figures(run):
        name = style.file_name(name)
        path = os.path.join(outdir, name)
        try:
            make(path)
        except Skip as why:
            print(f"skipped {name}: {why}", file=sys.stderr)
            continue
        except Exception:
            print(f"FAILED {name}:\n{traceback.format_exc()}", file=sys.stderr)
            status = 1
            continue
        print(path)
    return status


if __name__ == "__main__":
    sys.exit(main())
