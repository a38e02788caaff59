"""Diagnostic figures of one run: dust surface density and dust-to-gas ratio vs radius.

    panoptic-plot-profiles RUN.h5 [-o OUTDIR] [--times-yr 1e3,1e4,...] [--format pdf]
                           [--no-footer] [--title T] [--size column]
    (in the repository: python3 -m postprocess.plot RUN.h5 ...)

writes OUTDIR/sigma_d.png and OUTDIR/dust_to_gas.png (default OUTDIR: RUN_plots/ next
to RUN.h5) and prints the paths. One curve per snapshot, coloured by log time; by
default up to 12 snapshots spread evenly in log time, always the first and the last.
"""
import argparse
import os
import sys

import numpy as np
from matplotlib import colormaps, colors, ticker
from matplotlib.cm import ScalarMappable

from . import style
from .reader import load_run

MAX_CURVES = 12
DECADES_SHOWN = 8   # y axis spans at most this many decades below the largest value
# viridis without its palest yellow, which is hard to see on white
TIME_CMAP = colors.ListedColormap(colormaps["viridis"](np.linspace(0.0, 0.9, 256)))
GAS_STYLE = {"color": "0.45", "ls": "--", "lw": 1.4}
SNOW_STYLE = {"color": "tab:blue", "ls": ":", "lw": 1.3}


def select_snapshots(time, n_max=MAX_CURVES):
    """Indices of up to ~n_max snapshots spread evenly in log time [yr].

    Always includes the first and last snapshot; a snapshot at t <= 0 can only
    enter as the first one.
    """
    nt = len(time)
    if nt <= n_max:
        return list(range(nt))
    positive = np.flatnonzero(time > 0)
    chosen = {0, nt - 1}
    if len(positive) > 1:
        log_t = np.log(time[positive])
        for target in np.linspace(log_t[0], log_t[-1], n_max - (time[0] <= 0)):
            chosen.add(int(positive[np.argmin(np.abs(log_t - target))]))
    return sorted(chosen)


def nearest_snapshots(time, times_yr):
    """Sorted distinct indices of the snapshots nearest each requested time [yr]."""
    return sorted({int(np.argmin(np.abs(time - t))) for t in times_yr})


def format_years(t_yr):
    """Time [yr] as a short label: "500 yr", "3162 yr", "$2.5\\times10^{5}$ yr"."""
    if t_yr == 0 or (1e-2 <= abs(t_yr) < 1e4 and "e" not in f"{t_yr:.4g}"):
        return f"{t_yr:.4g} yr"     # 4 digits: 3162 yr, not 3.16e+03 yr
    mantissa, exponent = f"{t_yr:.2e}".split("e")
    mantissa = f"{float(mantissa):g}"
    prefix = "" if mantissa == "1" else rf"{mantissa}\times"
    return rf"${prefix}10^{{{int(exponent)}}}$ yr"


def masked_log(values):
    """Copy of values with entries <= 0 (and non-finite) set to NaN for log axes."""
    values = np.asarray(values, dtype=float)
    return np.where(np.isfinite(values) & (values > 0), values, np.nan)


def time_norm(times):
    """LogNorm spanning the positive times [yr] (a decade if only one), None if none."""
    positive = times[times > 0]
    if positive.size == 0:
        return None
    vmin, vmax = positive.min(), positive.max()
    return colors.LogNorm(vmin=vmin if vmin < vmax else vmax / 10.0, vmax=vmax)


def new_figure(ax=None):
    """Empty Agg-backed figure with one axes, log-log; or the figure of `ax`, made
    log-log."""
    if ax is None:
        fig = style.new_figure(6.4, 4.4)
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, which="major", color="0.88", lw=0.6)
    ax.grid(True, which="minor", color="0.95", lw=0.4)
    ax.set_axisbelow(True)
    return fig, ax


