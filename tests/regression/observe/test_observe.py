"""`panoptic observe` on constructed runs, against independent answers:
 - a narrow dust ring at 30 au: the deprojected, beam-convolved radial profile peaks at
   the ring radius (face-on and inclined); the model image puts the ring at r/d along the
   major axis and r cos(i)/d along the minor axis of the given PA; flux is conserved by
   the beam;
 - an optically thick disk at constant T: the model intensity is B_nu(T) (Planck law
   evaluated here) and the convolved image is B_nu(T) x beam area [Jy/beam];
 - a growth run: the snapshot nearest --time-yr is used and its sizes;
 - bad arguments: exit 2 with a message naming the problem, no file left behind."""
import glob
import os
import subprocess

import h5py
import numpy as np

from common import Checks, load_run, parse_args, run

H, C, K_B = 6.62607015e-27, 2.99792458e10, 1.3807e-16   # cgs; K_B as src/core/units.hpp
JY_ARCSEC2 = 1e-23 * (180 * 3600 / np.pi) ** 2        # erg/s/cm2/Hz/sr per Jy/arcsec^2
R_RING, D_PC = 30.0, 140.0


def observe(exe, run_file, out, *args, expect=0):
    cmd = [exe, "observe", run_file, "-o", out, "--overwrite", *args]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if expect is not None and p.returncode != expect:
        print(" ".join(cmd))
        print(p.stdout, p.stderr)
        raise SystemExit(f"panoptic observe exited with {p.returncode}, expected {expect}")
    return p


def planck_jy_arcsec2(lam_mm, T):
    nu = C / (lam_mm * 0.1)
    return 2 * H * nu**3 / C**2 / np.expm1(H * nu / (K_B * T)) / JY_ARCSEC2


def peak_radius(r, y):
    """Vertex of the parabola through the highest sample and its neighbours."""
    i = int(np.nanargmax(y))
    y0, y1, y2 = y[i - 1], y[i], y[i + 1]
    return r[i] + 0.5 * (r[1] - r[0]) * (y0 - y2) / (y0 - 2 * y1 + y2)


def ring_run(exe, workdir, name, sets):
    out = os.path.join(workdir, name + ".h5")
    run(exe, "params/tests/ring_diffusion.toml", out,
        ["output.times_yr=[10.0]", "output.t_end_yr=10.0", "output.t_first_yr=1.0",
         f"dust.ring_r_au={R_RING}", "grid.r_out_au=60.0", "grid.n_cells=400", *sets])
    return out


