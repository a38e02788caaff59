"""Viscous gas evolution (spec §1.2, gas.evolve) against the Lynden-Bell & Pringle (1974)
self-similar solution, gamma = 1, at two resolutions: relative L1 error of Sigma_g over
0.3-5 r_c (away from the zero-torque inner edge) and its convergence order; the gas mass
budget (grid + accreted through r_in) closes; and the dust, carried along by v_g, keeps
its own budget closed."""
import numpy as np

from common import Checks, load_run, parse_args, run
from postprocess.analytic import lbp_sigma

AU = 1.496e13
YR = 3.156e7
MSUN = 1.989e33


def errors(path):
    r = load_run(path)
    cfg = r.config["disk"]
    rc = cfg["r_c_au"] * AU
    m_disk = cfg["m_disk_msun"] * MSUN
    i = np.argmin(np.abs(r.r_c - cfg["r_c_au"]))
    nu = r.disk["alpha"] * r.disk["c_s"] * r.disk["h_g"]
    nu_c = nu[i] * (cfg["r_c_au"] / r.r_c[i])  # nu ∝ r
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
    c.check(min(orders) > 1.5, "converges at second order (> 1.5)")
    c.check(max(res[n][2] for n in res) < 1e-12, "gas budget closes to 1e-12")
    c.check(max(res[n][3] for n in res) < 1e-12, "dust budget closes to 1e-12")
    c.finish()


if __name__ == "__main__":
    main()
