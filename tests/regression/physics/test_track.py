"""`panoptic track` against the Lagrangian reference tracks of spec §13: a monomer
released at r0 grows (no erosion, MMSN, alpha = 1e-3, eps = 0.5, s_hs = -0.58, rho0 = 1.4,
Sigma_d = 0.01 Sigma_g) until a = 1 km; where and when must agree with the spec's numbers
(computed independently of this code) to within their rounding (half a unit of the last
digit they quote: 0.05 au, and 0.05 in the mantissa of t, i.e. 0.4-3.8 % of the values) plus
0.5 % for the integration, at the nominal and at 0.3x growth rate. (The issue asks for
10 %; measured at most 0.83 % in r and 1.77 % in t.)"""
import math
import re
import subprocess

from common import REPO, Checks, parse_args

# r0 [au], growth multiplier, r at 1 km [au], t at 1 km [yr]  (spec §13)
SPEC = [(4, 1.0, 3.7, 2.0e3), (6, 1.0, 5.2, 4.7e3), (10, 1.0, 7.2, 1.3e4),
        (20, 1.0, 9.6, 4.4e4), (50, 1.0, 11.3, 2.1e5), (80, 1.0, 11.8, 4.6e5),
        (4, 0.3, 3.2, 6.7e3), (10, 0.3, 5.0, 4.1e4), (80, 0.3, 6.0, 1.5e6)]


def main():
    args = parse_args()
    c = Checks()
    print(f"{'r0':>4} {'f_grow':>6} {'r spec':>7} {'r':>7} {'t spec':>9} {'t':>9}")
    for r0, f, r_spec, t_spec in SPEC:
        p = subprocess.run([args.exe, "track", f"{REPO}/params/fiducial.toml", "--r0-au", str(r0),
                            "--set", f"growth.f_grow={f}"], capture_output=True, text=True)
        m = re.search(r"reached a = \S+ cm at t = (\S+) yr, r = (\S+) au", p.stdout)
        if p.returncode != 0 or not m:
            c.check(False, f"r0 = {r0}: track failed: {p.stdout[-300:]} {p.stderr}")
            continue
        t, r = float(m.group(1)), float(m.group(2))
        print(f"{r0:4d} {f:6.1f} {r_spec:7.2f} {r:7.2f} {t_spec:9.3g} {t:9.3g}")
        tol_r = 0.05 / r_spec + 0.005
        tol_t = 0.05 * 10 ** math.floor(math.log10(t_spec)) / t_spec + 0.005
        c.check(abs(r / r_spec - 1) < tol_r and abs(t / t_spec - 1) < tol_t,
                f"r0 = {r0} au, f_grow = {f}: r {100 * (r / r_spec - 1):+.2f} % (< "
                f"{100 * tol_r:.1f} %), t {100 * (t / t_spec - 1):+.2f} % (< {100 * tol_t:.1f} %) "
                f"of spec §13")
    c.finish()


if __name__ == "__main__":
    main()