def main():
    args = parse_args()
    exe, wd = args.exe, args.workdir
    c = Checks()

    # 1 a narrow ring (Gaussian, sigma 1 au) at 30 au, 100 um grains
    ring = ring_run(exe, wd, "ring", ["dust.ring_width_au=1.0"])
    for incl, pa, beam in ((0.0, 0.0, "0.05,0.05,0"), (60.0, 30.0, "0.06,0.05,10")):
        obs = os.path.join(wd, f"ring_obs_{incl:g}.h5")
        observe(exe, ring, obs, "--time-yr", "10", "--lambda-mm", "0.87,1.3,3.0",
                "--incl-deg", str(incl), "--pa-deg", str(pa), "--beam-arcsec", beam,
                "--a-cm", "0.01")
        with h5py.File(obs) as f:
            r = f["profile/r_au"][()]
            for l, lam in enumerate(f["wavelength_mm"][()]):
                rp = peak_radius(r, f["profile/convolved"][l])
                print(f"  i = {incl:g}, {lam:g} mm: convolved profile peaks at {rp:.3f} au")
                # a ring convolved in 2-D with a Gaussian of sigma s peaks inward by about
                # s^2/(2R) (the 1/sqrt(r) of exp(-(r-R)^2/2s^2) I0(rR/s^2)): 0.15 au
                # face-on (s = 3 au), up to 0.6 au along the minor axis at i = 60 (the
                # deprojected beam is 2x longer); the bins are 1.4 au wide
                c.check(abs(rp - R_RING) < (0.4 if incl == 0 else 1.0),
                        f"i = {incl:g}, {lam:g} mm: ring radius from the profile {rp:.2f} au"
                        f" (ring at {R_RING} au)")
            fm, fc = f["flux/model"][()], f["flux/convolved"][()]
            c.check(np.all(np.abs(fc / fm - 1) < 1e-10),
                    f"i = {incl:g}: beam conserves the flux: max |Fc/Fm - 1| = "
                    f"{np.max(np.abs(fc / fm - 1)):.1e}")
            # the image's flux against the sum over the projected annuli, which no pixel
            # enters: the projection makes each annulus's flux exact (round-off)
            fa = f["flux/annuli"][()]
            c.check(np.all(np.abs(fm / fa - 1) < 1e-12),
                    f"i = {incl:g}: image flux = flux over the annuli to "
                    f"{np.max(np.abs(fm / fa - 1)):.1e} (1e-12 asserted)")
            c.check(f.attrs["snapshot_index"] == 1 and f.attrs["time_yr"] == 10.0,
                    "the snapshot at 10 yr is used")
            units = {"image/convolved": "Jy beam^-1", "image/model": "Jy arcsec^-2",
                     "image/x_arcsec": "arcsec", "profile/convolved": "Jy beam^-1",
                     "profile/model": "Jy arcsec^-2", "profile/r_au": "au",
                     "profile/r_arcsec": "arcsec", "model/kappa_abs": "cm^2 g^-1",
                     "model/intensity": "Jy arcsec^-2", "flux/model": "Jy"}
            got = {k: f[k].attrs["units"].decode() for k in units}
            c.check(got == units, f"units attributes: {sorted(set(got.values()))}")

    # 1b where the ring lands on the sky: PA = 90 (major axis east-west), i = 60
    obs = os.path.join(wd, "ring_obs_pa90.h5")
    observe(exe, ring, obs, "--time-yr", "10", "--lambda-mm", "1.3", "--incl-deg", "60",
            "--pa-deg", "90", "--beam-arcsec", "0.05,0.05,0", "--a-cm", "0.01")
    with h5py.File(obs) as f:
        img, x = f["image/model"][0], f["image/x_arcsec"][()]
        pix = f["image"].attrs["pixel_arcsec"]
        mid = len(x) // 2
        east = x[mid + np.argmax(img[mid, mid:])]     # along the row through the star
        north = x[mid + np.argmax(img[mid:, mid])]    # along the column
        c.check(abs(east - R_RING / D_PC) <= pix,
                f"major axis east-west: ring at x = {east:.4f}\" (r/d = {R_RING / D_PC:.4f}\")")
        c.check(abs(north - R_RING / D_PC * 0.5) <= pix,
                f"minor axis: ring at y = {north:.4f}\" (r cos i / d = "
                f"{R_RING / D_PC * 0.5:.4f}\")")

    # 1c a whole disk under beams from resolving it to far larger than it (1 - 300 au at
    # 140 pc: 2.1" in radius; pixels bmin / 5 from 0.01" to 20"): the image's flux is
    # the annuli's in every case (sampling pixel points alone lost 26 % of it with a 3"
    # beam and all of it with 100"), and under the 100" beam the disk is a point source:
    # the convolved image peaks at its flux in Jy/beam (a real disk of 2.1" under a beam
    # of sigma 42" would peak lower by ~(2.1/42)^2 / 2 ~ 1e-3; here the whole disk lies
    # in the centre pixel of 20", so measured 2e-16)
    disk = os.path.join(wd, "disk16.h5")
    run(exe, "params/fiducial.toml", disk,
        ["grid.n_cells=16", "output.t_end_yr=10.0", "output.t_first_yr=1.0"])
    fluxes = []
    for beam in ("0.05,0.05,0", "3,3,0", "100,100,0"):
        obs = os.path.join(wd, "disk16_obs.h5")
        observe(exe, disk, obs, "--time-yr", "10", "--lambda-mm", "1.3", "--beam-arcsec",
                beam)
        with h5py.File(obs) as f:
            fm, fa = f["flux/model"][0], f["flux/annuli"][0]
            fluxes.append(fm)
            c.check(abs(fm / fa - 1) < 1e-10,
                    f"disk, beam {beam}: image flux {fm:.6g} Jy = flux over the annuli "
                    f"{fa:.6g} Jy to {abs(fm / fa - 1):.1e} (1e-10 asserted)")
            if beam.startswith("100"):
                peak = f["image/convolved"][0].max()
                c.check(abs(peak / fa - 1) < 2e-3,
                        f"disk, beam {beam}: a point source, peak {peak:.6g} Jy/beam = flux "
                        f"{fa:.6g} Jy to {abs(peak / fa - 1):.1e} (2e-3 asserted)")
    c.check(max(fluxes) / min(fluxes) - 1 < 1e-10,
            f"disk: the flux does not depend on the beam ({min(fluxes):.6g} - "
            f"{max(fluxes):.6g} Jy)")

    # 2 optically thick at constant T = 30 K: B_nu(T), before and after the beam
    thick = ring_run(exe, wd, "thick", ["dust.ring_width_au=5.0", "dust.ring_sigma=1e6",
                                        "disk.q=0.0", "disk.T_1au=30.0"])
    obs = os.path.join(wd, "thick_obs.h5")
    observe(exe, thick, obs, "--time-yr", "10", "--lambda-mm", "0.87,3.0", "--a-cm", "0.01",
            "--beam-arcsec", "0.05,0.05,0")
    with h5py.File(obs) as f:
        r_c, tau = f["model/r_au"][()], f["model/tau"][()]
        for l, lam in enumerate(f["wavelength_mm"][()]):
            b = planck_jy_arcsec2(lam, 30.0)
            thick_cells = tau[l] > 50
            err = np.max(np.abs(f["model/intensity"][l][thick_cells] / b - 1))
            c.check(thick_cells.sum() > 10 and err < 1e-12,
                    f"{lam:g} mm: model I = B_nu(30 K) in the {thick_cells.sum()} thick "
                    f"cells to {err:.1e}")
            img, x = f["image/convolved"][l], f["image/x_arcsec"][()]
            mid = len(x) // 2
            j = mid + int(np.argmin(np.abs(x[mid:] - R_RING / D_PC)))
            val = img[mid, j] / (b * f.attrs["beam_area_arcsec2"])
            c.check(abs(val - 1) < 1e-10,
                    f"{lam:g} mm: convolved image at the ring = B_nu(T) x beam area to "
                    f"{abs(val - 1):.1e}")

    # 3 a growth run (porous particles, snow line): the nearest snapshot and its sizes
    grow = os.path.join(wd, "grow.h5")
    run(exe, "params/fiducial.toml", grow,
        ["output.times_yr=[100.0, 1000.0, 2000.0]", "output.t_end_yr=2000.0",
         "grid.n_cells=60"])
    obs = os.path.join(wd, "grow_obs.h5")
    p = observe(exe, grow, obs, "--time-yr", "1400", "--lambda-mm", "1.3,3.0",
                "--incl-deg", "40", "--pa-deg", "120")
    print(p.stdout)
    with h5py.File(grow) as g, h5py.File(obs) as f:
        c.check(f.attrs["snapshot_index"] == 2 and f.attrs["time_yr"] == 1000.0,
                f"--time-yr 1400 -> the snapshot at {f.attrs['time_yr']} yr (nearest: 1000)")
        # the mixing rule's filling factor is the volume fraction of the optical solid,
        # rho_int / rho_solid: silicate inside the snow line, the ice-silicate mix
        # outside, of density 1/(f_ice/rho_ice + (1 - f_ice)/rho_sil)
        cfg = load_run(grow).config  # the run's resolved scene, parsed by the reader
        rho_sil = cfg["material"]["sil_rho0"]
        f_ice, rho_ice = cfg["snowline"]["f_ice"], cfg["observe"]["water_ice_rho"]
        rho_solid = np.where(f["model/inner_species"][()] == 1, rho_sil,
                             1.0 / (f_ice / rho_ice + (1.0 - f_ice) / rho_sil))
        rho_int = g["snapshots/rho_int"][2]
        phi_expected = np.minimum(1.0, rho_int / rho_solid)
        c.check(np.array_equal(f["model/a"][()], g["snapshots/a"][2]) and
                np.array_equal(f["model/rho_int"][()], rho_int) and
                np.allclose(f["model/phi"][()], phi_expected, rtol=1e-14, atol=0) and
                np.allclose(g["snapshots/phi"][2], phi_expected, rtol=1e-2),
                "a and rho_int of that snapshot are used, phi = rho_int / rho of the "
                "optical solid (within 1 % of the run's phi for the default mix)")
        k = f["model/kappa_abs"][()]
        c.check(np.all(np.isfinite(k)) and np.all(k > 0), "kappa_abs finite and > 0")
        tau_ok = np.allclose(f["model/tau"][()], k * g["snapshots/sigma_d"][2], rtol=1e-14)
        c.check(tau_ok, "tau = Sigma_d kappa_abs")

    # 3b the figures
    p = subprocess.run(["/usr/bin/python3", "-m", "postprocess.plot_observe", obs, "-o",
                        os.path.join(wd, "grow_obs_plots")], capture_output=True, text=True)
    pngs = sorted(os.path.basename(x) for x in glob.glob(os.path.join(wd, "grow_obs_plots",
                                                                      "*.png")))
    c.check(p.returncode == 0 and pngs == ["image_1.3mm.png", "image_3mm.png",
                                           "profiles.png", "spectral_index.png"],
            f"postprocess.plot_observe: {pngs} {p.stderr.strip()}")

    # 3c centimetre wavelengths (VLA): the default tables reach 99.987 mm
    far = os.path.join(wd, "grow_obs_cm.h5")
    observe(exe, grow, far, "--time-yr", "1000", "--lambda-mm", "7,10,30,99", "--overwrite")
    with h5py.File(far) as f:
        c.check(np.allclose(f["wavelength_mm"][()], [7, 10, 30, 99]) and
                np.all(f["model/kappa_abs"][()] > 0),
                "observe at 7, 10, 30 and 99 mm runs")

    # 4 bad input: exit 2, the message names the problem, nothing written
    text = os.path.join(wd, "not_a_run.h5")
    with open(text, "w") as fh:
        fh.write("not hdf5\n")
    ring_obs = os.path.join(wd, "ring_obs_0.h5")   # HDF5, but not a run
    def at(time_yr="10", lambda_mm="1.3"):
        """The options of one observation of a sized run (the bad input is in them)."""
        return ["--time-yr", time_yr, "--lambda-mm", lambda_mm, "--a-cm", "0.01"]

    base = at()
    cases = [
        ("negative wavelength", ring, at(lambda_mm="1.3,-1"), "--lambda-mm"),
        ("wavelength not a number", ring, at(lambda_mm="1.3,abc"), "abc"),
        ("wavelength outside the tables", ring, at(lambda_mm="0.1"), "optical-constant"),
        # the silicate table ends at 99.987 mm (the ice table at 110)
        ("beyond the silicate table", ring, at(lambda_mm="100"), "silicate 0.29999 - 99.987"),
        ("time after the run", ring, at(time_yr="1e5"), "outside the run"),
        ("negative time", ring, at(time_yr="-5"), "outside the run"),
        ("not HDF5", text, base, "not an HDF5 file"),
        ("HDF5 but not a run", ring_obs, base, "not a panoptic run"),
        ("missing file", os.path.join(wd, "nope.h5"), base, "no such file"),
        ("no sizes and no --a-cm", ring, ["--time-yr", "10", "--lambda-mm", "1.3"],
         "--a-cm"),
        ("edge-on", ring, base + ["--incl-deg", "90"], "--incl-deg"),
        ("bmin > bmaj", ring, base + ["--beam-arcsec", "0.03,0.05,0"], "bmaj >= bmin"),
        ("beam with two numbers", ring, base + ["--beam-arcsec", "0.05,0.05"], "three"),
        ("negative distance", ring, base + ["--distance-pc", "-140"], "--distance-pc"),
        ("--set of a run key", ring, base + ["--set", "grid.n_cells=10"], "observe.*"),
        ("--set of a bad observe key", ring, base + ["--set", "observe.mix_rule=average"],
         "observe.mix_rule"),
        # the run's scene sets all three lists: the one the --set changed is named
        ("--set of a table of another length", ring,
         base + ["--set", "observe.ice_n=[1,2]"], "--set: observe.ice_n = [1.0, 2.0]"),
    ]
    # the output is the run file: --overwrite must not replace what observe reads
    before = open(ring, "rb").read()
    p = subprocess.run([exe, "observe", ring, "-o", ring, "--overwrite", *base],
                       capture_output=True, text=True)
    c.check(p.returncode == 2 and "the run file" in p.stderr and open(ring, "rb").read()
            == before, f"output is the run file: exit {p.returncode}, run file untouched")
    # a position angle of many turns, and nearly edge-on: a radius beyond an int crashed
    # the radial profile (segfault); nearly edge-on the pixels missed the disk (flux 0 at
    # PA 30), so such an inclination is refused, naming the option
    for extra, code in ((["--pa-deg", "1e308"], 0), (["--incl-deg", "89.999999"], 2),
                        (["--incl-deg", "89.999999", "--pa-deg", "30"], 2)):
        out = os.path.join(wd, "extreme_obs.h5")
        p = subprocess.run([exe, "observe", ring, "-o", out, "--overwrite", *base, *extra],
                           capture_output=True, text=True)
        c.check(p.returncode == code and (code == 0 or "--incl-deg" in p.stderr),
                f"{' '.join(extra)}: exit {p.returncode} (expected {code})")
    for label, run_file, extra, needle in cases:
        out = os.path.join(wd, "bad_obs.h5")
        p = subprocess.run([exe, "observe", run_file, "-o", out, *extra],
                           capture_output=True, text=True)
        msg = (p.stderr + p.stdout).strip().splitlines()
        ok = (p.returncode == 2 and needle in p.stderr and not os.path.exists(out)
              and not glob.glob(out + "*"))
        c.check(ok, f"{label}: exit {p.returncode}: {msg[-1] if msg else ''}")
    c.finish()


if __name__ == "__main__":
    main()
