"""Viscous gas evolution (spec §1.2, gas.evolve) against the Lynden-Bell & Pringle (1974)
self-similar solution, gamma = 1, at two resolutions: relative L1 error of Sigma_g over
0.3-5 r_c and its convergence order, with the default free-flow inner edge (gas leaves
through r_in as if the disk went on); the gas mass budget (grid + accreted through r_in)
closes; and the dust, carried along by v_g, keeps its own budget closed. Then the
zero-torque inner edge (gas.inner_bc = "zero_torque", nu Sigma_g r^1/2 = 0 at r_in): where
the inner disk has reached its steady state (r << r_c) the steady thin-disk solution with
zero torque at r_in gives Sigma = Mdot/(3 pi nu) (1 - sqrt(r_in/r)), so the ratio of the
zero-torque run to the free-flow run must follow 1 - sqrt(r_in/r) up to a constant (the
ratio of the two disks' accretion rates)."""
import numpy as np

from common import Checks, alpha_cs_h, load_run, parse_args, run
from postprocess.analytic import lbp_sigma

AU = 1.496e13
YR = 3.156e7
MSUN = 1.989e33


def errors(path):
    r = load_run(path)
    cfg = r.config["disk"]
    rc = cfg["r_c_au"] * AU
    m_disk = cfg["m_disk_msun"] * MSUN
    nu_c = float(alpha_cs_h(r.config, cfg["r_c_au"]))  # nu ∝ r (q = 1/2), from the scene
    sel = (r.r_c > 0.3 * cfg["r_c_au"]) & (r.r_c < 5 * cfg["r_c_au"])
    out = []
    for k in range(1, r.n_snapshots):
        exact = lbp_sigma(r.r_c * AU, r.time[k] * YR, m_disk, rc, nu_c, 1.0)
        num = r.snapshots["sigma_g"][k]
        out.append(np.sum(np.abs(num - exact)[sel] * r.area[sel]) / np.sum(exact[sel] * r.area[sel]))
    ts = rc**2 / (3 * nu_c) / YR
    m_gas = np.sum(r.snapshots["sigma_g"] * r.area, axis=1) + r.snapshots["m_out_gas"]
    gas_budget = np.max(np.abs(m_gas / m_gas[0] - 1))
    m_dust = r.snapshots["m_dust"] + r.snapshots["m_out_inner"]
    dust_budget = np.max(np.abs(m_dust / m_dust[0] - 1))
    return out, ts, gas_budget, dust_budget, r.time


def main():
    args = parse_args()
    c = Checks()
    res = {}
    for n in [100, 200, 400]:
        out = f"{args.workdir}/lbp_{n}.h5"
        run(args.exe, "params/tests/lbp_viscous.toml", out, [f"grid.n_cells={n}"])
        res[n] = errors(out)
        errs, ts, gb, db, t = res[n]
        print(f"N = {n}: t_s = {ts:.3g} yr; L1 error of Sigma_g at t = "
              + ", ".join(f"{tt:.0e} yr: {e:.2e}" for tt, e in zip(t[1:], errs))
              + f"; gas budget {gb:.1e}, dust budget {db:.1e}")
    e = [res[n][0][-1] for n in [100, 200, 400]]
    orders = [np.log2(e[0] / e[1]), np.log2(e[1] / e[2])]
    print("convergence orders: " + ", ".join(f"{o:.2f}" for o in orders))
    c.check(res[200][1] < res[200][4][-1], "the run spans more than one viscous time t_s")
    c.check(e[1] < 1e-3, f"N = 200: L1 error {e[1]:.2e} < 1e-3 after {res[200][4][-1]:.0e} yr")
    c.check(min(orders) >= 1.8, f"converges at second order (orders {orders[0]:.2f}, {orders[1]:.2f}; >= 1.8)")
    c.check(max(res[n][2] for n in res) < 1e-12, "gas budget closes to 1e-12")
    c.check(max(res[n][3] for n in res) < 1e-12, "dust budget closes to 1e-12")

    zt = f"{args.workdir}/lbp_200_zero_torque.h5"
    run(args.exe, "params/tests/lbp_viscous.toml", zt,
        ["grid.n_cells=200", 'gas.inner_bc="zero_torque"'])
    a, b = load_run(f"{args.workdir}/lbp_200.h5"), load_run(zt)
    sel = (a.r_c > 0.02) & (a.r_c < 0.3)  # au: 2-30 r_in, viscous time << 1e5 yr
    ratio = b.snapshots["sigma_g"][-1][sel] / a.snapshots["sigma_g"][-1][sel]
    shape = ratio / (1.0 - np.sqrt(a.r_f[0] / a.r_c[sel]))
    spread = shape.max() / shape.min() - 1.0
    m_gas = np.sum(b.snapshots["sigma_g"] * b.area, axis=1) + b.snapshots["m_out_gas"]
    print(f"zero torque: Sigma ratio / (1 - sqrt(r_in/r)) over 0.02-0.3 au = "
          f"{shape.min():.4f} .. {shape.max():.4f} (the accretion-rate ratio; spread "
          f"{spread:.1e}); free flow in its place would give 1/(1 - sqrt(r_in/r)) = "
          f"{1 / (1 - np.sqrt(a.r_f[0] / 0.02)):.2f} at 0.02 au")
    c.check(spread < 5e-3, f"zero torque: the inner profile is the steady zero-torque "
            f"shape 1 - sqrt(r_in/r) to {spread:.1e} (5e-3 asserted)")
    c.check(abs(np.median(shape) - 1.0) < 0.03,
            f"zero torque: accretion rate within 3 % of the free-flow disk's "
            f"({np.median(shape):.4f})")
    c.check(np.max(np.abs(m_gas / m_gas[0] - 1)) < 1e-12, "zero torque: gas budget closes")
    c.finish()


if __name__ == "__main__":
    main()
