"""DustPy-style panel of a size-distribution run (model.kind = "distribution").

    panoptic-plot-distribution RUN.h5 [-o OUTDIR] [--time-yr T] [--radii-au R1,R2,...]
                               [--format png|pdf|svg] [--no-footer] [--title T]
                               [--size column|page|INCHES]
    (in the repository: python3 -m postprocess.plot_distribution RUN.h5 ...)

writes OUTDIR/distribution.png (default OUTDIR: RUN_plots/ next to RUN.h5) and prints
its path: at the snapshot nearest --time-yr (default the last),
    top left    sigma(r, a) [g cm^-2] per mass bin (the bins are log-spaced, so per log a)
                on r [au] and a [cm], with the mass-dominating size (/snapshots/a), and
                the fragmentation and drift limits of Birnstiel et al. 2012 (eqs. 8 and
                18) when the scene sets v_frag and the disk has eta, at the internal
                density of the mass-dominating bin (porous runs: of the aggregates)
    top right   the distribution sigma(a) at the chosen radii (default 1, 3, 10, 30 au
                within the grid)
    bottom left Sigma_d(r) and Sigma_g(r)
    bottom right St of the mass-dominating bin, St_rep(r)
panel(run, t_yr, radii_au) returns the Figure.
"""
import os
import sys

import numpy as np
from matplotlib import colors

from . import plot, style
from .reader import load_run

F_FRAG, F_DRIFT = 0.37, 0.55   # Birnstiel, Klahr & Ercolano 2012, calibrated factors
DECADES = 10                   # colour range of the map below its maximum


def size_limits(run, t_yr):
    """(a_frag, a_drift) [cm] per cell at the snapshot nearest t_yr, Birnstiel et al.
    2012 eq. 8: a_frag = f_f 2 Sigma_g v_f^2 / (3 pi rho_s alpha c_s^2), and eq. 18 with
    |dlnP/dlnr| = 2 eta v_K^2 / c_s^2: a_drift = f_d Sigma_d / (pi rho_s eta); None for
    a limit whose inputs the file lacks. Both are Epstein Stokes numbers written as
    radii, a = St 2 Sigma_g / (pi rho_s): rho_s is the internal density of each cell's
    mass-dominating bin (/snapshots/rho_int), so that in a porous run (aggregates of
    rho_int ~ 1e-4 g cm^-3, 1e4 times the radius of a compact grain of the same St) the
    limits fall where its aggregates are, else the scene's ice_rho0."""
    cfg = run.config
    v_frag = cfg.get("fragmentation", {}).get("v_frag_ice_m_s")
    if "rho_int" in run.snapshots:
        rho_int = run.at_time("rho_int", t_yr)[1]
        rho_s = np.where(rho_int > 0, rho_int, np.nan)  # a cell without dust: no line
    else:
        rho_s = cfg.get("material", {}).get("ice_rho0")
    if rho_s is None:
        return None, None
    _, sigma_g = run.at_time("sigma_g", t_yr)
    _, sigma_d = run.at_time("sigma_d", t_yr)
    a_frag = a_drift = None
    if v_frag is not None and cfg.get("fragmentation", {}).get("enabled", True) \
            and "c_s" in run.disk and "alpha" in run.disk:
        a_frag = (F_FRAG * 2.0 * sigma_g * (100.0 * v_frag) ** 2
                  / (3.0 * np.pi * rho_s * run.disk["alpha"] * run.disk["c_s"] ** 2))
    if "eta" in run.disk:
        with np.errstate(divide="ignore"):
            a_drift = F_DRIFT * sigma_d / (np.pi * rho_s * np.abs(run.disk["eta"]))
    return a_frag, a_drift


def default_radii(run):
    """1, 3, 10, 30 au, those inside the grid."""
    return [r for r in (1.0, 3.0, 10.0, 30.0) if run.r_f[0] <= r <= run.r_f[-1]]


