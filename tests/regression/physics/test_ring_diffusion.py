"""A diffusing ring against the exact axisymmetric solution (spec §6.1 diffusion term):
relative L1 error at three resolutions, on the log-spaced and on a stretched grid, the
measured convergence order printed and asserted (>= 1.8: centred diffusion is second
order on both); and the dust diffusivity D_d = D_g / (1 + St^2) (spec §6.1): at St = 3,
run 10x longer, the ring spreads as the St = 1e-8 one does (D_g/(1 + St) would spread it
2.5x further)."""
import numpy as np

from common import Checks, alpha_cs_h, load_run, parse_args, run
from postprocess.analytic import ring_diffusion

AU = 1.496e13
YR = 3.156e7


def l1_error(path):
    r = load_run(path)
    st = r.config["transport"]["St"]
    # D_d = alpha c_s H / (1 + St^2) (spec §6.1; Youdin & Lithwick 2007)
    # (alpha c_s H from the scene: with q = 3/2 it is the same at every r)
    D = float(alpha_cs_h(r.config, 1.0)) / (1 + st * st)
    # the initial profile is the ring solution at t0 with 2 D t0 = w^2
    cfg = r.config["dust"]
    r0, w = cfg["ring_r_au"] * AU, cfg["ring_width_au"] * AU
    t0 = w * w / (2 * D)
    rc = r.r_c * AU
    ref0 = ring_diffusion(rc, t0, r0, D, 1.0)
    peak = ring_diffusion(np.array([r0]), t0, r0, D, 1.0)[0]
    mass = cfg["ring_sigma"] / peak  # mass that gives Sigma(r0, t0) = ring_sigma
    errs = []
    for k in range(1, r.n_snapshots):
        t = t0 + r.time[k] * YR
        exact = ring_diffusion(rc, t, r0, D, mass)
        num = r.snapshots["sigma_d"][k]
        errs.append(np.sum(np.abs(num - exact) * r.area) / np.sum(exact * r.area))
    dvar = float(np.std(r.disk["alpha"] * r.disk["c_s"] * r.disk["h_g"]) / D)
    return errs[-1], dvar, ref0


def main():
    args = parse_args()
    c = Checks()
    ns = [100, 200, 400]
    # log-spaced, and stretched (d ln r ∝ r^0.5, grid.stretch): centred diffusion on a
    # smoothly stretched grid stays second order
    for stretch in (0.0, 0.5):
        errs = []
        for n in ns:
            out = f"{args.workdir}/ring_{n}_s{stretch:g}.h5"
            run(args.exe, "params/tests/ring_diffusion.toml", out,
                [f"grid.n_cells={n}", f"grid.stretch={stretch:g}"])
            e, dvar, _ = l1_error(out)
            errs.append(e)
            print(f"stretch {stretch:g}, N = {n:4d}: relative L1 error at t_end = {e:.3e}")
        c.check(dvar < 1e-10, f"diffusivity is uniform in this scene (spread {dvar:.1e})")
        orders = [np.log(errs[i] / errs[i + 1]) / np.log(ns[i + 1] / ns[i]) for i in range(2)]
        print("measured convergence orders: " + ", ".join(f"{o:.3f}" for o in orders))
        c.check(all(o >= 1.8 for o in orders),
                f"stretch {stretch:g}: second-order convergence (order >= 1.8)")
        c.check(errs[-1] < 1e-3, f"stretch {stretch:g}: N = 400 error {errs[-1]:.2e} < 1e-3")
        if stretch == 0.0:
            err_200 = errs[1]

    # D_d = D_g / (1 + St^2): St = 3 (a prescribed Stokes number, drift off) for 10x the
    # time is the same ring problem in D t
    out = f"{args.workdir}/ring_200_st3.h5"
    t_end = 10 * load_run(f"{args.workdir}/ring_200_s0.h5").time[-1]
    run(args.exe, "params/tests/ring_diffusion.toml", out,
        ["grid.n_cells=200", "transport.St=3.0", f"output.t_end_yr={t_end:g}"])
    e, _, _ = l1_error(out)
    print(f"St = 3, N = 200, t_end = {t_end:g} yr: relative L1 error {e:.3e} (St = 1e-8: {err_200:.3e})")
    c.check(e < 2 * err_200, f"St = 3: the ring diffuses with D_g/(1 + St^2) (L1 error {e:.2e})")
    c.finish()


if __name__ == "__main__":
    main()