def plot_profiles(ax, run, profiles, indices):
    """One line per snapshot index, coloured by log time; t <= 0 drawn in black.

    profiles: (nt, N) array at the cell centres run.r_c [au]. Returns the time norm
    (None when every plotted time is <= 0).
    """
    norm = time_norm(run.time[indices])
    for i in indices:
        t = run.time[i]
        style = ({"color": "k", "lw": 1.3, "zorder": 3, "label": f"t = {format_years(t)}"}
                 if t <= 0 else {"color": TIME_CMAP(norm(t)), "lw": 1.2})
        ax.plot(run.r_c, masked_log(profiles[i]), **style)
    return norm


def plot_gas(ax, run, indices):
    """Sigma_g [g cm^-2] at the last plotted snapshot, and at the first if it differs."""
    first, last = indices[0], indices[-1]
    sigma_g = run.snapshots["sigma_g"]
    if np.allclose(sigma_g[first], sigma_g[last], rtol=1e-6, atol=0.0):
        ax.plot(run.r_c, masked_log(sigma_g[last]), label=r"$\Sigma_\mathrm{g}$", **GAS_STYLE)
        return
    for i, alpha in ((first, 0.45), (last, 1.0)):
        ax.plot(run.r_c, masked_log(sigma_g[i]), alpha=alpha,
                label=rf"$\Sigma_\mathrm{{g}}$, t = {format_years(run.time[i])}", **GAS_STYLE)


def mark_snow_line(ax, run):
    """Vertical dotted line at the snow line when it is finite and on the grid."""
    r_snow = run.r_snow_au
    if np.isfinite(r_snow) and run.r_f[0] <= r_snow <= run.r_f[-1]:
        ax.axvline(r_snow, label=f"snow line ({r_snow:.3g} au)", **SNOW_STYLE)


def set_log_ylim(ax, arrays):
    """y range of the positive finite values in arrays, 2 to DECADES_SHOWN decades wide."""
    values = np.concatenate([masked_log(a).ravel() for a in arrays])
    values = values[np.isfinite(values)]
    if values.size == 0:
        ax.text(0.5, 0.5, "no positive values", transform=ax.transAxes, ha="center",
                va="center", color="0.4")
    else:
        top = values.max()
        bottom = max(values.min(), top * 10.0 ** -DECADES_SHOWN)
        centre = np.sqrt(top * bottom)
        half_span = max(np.sqrt(top / bottom), 10.0)
        ax.set_ylim(centre / half_span / 2.0, centre * half_span * 2.0)


def add_time_colorbar(fig, ax, norm, times):
    """Colour bar of log time [yr], with a tick mark at each plotted time > 0."""
    colorbar = fig.colorbar(ScalarMappable(norm=norm, cmap=TIME_CMAP), ax=ax, pad=0.02)
    colorbar.set_label(r"$t$ [yr]")
    colorbar.ax.hlines(times[times > 0], 0.0, 0.3, colors="w", lw=0.9)


def label_minor_log_ticks(axis, lo, hi):
    """Label the minor ticks 2, 3 and 5 x 10^n of a log axis spanning less than two
    decades (lo, hi > 0), where the decade labels alone are too few."""
    if hi / lo < 100.0:
        axis.set_minor_formatter(ticker.FuncFormatter(
            lambda x, _: f"{x:g}" if round(x / 10.0 ** np.floor(np.log10(x) + 1e-9), 6)
            in (2.0, 3.0, 5.0) else ""))
        axis.set_major_formatter(ticker.FuncFormatter(lambda x, _: f"{x:g}"))


def finish(fig, ax, run, indices, norm, ylabel, out_path, own=True):
    """Labels, time colour bar, legend, title and provenance (own: the figure was made
    here, not given through ax=); save to out_path. The title gives t_end, or for an
    unfinished run (killed, stopped or failed) its last snapshot."""
    ax.set_xlim(run.r_f[0], run.r_f[-1])
    label_minor_log_ticks(ax.xaxis, run.r_f[0], run.r_f[-1])  # a grid of < 2 decades
    ax.set_xlabel(r"$r$ [au]")
    ax.set_ylabel(ylabel)
    if norm is not None:
        add_time_colorbar(fig, ax, norm, run.time[indices])
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize=8, frameon=False)
    last = format_years(run.time[-1])
    ax.set_title(style.title(f"{run.scene or 'run'}: " + (
        f"$t_\\mathrm{{end}}$ = {last}" if run.finished
        else f"unfinished, last snapshot {last}")), fontsize="large")
    if own:
        style.footer(fig, _provenance(run))
    if out_path is not None:  # None: only the Figure, returned (a notebook)
        style.savefig(fig, out_path)
    return fig


