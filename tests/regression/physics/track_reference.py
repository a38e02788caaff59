"""Independent reference for the Lagrangian track of physics-spec §13.

A single particle, released as an ice monomer (m = m0, phi = 1) at r0, is followed along
its drift path dr/dt = v_r (spec §3.2, §6.1, static gas) with the local growth model of
spec §2-§4: MMSN gas (§1, §12), no erosion, alpha = 1e-3, eps = 0.5, s_hs = -0.58,
rho0 = 1.4, E_roll = 4.74e-9 erg (§0), Sigma_d = 0.01 Sigma_g(r) along the path. The
script reports where and when its radius reaches a = 1 km and prints that next to the
numbers quoted in spec §13.

Written from the spec alone (numpy only, no code shared with the C++ under physics/).
By default every regime change is a HARD switch, exactly as the spec writes it:

  * drag (§2):            St = St_Ep max(1, x/f_Re),  f_Re = max(1, Re_p^0.4, 0.01833 Re_p),
                          solved for the implicit Re_p(St) to round-off (bracketed root),
  * turbulence (§3.5):    OC07 piecewise at St1 = St_eta and St1 = 1,
  * compression (§4.3):   slope s = s_hs if E_imp <= 3 b E_roll, else -1/8 (Epstein, St < 1),
                          0 (Stokes, St < 1), -1/5 (St >= 1),
  * filling factor (§4.4): phi = min(phi_max, max(phi_dyn, phi_gas, phi_grav)), with
                          d ln phi_dyn / d ln m = s and phi_dyn reset up to the floor
                          whenever the floor exceeds it (irreversible compaction).

`--smooth` switches on, instead, the smooth forms that an implicit (CVODE) code needs and
that the C++ implementation uses (p = 8 soft-max drag, +-0.1 dex logistic blends in OC07
and in the slopes, soft-max floor, and the ODE form of §4.4,
  d ln phi/dt = s d ln m/dt + softplus_k(ln phi_floor - ln phi) / t_relax,
  softplus_k(z) = ln(1 + e^(k z))/k, t_relax = 0.01 min(t_grow, 1/Omega), k = --k-softplus).
`--smooth-only NAME[,NAME]` / `--hard-only NAME[,NAME]` switch single elements, to measure
what each one does to the end point (names: drag, oc07, slopes, floor, relax).

Findings (2026-11, fiducial scene):
  * hard switches: r(1 km) within 0.8% and t within 2.8% of every §13 number (f_grow 1, 0.3);
  * --smooth reproduces `panoptic track` to 3-4 digits (k = 10: the build of 2026-11-23
    00:11; k = 100: the later one), so C++ and this script evaluate the same laws;
  * of the smoothings, only the softplus relaxation moves the end point: its tail pushes
    phi above the floor at a rate ~ e^(k z)/(k t_relax), which with t_relax << t_grow holds
    phi at ~(1/k) ln(1/(k |s| t_relax/t_grow)) above ln phi_floor: x2.0-2.2 for k = 10
    (r -2% at 4 au ... -16% at 80 au), x1.05 for k = 100 (r -1%), < 0.2% for k = 1000.
    Drag soft-max, OC07 blends, slope blends and the soft floor: |dr/r| < 0.2%.

Integration: explicit RK4 in the hard mode (no stiffness: the floor is algebraic, applied
after each step); a 2-stage L-stable Rosenbrock method (ROS2) when the relaxation is on (it
is stiff). Steps are limited to d ln m <= 0.01 (default), d ln r <= 0.002 and
d ln phi <= 0.01, which converges the end point to < 0.05% (check with --dlnm 0.003).

Usage:
  /usr/bin/python3 tests/regression/physics/track_reference.py [--f-grow 0.3] [--r0 4,6,10,20,50,80]
      [--smooth | --smooth-only relax,... | --smooth --hard-only relax] [--k-softplus 10]
      [--cap-phi-dyn] [--dlnm 0.01] [--dump R0]   (--dump: the track, one row per step)
"""
import argparse
import math
import sys

import numpy as np

# ------------------------------------------------------------------------------------------
# Constants (spec §1.1) and scene parameters (spec §0, §10.1, §13)
# ------------------------------------------------------------------------------------------
G = 6.674e-8
MSUN = 1.989e33
AU = 1.496e13
KB = 1.3807e-16
MH = 1.6735e-24
YR = 3.156e7
MU = 2.34
SIGMA_MOL = 2e-15  # §1.6

