"""Dust trapped in a static Gaussian pressure bump (growth off, St prescribed) against the
drift-diffusion balance of Dullemond et al. (2018, ApJL 869, L46, §3.1, DSHARP VI): in a
bump P ∝ exp(-(r - r0)^2 / (2 w^2)) the dust settles into a Gaussian ring of width
    w_d = w sqrt(alpha / (alpha + St)).
Their derivation: zero net dust flux, drift v = St (c_s^2/Omega) dlnP/dr (St << 1) against
diffusion D_d = alpha c_s^2/Omega with the gas as the reference, so Sigma_d/Sigma_g ∝
P^(St/alpha). panoptic's v_r and D_d (spec §6.1) carry the same 1/(1 + St^2), which
cancels, so the balance holds at any St; their other approximations (Sigma_g and the
pressure bump of one width, c_s and Omega constant across the ring) are made exact here:
the disk is a table (disk.model = "table") with T ∝ r^3, so that c_s Omega is constant
and P ∝ Sigma_g, and Sigma_g is the Gaussian itself. Sigma_d is then exactly Gaussian with
width w_d; what remains is the grid's truncation error. Measured: the second moment of
Sigma_d(r) for three (alpha, St) pairs at N = 50, 100, 200 cells over 6-14 au (w = 1 au):
the error must fall with N, as a second-order scheme's does (at least by 8x from N = 50
to 200: the order >= 1.5), and at N = 200 be below 0.5 %.
With alpha(r) (disk.alpha_profile = "gaussian", a bump of alpha beside the pressure
maximum) the same balance gives Sigma_d/Sigma_g = exp(int St/alpha(r) dlnP/dr dr): the
ring is lopsided, wider and shifted outward where alpha is larger. Its width and centre,
integrated from that formula, against the runs: the dust diffusion must follow alpha(r)
(predicted 0.397 au and 10.087 au; with alpha_0 everywhere 0.302 au and 10.000 au)."""
import os

import numpy as np

from common import Checks, load_run, parse_args, run

R0, W = 10.0, 1.0          # bump centre and width [au]
R_IN, R_OUT = 6.0, 14.0    # grid [au]: +-4 w, the ring cut off at > 5.6 w_d


# the alpha(r) case: alpha_0 [1 + A exp(-(r - ra)^2 / (2 wa^2))]
ALPHA_BUMP = (2.0, 10.5, 0.5)


def write_scene(workdir, alpha, st, t_end, alpha_bump=None):
    r = np.linspace(5.9, 14.1, 2000)
    sigma = 100.0 * np.exp(-(r - R0) ** 2 / (2 * W * W))
    temp = 50.0 * (r / R0) ** 3   # c_s Omega ∝ sqrt(T) r^-3/2 constant: P ∝ Sigma_g
    with open(os.path.join(workdir, "bump.csv"), "w") as f:
        f.write("r_au,sigma_g_gcm2,T_K\n")
        for a, b, c in zip(r, sigma, temp):
            f.write(f"{a:.17g},{b:.17g},{c:.17g}\n")
    path = os.path.join(workdir, f"ring_{alpha:g}_{st:g}{'_bump' if alpha_bump else ''}.toml")
    profile = ""
    if alpha_bump:
        profile = ("alpha_profile = \"gaussian\"\nalpha_bump_amplitude = {!r}\n"
                   "alpha_bump_r_au = {!r}\nalpha_bump_width_au = {!r}\n").format(*alpha_bump)
    with open(path, "w") as f:
        f.write(f"""[disk]
model = "table"
table_file = "bump.csv"
alpha = {alpha!r}
{profile}[transport]
St = {st!r}
advection = "van_leer"
[grid]
r_in_au = {R_IN}
r_out_au = {R_OUT}
[output]
t_end_yr = {t_end:g}
n_snapshots = 2
[snowline]
enabled = false
""")
    return path


def ring_width(path):
    r = load_run(path)
    rc, dr = r.r_c, np.diff(r.r_f)
    s = r.snapshots["sigma_d"][-1]
    m0 = np.sum(s * dr)
    mean = np.sum(s * rc * dr) / m0
    return np.sqrt(np.sum(s * (rc - mean) ** 2 * dr) / m0), mean