def _provenance(run):
    """Footer text: file name, code version and git commit."""
    sha = run.attrs.get("git_sha", "")[:10]
    return f"{os.path.basename(run.path)}   panoptic {run.attrs.get('version', '?')} ({sha})"


def plot_sigma_d(run, indices=None, out_path=None, ax=None):
    """Figure of Sigma_d(r) [g cm^-2] at the snapshots `indices` (default:
    select_snapshots), gas and snow line; into `ax` if given. Returns the Figure."""
    indices = select_snapshots(run.time) if indices is None else indices
    fig, ax, own = (*new_figure(ax), ax is None)
    plot_gas(ax, run, indices)
    norm = plot_profiles(ax, run, run.snapshots["sigma_d"], indices)
    mark_snow_line(ax, run)
    set_log_ylim(ax, [run.snapshots[name][indices] for name in ("sigma_d", "sigma_g")])
    return finish(fig, ax, run, indices, norm, r"$\Sigma_\mathrm{d}$ [g cm$^{-2}$]", out_path,
                  own)


def plot_dust_to_gas(run, indices=None, out_path=None, ax=None):
    """Figure of Sigma_d / Sigma_g(r) [] at the snapshots `indices` (default:
    select_snapshots), and snow line; into `ax` if given. Returns the Figure."""
    indices = select_snapshots(run.time) if indices is None else indices
    sigma_d, sigma_g = run.snapshots["sigma_d"], run.snapshots["sigma_g"]
    ratio = np.divide(sigma_d, sigma_g, out=np.full(sigma_d.shape, np.nan), where=sigma_g > 0)
    fig, ax, own = (*new_figure(ax), ax is None)
    norm = plot_profiles(ax, run, ratio, indices)
    mark_snow_line(ax, run)
    set_log_ylim(ax, [ratio[indices]])
    return finish(fig, ax, run, indices, norm, r"$\Sigma_\mathrm{d}\,/\,\Sigma_\mathrm{g}$",
                  out_path, own)


def default_outdir(run_path):
    """RUN.h5 -> RUN_plots (next to the run file)."""
    return run_path.removesuffix(".h5") + "_plots"


def parse_times(text):
    """'1e3,1e4' -> [1000.0, 10000.0] (argparse type)."""
    try:
        return [float(t) for t in text.split(",") if t.strip()]
    except ValueError as err:
        raise argparse.ArgumentTypeError(f"expected comma-separated times in yr: {err}")


def main(argv=None):
    """Command-line entry point; returns the exit status."""
    parser = run_cli_parser(__doc__)
    parser.add_argument("--times-yr", type=parse_times,
                        help="comma-separated times [yr]; the nearest snapshots are plotted")
    return style.run_cli(parser, argv, _main)


def run_cli_parser(doc):
    """The parser of a command that plots one run: RUN and -o/--outdir."""
    return style.cli_parser(doc, "run", "run file (HDF5) written by panoptic",
                            "output directory (default: RUN_plots/)")


def load_run_to_plot(path):
    """The run at `path`, or None (said on stderr) where it holds no snapshot."""
    run = load_run(path)
    if run.n_snapshots == 0:
        print(f"{path}: no snapshots to plot", file=sys.stderr)
        return None
    return run


def _main(args):
    """main() inside the style options of the command line."""
    run = load_run_to_plot(args.run)
    if run is None:
        return 1
    indices = (nearest_snapshots(run.time, args.times_yr) if args.times_yr
               else select_snapshots(run.time))
    outdir = args.outdir or default_outdir(args.run)
    os.makedirs(outdir, exist_ok=True)
    for name, make in (("sigma_d.png", plot_sigma_d), ("dust_to_gas.png", plot_dust_to_gas)):
        path = os.path.join(outdir, style.file_name(name))
        make(run, indices, path)
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