SIGMA1, P_SIG = 1700.0, 1.5  # §1.2 (A) MMSN
T1, Q_T = 280.0, 0.5  # §1.3
ALPHA = 1e-3  # §1.5
Z_DUST = 0.01  # §13: Sigma_d = 0.01 Sigma_g(r)

A0 = 1e-5  # §0 monomer radius [cm]
RHO0 = 1.4  # §0 ice, as in Okuzumi 2012
GAMMA_ICE, XI_CRIT = 100.0, 8e-8
E_ROLL = 6.0 * math.pi**2 * GAMMA_ICE * A0 * XI_CRIT  # §0, R_r = a0 -> 4.74e-9 erg
M0 = 4.0 * math.pi / 3.0 * A0**3 * RHO0  # §2 -> 5.86e-15 g

EPS = 0.5  # §3 partner size ratio
Y_A = 1.6  # §3.5 OC07
S_HS = -0.58  # §4.3
B_COMP = 0.15  # §4.2
PHI_MAX = 0.5  # §4.3

A_STOP = 1e5  # §13: a = 1 km

# spec §13 reference numbers: r0 -> (r [au], t [yr]) where a reaches 1 km
SPEC_13 = {
    1.0: {4: (3.7, 2.0e3), 6: (5.2, 4.7e3), 10: (7.2, 1.3e4), 20: (9.6, 4.4e4),
          50: (11.3, 2.1e5), 80: (11.8, 4.6e5)},
    0.3: {4: (3.2, 6.7e3), 10: (5.0, 4.1e4), 80: (6.0, 1.5e6)},
}

# smooth-switch parameters (only with --smooth; the forms suggested in §2, §3.5, §4.4)
P_SOFT = 8.0  # §2 p-norm soft-max
BLEND_DEX = 0.1  # §3.5 logistic over +-0.1 dex
K_SOFTPLUS = 10.0  # §4.4 softplus sharpness (the C++ value)
RELAX_FRAC = 0.01  # §4.4 t_relax = 0.01 min(t_grow, 1/Omega)
SMOOTH_ELEMENTS = ("drag", "oc07", "slopes", "floor", "relax")


# ------------------------------------------------------------------------------------------
# Gas (spec §1.3-§1.6)
# ------------------------------------------------------------------------------------------
class Gas:
    """Midplane gas at radius r [cm] of the MMSN of spec §1.2 (A), §1.3-§1.6."""

    def __init__(self, r):
        r_au = r / AU
        self.sigma_g = SIGMA1 * r_au ** (-P_SIG)
        self.T = max(T1 * r_au ** (-Q_T), 10.0)
        self.cs = math.sqrt(KB * self.T / (MU * MH))
        self.vth = math.sqrt(8.0 / math.pi) * self.cs
        self.om = math.sqrt(G * MSUN / r**3)
        self.vk = self.om * r
        self.H = self.cs / self.om
        self.rho_g = self.sigma_g / (math.sqrt(2.0 * math.pi) * self.H)
        self.lam = MU * MH / (SIGMA_MOL * self.rho_g)
        self.nu = 0.5 * self.vth * self.lam
        dlnp = -(P_SIG + 1.5 + Q_T / 2.0)  # §1.4: -3.25 for the MMSN
        self.eta = -0.5 * (self.H / r) ** 2 * dlnp
        self.vhw = self.eta * self.vk  # headwind, 53.9 m/s
        self.re = ALPHA * self.cs * self.H / self.nu  # §1.5
        self.st_eta = self.re ** -0.5  # §3.5
        self.sigma_d = Z_DUST * self.sigma_g


# ------------------------------------------------------------------------------------------
# Smooth helpers (only used for the --smooth elements)
# ------------------------------------------------------------------------------------------
def soft_max(a, b, p=P_SOFT):
    """p-norm (a^p + b^p)^(1/p), written without overflow (§2)."""
    hi, lo = (a, b) if a >= b else (b, a)
    return hi * (1.0 + (lo / hi) ** p) ** (1.0 / p)


def soft_min(a, b, p=P_SOFT):
    return a * b / soft_max(a, b, p)


