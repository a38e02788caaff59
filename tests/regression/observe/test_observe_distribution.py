"""`panoptic observe` of a size-distribution run (src/observe/README.md), end to end on
params/tests/distribution_small.toml (12 cells, 50 bins) run to 1 000 yr, compact, with
the snow line and with porous bins:
 - the run is observed (exit 0, no longer refused): images finite, the image's flux equal
   to the annuli's and kept by the beam, the `opacity` attribute naming the distribution;
 - the opacity is the mass-weighted mean of the bins': with the optical solid of the
   run's monomer density (observe.outer_species = "ice", observe.water_ice_rho =
   material.ice_rho0), a compact bin is the particle `--a-cm a_k` (/grid/a_bins), so
   one observation per bin gives kappa_k, and Sum_k sigma_k kappa_k / Sigma_d over the
   snapshot's /snapshots/sigma is computed here;
 - /model/a (and, porous, rho_int) is the run's mass-dominating bin's, bit for bit, with
   the snow line too (silicate cells of their own monomer density)."""
import os

import h5py
import numpy as np

from common import Checks, parse_args, run, run_checked

SCENE = "params/tests/distribution_small.toml"
T_YR = "1000"
SETS = ["output.t_end_yr=1e3", "output.t_first_yr=10.0"]
# the optical solid of the compact bins themselves (the scene's material.ice_rho0)
SOLID = ["--set", "observe.outer_species=ice", "--set", "observe.water_ice_rho=1.67"]
WIDE_BEAM = ["--beam-arcsec", "3,3,0"]  # a small image: the opacities are what is read


def observe(exe, run_file, out, *extra):
    run_checked([exe, "observe", run_file, "-o", out, "--overwrite", "--time-yr", T_YR,
                 *extra])
    return h5py.File(out, "r")


def check_images(c, f, what):
    finite = all(np.all(np.isfinite(f[k][()])) for k in
                 ("image/model", "image/convolved", "model/kappa_abs", "model/tau",
                  "flux/model"))
    fm, fc, fa = f["flux/model"][()], f["flux/convolved"][()], f["flux/annuli"][()]
    c.check(finite and np.all(fm > 0), f"{what}: images, opacities, fluxes finite "
            f"({', '.join(f'{x:.4g}' for x in fm)} Jy)")
    c.check(np.all(np.abs(fm / fa - 1) < 1e-12) and np.all(np.abs(fc / fm - 1) < 1e-10),
            f"{what}: image flux = annuli's to {np.max(np.abs(fm / fa - 1)):.1e}, "
            f"kept by the beam to {np.max(np.abs(fc / fm - 1)):.1e}")
    opacity = f.attrs["opacity"]
    opacity = opacity.decode() if isinstance(opacity, bytes) else opacity
    c.check(opacity.startswith("of the size distribution"),
            f"{what}: the opacity attribute names the distribution ({opacity[:60]}...)")


def main():
    args = parse_args()
    exe, wd = args.exe, args.workdir
    c = Checks()

    compact = os.path.join(wd, "distribution.h5")
    run(exe, SCENE, compact, SETS)
    with h5py.File(compact) as g:
        row = int(np.argmin(np.abs(g["snapshots/time"][()] - float(T_YR))))
        a_bins, n = g["grid/a_bins"][()], g["grid/r_c"].shape[0]
        sigma = g["snapshots/sigma"][row].reshape(n, a_bins.size)
        sigma_d, a_run = g["snapshots/sigma_d"][row], g["snapshots/a"][row]

    lambdas = "0.87,1.3,3.0"
    with observe(exe, compact, os.path.join(wd, "distribution_obs.h5"), "--lambda-mm",
                 lambdas, "--incl-deg", "35", "--pa-deg", "60") as f:
        check_images(c, f, "compact")
        c.check(np.array_equal(f["model/a"][()], a_run),
                "/model/a is the run's mass-dominating bin (/snapshots/a), bit for bit")

    # kappa of every bin holding dust, each from its own single-particle observation
    with observe(exe, compact, os.path.join(wd, "mixture_obs.h5"), "--lambda-mm", lambdas,
                 *SOLID, *WIDE_BEAM) as f:
        kappa, tau = f["model/kappa_abs"][()], f["model/tau"][()]
    held = np.flatnonzero((sigma > 0).any(axis=0))
    kappa_bins = np.zeros((len(lambdas.split(",")), a_bins.size))
    for k in held:
        with observe(exe, compact, os.path.join(wd, "bin_obs.h5"), "--lambda-mm", lambdas,
                     "--a-cm", repr(float(a_bins[k])), *SOLID, *WIDE_BEAM) as f:
            kappa_bins[:, k] = f["model/kappa_abs"][:, 0]  # one species: every cell's
    weights = np.where(sigma > 0, sigma, 0.0)
    expected = kappa_bins @ weights.T / weights.sum(axis=1)
    err = np.max(np.abs(kappa / expected - 1))
    spread = np.max(kappa_bins[:, held], axis=1) / np.min(kappa_bins[:, held], axis=1)
    print(f"{held.size} bins hold dust; their kappa_abs spans a factor "
          f"{', '.join(f'{x:.3g}' for x in spread)} at {lambdas} mm")
    c.check(err < 1e-12 and np.all(spread > 2),
            f"kappa_abs = Sum_k sigma_k kappa_k / Sigma_d of {held.size} bins, each "
            f"observed alone, to {err:.1e} (1e-12 asserted)")
    tau_err = np.max(np.abs(tau / (kappa_bins @ weights.T * sigma_d / weights.sum(axis=1))
                            - 1))
    c.check(tau_err < 1e-12, f"tau = Sum_k sigma_k kappa_k to {tau_err:.1e}")

    # with the snow line: silicate cells inside it (their own monomers), icy outside
    snow = os.path.join(wd, "distribution_snowline.h5")
    run(exe, SCENE, snow, SETS + ["snowline.enabled=true"])
    with h5py.File(snow) as g:
        a_run = g["snapshots/a"][row]
    with observe(exe, snow, os.path.join(wd, "snowline_obs.h5"), "--lambda-mm",
                 lambdas, *WIDE_BEAM) as f:
        check_images(c, f, "snow line")
        inner = f["model/inner_species"][()]
        c.check(np.array_equal(f["model/a"][()], a_run) and 0 < inner.sum() < inner.size,
                f"snow line ({int(inner.sum())} silicate cells of {inner.size}): /model/a "
                f"is the run's mass-dominating bin's, bit for bit")

    porous = os.path.join(wd, "distribution_porous.h5")
    run(exe, SCENE, porous, SETS + ["porosity.enabled=true"])
    with h5py.File(porous) as g:
        phi_bins = g["snapshots/phi_bins"][row]
        a_run, rho_run = g["snapshots/a"][row], g["snapshots/rho_int"][row]
    with observe(exe, porous, os.path.join(wd, "porous_obs.h5"), "--lambda-mm", lambdas,
                 "--incl-deg", "35", "--pa-deg", "60") as f:
        check_images(c, f, "porous")
        c.check(np.array_equal(f["model/a"][()], a_run) and
                np.array_equal(f["model/rho_int"][()], rho_run),
                f"porous (phi_bins {phi_bins.min():.1e} .. {phi_bins.max():.2g}): /model/a "
                f"and rho_int are the run's mass-dominating bin's, bit for bit")
    c.finish()


if __name__ == "__main__":
    main()
