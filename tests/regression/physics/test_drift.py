"""Radial drift (spec §6.1, §6.3) where the drift speed is uniform (see params/tests/drift.toml):
0. the drift speed on every face against the closed form -2 St eta v_K / (1 + St^2)
   (postprocess.analytic.drift_velocity), with eta v_K of the power-law disk worked out
   here from the scene's p, q, T_1au, mu and M_star with the constants of spec §1.1;
1. steady drift flux: Sigma_d = Z Sigma_g ∝ 1/r stays steady inside the region the closed
   outer edge has not yet reached, and the mass flow through r_in equals 2 pi r Sigma v_r
   of cell 0 (the upwind flux of the steady state: exact on the log grid, to the
   solver's tolerance on the stretched one and with van Leer);
2. a drifting ring (diffusion off): its centre of mass moves at v_r, with an error that
   falls at first order with the cell size;
3. the same with transport.advection = "van_leer" (second-order limited reconstruction):
   the steady flux stays exact, mass is conserved to round-off, and the errors of the
   centre-of-mass speed and of the L1 profile against the exactly translated ring fall at
   second order in this smooth problem."""
import numpy as np

from common import Checks, load_run, parse_args, run
from postprocess.analytic import drift_velocity

AU = 1.496e13
YR = 3.156e7


# The constants of spec §1.1, copied from the spec (not read from src/core/units.hpp), so that
# the face velocity is checked to round-off (CODATA 2018 / IAU 2015 values differ from
# them by up to 1.3e-4 in eta v_K)
K_B = 1.3807e-16        # [erg/K]
M_H = 1.6735e-24        # [g] hydrogen atom
GM_SUN = 6.674e-8 * 1.989e33  # [cm^3 s^-2]
AU_EXACT = 1.496e13     # [cm]


def eta_vk_powerlaw(r_au, cfg):
    """eta v_K [cm/s] of the power-law disk: P = rho c_s^2 with Sigma ∝ r^-p, T ∝ r^-q,
    H = c_s/Omega ∝ r^((3-q)/2), so dlnP/dlnr = -(p + 3/2 + q/2) and (spec §1.4)
    eta v_K = -(1/2) (c_s/v_K)^2 dlnP/dlnr v_K = (1/2) c_s^2/v_K (p + 3/2 + q/2)."""
    d, s = cfg["disk"], cfg["star"]
    p, q = d["p"], d["q"]
    temp = d["T_1au"] * s["luminosity_lsun"] ** 0.25 * r_au ** -q
    assert np.all(temp > d["T_floor"]), "the T floor would break the power law"
    cs2 = K_B * temp / (d["mu"] * M_H)
    vk = np.sqrt(GM_SUN * s["mass_msun"] / (r_au * AU_EXACT))
    return 0.5 * cs2 / vk * (p + 1.5 + 0.5 * q)


def steady_deviation(r, r_max):
    """Largest |Sigma_d(t_end)/Sigma_d(0) - 1| over the cells inside r_max [au]."""
    inside = r.r_c < r_max
    sig0, sig1 = r.snapshots["sigma_d"][0], r.snapshots["sigma_d"][-1]
    return np.max(np.abs(sig1[inside] / sig0[inside] - 1))


def inflow(r, vr):
    """Mass flow through r_in at t_end and its steady value 2 pi r Sigma_d |v_r| (the
    same at every r for Sigma_d ∝ 1/r: taken at cell 0) [g/s]."""
    exact = 2 * np.pi * (r.r_c[0] * AU) * r.snapshots["sigma_d"][0][0] * abs(vr)
    return -r.snapshots["mdot_d"][-1][0], exact