def log_step(x, x0, w=BLEND_DEX):
    """Logistic step in ln x: 0.05 at x0 10^-w, 0.5 at x0, 0.95 at x0 10^w (§3.5)."""
    k = math.log(19.0) / (w * math.log(10.0))
    z = k * math.log(x / x0)
    if z >= 0:
        return 1.0 / (1.0 + math.exp(-z))
    e = math.exp(z)
    return e / (1.0 + e)


def softplus(z, k):
    kz = k * z
    return z if kz > 30.0 else math.log1p(math.exp(kz)) / k


# ------------------------------------------------------------------------------------------
# Particle (spec §2)
# ------------------------------------------------------------------------------------------
def radius(m, phi):
    """a = (3 m / (4 pi rho0 phi))^(1/3) (§2)."""
    return (3.0 * m / (4.0 * math.pi * RHO0 * phi)) ** (1.0 / 3.0)


def dv_pg(St, gas):
    """Particle-gas speed eta v_K St sqrt(4 + St^2)/(1 + St^2) (§2)."""
    return gas.vhw * St * math.sqrt(4.0 + St * St) / (1.0 + St * St)


def drag_factor(x, re_p, smooth):
    """g = St/St_Ep = max(1, x/f_Re), f_Re = max(1, Re_p^0.4, 0.01833 Re_p) (§2);
    smooth: the p = 8 norms of the same maxima."""
    if smooth:
        f = (1.0 + re_p ** (0.4 * P_SOFT) + (re_p * 0.44 / 24.0) ** P_SOFT) ** (1.0 / P_SOFT)
        return soft_max(1.0, x / f)
    f = max(1.0, re_p**0.4, 0.44 / 24.0 * re_p)
    return max(1.0, x / f)


def stokes(m, phi, gas, smooth=False):
    """Stokes number (§2, Re_p-dependent law): the root of
    u = ln St_Ep + ln g(x, Re_p(e^u)),  Re_p = 2 a dv_pg(St) / nu_mol,
    found by bracketed bisection/secant (the map is monotone: dG/du in [0.88, 2])."""
    a = radius(m, phi)
    st_ep = phi * RHO0 * a * gas.om / (gas.rho_g * gas.vth)  # Epstein, t_s Omega
    x = 4.0 * a / (9.0 * gas.lam)
    if x < 0.3:  # Epstein throughout (g = 1 to < 1e-4 even when smooth)
        return st_ep
    lse = math.log(st_ep)

    def resid(u):
        st = math.exp(u)
        re_p = 2.0 * a * dv_pg(st, gas) / gas.nu
        return u - lse - math.log(drag_factor(x, re_p, smooth))

    lo = lse - 1e-12  # g >= 1 -> resid(lo) <= 0
    hi = lse + math.log(drag_factor(x, 0.0, smooth)) + 1e-12  # Re_p = 0 -> resid(hi) >= 0
    flo, fhi = resid(lo), resid(hi)
    for _ in range(200):  # Illinois regula falsi with a bisection fall-back
        if hi - lo < 1e-13:
            break
        u = hi - fhi * (hi - lo) / (fhi - flo) if fhi != flo else 0.5 * (lo + hi)
        if not (lo < u < hi):
            u = 0.5 * (lo + hi)
        fu = resid(u)
        if fu == 0.0:
            return math.exp(u)
        if (fu < 0) == (flo < 0):
            lo, flo = u, fu
            fhi *= 0.5
        else:
            hi, fhi = u, fu
            flo *= 0.5
    return math.exp(0.5 * (lo + hi))


def h_dust(St, gas):
    """h_d = H [1 + (St/alpha)(1 + 2 St)/(1 + St)]^(-1/2) (§2, Youdin & Lithwick 2007)."""
    return gas.H / math.sqrt(1.0 + St / ALPHA * (1.0 + 2.0 * St) / (1.0 + St))


# ------------------------------------------------------------------------------------------
# Relative velocities (spec §3)
# ------------------------------------------------------------------------------------------
def beta_oc07(e):
    return 2.0 * Y_A - (1.0 + e) + 2.0 / (1.0 + e) * (1.0 / (1.0 + Y_A) + e**3 / (Y_A + e))


