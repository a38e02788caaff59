"""Figures of several runs at once: profiles at one time, outcomes against time.

    fig = overlay_profiles([run_a, run_b], "sigma_d", t_yr=1e5, labels=["a", "b"])
    fig = overlay_series([run_a, run_b], "planetesimal_mass")
    fig.savefig("compare.pdf")

Runs are Run objects (load_run) or paths. Each function takes ax= and returns the Figure.
"""
import os

import numpy as np

from . import plot, plot_run, style
from .reader import as_run

RUN_COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
              "tab:pink", "tab:gray", "tab:olive", "tab:cyan")
# y label of a snapshot field [its unit in the file]
PROFILE_LABELS = {"sigma_d": r"$\Sigma_\mathrm{d}$", "sigma_g": r"$\Sigma_\mathrm{g}$",
                  "St": "Stokes number St", "a": "particle radius $a$",
                  "phi": r"filling factor $\phi$", "sigma_pl": r"$\Sigma_\mathrm{pl}$",
                  "dust_to_gas": r"$\Sigma_\mathrm{d}\,/\,\Sigma_\mathrm{g}$"}
# the time series overlay_series knows by name: (y label, function run -> (t, value))
SERIES = {
    "planetesimal_mass": (r"planetesimal mass [$M_\oplus$]", lambda r: r.planetesimal_mass()),
    "dust_mass": (r"dust on the grid [$M_\oplus$]", lambda r: r.series("m_dust")),
    "m_out_inner": (r"mass through $r_\mathrm{in}$ [$M_\oplus$]",
                    lambda r: r.series("m_out_inner")),
    "budget_error": (r"budget error [$M_\oplus$]", lambda r: r.series("error")),
}


def _runs(runs):
    """Run objects of runs (Run or path)."""
    return [as_run(r) for r in runs]


def _labels(runs, labels):
    """The legend labels: given, else each run's file name (without .h5)."""
    if labels is not None:
        if len(labels) != len(runs):
            raise ValueError(f"{len(labels)} labels for {len(runs)} runs")
        return list(labels)
    return [os.path.basename(r.path).removesuffix(".h5") for r in runs]


def _axes(ax, log_x=True, log_y=True):
    """(figure, axes, own) of a new figure or of `ax`, with log scales and a light grid."""
    own = ax is None
    fig = style.new_figure(6.4, 4.4) if own else ax.figure
    ax = fig.add_subplot() if own else ax
    if log_x:
        ax.set_xscale("log")
    if log_y:
        ax.set_yscale("log")
    ax.grid(True, which="major", color="0.88", lw=0.6)
    ax.set_axisbelow(True)
    return fig, ax, own


def _finish(fig, ax, own, title, out_path):
    ax.legend(fontsize="small", frameon=False)
    if own and title:
        ax.set_title(style.title(title), fontsize="large")
    if out_path is not None:
        style.savefig(fig, out_path)
    return fig


def overlay_profiles(runs, field="sigma_d", t_yr=None, ax=None, labels=None, gas=False,
                     out_path=None):
    """One line per run of snapshot field `field` (or "dust_to_gas") vs r [au] at the
    snapshot nearest t_yr (default: each run's last), in the unit of the file (the
    y label says it); gas=True adds each run's Sigma_g dashed. The legend gives each
    run's label and the time of the snapshot drawn. Returns the Figure."""
    runs = _runs(runs)
    fig, ax, own = _axes(ax)
    unit = ""
    for k, (run, label) in enumerate(zip(runs, _labels(runs, labels))):
        colour = RUN_COLORS[k % len(RUN_COLORS)]
        t_want = run.time[-1] if t_yr is None else t_yr
        if field == "dust_to_gas":
            t, sigma_d = run.at_time("sigma_d", t_want)
            _, sigma_g = run.at_time("sigma_g", t_want)
            values = np.divide(sigma_d, sigma_g, out=np.full(sigma_d.shape, np.nan),
                               where=sigma_g > 0)
        else:
            t, values = run.at_time(field, t_want)
            unit = run.unit(f"snapshots/{field}")
        r = run.r_c if len(values) == len(run.r_c) else run.r_f
        ax.plot(r, plot.masked_log(values), color=colour, lw=1.5,
                label=f"{label}, t = {plot.format_years(t)}")
        if gas:
            _, sigma_g = run.at_time("sigma_g", t_want)
            ax.plot(run.r_c, plot.masked_log(sigma_g), color=colour, lw=1.0, ls="--",
                    label=rf"{label}: $\Sigma_\mathrm{{g}}$")
    name = PROFILE_LABELS.get(field, field)
    ax.set_xlabel(r"$r$ [au]")
    ax.set_ylabel(f"{name} [{_unit_tex(unit)}]" if unit else name)
    when = "last snapshots" if t_yr is None else plot.format_years(t_yr)
    return _finish(fig, ax, own, f"{name} at {when}", out_path)


def overlay_series(runs, quantity="planetesimal_mass", ax=None, labels=None, monitor=None,
                   out_path=None):
    """One line per run of a time series vs t [yr]: "planetesimal_mass", "dust_mass",
    "m_out_inner", "budget_error" [M_earth], "pebble_flux" [M_earth Myr^-1] through
    `monitor` (a name or a monitor radius [au]: Run.pebble_flux), or any name
    Run.series accepts (its unit: Run.series_unit). Returns the Figure."""
    runs = _runs(runs)
    fig, ax, own = _axes(ax)
    ylabel, shown = None, []
    for k, (run, label) in enumerate(zip(runs, _labels(runs, labels))):
        if quantity == "pebble_flux":
            if monitor is None:
                raise ValueError("overlay_series(..., 'pebble_flux') needs monitor= (a "
                                 "monitor name or radius [au])")
            t, value = run.pebble_flux(monitor)
            ylabel = rf"pebble flux through {monitor} [$M_\oplus$ Myr$^{{-1}}$]"
        elif quantity in SERIES:
            ylabel, get = SERIES[quantity]
            t, value = get(run)
        else:
            t, value = run.series(quantity)
            unit = run.series_unit(quantity)
            ylabel = f"{quantity} [{_unit_tex(unit)}]" if unit else quantity
        positive = t > 0
        ax.plot(t[positive], plot.masked_log(value[positive]),
                color=RUN_COLORS[k % len(RUN_COLORS)], lw=1.5, label=label)
        shown.append(value[positive])
    # the top LINE_DECADES decades: the first, vanishingly small samples of a growing
    # quantity would squeeze the rest
    plot_run.set_decades_ylim(ax, np.concatenate(shown), plot_run.LINE_DECADES)
    ax.set_xlabel(r"$t$ [yr]")
    ax.set_ylabel(ylabel or quantity)
    return _finish(fig, ax, own, quantity.replace("_", " "), out_path)


def _unit_tex(unit):
    """'M_earth Myr^-1' -> mathtext."""
    unit = unit.replace("M_earth", r"$M_\oplus$")
    words = []
    for word in unit.split():
        base, _, power = word.partition("^")
        words.append(f"{base}$^{{{power}}}$" if power else base)
    return " ".join(words)