def panel(run, t_yr=None, radii_au=None, out_path=None):
    """The four-panel figure (module doc) at the snapshot nearest t_yr (default the
    last); returns the Figure."""
    t_yr = float(run.time[-1]) if t_yr is None else t_yr
    t, sigma = run.size_distribution(t_yr)
    a_bins = run.grid["a_bins"]
    radii_au = default_radii(run) if radii_au is None else radii_au
    fig = style.new_figure(10.0, 7.0)
    (ax_map, ax_dist), (ax_sig, ax_st) = fig.subplots(2, 2)

    # the map: cell and bin edges at the geometric means (log grids)
    a_edges = np.concatenate([[a_bins[0] ** 1.5 / a_bins[1] ** 0.5],
                              np.sqrt(a_bins[1:] * a_bins[:-1]),
                              [a_bins[-1] ** 1.5 / a_bins[-2] ** 0.5]])
    top = sigma.max() if sigma.max() > 0 else 1.0
    shown = np.ma.masked_less_equal(sigma.T, top * 10.0 ** -DECADES)
    mesh = ax_map.pcolormesh(run.r_f, a_edges, shown, shading="flat",
                             norm=colors.LogNorm(top * 10.0 ** -DECADES, top),
                             cmap="magma")
    fig.colorbar(mesh, ax=ax_map, label=r"$\sigma$ per mass bin [g cm$^{-2}$]")
    _, a_rep = run.at_time("a", t)
    ax_map.plot(run.r_c, a_rep, color="w", lw=1.2, label="mass-dominating")
    a_frag, a_drift = size_limits(run, t)
    if a_frag is not None:
        ax_map.plot(run.r_c, a_frag, color="tab:cyan", ls="--", lw=1, label="fragmentation")
    if a_drift is not None:
        ax_map.plot(run.r_c, a_drift, color="tab:green", ls=":", lw=1.2, label="drift")
    ax_map.set(xscale="log", yscale="log", xlabel="r [au]", ylabel="a [cm]",
               ylim=(a_edges[0], a_edges[-1]))
    ax_map.legend(fontsize="x-small", loc="upper right")

    for r in radii_au:
        i = int(np.argmin(np.abs(np.log(run.r_c / r))))
        ax_dist.loglog(a_bins, np.where(sigma[i] > 0, sigma[i], np.nan),
                       label=f"{run.r_c[i]:.3g} au")
    ax_dist.set(xlabel="a [cm]", ylabel=r"$\sigma$ per mass bin [g cm$^{-2}$]",
                ylim=(top * 10.0 ** -DECADES, 2 * top))
    ax_dist.legend(fontsize="x-small")

    _, sigma_d = run.at_time("sigma_d", t)
    _, sigma_g = run.at_time("sigma_g", t)
    ax_sig.loglog(run.r_c, np.where(sigma_g > 0, sigma_g, np.nan), label=r"$\Sigma_g$")
    ax_sig.loglog(run.r_c, np.where(sigma_d > 0, sigma_d, np.nan), label=r"$\Sigma_d$")
    ax_sig.set(xlabel="r [au]", ylabel=r"$\Sigma$ [g cm$^{-2}$]")
    ax_sig.legend(fontsize="x-small")

    _, st = run.at_time("St", t)
    ax_st.loglog(run.r_c, np.where(st > 0, st, np.nan))
    ax_st.set(xlabel="r [au]", ylabel=r"St$_{\rm rep}$ (mass-dominating bin)")
    for ax in (ax_map, ax_dist, ax_sig, ax_st):
        ax.grid(alpha=0.3)
    fig.suptitle(style.title(f"{run.scene or 'run'}: size distribution at {t:.4g} yr"),
                 fontsize="medium")
    style.footer(fig, plot._provenance(run))
    if out_path is not None:
        style.savefig(fig, out_path)
    return fig


def main(argv=None):
    """Command line: the panel of a run into OUTDIR; returns the exit status."""
    parser = style.cli_parser(__doc__, "run", "output of a size-distribution run (HDF5)",
                              "output directory (default RUN_plots/)")
    parser.add_argument("--time-yr", type=float, help="time [yr] (default the last snapshot)")
    parser.add_argument("--radii-au", help="radii [au] of the sigma(a) panel, comma-separated")
    return style.run_cli(parser, argv, _main)


def _main(args):
    """main() inside the style options of the command line."""
    run = load_run(args.run)
    if not run.has_distribution:
        print(f"{args.run}: not a size-distribution run (no /snapshots/sigma)",
              file=sys.stderr)
        return 1
    radii = [float(x) for x in args.radii_au.split(",")] if args.radii_au else None
    outdir = args.outdir or os.path.splitext(args.run)[0] + "_plots"
    os.makedirs(outdir, exist_ok=True)
    p = os.path.join(outdir, style.file_name("distribution.png"))
    panel(run, args.time_yr, radii, p)
    print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
