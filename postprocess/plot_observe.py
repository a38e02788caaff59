"""Figures of a synthetic observation (the output of `panoptic observe`).

    python3 -m postprocess.plot_observe OBS.h5 [-o OUTDIR]

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
"""
import argparse
import os
import sys

import h5py
import numpy as np
from matplotlib import colormaps, colors
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Ellipse

COLORS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown"]
PROFILE_DECADES = 4     # y range of the profile panel below its maximum


def load(path):
    """The datasets and attributes of an observation file as a dict."""
    with h5py.File(path, "r") as f:
        d = {k: f.attrs[k] for k in f.attrs}
        for group in ("model", "image", "profile", "flux", "spectral_index"):
            for k, v in f[group].items():
                d[f"{group}/{k}"] = v[()]
        d["lambda_mm"] = f["wavelength_mm"][()]
        d["pixel_arcsec"] = f["image"].attrs["pixel_arcsec"]
    return d


def save(fig, path):
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=110)
    print(path)


def lam_label(lam):
    return f"{lam:g} mm"


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


def plot_images(d, outdir, title):
    """One figure per wavelength: model and convolved images, a square-root colour
    stretch (faint outer emission visible next to a bright centre), zoomed to the
    emission (field_of_view), beam ellipse in the corner."""
    x = d["image/x_arcsec"]
    ext = [x[0] - d["pixel_arcsec"] / 2, x[-1] + d["pixel_arcsec"] / 2] * 2
    paths = []
    for l, lam in enumerate(d["lambda_mm"]):
        fig = Figure(figsize=(10.5, 4.6))
        for ax_i, (key, unit, name) in enumerate(
                (("image/model", "Jy arcsec$^{-2}$", "model"),
                 ("image/convolved", "Jy beam$^{-1}$", "convolved with the beam"))):
            ax = fig.add_subplot(1, 2, ax_i + 1)
            img = d[key][l]
            vmax = np.nanmax(img) if np.nanmax(img) > 0 else 1.0
            im = ax.imshow(img, origin="lower", extent=ext, cmap=colormaps["inferno"],
                           norm=colors.PowerNorm(0.5, vmin=0.0, vmax=vmax),
                           interpolation="nearest")
            fov = field_of_view(d, l)
            ax.set_xlim(fov, -fov)   # east to the left
            ax.set_ylim(-fov, fov)
            ax.set_xlabel(r"$\Delta\alpha$ (east) [arcsec]")
            ax.set_ylabel(r"$\Delta\delta$ (north) [arcsec]")
            ax.set_title(f"{lam_label(lam)}: {name}", fontsize=10)
            fig.colorbar(im, ax=ax, label=unit + " (square-root stretch)", shrink=0.85)
            if ax_i == 1:
                bmaj, bmin = d["beam_bmaj_arcsec"], d["beam_bmin_arcsec"]
                # matplotlib's angle: counter-clockwise from +x of the data; with east
                # to the left, PA (north through east) is 90 deg + PA from +x (west)
                cx = fov - 1.0 * bmaj
                cy = -fov + 1.0 * bmaj
                ax.add_patch(Ellipse((cx, cy), bmin, bmaj, angle=-d["beam_pa_deg"],
                                     fc="none", ec="w", lw=1.2))
        fig.suptitle(title, fontsize=10)
        fig.tight_layout()
        p = os.path.join(outdir, f"image_{lam:g}mm.png")
        save(fig, p)
        paths.append(p)
    return paths


def plot_profiles(d, outdir, title):
    fig = Figure(figsize=(6.6, 4.6))
    ax = fig.add_subplot(1, 1, 1)
    r = d["profile/r_au"]
    ymax = 0.0
    area = d["beam_area_arcsec2"]
    for l, lam in enumerate(d["lambda_mm"]):
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
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    p = os.path.join(outdir, "profiles.png")
    save(fig, p)
    return p


def plot_spectral_index(d, outdir, title):
    pairs = d["spectral_index/pairs_mm"]
    if len(pairs) == 0:
        print("spectral_index.png: one wavelength only, no spectral index", file=sys.stderr)
        return None
    fig = Figure(figsize=(6.6, 4.6))
    ax = fig.add_subplot(1, 1, 1)
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
    ax.set_title(title + "\nsolid: convolved profiles; dashed: model", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    p = os.path.join(outdir, "spectral_index.png")
    save(fig, p)
    return p


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("obs", help="output of panoptic observe (HDF5)")
    ap.add_argument("-o", "--outdir", help="output directory (default OBS_plots/)")
    args = ap.parse_args(argv)
    d = load(args.obs)
    outdir = args.outdir or os.path.splitext(args.obs)[0] + "_plots"
    os.makedirs(outdir, exist_ok=True)
    title = (f"t = {d['time_yr']:.4g} yr, d = {d['distance_pc']:g} pc, "
             f"i = {d['incl_deg']:g}°, PA = {d['pa_deg']:g}°, beam "
             f"{d['beam_bmaj_arcsec']:g}\" x {d['beam_bmin_arcsec']:g}\"")
    plot_images(d, outdir, title)
    plot_profiles(d, outdir, title)
    plot_spectral_index(d, outdir, title)
    return 0


if __name__ == "__main__":
    sys.exit(main())