def dv2_turb(st1, st2, gas, smooth=False):
    """OC07 closed forms (§3.5), st1 >= st2, V_g^2 = alpha c_s^2; piecewise (hard) or with
    the +-0.1 dex logistic blends at St_eta and at 1 (smooth)."""
    vg2 = ALPHA * gas.cs**2
    se = gas.st_eta
    tight = (st1 - st2) / (st1 + st2) * (st1**2 / (st1 + se) - st2**2 / (st2 + se))
    inter = beta_oc07(st2 / st1) * st1
    heavy = 1.0 / (1.0 + st1) + 1.0 / (1.0 + st2)
    if smooth:
        w_eta, w_one = log_step(st1, se), log_step(st1, 1.0)
        return vg2 * ((1 - w_eta) * tight + w_eta * ((1 - w_one) * inter + w_one * heavy))
    if st1 < se:
        return vg2 * tight
    if st1 < 1.0:
        return vg2 * inter
    return vg2 * heavy


def dv_components(m, St, gas, smooth_oc07=False):
    """Squared components of dv(St, eps St) (§3, pair convention m2 = eps^3 m)."""
    st1, st2 = St, EPS * St
    m1, m2 = m, EPS**3 * m
    b2 = 8.0 * KB * gas.T * (m1 + m2) / (math.pi * m1 * m2)
    vr = lambda s: -2.0 * s * gas.vhw / (1.0 + s * s)  # noqa: E731
    vphi = lambda s: -gas.vhw / (1.0 + s * s)  # noqa: E731
    vz = lambda s: h_dust(s, gas) * gas.om * s / (1.0 + s)  # noqa: E731
    return {
        "brown": b2,
        "rad": (vr(st1) - vr(st2)) ** 2,
        "azi": (vphi(st1) - vphi(st2)) ** 2,
        "vert": (vz(st1) - vz(st2)) ** 2,
        "turb": dv2_turb(st1, st2, gas, smooth_oc07),
    }


# ------------------------------------------------------------------------------------------
# Growth and filling factor (spec §4)
# ------------------------------------------------------------------------------------------
def compression_slope(m, a, St, dv, gas, smooth):
    """d ln phi_dyn / d ln m (§4.3), E_imp = m dv^2/4 against 3 b E_roll (§4.2)."""
    e_imp = 0.25 * m * dv * dv
    x = 4.0 * a / (9.0 * gas.lam)
    if smooth:
        w_c, w_s, w_h = log_step(e_imp, 3 * B_COMP * E_ROLL), log_step(x, 1.0), log_step(St, 1.0)
        s_c = (1 - w_h) * (1 - w_s) * (-0.125) + w_h * (-0.2)
        return (1 - w_c) * S_HS + w_c * s_c
    if e_imp <= 3.0 * B_COMP * E_ROLL:
        return S_HS
    if St >= 1.0:
        return -0.2
    return -0.125 if x < 1.0 else 0.0


def phi_floor(m, St, gas, smooth):
    """max(phi_gas, phi_grav), capped at phi_max (§4.3, §4.4)."""
    n = m / M0
    phi_gas = (A0 * M0 * dv_pg(St, gas) * gas.om / (math.pi * E_ROLL * St)) ** (3.0 / 7.0) * n ** (1.0 / 7.0)
    phi_grav = (G * M0**2 / (math.pi * A0 * E_ROLL)) ** 0.6 * n**0.4
    if smooth:
        return soft_min(soft_max(phi_gas, phi_grav), PHI_MAX)
    return min(max(phi_gas, phi_grav), PHI_MAX)


