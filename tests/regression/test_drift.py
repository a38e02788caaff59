"""Radial drift (spec §6.1, §6.3) where the drift speed is uniform (see params/tests/drift.toml):
1. steady drift flux: Sigma_d = Z Sigma_g ∝ 1/r stays steady inside the region the closed
   outer edge has not yet reached, and the mass flow through r_in equals 2 pi r Sigma v_r
   (to first order in dr/r, the upwind truncation error);
2. a drifting ring (diffusion off): its centre of mass moves at v_r, with an error that
   falls at first order with the cell size."""
import numpy as np

from common import Checks, load_run, parse_args, run

AU = 1.496e13
YR = 3.156e7


def main():
    args = parse_args()
    c = Checks()

    # 1. steady flux
    out = f"{args.workdir}/steady.h5"
    run(args.exe, "params/tests/drift.toml", out, ["output.t_end_yr=2e4"])
    r = load_run(out)
    v = r.snapshots["v_r"][0][:-1]  # faces 0..N-1 (the outer face carries no flux)
    c.check(np.ptp(v) < 1e-10 * abs(v.mean()), f"uniform drift speed v_r = {v.mean() / 100:.3f} m/s")
    vr = v.mean()
    t_end = r.time[-1] * YR
    # The closed outer edge sends a rarefaction inward at |v_r|; first-order upwind smears
    # its front over many cells (a Poisson tail), so test steadiness inside 40% of the
    # front radius.
    front = r.r_f[-1] * AU - abs(vr) * t_end
    reach = 0.4 * front / AU
    inside = r.r_c < reach
    sig0, sig1 = r.snapshots["sigma_d"][0], r.snapshots["sigma_d"][-1]
    dev = np.max(np.abs(sig1[inside] / sig0[inside] - 1))
    c.check(dev < 1e-6, f"Sigma_d steady to {dev:.1e} inside r < {reach:.0f} au after {r.time[-1]:.0f} yr")
    mdot_in = -r.snapshots["mdot_d"][-1][0]
    # 2 pi r Sigma_d |v| is the same at every r for Sigma_d ∝ 1/r: take it at cell 0
    exact = 2 * np.pi * (r.r_c[0] * AU) * r.snapshots["sigma_d"][0][0] * abs(vr)
    rel = abs(mdot_in / exact - 1)
    print(f"mass flow through r_in {mdot_in:.6e} g/s, analytic {exact:.6e} g/s, rel. diff {rel:.2e}")
    c.check(rel < 1e-6, "pebble flux through r_in equals 2 pi r Sigma v (steady state exact)")
    budget = (r.snapshots["m_dust"] + r.snapshots["m_out_inner"]) / r.snapshots["m_dust"][0] - 1
    c.check(np.max(np.abs(budget)) < 1e-12, f"budget closes: max |error| {np.max(np.abs(budget)):.1e}")

    # 2. drifting ring, first-order convergence of its centre-of-mass speed
    errs = []  # first-order upwind: expect an error ~ (dr/r)/2
    for n in [100, 200, 400]:
        out = f"{args.workdir}/ring_{n}.h5"
        run(args.exe, "params/tests/drift.toml", out,
            [f"grid.n_cells={n}", "transport.diffusion=false", 'dust.init="gaussian_ring"',
             "dust.ring_r_au=60", "dust.ring_width_au=3", "output.t_end_yr=2e4"])
        r = load_run(out)
        m = r.snapshots["sigma_d"] * r.area
        com = (m @ r.r_c) / m.sum(axis=1) * AU
        t = r.time * YR
        speed = (com[-1] - com[0]) / (t[-1] - t[0])
        vr = r.snapshots["v_r"][0][:-1].mean()
        err = abs(speed / vr - 1)
        errs.append(err)
        print(f"N = {n}: ring centre moved {(com[-1] - com[0]) / AU:.3f} au, speed {speed / 100:.4f} m/s vs v_r {vr / 100:.4f} m/s (rel. error {err:.2e})")
    dlnr200 = np.log(100.0 / 5.0) / 200
    c.check(errs[1] < dlnr200, f"N = 200: centre-of-mass speed error {errs[1]:.1e} below dr/r = {dlnr200:.1e}")
    order = np.log(errs[0] / errs[2]) / np.log(4)
    print(f"measured order of the centre-of-mass speed error: {order:.2f}")
    c.check(order > 0.8, "the error falls at least at first order")
    c.finish()


if __name__ == "__main__":
    main()
