"""The local growth model without transport (params/tests/growth_local.toml, spec §4-§5):
1. hit-and-stick: phi ∝ m^s_hs with s_hs = -0.58 while E_imp < 3 b E_roll (spec §4.3);
2. the slope changes to the collisional-compression value -1/8 (Epstein drag, St < 1)
   once E_imp > 3 b E_roll (compaction floors off, to isolate the collisional law);
3. erosion (E1 halt, spec §5.2): the particles stall within 10% of the Stokes numbers the
   spec gives for v_eros = 20, 40, 60 m/s (MMSN, alpha = 1e-3), at 3 and 5 au.
"""
import numpy as np

from common import Checks, load_run, parse_args, run

E_ROLL_ICE = 4.74e-9  # erg, spec §0 [D]
B = 0.15              # spec §4.2
MFP_5AU = 120.0       # cm, mean free path at 5 au (spec §12)
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

    for v, (lo, hi) in STALL.items():
        for r_au in (3.0, 5.0):
            out = f"{args.workdir}/erosion_{v}_{r_au:g}.h5"
            run(args.exe, scene, out,
                ['erosion.model="halt"', f"erosion.v_eros_m_s={v}",
                 f"grid.r_in_au={0.99 * r_au}", f"grid.r_out_au={1.01 * r_au}",
                 "output.t_end_yr=1e4", "output.n_snapshots=10"])
            st = load_run(out).snapshots["St"][-1][1]
            ok = 0.9 * lo <= st <= 1.1 * hi
            c.check(ok, f"v_eros = {v} m/s at {r_au:g} au: stall St = {st:.3f} "
                        f"(spec {lo}-{hi}, ±10%)")
    c.finish()


if __name__ == "__main__":
    main()
