"""Erosion `halt` (E1, spec §5.2) on the grid: params/erosion_40.toml, where growth stops
once the speed against small projectiles, dv_ls, reaches v_eros = 40 m/s. The growth rate
is the coagulation rate times S(x) = 1/2 [1 - tanh((x - 1)/w)], x = dv_ls/v_eros (w =
erosion.width), and the log-moment Q_m = Sigma_d ln m (spec §6.2), advected by the drift
speed v_r (diffusion off here), carries ln m along each particle's path:

    d ln m/dt + v_r d ln m/dr = S(x) / t_coag,   t_coag = m / (dm/dt)_coag,

with (dm/dt)_coag of spec §4.1 and h_d of spec §2 (common.growth_along_paths). This
script runs the scene with diffusion off, rtol 1e-7 and snapshot triples 1e-4 apart
around 1e4, 1e5 and 1e6 yr, reads dv_ls from /snapshots/dv_ls, works t_coag and the gradient of ln m out of
the snapshots, and checks
  * that the stalled cells (x > 1.05, S < e^-10) hold their particles: along the drift
    path (centred gradient) ln m changes at under 1e-2 of the coagulation rate, against 1
    for an unhalted particle;
  * the balance in the upwind scheme's own form (the inflow through each face times the
    jump of ln m) in every cell with dust above the monomer floor, stalled or growing:
    S(x) to 5e-3 of the coagulation rate (the time difference's error, as in
    test_fragmentation_limit: measured <= 1.5e-3);
  * that dv_ls is written with erosion on, with its units, and not without.
A halt factor left out of the growth rate, or ln m carried at another speed, fails it.
The cells beside the snow-line face (two on each side) are left out: there the
sublimation makes ln m jump."""
import numpy as np

from common import (M0_SIL, Checks, beside_snow_face, growth_along_paths, load_run, parse_args,
                    run, run_with_triples)

def main():
    args = parse_args()
    c = Checks()
    r, middles = run_with_triples(args.exe, "params/erosion_40.toml",
                                  f"{args.workdir}/erosion_40.h5", (1e4, 1e5, 1e6))
    unit = r.units.get("snapshots/dv_ls")
    c.check("dv_ls" in r.snapshots and unit == "cm s^-1", f"/snapshots/dv_ls written, units {unit!r}")
    ero = r.config["erosion"]
    c.check(ero["model"] == "halt", "erosion_40 uses halt")
    v_eros, width = 100.0 * ero["v_eros_m_s"], ero["width"]
    near_snow = beside_snow_face(r)

    for k in middles:
        t = r.time[k]
        s = {n: r.snapshots[n][k] for n in ("m", "dv_ls", "St", "sigma_d", "sigma_g")}
        paths = growth_along_paths(r, k)
        x = s["dv_ls"] / v_eros
        halt = 0.5 * (1 - np.tanh((x - 1) / width))  # spec §5.2
        dusty = (s["sigma_d"] > 1e-6 * s["sigma_g"]) & ~near_snow & (s["m"] > 10 * M0_SIL)

        stalled = dusty & (x > 1.05)
        c.check(stalled.sum() >= 5, f"t = {t:.5g} yr: erosion stalls growth in "
                f"{stalled.sum()} cells (>= 5)")
        if stalled.any():
            worst = np.max(np.abs(paths["continuum"][stalled]))
            st = s["St"][stalled]
            print(f"t = {t:.5g} yr: {stalled.sum()} stalled cells, {r.r_c[stalled].min():.2f}-"
                  f"{r.r_c[stalled].max():.2f} au, St {st.min():.3f}-{st.max():.3f}, "
                  f"dv_ls/v_eros {x[stalled].min():.3f}-{x[stalled].max():.3f}, S <= "
                  f"{halt[stalled].max():.1e}")
            c.check(worst < 1e-2, f"t = {t:.5g} yr: the stalled particles hold their mass "
                    f"along the drift path ({worst:.1e} of the coagulation rate; 1e-2 asserted)")
        gap = np.max(np.abs(paths["discrete"][dusty] - halt[dusty]))
        growing = dusty & (x < 0.9)
        c.check(growing.sum() >= 5, f"t = {t:.5g} yr: {growing.sum()} cells still grow (>= 5)")
        c.check(gap < 5e-3, f"t = {t:.5g} yr: in the upwind scheme's form ln m changes at "
                f"S(dv_ls/v_eros) times the coagulation rate in all {dusty.sum()} cells with "
                f"dust ({stalled.sum()} stalled, {growing.sum()} growing) to {gap:.1e} "
                f"(5e-3 asserted)")

    plain = f"{args.workdir}/fiducial_short.h5"
    run(args.exe, "params/fiducial.toml", plain, ["output.t_end_yr=1000", "grid.n_cells=32"])
    c.check("dv_ls" not in load_run(plain).snapshots, "no /snapshots/dv_ls without erosion")
    c.finish()


if __name__ == "__main__":
    main()