class Model:
    """The track ODE; `smooth` is the set of smooth elements switched on."""

    def __init__(self, f_grow=1.0, smooth=(), k_softplus=K_SOFTPLUS, relax_frac=RELAX_FRAC,
                 cap_phi_dyn=False):
        self.cap_phi_dyn = cap_phi_dyn
        self.f_grow = f_grow
        self.smooth = set(smooth)
        self.k_softplus = k_softplus
        self.relax_frac = relax_frac

    def local(self, r, lnm, lnphi):
        """All local quantities of the particle at r; lnphi is ln phi_dyn in the hard mode
        (phi = min(phi_max, phi_dyn), phi_dyn >= floor after project()), ln phi with 'relax'."""
        gas = Gas(r)
        m = math.exp(lnm)
        phi = math.exp(lnphi) if "relax" in self.smooth else min(PHI_MAX, math.exp(lnphi))
        a = radius(m, phi)
        St = stokes(m, phi, gas, "drag" in self.smooth)
        hd = h_dust(St, gas)
        comp = dv_components(m, St, gas, "oc07" in self.smooth)
        dv = math.sqrt(sum(comp.values()))
        dmdt = self.f_grow * 2.0 * math.sqrt(math.pi) * a * a * dv * gas.sigma_d / hd  # §4.1
        s = compression_slope(m, a, St, dv, gas, "slopes" in self.smooth)
        floor = phi_floor(m, St, gas, "floor" in self.smooth)
        vr = -2.0 * St * gas.vhw / (1.0 + St * St)  # §3.2, §6.1
        return dict(gas=gas, m=m, phi=phi, a=a, St=St, hd=hd, dv=dv, comp=comp, dmdt=dmdt,
                    dlnm=dmdt / m, s=s, floor=floor, vr=vr)

    def rhs(self, y):
        """y = (r, ln m, ln phi): d/dt. In the hard mode ln phi is ln phi_dyn (its floor is
        applied by the caller); with 'relax' the floor enters as the §4.4 relaxation."""
        q = self.local(*y)
        dlnphi = q["s"] * q["dlnm"]
        if "relax" in self.smooth:
            t_relax = self.relax_frac * soft_min(1.0 / q["dlnm"], 1.0 / q["gas"].om)
            dlnphi += softplus(math.log(q["floor"]) - y[2], self.k_softplus) / t_relax
        return np.array([q["vr"], q["dlnm"], dlnphi]), q


def project(model, y):
    """Hard §4.4: phi = min(phi_max, max(phi_dyn, floor)), and phi_dyn is reset up to the
    floor whenever the floor exceeds it (irreversible compaction). The floor depends on St,
    hence on phi: the reset is iterated to its fixed point. phi_dyn itself is not capped
    (a monomer has phi_dyn = 1 and is used with phi = phi_max), unless cap_phi_dyn."""
    if "relax" in model.smooth:
        return y
    y = y.copy()
    for _ in range(20):
        lf = math.log(model.local(*y)["floor"])
        if y[2] >= lf - 1e-12 or lf >= math.log(PHI_MAX):
            break
        y[2] = lf
    if model.cap_phi_dyn:
        y[2] = min(y[2], math.log(PHI_MAX))
    return y


def track(r0_au, model, dlnm_max=0.01, dlnr_max=0.002, t_max=1e8 * YR, record=False):
    """Integrates from a monomer at r0 until a = 1 km; returns (r [au], t [yr], rows)."""
    y = np.array([r0_au * AU, math.log(M0), 0.0])
    t = 0.0
    stiff = "relax" in model.smooth
    rows = []
    f, q = model.rhs(y)
    while t < t_max:
        if record:
            rows.append((t, q))
        # step: d ln m <= dlnm_max, |d ln r| <= dlnr_max, |d ln phi| <= dlnm_max
        rates = [abs(f[1]) / dlnm_max, abs(f[0] / y[0]) / dlnr_max, abs(f[2]) / dlnm_max]
        if stiff:  # the relaxation term is handled implicitly; limit by the s-term only
            rates[2] = abs(q["s"] * q["dlnm"]) / dlnm_max
        dt = 1.0 / max(max(rates), 1e-300)
        y_new = ros2_step(model, y, f, dt) if stiff else rk4_step(model, y, f, dt)
        y_new = project(model, y_new)
        f_new, q_new = model.rhs(y_new)
        if q_new["a"] >= A_STOP:  # interpolate in ln a
            w = math.log(A_STOP / q["a"]) / math.log(q_new["a"] / q["a"])
            r_stop = y[0] + w * (y_new[0] - y[0])
            if record:
                rows.append((t + dt, q_new))
            return r_stop / AU, (t + w * dt) / YR, rows
        y, f, q, t = y_new, f_new, q_new, t + dt
        if y[0] < 1.0 * AU:
            break
    return float("nan"), float("nan"), rows


def rk4_step(model, y, f, dt):
    k1 = f
    k2, _ = model.rhs(y + 0.5 * dt * k1)
    k3, _ = model.rhs(y + 0.5 * dt * k2)
    k4, _ = model.rhs(y + dt * k3)
    return y + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)


