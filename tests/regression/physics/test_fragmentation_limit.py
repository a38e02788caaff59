"""The compact-particle mode on the grid (spec §5.3, params/compact_fragmentation.toml:
phi = 1, fragmentation at v_frag = 1 m/s, LBP disk): where particles are held by
fragmentation, the fragmentation factor F = 1 - 2 dv^2/(dv^2 + v_frag^2) (spec §5.3) must
balance what the transport does to ln m. With the log-moment Q_m = Sigma_d ln m (spec
§6.2) advected by the drift speed v_r and diffusion off, each cell's particle obeys

    d ln m/dt + v_r d ln m/dr = F / t_coag,   t_coag = m / (dm/dt)_coag,

(dm/dt)_coag = f_grow 2 sqrt(pi) a^2 dv Sigma_d / h_d (spec §4.1) and h_d = H / sqrt(1 +
St/alpha (1 + 2 St)/(1 + St)) (spec §2). This script runs the scene with diffusion off and
rtol 1e-7 and snapshot triples 1e-4 apart around 1e5 and 1e6 yr (for d ln m/dt), works
t_coag, the gradient of
ln m and F out of the snapshots' fields with the spec's formulas
(common.growth_along_paths), and checks
  * the balance with the centred gradient, cell by cell where dv is within 10 % of
    v_frag: the residual is the first-order upwind scheme's truncation error, O(dr/r), and
    2 d ln r is asserted;
  * the balance in the upwind scheme's own form (the inflow through each face times the
    jump of ln m) in every cell with dust above the monomer floor, held or still growing:
    5e-3 of the coagulation rate is asserted. What is left is the time difference's: the
    snapshots' integration error over their short spacing, ~rtol |ln m| t_coag / dt
    (7e-4 for a cell at the growth front of erosion_40), measured <= 1.5e-3 in these two
    tests.
The cells beside the snow-line face are left out (the sublimation makes ln m jump there),
and so are monomers at the mass floor m0 (spec §6.4), as in the thin outer disk where
even monomers collide at about v_frag. A doubled growth rate, a fragmentation factor with
dv^2 in place of its smooth form, or ln m carried at another speed fails it.

It also prints how the mass-dominating particle's St compares with the fragmentation
limit of the two-population codes, St_frag = v_frag^2 / (3 alpha c_s^2) from dv_t^2 = 3
alpha St c_s^2 (Birnstiel, Klahr & Ercolano 2012, before their calibration factor), and
checks that it is at most 3/k times it, where k = 2 y_a - (1 + eps) + 2/(1 + eps) (1/(1 +
y_a) + eps^3/(y_a + eps)) is the Ormel & Cuzzi (2007) intermediate-regime coefficient of
dv_t^2 = k alpha St c_s^2 for the partner eps St (spec §3; y_a = 1.6): turbulence alone
would put the particle at 3/k times St_frag, and every other source of dv (Brownian,
drift) only lowers it."""
import math

import numpy as np

from common import M0_SIL, Checks, beside_snow_face, growth_along_paths, parse_args, run_with_triples

def main():
    args = parse_args()
    c = Checks()
    r, middles = run_with_triples(args.exe, "params/compact_fragmentation.toml",
                                  f"{args.workdir}/compact_frag.h5", (1e5, 1e6))
    cfg = r.config
    v_frag = 100.0 * cfg["fragmentation"]["v_frag_ice_m_s"]
    c.check(cfg["fragmentation"]["v_frag_sil_m_s"] == cfg["fragmentation"]["v_frag_ice_m_s"],
            "one v_frag for both species")
    eps = cfg.get("growth", {}).get("eps", 0.5)
    alpha, c_s = r.disk["alpha"], r.disk["c_s"]
    near_snow = beside_snow_face(r)
    dlnr = np.log(r.r_f[1:] / r.r_f[:-1]).max()

    y_a = 1.6
    k_oc07 = 2 * y_a - (1 + eps) + 2 / (1 + eps) * (1 / (1 + y_a) + eps**3 / (y_a + eps))
    for k in middles:
        t = r.time[k]
        snap = {name: r.snapshots[name][k] for name in ("dv", "St", "sigma_d", "sigma_g", "m")}
        st, m = snap["St"], snap["m"]
        paths = growth_along_paths(r, k)
        x = snap["dv"] / v_frag
        f_meas = (1 - x**2) / (1 + x**2)  # spec §5.3
        dusty = (snap["sigma_d"] > 1e-4 * snap["sigma_g"]) & ~near_snow & (m > 10 * M0_SIL)

        # held by fragmentation: dv within 10 % of v_frag (|F| < 0.1); further out, at
        # the edge of the drifting dust, the transport sets m
        sel = dusty & (np.abs(x - 1) < 0.1)
        ratio = paths["continuum"][sel] / f_meas[sel]
        worst = np.max(np.abs(ratio - 1))
        span = f"{r.r_c[sel].min():.2f}-{r.r_c[sel].max():.1f} au"
        print(f"t = {t:.5g} yr: {sel.sum()} cells held by fragmentation ({span}); "
              f"|dv/v_frag - 1| from {np.min(np.abs(x[sel] - 1)):.1e} to "
              f"{np.max(np.abs(x[sel] - 1)):.1e}; F_pred/F_meas {ratio.min():.4f} .. {ratio.max():.4f}")
        c.check(sel.sum() >= 50, f"t = {t:.5g} yr: at least 50 cells held by fragmentation ({sel.sum()})")
        c.check(worst < 2 * dlnr, f"t = {t:.5g} yr: the fragmentation factor balances the "
                f"advection of ln m, t_coag (d ln m/dt + v_r d ln m/dr), to {worst:.2e} "
                f"(2 d ln r = {2 * dlnr:.3f} asserted)")
        gap = np.max(np.abs(paths["discrete"][dusty] - f_meas[dusty]))
        c.check(gap < 5e-3, f"t = {t:.5g} yr: in the upwind scheme's form the balance holds in "
                f"all {dusty.sum()} cells with dust to {gap:.1e} of the coagulation rate "
                f"(5e-3 asserted)")
        inner = sel & (r.r_c < 10.0)
        print(f"  inside 10 au: |dv/v_frag - 1| <= {np.max(np.abs(x[inner] - 1)):.1e}")

        st_frag = v_frag**2 / (3 * alpha * c_s**2)  # Birnstiel et al. 2012
        held = sel & (r.r_c < 30.0)
        q = st[held] / st_frag[held]
        print(f"  St / (v_frag^2 / (3 alpha c_s^2)) = {q.min():.3f} .. {q.max():.3f} over "
              f"{r.r_c[held].min():.2f}-{r.r_c[held].max():.1f} au (turbulence alone: 3/k = "
              f"{3 / k_oc07:.3f}, k = {k_oc07:.4f})")
        c.check(q.max() <= 3 / k_oc07 * (1 + 1e-6) and q.min() > 0.8,
                f"t = {t:.5g} yr: St of the held particles below the turbulence-only limit "
                f"{3 / k_oc07:.3f} St_frag and above 0.8 St_frag")
    c.check(math.isfinite(r.r_snow_au), "the scene has a snow line on the grid")
    c.finish()


if __name__ == "__main__":
    main()
