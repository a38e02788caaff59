"""Figures of a synthetic observation (the output of `panoptic observe`).

    panoptic-plot-observe OBS.h5 [-o OUTDIR] [--format png|pdf|svg] [--no-footer]
                          [--title T] [--size column|page|INCHES]
    (in the repository: python3 -m postprocess.plot_observe OBS.h5 ...)

writes into OUTDIR (default: OBS_plots/ next to OBS.h5) and prints the path of each:
    image_<lambda>mm.png   model image [Jy/arcsec^2] and beam-convolved image [Jy/beam],
                           east to the left, north up, beam ellipse in the corner;
                           square-root colour stretch, zoomed to the radius holding 99.5 %
                           of the flux (x 1.3, at least 3 beams)
    profiles.png           deprojected, azimuthally averaged profiles of the convolved
                           images [Jy/beam] vs radius [au], with the model intensity at
                           the cell centres times the beam area (dashed)
    spectral_index.png     spectral index of every wavelength pair vs radius: of the
                           convolved profiles (solid) and of the model (dashed)
The figures share the style of the run's (panoptic-plot): constrained layout, light grid,
the title above, a provenance footer. Every plot_* function takes an Observation
(load_observation) and `ax=`, and returns its Figure.
"""
import os
import sys

import numpy as np
from matplotlib import colormaps, colors
from matplotlib.patches import Ellipse

from . import style
from .observation import load_observation

COLORS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown"]
PROFILE_DECADES = 4     # y range of the profile panel below its maximum


def lam_label(lam):
    return f"{lam:g} mm"


def default_title(d):
    """Time, distance, inclination, position angle and beam of the observation."""
    return (f"t = {d['time_yr']:.4g} yr, d = {d['distance_pc']:g} pc, "
            f"i = {d['incl_deg']:g}°, PA = {d['pa_deg']:g}°, beam "
            f"{d['beam_bmaj_arcsec']:g}\" x {d['beam_bmin_arcsec']:g}\"")


def provenance(d):
    """Footer text: file name, code version and git commit."""
    sha = str(d.data.get("git_sha", ""))[:10]
    return f"{os.path.basename(d.path)}   panoptic {d.data.get('version', '?')} ({sha})"


def field_of_view(d, l):
    """Half-width [arcsec] of the view of wavelength l: the radius holding 99.5 % of the
    convolved image's flux, times 1.3, at least 3 beams and at most the image's."""
    x = d["image/x_arcsec"]
    img = np.clip(np.nan_to_num(d["image/convolved"][l]), 0.0, None)
    half = 0.5 * (x[-1] - x[0]) + 0.5 * d["pixel_arcsec"]
    if img.sum() <= 0:
        return half
    xx, yy = np.meshgrid(x, x)
    rr = np.hypot(xx, yy).ravel()
    order = np.argsort(rr)
    cum = np.cumsum(img.ravel()[order])
    r995 = rr[order][min(np.searchsorted(cum, 0.995 * cum[-1]), len(rr) - 1)]
    return float(min(half, max(1.3 * r995, 3.0 * d["beam_bmaj_arcsec"])))


def _axes(ax, width, height):
    """(figure, axes, own): a new figure and axes, or those of `ax`."""
    if ax is not None:
        return ax.figure, ax, False
    fig = style.new_figure(width, height)
    return fig, fig.add_subplot(), True


def _finish(fig, d, own, title, out_path):
    """Title, footer (a figure made here) and save; returns fig."""
    if own:
        fig.suptitle(style.title(title), fontsize="medium")
        style.footer(fig, provenance(d))
    if out_path is not None:
        style.savefig(fig, out_path)
    return fig


def plot_image(d, lambda_mm, kind="convolved", ax=None, out_path=None):
    """Image of wavelength lambda_mm [mm], kind "convolved" [Jy/beam] (beam ellipse in
    the corner) or "model" [Jy/arcsec^2]: square-root stretch (faint outer emission
    visible next to a bright centre), zoomed to the emission (field_of_view), east to
    the left. Returns the Figure."""
    l = d._index(lambda_mm)
    unit, name = {"model": ("Jy arcsec$^{-2}$", "model"),
                  "convolved": ("Jy beam$^{-1}$", "convolved with the beam")}[kind]
    fig, ax, own = _axes(ax, 5.4, 4.6)
    x = d["image/x_arcsec"]
    ext = [x[0] - d["pixel_arcsec"] / 2, x[-1] + d["pixel_arcsec"] / 2] * 2
    img = d[f"image/{kind}"][l]
    vmax = np.nanmax(img) if np.nanmax(img) > 0 else 1.0
    im = ax.imshow(img, origin="lower", extent=ext, cmap=colormaps["inferno"],
                   norm=colors.PowerNorm(0.5, vmin=0.0, vmax=vmax), interpolation="nearest")
    fov = field_of_view(d, l)
    ax.set_xlim(fov, -fov)   # east to the left
    ax.set_ylim(-fov, fov)
    ax.set_xlabel(r"$\Delta\alpha$ (east) [arcsec]")
    ax.set_ylabel(r"$\Delta\delta$ (north) [arcsec]")
    ax.set_title(f"{lam_label(d.wavelength_mm[l])}: {name}", fontsize="medium")
    fig.colorbar(im, ax=ax, label=unit + " (square-root stretch)", shrink=0.85)
    if kind == "convolved":
        bmaj, bmin = d["beam_bmaj_arcsec"], d["beam_bmin_arcsec"]
        # matplotlib's angle: counter-clockwise from +x of the data; with east to the
        # left, PA (north through east) is 90 deg + PA from +x (west)
        ax.add_patch(Ellipse((fov - bmaj, -fov + bmaj), bmin, bmaj, angle=-d["beam_pa_deg"],
                             fc="none", ec="w", lw=1.2))
    return _finish(fig, d, own, default_title(d), out_path)