def ros2_step(model, y, f, dt):
    """2-stage L-stable Rosenbrock (ROS2, Verwer et al. 1999), finite-difference Jacobian."""
    gam = 1.0 + 1.0 / math.sqrt(2.0)
    J = np.empty((3, 3))
    for j in range(3):
        h = 1e-6 * max(abs(y[j]), 1.0)
        yp = y.copy()
        yp[j] += h
        J[:, j] = (model.rhs(yp)[0] - f) / h
    W = np.eye(3) - gam * dt * J
    k1 = np.linalg.solve(W, f)
    f2, _ = model.rhs(y + dt * k1)
    k2 = np.linalg.solve(W, f2 - 2.0 * k1)
    return y + dt * (1.5 * k1 + 0.5 * k2)


# ------------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--f-grow", type=float, default=1.0, help="growth-rate multiplier (§4.1)")
    ap.add_argument("--r0", default=None, help="release radii [au], comma separated")
    ap.add_argument("--smooth", action="store_true", help="all smooth elements (C++-like)")
    ap.add_argument("--smooth-only", default="", help="switch on only these smooth elements")
    ap.add_argument("--hard-only", default="", help="with --smooth: keep these elements hard")
    ap.add_argument("--k-softplus", type=float, default=K_SOFTPLUS,
                    help="with relax smooth: softplus sharpness k of §4.4 (C++: 10)")
    ap.add_argument("--relax-frac", type=float, default=RELAX_FRAC,
                    help="with relax smooth: t_relax = FRAC min(t_grow, 1/Omega) (§4.4: 0.01)")
    ap.add_argument("--cap-phi-dyn", action="store_true",
                    help="hard mode: cap phi_dyn itself at phi_max (the monomer starts at 0.5)")
    ap.add_argument("--dlnm", type=float, default=0.01, help="max d ln m per step")
    ap.add_argument("--dump", type=float, default=None, help="print the track for this r0")
    args = ap.parse_args()

    smooth = set(SMOOTH_ELEMENTS) if args.smooth else set()
    smooth |= {s for s in args.smooth_only.split(",") if s}
    smooth -= {s for s in args.hard_only.split(",") if s}
    bad = smooth - set(SMOOTH_ELEMENTS)
    if bad:
        sys.exit(f"unknown smooth element(s) {sorted(bad)}; choose from {SMOOTH_ELEMENTS}")
    spec = SPEC_13.get(args.f_grow, {})
    r0s = [float(s) for s in args.r0.split(",")] if args.r0 else sorted(spec) or [4, 6, 10, 20, 50, 80]
    model = Model(args.f_grow, smooth, args.k_softplus, args.relax_frac, args.cap_phi_dyn)

    if args.dump is not None:
        _, _, rows = track(args.dump, model, args.dlnm, record=True)
        print("# t[yr] r[au] m[g] phi a[cm] St dv[cm/s] dm/dt[g/s] v_r[cm/s] s floor")
        for t, q in rows[:: max(1, len(rows) // 400)] + rows[-1:]:
            print(f"{t / YR:.6e} {_r_of(q):.6e} {q['m']:.6e} {q['phi']:.6e} {q['a']:.6e} "
                  f"{q['St']:.6e} {q['dv']:.6e} {q['dmdt']:.6e} {q['vr']:.6e} {q['s']:.4f} "
                  f"{q['floor']:.6e}")
        return

    label = "hard switches (spec as written)" if not smooth else "smooth: " + ",".join(sorted(smooth))
    print(f"# physics-spec §13 track, independent Python reference; f_grow = {args.f_grow:g}; {label}")
    print(f"# {'r0 [au]':>8} {'r_spec':>8} {'r_here':>8} {'dr/r':>7} {'t_spec [yr]':>12} {'t_here [yr]':>12} {'dt/t':>7}")
    for r0 in r0s:
        r, t, _ = track(r0, model, args.dlnm)
        rs, ts = spec.get(int(r0) if r0 == int(r0) else r0, (float("nan"), float("nan")))
        print(f"  {r0:8g} {rs:8.2f} {r:8.3f} {r / rs - 1:+7.1%} {ts:12.3g} {t:12.4g} {t / ts - 1:+7.1%}")


def _r_of(q):
    """Radius [au] of a local-state record (recovered from Omega_K)."""
    return (G * MSUN / q["gas"].om ** 2) ** (1.0 / 3.0) / AU


if __name__ == "__main__":
    main()
