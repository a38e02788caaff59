"""alpha(r) in the viscous gas (gas.evolve, spec §1.2, §1.5) against the steady accretion
solution: with no torque at the inner edge (gas.inner_bc = "free_flow") a disk accreting
at a rate Mdot has nu Sigma_g = Mdot / (3 pi) at every radius (Lynden-Bell & Pringle
1974; Pringle 1981 eq. 3.10 far from the inner edge). The gas starts on that solution for
an alpha profile with a Gaussian dip at 10 au (alpha_0 = 1e-3, A = -0.5, w = 2 au:
Sigma_g doubles there, the pressure bump an alpha dip makes), given as a table
(disk.model = "table", Sigma_g = C / nu(r)), and runs for 0.5 Myr, 4.5 viscous times
of the dip's width (w^2 / nu = 1.1e5 yr at alpha = 5e-4). Measured, at N = 100 and 200
cells (1-300 au; the closed outer edge drains the disk from outside in, so the checks
stay inside 30 au):
  - nu Sigma_g at 0.5 Myr against its initial value, the largest relative change;
  - Mdot(r) through every face, from the scheme's flux -3/r^(1/2) d(nu Sigma_g r^(1/2))/dr
    (disk/viscous_gas.hpp) on the final Sigma_g, against Mdot through r_in (3 pi nu
    Sigma_g of the first cell): constant with radius;
both must fall with resolution (the discrete steady state differs from nu Sigma_g = C
at second order in d ln r) and be < 1e-4 at N = 200. A control run with alpha constant
(the same table, alpha_profile = "constant") must leave the steady state by > 10 %:
what the checks would see if alpha(r) did not reach the viscosity."""
import os

import numpy as np

from common import Checks, load_run, parse_args, run

AU, YR = 1.496e13, 3.156e7
KB, MH, G, MSUN = 1.380649e-16, 1.6735e-24, 6.674e-8, 1.989e33
ALPHA0, A, R0, W = 1e-3, -0.5, 10.0, 2.0


def nu_of(r_au):
    alpha = ALPHA0 * (1 + A * np.exp(-(r_au - R0) ** 2 / (2 * W * W)))
    temp = 280.0 * r_au ** -0.5
    cs2 = KB * temp / (2.34 * MH)
    omega = np.sqrt(G * MSUN / (r_au * AU) ** 3)
    return alpha * cs2 / omega


def write_scene(workdir):
    r = np.geomspace(0.99, 303.0, 4000)
    c = 1e-8 * MSUN / YR / (3 * np.pi)   # Mdot = 1e-8 M_sun/yr
    with open(os.path.join(workdir, "steady.csv"), "w") as f:
        f.write("r_au,sigma_g_gcm2,T_K\n")
        for x in r:
            f.write(f"{x:.17g},{c / nu_of(x):.17g},{280.0 * x ** -0.5:.17g}\n")
    path = os.path.join(workdir, "steady.toml")
    with open(path, "w") as f:
        f.write(f"""[disk]
model = "table"
table_file = "steady.csv"
alpha = {ALPHA0!r}
alpha_profile = "gaussian"
alpha_bump_amplitude = {A!r}
alpha_bump_r_au = {R0!r}
alpha_bump_width_au = {W!r}
[gas]
evolve = true
inner_bc = "free_flow"
[grid]
r_in_au = 1.0
r_out_au = 300.0
[output]
t_end_yr = 5e5
times_yr = [2.5e5]
[snowline]
enabled = false
""")
    return path, c


def measure(path):
    """(largest change of nu Sigma_g, largest departure of Mdot(r) from Mdot(r_in)) inside
    30 au, and the run."""
    r = load_run(path)
    nu = r.disk["alpha"] * r.disk["c_s"] * r.disk["h_g"]
    sig = r.snapshots["sigma_g"]
    inside = r.r_c < 30.0
    change = np.max(np.abs((nu * sig[-1])[inside] / (nu * sig[0])[inside] - 1))
    rc, rf = r.r_c * AU, r.r_f * AU
    g = nu * np.sqrt(rc) * sig[-1]
    mdot = 2 * np.pi * rf[1:-1] * 3 / np.sqrt(rf[1:-1]) * (g[1:] - g[:-1]) / (rc[1:] - rc[:-1])
    mdot_in = 3 * np.pi * nu[0] * sig[-1][0]
    faces = r.r_f[1:-1] < 30.0
    return change, np.max(np.abs(mdot[faces] / mdot_in - 1)), r


def main():
    args = parse_args()
    checks = Checks()
    scene, _ = write_scene(args.workdir)
    changes, mdot_errs = [], []
    for n in (100, 200):
        out = os.path.join(args.workdir, f"steady_{n}.h5")
        p = run(args.exe, scene, out, [f"grid.n_cells={n}"])
        checks.check("alpha(r) gaussian from 0.0005" in p.stdout,
                     f"N = {n}: the run header gives the range of alpha(r)")
        change, mdot_err, r = measure(out)
        dip = np.argmin(np.abs(r.r_c - R0))
        print(f"N = {n}: alpha at 10 au {r.disk['alpha'][dip]:.3e}; inside 30 au after "
              f"0.5 Myr nu Sigma_g changed by at most {change:.2e}, Mdot(r) departs from "
              f"Mdot(r_in) by at most {mdot_err:.2e}")
        changes.append(change)
        mdot_errs.append(mdot_err)
        checks.check(abs(r.disk["alpha"][dip] / (ALPHA0 * (1 + A)) - 1) < 0.01,
                     f"N = {n}: the output's alpha has the dip")
    for name, e in (("nu Sigma_g", changes), ("Mdot(r)", mdot_errs)):
        checks.check(e[1] < e[0] and e[1] < 1e-4,
                     f"{name}: steady to {e[0]:.1e} (N = 100), {e[1]:.1e} (N = 200) < 1e-4")
    out = os.path.join(args.workdir, "control.h5")
    run(args.exe, scene, out, ["grid.n_cells=100", 'disk.alpha_profile="constant"'])
    change, mdot_err, _ = measure(out)
    print(f"control, alpha constant: nu Sigma_g changed by {change:.2e}, Mdot(r) by {mdot_err:.2e}")
    checks.check(change > 0.1 and mdot_err > 0.1,
                 "the control with alpha constant leaves the steady state (> 10 %)")
    checks.finish()


if __name__ == "__main__":
    main()