def plot_images(d, outdir, title=None):
    """One figure per wavelength: the model and the convolved image side by side
    (plot_image); returns the paths written."""
    paths = []
    for lam in d.wavelength_mm:
        fig = style.new_figure(10.5, 4.6)
        ax_model, ax_conv = fig.subplots(1, 2)
        plot_image(d, lam, "model", ax=ax_model)
        plot_image(d, lam, "convolved", ax=ax_conv)
        p = os.path.join(outdir, style.file_name(f"image_{lam:g}mm.png"))
        _finish(fig, d, True, title or default_title(d), p)
        print(p)
        paths.append(p)
    return paths


def _grid(ax):
    """The light grid of the run's figures."""
    ax.grid(True, which="major", color="0.88", lw=0.6)
    ax.set_axisbelow(True)


def plot_profiles(d, out_path=None, ax=None, title=None):
    """Deprojected, azimuthally averaged profiles of the convolved images [Jy/beam] vs
    radius [au], with the model intensity times the beam area (dashed). Returns the
    Figure."""
    fig, ax, own = _axes(ax, 6.4, 4.6)
    _grid(ax)
    r = d["profile/r_au"]
    ymax = 0.0
    area = d["beam_area_arcsec2"]
    for l, lam in enumerate(d.wavelength_mm):
        c = COLORS[l % len(COLORS)]
        prof = d["profile/convolved"][l]
        ax.plot(r, prof, color=c, lw=1.6, label=f"{lam_label(lam)} (beam)")
        ax.plot(d["model/r_au"], d["model/intensity"][l] * area, color=c, lw=1.0, ls="--",
                label=f"{lam_label(lam)} model x beam area")
        ymax = max(ymax, np.nanmax(prof), np.nanmax(d["model/intensity"][l] * area))
    ax.set_yscale("log")
    if ymax > 0:
        ax.set_ylim(ymax * 10.0 ** -PROFILE_DECADES, ymax * 2.0)
    ax.set_xlim(0, r[-1])
    ax.set_xlabel("deprojected radius [au]")
    ax.set_ylabel(r"$I_\nu$ [Jy beam$^{-1}$]")
    ax.legend(fontsize="small", frameon=False)
    return _finish(fig, d, own, title or default_title(d), out_path)


def plot_spectral_index(d, out_path=None, ax=None, title=None):
    """Spectral index of every wavelength pair vs radius: of the convolved profiles
    (solid) and of the model (dashed). Returns the Figure, None with one wavelength."""
    pairs = d["spectral_index/pairs_mm"]
    if len(pairs) == 0:
        return None
    fig, ax, own = _axes(ax, 6.4, 4.6)
    _grid(ax)
    lo, hi = np.inf, -np.inf
    for p, (l1, l2) in enumerate(pairs):
        c = COLORS[p % len(COLORS)]
        a = d["spectral_index/profile"][p]
        am = d["spectral_index/model"][p]
        ax.plot(d["profile/r_au"], a, color=c, lw=1.6,
                label=f"{l1:g}-{l2:g} mm (beam); total {d['spectral_index/total'][p]:.2f}")
        ax.plot(d["model/r_au"], am, color=c, lw=1.0, ls="--")
        for v in (a, am):
            if np.isfinite(v).any():
                lo, hi = min(lo, np.nanmin(v)), max(hi, np.nanmax(v))
    ax.axhline(2.0, color="0.5", lw=0.8, ls=":")
    if np.isfinite(lo):
        ax.set_ylim(min(lo, 2.0) - 0.2, hi + 0.2)
    ax.set_xlim(0, d["profile/r_au"][-1])
    ax.set_xlabel("deprojected radius [au]")
    ax.set_ylabel(r"spectral index $\alpha$ ($I_\nu \propto \nu^\alpha$)")
    ax.plot([], [], color="0.3", lw=1.6, label="solid: convolved profiles")
    ax.plot([], [], color="0.3", lw=1.0, ls="--", label="dashed: model")
    ax.legend(fontsize="small", frameon=False)
    return _finish(fig, d, own, title or default_title(d), out_path)


def main(argv=None):
    """Command line: the figures of an observation into OUTDIR; returns the exit status."""
    parser = style.cli_parser(__doc__, "obs", "output of panoptic observe (HDF5)",
                              "output directory (default OBS_plots/)")
    return style.run_cli(parser, argv, _main)


def _main(args):
    """main() inside the style options of the command line."""
    d = load_observation(args.obs)
    outdir = args.outdir or os.path.splitext(args.obs)[0] + "_plots"
    os.makedirs(outdir, exist_ok=True)
    plot_images(d, outdir)
    p = os.path.join(outdir, style.file_name("profiles.png"))
    plot_profiles(d, p)
    print(p)
    p = os.path.join(outdir, style.file_name("spectral_index.png"))
    if plot_spectral_index(d, p) is None:
        print("spectral_index.png: one wavelength only, no spectral index", file=sys.stderr)
    else:
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
