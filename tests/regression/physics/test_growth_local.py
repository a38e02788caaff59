"""The local growth model without transport (params/tests/growth_local.toml, spec §4-§5):
1. hit-and-stick: phi ∝ m^s_hs with s_hs = -0.58 while E_imp < 3 b E_roll (spec §4.3);
2. the slope changes to the collisional-compression value -1/8 (Epstein drag, St < 1)
   once E_imp > 3 b E_roll (compaction floors off, to isolate the collisional law);
3. erosion (E1 halt, spec §5.2): the particles stall within 10% of the Stokes numbers the
   spec gives for v_eros = 20, 40, 60 m/s (MMSN, alpha = 1e-3), at 3 and 5 au;
4. the growth rate as integrated on the grid: d ln m/dt from the snapshots' m(t) against
   spec §4.1, dm/dt = 2 sqrt(pi) a^2 dv Sigma_d / h_d, with h_d of spec §2 (Youdin &
   Lithwick form) worked out here from the snapshots' a, dv, St, Sigma_d and the scene's
   H (the slopes above do not depend on how fast the particle grows).
"""
import numpy as np

from common import Checks, load_run, parse_args, run

E_ROLL_ICE = 4.74e-9  # erg, spec §0 [D]
B = 0.15              # spec §4.2
MFP_5AU = 120.0       # cm, mean free path at 5 au (spec §12)
YR = 3.156e7          # s, src/core/units.hpp
STALL = {20: (0.12, 0.15), 40: (0.32, 0.36), 60: (0.6, 0.7)}  # spec §5.2 [D]


def slope(m, phi, sel):
    return np.polyfit(np.log(m[sel]), np.log(phi[sel]), 1)[0]


def main():
    args = parse_args()
    c = Checks()
    scene = "params/tests/growth_local.toml"

    out = f"{args.workdir}/hs.h5"
    run(args.exe, scene, out, ["porosity.gas_compaction=false", "porosity.self_gravity=false",
                               "output.n_snapshots=1500"])
    r = load_run(out)
    m, phi = r.snapshots["m"][:, 1], r.snapshots["phi"][:, 1]
    dv, st = r.snapshots["dv"][:, 1], r.snapshots["St"][:, 1]
    e_ratio = m * dv**2 / 4 / (3 * B * E_ROLL_ICE)
    hs = (m > 1e3 * 5.9e-15) & (e_ratio < 0.1)
    a = r.snapshots["a"][:, 1]
    # Epstein regime (a well below 9 lambda/4, away from the smooth blend into Stokes drag)
    comp = (e_ratio > 30) & (st < 0.05) & (a < 0.3 * 9 * MFP_5AU / 4)
    s_hs, s_c = slope(m, phi, hs), slope(m, phi, comp)
    print(f"hit-and-stick: d ln phi/d ln m = {s_hs:.4f} over {hs.sum()} snapshots "
          f"(m {m[hs].min():.1e}-{m[hs].max():.1e} g)")
    print(f"compression:   d ln phi/d ln m = {s_c:.4f} over {comp.sum()} snapshots "
          f"(m {m[comp].min():.1e}-{m[comp].max():.1e} g)")
    c.check(hs.sum() >= 20 and abs(s_hs + 0.58) < 0.01, "hit-and-stick slope -0.58 (±0.01)")
    c.check(comp.sum() >= 10 and abs(s_c + 0.125) < 0.01, "compression slope -1/8 (±0.01)")

    # 4. growth rate: centred differences of ln m over the 1500 log-spaced snapshots
    # against spec §4.1 at the midpoints (geometric means of the neighbouring snapshots'
    # a, dv, St, Sigma_d), where the growth is resolved (m from 1e3 m0 up to 1e4 g).
    t = r.time * YR
    sig = r.snapshots["sigma_d"][:, 1]
    alpha = r.config["disk"]["alpha"]
    h_g = r.disk["h_g"][1]
    lnm = np.log(m)
    mid = lambda x: np.sqrt(x[1:] * x[:-1])  # noqa: E731
    rate_grid = np.diff(lnm) / np.diff(t)
    st_m = mid(st)
    h_d = h_g / np.sqrt(1 + st_m / alpha * (1 + 2 * st_m) / (1 + st_m))  # spec §2
    rate_spec = 2 * np.sqrt(np.pi) * mid(a) ** 2 * mid(dv) * mid(sig) / h_d / mid(m)
    sel = (mid(m) > 1e3 * 5.9e-15) & (mid(m) < 1e4) & (t[1:] > 0) & (t[:-1] > 0)
    dev = np.abs(rate_grid[sel] / rate_spec[sel] - 1)
    print(f"growth rate: d ln m/dt of the grid against spec §4.1 over {sel.sum()} intervals: "
          f"median rel. diff {np.median(dev):.1e}, largest {dev.max():.1e}")
    c.check(sel.sum() >= 100 and np.median(dev) < 1e-3 and dev.max() < 1e-2,
            "grid growth rate = 2 sqrt(pi) a^2 dv Sigma_d / h_d (median < 1e-3, all < 1e-2)")

    for v, (lo, hi) in STALL.items():
        for r_au in (3.0, 5.0):
            out = f"{args.workdir}/erosion_{v}_{r_au:g}.h5"
            run(args.exe, scene, out,
                ['erosion.model="halt"', f"erosion.v_eros_m_s={v}",
                 f"grid.r_in_au={0.99 * r_au}", f"grid.r_out_au={1.01 * r_au}",
                 "output.t_end_yr=1e4", "output.n_snapshots=10"])
            st = load_run(out).snapshots["St"][-1][1]
            # The requirement: the stall Stokes numbers of spec §5.2 within 10 %.
            # Measured (2026-11-24): 0.128/0.347/0.687 at 3 au, 0.141/0.366/0.731 at 5 au
            # for 20/40/60 m/s, i.e. the 5 au stalls 1.7-4.4 % above the spec's ranges: with
            # the switch of width erosion.width = 0.01 growth goes on at S ~ 1e-3..1e-5
            # for 1e4 yr (the stall creeps with t_end), and compaction raises St at a
            # halted mass. Where Delta v_ls = v_eros exactly (S = 1/2, spec §5.2's
            # definition) the spec's formulas give 0.117/0.316/0.604 at 3 au and
            # 0.130/0.337/0.649 at 5 au (an independent mpmath evaluation of spec §3).
            ok = 0.9 * lo <= st <= 1.1 * hi
            c.check(ok, f"v_eros = {v} m/s at {r_au:g} au: stall St = {st:.3f} "
                        f"(spec {lo}-{hi}, within 10 %)")
    c.finish()


if __name__ == "__main__":
    main()