def predicted_ring(alpha0, st, bump):
    """Width and centre [au] of Sigma_d = Sigma_g exp(int St/alpha(r) dlnP/dr dr) with
    P ∝ Sigma_g ∝ exp(-(r - R0)^2 / (2 W^2)), on a fine grid over the run's domain."""
    r = np.linspace(R_IN, R_OUT, 400001)
    a, ra, wa = bump
    alpha = alpha0 * (1 + a * np.exp(-(r - ra) ** 2 / (2 * wa * wa)))
    slope = st / alpha * (-(r - R0) / W ** 2)      # d ln(Sigma_d/Sigma_g)/dr
    f = np.concatenate(([0.0], np.cumsum(0.5 * (slope[1:] + slope[:-1]) * np.diff(r))))
    s = np.exp(-(r - R0) ** 2 / (2 * W * W) + f - f.max())
    m0 = np.trapz(s, r)
    mean = np.trapz(s * r, r) / m0
    return np.sqrt(np.trapz(s * (r - mean) ** 2, r) / m0), mean


def main():
    args = parse_args()
    c = Checks()
    ns = [50, 100, 200]
    for alpha, st in [(1e-3, 1e-2), (1e-3, 1e-3), (1e-2, 3e-2)]:
        w_d = W * np.sqrt(alpha / (alpha + st))
        # relaxation: the ring's variance approaches w_d^2 as exp(-2 k t), k = (St +
        # alpha) c_s^2 / (Omega w^2) at the centre; 30 e-folds
        cs2_over_omega = 1.380649e-16 * 50.0 / (2.34 * 1.6735e-24) / (2 * np.pi / (
            R0 ** 1.5 * 3.156e7))
        k = (st + alpha) * cs2_over_omega / (W * 1.496e13) ** 2
        t_end = 15.0 / k / 3.156e7
        scene = write_scene(args.workdir, alpha, st, t_end)
        errs = []
        for n in ns:
            out = os.path.join(args.workdir, f"ring_{alpha:g}_{st:g}_{n}.h5")
            run(args.exe, scene, out, [f"grid.n_cells={n}"])
            width, mean = ring_width(out)
            errs.append(abs(width / w_d - 1.0))
            print(f"alpha = {alpha:g}, St = {st:g}, N = {n:3d}: ring width {width:.5f} au "
                  f"(w_d = {w_d:.5f} au, relative error {errs[-1]:.2e}), centre {mean:.4f} au")
        c.check(all(errs[i + 1] < errs[i] for i in range(len(ns) - 1)),
                f"alpha = {alpha:g}, St = {st:g}: the width error falls with resolution "
                f"({', '.join(f'{e:.1e}' for e in errs)})")
        order = np.log(errs[0] / errs[-1]) / np.log(ns[-1] / ns[0])
        c.check(order >= 1.5,
                f"alpha = {alpha:g}, St = {st:g}: convergence order {order:.2f} >= 1.5")
        c.check(errs[-1] < 0.005,
                f"alpha = {alpha:g}, St = {st:g}: N = {ns[-1]} width within 0.5 % of w_d "
                f"({errs[-1]:.2e})")
    # alpha(r): the lopsided ring
    alpha, st = 1e-3, 1e-2
    width_p, mean_p = predicted_ring(alpha, st, ALPHA_BUMP)
    width_0, mean_0 = predicted_ring(alpha, st, (0.0, R0, 1.0))
    print(f"alpha(r) bump at {ALPHA_BUMP[1]} au: predicted width {width_p:.5f} au, centre "
          f"{mean_p:.5f} au (alpha_0 everywhere: {width_0:.5f}, {mean_0:.5f})")
    k = st * 1.380649e-16 * 50.0 / (2.34 * 1.6735e-24) / (2 * np.pi / (
        R0 ** 1.5 * 3.156e7)) / (W * 1.496e13) ** 2
    scene = write_scene(args.workdir, alpha, st, 15.0 / k / 3.156e7, ALPHA_BUMP)
    errs = []
    for n in ns:
        out = os.path.join(args.workdir, f"ring_bump_{n}.h5")
        run(args.exe, scene, out, [f"grid.n_cells={n}"])
        width, mean = ring_width(out)
        errs.append(max(abs(width / width_p - 1), abs(mean - mean_p) / width_p))
        print(f"alpha(r), N = {n:3d}: width {width:.5f} au, centre {mean:.5f} au "
              f"(error {errs[-1]:.2e} of the width)")
    c.check(errs[-1] < errs[0] / 8 and errs[-1] < 0.005,
            f"alpha(r): width and centre as predicted ({', '.join(f'{e:.1e}' for e in errs)}"
            f"; < 0.5 % at N = {ns[-1]}, order >= 1.5)")
    c.finish()


if __name__ == "__main__":
    main()