def main():
    args = parse_args()
    c = Checks()

    # 1. steady flux
    out = f"{args.workdir}/steady.h5"
    run(args.exe, "params/tests/drift.toml", out, ["output.t_end_yr=2e4"])
    r = load_run(out)
    v = r.snapshots["v_r"][0][:-1]  # faces 0..N-1 (the outer face carries no flux)
    c.check(np.ptp(v) < 1e-10 * abs(v.mean()), f"uniform drift speed v_r = {v.mean() / 100:.3f} m/s")
    # 0. its value: -2 St eta v_K / (1 + St^2) on every face
    v_exact = drift_velocity(r.config["transport"]["St"], eta_vk_powerlaw(r.r_f[:-1], r.config), 1.0)
    dv = np.max(np.abs(v / v_exact - 1))
    print(f"drift speed {v.mean() / 100:.5f} m/s, closed form {v_exact.mean() / 100:.5f} m/s, largest rel. diff {dv:.1e}")
    c.check(dv < 1e-12, f"v_r on every face equals -2 St eta v_K/(1 + St^2) to {dv:.1e} (< 1e-12)")
    vr = v.mean()
    t_end = r.time[-1] * YR
    # The closed outer edge sends a rarefaction inward at |v_r|; first-order upwind smears
    # its front over many cells (a Poisson tail), so test steadiness inside 40% of the
    # front radius.
    front = r.r_f[-1] * AU - abs(vr) * t_end
    reach = 0.4 * front / AU
    dev = steady_deviation(r, reach)
    c.check(dev < 1e-6, f"Sigma_d steady to {dev:.1e} inside r < {reach:.0f} au after {r.time[-1]:.0f} yr")
    mdot_in, exact = inflow(r, vr)
    rel = abs(mdot_in / exact - 1)
    print(f"mass flow through r_in {mdot_in:.6e} g/s, analytic {exact:.6e} g/s, rel. diff {rel:.2e}")
    c.check(rel < 1e-12, "pebble flux through r_in equals 2 pi r Sigma v (steady state exact)")
    budget = (r.snapshots["m_dust"] + r.snapshots["m_out_inner"]) / r.snapshots["m_dust"][0] - 1
    c.check(np.max(np.abs(budget)) < 1e-12, f"budget closes: max |error| {np.max(np.abs(budget)):.1e}")

    # the same steady state on a stretched grid (the upwinded r Sigma is exact for any
    # spacing of the cells). Its outer cells are 2.3x wider than the log grid's, so the
    # rarefaction tail reaches further in (|dSigma/Sigma| grows smoothly from 1e-11 at
    # r_in to 5e-5 at 24 au): tested inside 10 au, to 1e-8.
    out = f"{args.workdir}/steady_s0.5.h5"
    run(args.exe, "params/tests/drift.toml", out, ["output.t_end_yr=2e4", "grid.stretch=0.5"])
    r = load_run(out)
    dev = steady_deviation(r, 10.0)
    c.check(dev < 1e-8, f"stretch 0.5: Sigma_d steady to {dev:.1e} inside r < 10 au")
    mdot_in, exact = inflow(r, vr)
    rel = abs(mdot_in / exact - 1)
    c.check(rel < 1e-9, f"stretch 0.5: flux through r_in exact (rel. diff {rel:.1e})")

    # 2. drifting ring, first-order convergence of its centre-of-mass speed, on the
    # log-spaced grid and on a stretched one (grid.stretch: d ln r ∝ r^0.5)
    for stretch in (0.0, 0.5):
        errs = []  # first-order upwind: expect an error ~ (dr/r)/2
        for n in [100, 200, 400]:
            out = f"{args.workdir}/ring_{n}_s{stretch:g}.h5"
            run(args.exe, "params/tests/drift.toml", out,
                [f"grid.n_cells={n}", f"grid.stretch={stretch:g}", "transport.diffusion=false",
                 'dust.init="gaussian_ring"', "dust.ring_r_au=60", "dust.ring_width_au=3",
                 "output.t_end_yr=2e4"])
            r = load_run(out)
            m = r.snapshots["sigma_d"] * r.area
            com = (m @ r.r_c) / m.sum(axis=1) * AU
            t = r.time * YR
            speed = (com[-1] - com[0]) / (t[-1] - t[0])
            vr = r.snapshots["v_r"][0][:-1].mean()
            err = abs(speed / vr - 1)
            errs.append(err)
            cons = np.max(np.abs((m.sum(axis=1) + r.snapshots["m_out_inner"]) / m.sum(axis=1)[0] - 1))
            c.check(cons < 1e-12, f"stretch {stretch:g}, N = {n}: mass conserved to {cons:.1e}")
            print(f"stretch {stretch:g}, N = {n}: ring centre moved {(com[-1] - com[0]) / AU:.3f} au, speed {speed / 100:.4f} m/s vs v_r {vr / 100:.4f} m/s (rel. error {err:.2e})")
        # the cell width at the ring, from the faces of the N = 200 grid
        r200 = load_run(f"{args.workdir}/ring_200_s{stretch:g}.h5")
        k = int(np.searchsorted(r200.r_f, 60.0)) - 1
        dlnr200 = float(np.log(r200.r_f[k + 1] / r200.r_f[k]))
        c.check(errs[1] < dlnr200, f"stretch {stretch:g}, N = 200: centre-of-mass speed error {errs[1]:.1e} below dr/r = {dlnr200:.1e} at the ring")
        if stretch == 0.0:
            errs_log = errs  # upwind on the log-spaced grid, compared with van Leer below
        order = np.log(errs[0] / errs[2]) / np.log(4)
        print(f"stretch {stretch:g}: measured order of the centre-of-mass speed error: {order:.2f}")
        c.check(order > 0.8, f"stretch {stretch:g}: the error falls at least at first order")

    # 3. van Leer: steady state exact, conservation, second-order convergence
    vl = ['transport.advection="van_leer"']
    out = f"{args.workdir}/steady_vl.h5"
    run(args.exe, "params/tests/drift.toml", out, ["output.t_end_yr=2e4"] + vl)
    r = load_run(out)
    dev = steady_deviation(r, reach)
    c.check(dev < 1e-6, f"van Leer: Sigma_d steady to {dev:.1e} inside r < {reach:.0f} au")
    mdot_in, exact = inflow(r, vr)
    rel = abs(mdot_in / exact - 1)
    c.check(rel < 1e-6, f"van Leer: flux through r_in to the tolerance (rel. diff {rel:.1e})")
    errs_vl, l1_vl, l1_up = [], [], []
    for n in [100, 200, 400]:
        profiles = {}
        for scheme, extra in (("upwind", []), ("van_leer", vl)):
            out = f"{args.workdir}/ring_{scheme}_{n}.h5"
            run(args.exe, "params/tests/drift.toml", out,
                [f"grid.n_cells={n}", "transport.diffusion=false", 'dust.init="gaussian_ring"',
                 "dust.ring_r_au=60", "dust.ring_width_au=3", "output.t_end_yr=2e4"] + extra)
            profiles[scheme] = load_run(out)
        r = profiles["van_leer"]
        m = r.snapshots["sigma_d"] * r.area
        total = m.sum(axis=1) + r.snapshots["m_out_inner"]
        cons = np.max(np.abs(total / total[0] - 1))
        c.check(cons < 1e-12, f"van Leer N = {n}: mass conserved to {cons:.1e}")
        com = (m @ r.r_c) / m.sum(axis=1) * AU
        t = r.time * YR
        vr = r.snapshots["v_r"][0][:-1].mean()
        errs_vl.append(abs((com[-1] - com[0]) / (t[-1] - t[0]) / vr - 1))
        # L1 error of the mass per unit radius 2 pi r Sigma against the initial one shifted
        # by v_r t: with uniform v_r, d(r Sigma)/dt = -v_r d(r Sigma)/dr exactly.
        shift = vr * (t[-1] - t[0]) / AU
        for scheme, store in (("van_leer", l1_vl), ("upwind", l1_up)):
            rr = profiles[scheme]
            q0 = rr.r_c * rr.snapshots["sigma_d"][0]
            q1 = rr.r_c * rr.snapshots["sigma_d"][-1]
            q_exact = np.interp(rr.r_c - shift, rr.r_c, q0)
            dr = np.diff(rr.r_f)
            store.append(np.sum(np.abs(q1 - q_exact) * dr) / np.sum(q0 * dr))
        print(f"N = {n}: c.o.m. speed error {errs_vl[-1]:.2e} (van Leer) vs {errs_log[[100, 200, 400].index(n)]:.2e} (upwind); "
              f"L1 profile error {l1_vl[-1]:.2e} (van Leer) vs {l1_up[-1]:.2e} (upwind)")
    order_com = np.log(errs_vl[0] / errs_vl[2]) / np.log(4)
    order_l1 = np.log(l1_vl[0] / l1_vl[2]) / np.log(4)
    order_l1_up = np.log(l1_up[0] / l1_up[2]) / np.log(4)
    print(f"van Leer orders: c.o.m. speed {order_com:.2f}, L1 profile {order_l1:.2f} (upwind L1: {order_l1_up:.2f})")
    c.check(order_com > 1.7, "van Leer: c.o.m. speed error falls at second order")
    c.check(order_l1 > 1.5, "van Leer: L1 profile error falls at (nearly) second order")
    c.check(all(a < b for a, b in zip(l1_vl, l1_up)), "van Leer: L1 error below upwind's at every N")
    c.finish()


if __name__ == "__main__":
    main()
