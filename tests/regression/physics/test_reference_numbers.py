"""Independent re-derivation of the reference numbers hard-coded in four unit tests:
tests/unit/physics/test_contact_mechanics.cpp, test_particle.cpp, test_relative_velocity.cpp and
test_growth_*.cpp (with the MMSN gas of tests/unit/support/mmsn_gas.hpp). Their comments say
the numbers were "worked out independently" by "a separate python3 script written from the
spec"; that script is not in the repository. This is such a script: everything below is
computed here from the formulas of the physics spec (physics/physics-spec.md, cited
by section) and, where the spec leaves a smooth blend open, from the form the headers
document (physics/drag.hpp: the p = 8 soft-max drag law; physics/relative_velocity.hpp:
the OC07 blends; physics/contact_mechanics.hpp: w = 2 gamma). The C++ is neither called
nor read; no output of it is used. numpy only (no scipy): St by bisection in ln St, peaks
by golden section, switch points by bisection in ln m.

How a number is compared. Each check names a literal as it is written in the test (e.g.
"0.20427797089107294") and the unique anchor of the test that holds it (its TEST name, or
the line of a file-scope constant); table rows are parsed field by field from the row that
starts with the given prefix. The script finds the literal in that test's block of the
.cpp file (so a test whose number changes, or a literal mistyped here, fails), parses it,
and compares it with the value computed here, within the tolerance the test asserts for it
(rel: |python/test - 1|; abs: |python - test|). A number the test only passes in as an
input (e.g. the python St handed to particle_rates) is held to 1e-9, the tolerance
test_particle.cpp asserts for the same python St values; closed forms quoted to 16 digits
to 1e-12. Numbers quoted only in comments ("digits") are held to one unit of their last
quoted digit (they are sometimes rounded, sometimes truncated: 57.808 for 57.8086, 21.5
for 21.55). Claims of a test (a bound, a regime: "E_imp > 1e9 x threshold", "x > 20")
are checked with the python numbers. Every check prints
"file:line [test] what: python X vs test Y". A comment-level discrepancy that is
understood (a comment number off beyond its digits while every asserted number agrees) is
printed as a NOTE with both values, and not failed; see NOTES in the output.

Called by CTest like the other regression scripts:
    /usr/bin/python3 tests/regression/physics/test_reference_numbers.py --exe build/panoptic --workdir DIR
(both arguments are accepted and ignored: nothing is run). Exit 1 if any check fails.

Observations made while writing this (all within the tests' tolerances):
* the tests' python used the hard ordering St1 >= St2 (eps = 0.5 exactly) in OC07; the
  soft ordering documented in physics/relative_velocity.hpp (p = 32), used here, moves
  dv_t^2 of the eps = 0.5 pair by 1e-11;
* it used C_D = 0.44 as 0.44/24 Re_p (spec: 0.01833 Re_p), see CD_NEWTON;
* SpecDerivedMagnitudes passes, for its two self-gravity rows, St(m, 1e-4) and
  St(m, 1e-5), not the St of a self-consistent state as its comment says (phi_grav does
  not depend on St).

Not covered (and why):
* test_relative_velocity.cpp, ContinuousAcrossRegimeBoundaries (the continuity
  tolerances), the AutoDiff tests; test_particle.cpp, the Newton/shortcut round-off tests,
  the AutoDiff tests, the log-space soft-max, log1p, tanh_step and log_step saturation
  tests and the continuity scans; test_growth_*.cpp, GrowthContinuity,
  GrowthAutoDiff, SoftStokesCap, GrowthMultiplier, Bouncing, RememberedLogs: bounds on
  jumps, round-off and derivatives of the C++ functions, not reference values. Checked of
  them: the numbers they quote that follow from the spec (k = 12.8 and 25.6, dv_pair never
  reaching 60 m/s at 5 AU, phi_grav(1e19 g) = 0.40, the switch masses of GrowthAutoDiff,
  the 0.05/0.95 points of log_step, 2^(1/8), the "measured maxima" 4.5 and 7.4 of the
  sampled log-slopes of dv, which the python law reproduces).
* test_growth_*.cpp, the ratios of particle_rates() asserted in GrowthErosionHalt,
  GrowthErosionBalance and GrowthFragmentation: the test computes those expectations at run
  time from the C++ dv_pair / dv_small_projectile and formulas written out in the test; the
  hard-coded inputs (St*, K_d, K_s, R_s/R_coag, the St of each state) are covered, and so
  are the numbers its comments quote.
* test_growth_*.cpp, the compaction push (PushFarBelowFloor, RelaxationCapped, ...):
  it depends on t_relax = 0.03 soft_min(t_grow, 100/Omega), a choice of the code
  (kRelaxFraction, kRelaxCapOmega; spec §4.4 has 0.01 min(t_grow, 1/Omega)); the floors
  (spec §4.3), the St and the t_grow Omega regimes of those tests are covered, and the test's
  own written-out t_relax() is used only for the comment magnitudes of LittleLeakAboveFloor.
* test_contact_mechanics.cpp, DefaultMaterials: the spec §0 material constants (inputs here).
"""
import glob
import math
import os
import re
import time

import numpy as np

from common import REPO, Checks, parse_args

T_START = time.time()

# -------------------------------------------------------------------------------------------
# Constants. cgs. Physical constants as the C++ has them: src/core/units.hpp, which are the
# values of spec §1.1 (the tests' python numbers were derived with these).
# -------------------------------------------------------------------------------------------
PI = 3.14159265358979323846  # units::kPi
G_GRAV = 6.674e-8            # units::kG, spec §1.1
M_SUN = 1.989e33             # units::kMsun, spec §1.1
AU = 1.496e13                # units::kAu, spec §1.1
K_B = 1.3807e-16             # units::kBoltzmann, spec §1.1
M_H = 1.6735e-24             # units::kMassH, spec §1.1
YR = 3.156e7                 # units::kYr, spec §1.1
MU = 2.34                    # spec §1.1 [C] (mmsn_gas.hpp)
SIGMA_MOL = 2e-15            # spec §1.6 [C] (mmsn_gas.hpp)
ALPHA = 1e-3                 # spec §1.5 fiducial (mmsn_gas.hpp)
DLNP_DLNR = -3.25            # spec §1.4, MMSN p = 1.5, q = 0.5 (mmsn_gas.hpp)
P_SOFT = 8.0                 # spec §2: p-norm soft max, p = 8 (physics/smooth_switches.hpp)
P_ORDER = 32.0               # soft (St_hi, St_lo) ordering, physics/relative_velocity.hpp
CD_NEWTON = 0.44 / 24.0      # spec §2: C_D = 0.44 = 24/Re_p * (0.01833 Re_p). The spec
#                              rounds 0.44/24 = 0.0183333 to 0.01833; the tests' numbers
#                              were made with 0.44/24 (with 0.01833 the C_D = 0.44 states
#                              of test_particle.cpp move by 1.0e-5 .. 1.5e-4, beyond 1e-9).
Y_A = 1.6                    # spec §3.5, OC07
BLEND_DEX = 0.1              # spec §3.5: logistic in ln St over +-0.1 dex
EPS_PAIR = 0.5               # spec §3 pair convention


# -------------------------------------------------------------------------------------------
# Gas, spec §1.2-1.6 (MMSN, as tests/unit/support/mmsn_gas.hpp builds it)
# -------------------------------------------------------------------------------------------
class Gas:
    def __init__(self, r_au):
        r = r_au * AU
        self.r = r
        self.sigma = 1700.0 * r_au ** -1.5                   # §1.2 (A)
        self.temp = 280.0 / math.sqrt(r_au)                  # §1.3
        self.cs = math.sqrt(K_B * self.temp / (MU * M_H))    # §1.3
        self.vth = math.sqrt(8.0 / PI) * self.cs             # §1.3
        self.omega = math.sqrt(G_GRAV * M_SUN / r ** 3)      # §1.3
        self.vk = self.omega * r
        self.h = self.cs / self.omega
        self.rho = self.sigma / (math.sqrt(2.0 * PI) * self.h)
        self.mfp = MU * M_H / (SIGMA_MOL * self.rho)         # §1.6
        self.nu = 0.5 * self.vth * self.mfp                  # §1.6
        self.eta = -0.5 * (self.h / r) ** 2 * DLNP_DLNR      # §1.4
        self.vw = self.eta * self.vk                         # headwind eta v_K
        self.alpha = ALPHA
        self.re = ALPHA * self.cs * self.h / self.nu         # §1.5
        self.st_eta = 1.0 / math.sqrt(self.re)               # §3.5


GAS_CACHE = {}



def table_row(ref, s, anchor, prefix):
    """The fields and line of the table row of test `anchor` that starts with `prefix`,
    or None (reported as a failed check) when there is no such row."""
    try:
        return s.row(anchor, prefix)
    except LookupError as e:
        ref._report(s, False, "?", anchor, "row", str(e))
        return None


def particle_row(ref, s, anchor, prefix, g):
    """A {m, phi, St, ...} row of test `anchor` (table_row), its St, which the test
    passes to the C++, checked against the St worked out here at (m, phi) to 1e-9:
    (fields, line, m, phi, St), or None."""
    got = table_row(ref, s, anchor, prefix)
    if got is None:
        return None
    f, line = got
    m, phi = float(f[0]), float(f[1])
    st = stokes(m, phi, g)
    ref.value(s, anchor, f[2], float(f[2]), line, st, 1e-9, "rel", f"St({f[0]} g, {f[1]})")
    return f, line, m, phi, st

def gas(r_au):
    if r_au not in GAS_CACHE:
        GAS_CACHE[r_au] = Gas(r_au)
    return GAS_CACHE[r_au]


# -------------------------------------------------------------------------------------------
# Monomers and contact mechanics, spec §0 (JKR/Tabor with w = 2 gamma, as
# physics/contact_mechanics.hpp documents; E_roll with gamma per surface)
# -------------------------------------------------------------------------------------------
ICE = dict(a0=1e-5, rho0=1.4, gamma=100.0, E=7e10, nu=0.25, xi=8e-8, z0=4e-8)
SIL = dict(a0=1e-5, rho0=3.0, gamma=25.0, E=5.4e11, nu=0.17, xi=8e-8, z0=4e-8)


def combined_modulus(e1, nu1, e2, nu2):
    return 1.0 / ((1 - nu1 ** 2) / e1 + (1 - nu2 ** 2) / e2)


def contact(mat, rr_factor=1.0):
    R = mat["a0"] / 2.0
    es = combined_modulus(mat["E"], mat["nu"], mat["E"], mat["nu"])
    w = 2.0 * mat["gamma"]
    return dict(
        R=R, e_star=es, w=w,
        a_eq=(9 * PI * w * R ** 2 / (2 * es)) ** (1 / 3),
        f_c=1.5 * PI * w * R,
        tabor=(R * w ** 2 / (es ** 2 * mat["z0"] ** 3)) ** (1 / 3),
        e_roll=6 * PI ** 2 * mat["gamma"] * rr_factor * mat["a0"] * mat["xi"],
        m0=4 * PI / 3 * mat["a0"] ** 3 * mat["rho0"])


def hertz_delta(a, R):
    return a * a / R


def hertz_force(a, R, es):
    return 4 * es * a ** 3 / (3 * R)


def jkr_delta(a, R, es, w):
    return a * a / R - math.sqrt(2 * PI * w * a / es)


def jkr_force(a, R, es, w):
    return 4 * es * a ** 3 / (3 * R) - math.sqrt(8 * PI * w * es * a ** 3)


# -------------------------------------------------------------------------------------------
# Numerical helpers
# -------------------------------------------------------------------------------------------
def bisect(f, lo, hi, n=300):
    """Root of f on [lo, hi] (f(lo), f(hi) of opposite sign), to the last bit."""
    flo = f(lo)
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        fm = f(mid)
        if (fm > 0) == (flo > 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


def log_root(f, x_lo, x_hi):
    """Root of f(x) = 0 by bisection in ln x."""
    return math.exp(bisect(lambda u: f(math.exp(u)), math.log(x_lo), math.log(x_hi)))


def golden_max(f, lo, hi, n=200):
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(n):
        c, d = hi - g * (hi - lo), lo + g * (hi - lo)
        if f(c) > f(d):
            hi = d
        else:
            lo = c
    return 0.5 * (lo + hi)


def soft_max(a, b, p=P_SOFT):
    """p-norm soft maximum (a^p + b^p)^(1/p) (spec §2)."""
    hi, lo = np.maximum(a, b), np.minimum(a, b)
    return hi * (1.0 + (lo / hi) ** p) ** (1.0 / p)


def soft_min(a, b, p=P_SOFT):
    return a * b / soft_max(a, b, p)


def log_step(x, x0, half_width_dex):
    """Logistic step in ln x: 0.5 at x0, 0.05/0.95 at x0 10^-+w (spec §3.5; the form
    physics/smooth_switches.hpp documents, 1 / (1 + (x0/x)^k), k = ln 19 / (w ln 10))."""
    k = math.log(19.0) / (half_width_dex * math.log(10.0))
    return 0.5 * (1.0 + np.tanh(0.5 * k * np.log(x / x0)))


# -------------------------------------------------------------------------------------------
# Particle, spec §2
# -------------------------------------------------------------------------------------------
RHO0 = 1.4  # ice monomers, spec §0/§12
A0 = 1e-5


def radius(m, phi, rho0=RHO0):
    return (3.0 * m / (4.0 * PI * rho0 * phi)) ** (1.0 / 3.0)


def st_epstein(a, rho_int, g):
    """t_s Omega with t_s = rho_int a / (rho_g v_th) (spec §2)."""
    return rho_int * a * g.omega / (g.rho * g.vth)


def dv_pg(st, g):
    """eta v_K St sqrt(4 + St^2) / (1 + St^2) (spec §2)."""
    return g.vw * st * math.sqrt(4.0 + st * st) / (1.0 + st * st)


def reynolds_p(a, st, g):
    return 2.0 * a * dv_pg(st, g) / g.nu


def ln_f_re(re):
    """ln of f_Re = soft_max_8(1, Re^0.4, 0.01833 Re) = (1 + Re^3.2 + (Re/54.5)^8)^(1/8)."""
    return math.log1p(re ** (0.4 * P_SOFT) + (CD_NEWTON * re) ** P_SOFT) / P_SOFT


def ln_g_drag(x, re):
    """ln g, g = soft_max_8(1, x / f_Re) (spec §2, smooth DiscEvolution form)."""
    y = P_SOFT * (math.log(x) - ln_f_re(re))
    return math.log1p(math.exp(y)) / P_SOFT if y < 700 else y / P_SOFT


def stokes(m, phi, g, rho0=RHO0, law="smooth"):
    """St(m, phi): Epstein, or the smooth law St = St_Ep g(x, Re_p(St)) solved by
    bisection in ln St (g >= 1, and g <= soft_max(1, x) since f_Re >= 1)."""
    a = radius(m, phi, rho0)
    st_ep = st_epstein(a, phi * rho0, g)
    if law == "epstein":
        return st_ep
    x = 4.0 * a / (9.0 * g.mfp)
    if law == "hard":  # spec §2 piecewise: max(1, x / max(1, Re^0.4, 0.01833 Re))
        def ln_g(u):
            re = reynolds_p(a, math.exp(u), g)
            f = max(1.0, re ** 0.4, CD_NEWTON * re)
            return math.log(max(1.0, x / f))
        hi = math.log(st_ep) + max(0.0, math.log(x))
    else:
        def ln_g(u):
            return ln_g_drag(x, reynolds_p(a, math.exp(u), g))
        hi = math.log(st_ep) + ln_g_drag(x, 0.0)
    lo = math.log(st_ep)
    if hi == lo:
        return st_ep
    return math.exp(bisect(lambda u: u - lo - ln_g(u), lo, hi))


def h_dust(st, g):
    """Youdin & Lithwick form (spec §2)."""
    return g.h / np.sqrt(1.0 + (st / g.alpha) * (1.0 + 2.0 * st) / (1.0 + st))


# -------------------------------------------------------------------------------------------
# Relative velocities, spec §3 (numpy-friendly: used on scalars and arrays)
# -------------------------------------------------------------------------------------------
def beta_oc07(eps, y_a=Y_A):
    return 2 * y_a - (1 + eps) + 2 / (1 + eps) * (1 / (1 + y_a) + eps ** 3 / (y_a + eps))


def dv2_turbulent(st1, st2, g, vg2_factor=1.0, mode="blend"):
    """OC07 closed forms (spec §3.5). mode "blend": the logistic blends over +-0.1 dex
    and the soft (p = 32) size ordering of physics/relative_velocity.hpp; "hard": the
    regimes as the spec states them (St1 < St_eta, St_eta <= St1 < 1, St1 >= 1)."""
    vg2 = vg2_factor * ALPHA * g.cs ** 2
    se = g.st_eta
    tight = (st1 - st2) / (st1 + st2) * (st1 ** 2 / (st1 + se) - st2 ** 2 / (st2 + se))
    heavy = 1.0 / (1.0 + st1) + 1.0 / (1.0 + st2)
    if mode == "blend":
        hi = soft_max(st1, st2, P_ORDER)
        lo = soft_min(st1, st2, P_ORDER)
        w_eta, w_one = log_step(hi, se, BLEND_DEX), log_step(hi, 1.0, BLEND_DEX)
    else:
        hi, lo = np.maximum(st1, st2), np.minimum(st1, st2)
        w_eta, w_one = 1.0 * (hi >= se), 1.0 * (hi >= 1.0)
    inter = beta_oc07(lo / hi) * hi
    return vg2 * ((1 - w_eta) * tight + w_eta * ((1 - w_one) * inter + w_one * heavy))


def dv2_parts(st1, st2, m1, m2, g, vg2_factor=1.0, mode="blend"):
    """Squared components (spec §3.1-3.5): Brownian, radial, azimuthal, vertical, turb."""
    brown = 8 * K_B * g.temp * (m1 + m2) / (PI * m1 * m2)
    vr = lambda s: -2 * s * g.vw / (1 + s * s)  # noqa: E731
    vphi = lambda s: -g.vw / (1 + s * s)  # noqa: E731
    vz = lambda s: h_dust(s, g) * g.omega * s / (1 + s)  # noqa: E731
    return (brown, (vr(st1) - vr(st2)) ** 2, (vphi(st1) - vphi(st2)) ** 2,
            (vz(st1) - vz(st2)) ** 2, dv2_turbulent(st1, st2, g, vg2_factor, mode))


def dv_total(st1, st2, m1, m2, g, vg2_factor=1.0, mode="blend"):
    return np.sqrt(sum(dv2_parts(st1, st2, m1, m2, g, vg2_factor, mode)))


def dv_pair(st, m, g, mode="blend"):
    """dv(St, eps St) with m2 = eps^3 m (spec §3 pair convention)."""
    return dv_total(st, EPS_PAIR * st, m, EPS_PAIR ** 3 * m, g, mode=mode)


def dv_small(st, m, st_s, m_s, g, mode="blend"):
    """Speed against small projectiles (St_s, m_s) (spec §3)."""
    return dv_total(st, st_s, m, m_s, g, mode=mode)


# -------------------------------------------------------------------------------------------
# Growth, compaction, erosion, fragmentation (spec §4, §5)
# -------------------------------------------------------------------------------------------
def k_coag(m, phi, st, sigma_d, g):
    """dm/dt = K dv, K = 2 sqrt(pi) a^2 Sigma_d / h_d (spec §4.1)."""
    a = radius(m, phi)
    return 2.0 * math.sqrt(PI) * a * a * sigma_d / h_dust(st, g)


def erosion_s(x, w):
    """E1 switch S(x) = 1/2 [1 - tanh((x - 1)/w)] (spec §5.2)."""
    return 0.5 * (1.0 - math.tanh((x - 1.0) / w))


def frag_factor(dv, v_frag):
    """1 - 2 dv^2/(dv^2 + v_frag^2) (spec §5.3)."""
    return 1.0 - 2.0 * dv * dv / (dv * dv + v_frag * v_frag)


def phi_gas(m, st, g, m0, e_roll, a0=A0):
    """[a0 m0 dv_pg Omega/(pi E_roll St)]^(3/7) (m/m0)^(1/7) (spec §4.3)."""
    return (a0 * m0 * dv_pg(st, g) * g.omega / (PI * e_roll * st)) ** (3 / 7) * (m / m0) ** (1 / 7)


def phi_grav(m, m0, e_roll, a0=A0):
    """[G m0^2/(pi a0 E_roll)]^(3/5) (m/m0)^(2/5) (spec §4.3)."""
    return (G_GRAV * m0 * m0 / (PI * a0 * e_roll)) ** 0.6 * (m / m0) ** 0.4


def softplus(z, k):
    return math.log1p(math.exp(k * z)) / k if k * z < 700 else z


# -------------------------------------------------------------------------------------------
# Locating the literals in the test files
# -------------------------------------------------------------------------------------------
class Source:
    # Ends a file's last block where several test files are read as one Source.
    END_OF_FILE = "TEST(end of file)"

    def __init__(self, rel, *more):
        """`rel` (and `more`): one test file, or globs of the files one law's tests and
        their shared set-up are split into (their anchors are unique across them)."""
        self.rel = rel
        self.name = os.path.basename(rel)
        paths = []
        for pattern in (rel,) + more:
            found = sorted(glob.glob(os.path.join(REPO, pattern)))
            if not found:
                raise FileNotFoundError(os.path.join(REPO, pattern))
            paths += found
        self.lines, self.origin = [], []
        for path in paths:
            with open(path) as f:
                text = f.read().split("\n")
            self.lines += text + [self.END_OF_FILE]
            self.origin += [(os.path.basename(path), k + 1) for k in range(len(text) + 1)]
        self.count = {"asserted/input": 0, "comment": 0, "claim": 0}

    def where(self, line):
        """'file:line' of the 1-based line `line` of the concatenated files."""
        if not isinstance(line, int):
            return f"{self.name}:{line}"
        name, k = self.origin[line - 1]
        return f"{name}:{k}"

    def block(self, anchor):
        """Lines [i0, i1) from the unique line holding `anchor` to the next TEST."""
        hits = [i for i, line in enumerate(self.lines) if anchor in line]
        if len(hits) != 1:
            raise LookupError(f"anchor {anchor!r} occurs {len(hits)} times in {self.name}")
        i0 = i1 = hits[0]
        i1 += 1
        while i1 < len(self.lines) and not re.match(r"TEST(_F)?\(", self.lines[i1]):
            i1 += 1
        return i0, i1

    def find(self, anchor, literal, nth=1):
        """(value, 1-based line) of the nth occurrence of `literal` (as a whole number
        token) in the block of `anchor`."""
        i0, i1 = self.block(anchor)
        # a whole token: no digit, letter or decimal point glued on either side (a
        # sentence's full stop after it is fine)
        pat = re.compile(r"(?<![\w.])" + re.escape(literal) + r"(?![\w]|\.\w)")
        k = 0
        for i in range(i0, i1):
            for _ in pat.finditer(self.lines[i]):
                k += 1
                if k == nth:
                    try:
                        return float(literal), i + 1
                    except ValueError:  # a claim anchored on text, not a number
                        return math.nan, i + 1
        raise LookupError(f"{literal!r} (occurrence {nth}) not in [{anchor}] of {self.name}")

    def row(self, anchor, prefix):
        """Fields of the brace-enclosed row of the block of `anchor` starting with
        `prefix` (which may continue over several lines): (list of str, line)."""
        i0, i1 = self.block(anchor)
        for i in range(i0, i1):
            j = self.lines[i].find(prefix)
            if j < 0:
                continue
            text = self.lines[i][j:]
            k = i
            while "}" not in text and k + 1 < i1:
                k += 1
                text += " " + self.lines[k].strip()
            body = text[text.index("{") + 1:text.index("}")]
            body = re.sub(r"//[^\n]*", "", body)
            fields = re.findall(r'"[^"]*"|[^,]+', body)
            return [t.strip() for t in fields if t.strip()], i + 1
        raise LookupError(f"row {prefix!r} not in [{anchor}] of {self.name}")

    def anchor_line(self, anchor):
        return self.block(anchor)[0] + 1


def digits_tol(literal):
    """One unit of the last quoted digit of `literal` (absolute): the numbers quoted in
    the tests' comments are sometimes rounded, sometimes truncated (57.808 for 57.8086,
    37.26 for 37.2699, 21.5 for 21.55)."""
    mant, _, exp = literal.lower().lstrip("-+").partition("e")
    dec = len(mant.partition(".")[2])
    return 10.0 ** ((int(exp) if exp else 0) - dec)


NOTES = []


class Ref:
    def __init__(self, checks):
        self.c = checks

    def _report(self, src, ok, line, anchor, what, text, category="claim"):
        src.count[category] += 1
        self.c.check(ok, f"{src.where(line)} [{anchor}] {what}: {text}")

    def cmp(self, src, anchor, literal, mine, tol, kind="rel", what="", nth=1):
        """Compare the literal of the test with `mine`."""
        try:
            val, line = src.find(anchor, literal, nth)
        except LookupError as e:
            self._report(src, False, "?", anchor, what, str(e))
            return
        self.value(src, anchor, literal, val, line, mine, tol, kind, what)

    def value(self, src, anchor, literal, val, line, mine, tol, kind, what):
        if kind == "rel":
            err = abs(mine / val - 1.0)
            desc = f"|rel| {err:.1e} <= {tol:g}"
        elif kind == "abs":
            err = abs(mine - val)
            desc = f"|diff| {err:.1e} <= {tol:g}"
        else:  # digits
            tol = digits_tol(literal) * abs(val / float(literal)) * (1 + 1e-9)
            err = abs(mine - val)
            desc = f"within a unit of the last quoted digit (+-{tol:.2g})"
        ok = bool(err <= tol) and math.isfinite(mine)
        self._report(src, ok, line, anchor, what, f"python {mine:.16g} vs test {literal} ({desc})",
                     "comment" if kind == "digits" or "(comment" in what else "asserted/input")

    def note(self, src, anchor, literal, mine, text):
        """A comment-level discrepancy, explained: printed and listed, not failed."""
        try:
            line = src.find(anchor, literal)[1]
        except LookupError:
            line = "?"
        msg = f"{src.where(line)} [{anchor}] {text}"
        NOTES.append(msg)
        print("NOTE  " + msg)

    def claim(self, src, anchor, ok, what, literal=None):
        """A claim of the test (a bound, a regime), checked with the python numbers."""
        try:
            line = src.find(anchor, literal)[1] if literal else src.anchor_line(anchor)
        except LookupError as e:
            self._report(src, False, "?", anchor, what, str(e))
            return
        self._report(src, bool(ok), line, anchor, what, "claim holds" if ok else "claim FAILS")


# ===========================================================================================
# test_contact_mechanics.cpp
# ===========================================================================================
def check_contact(ref):
    s = Source("tests/unit/physics/test_contact_mechanics.cpp")
    ice, sil = contact(ICE), contact(SIL)
    A = "RollingEnergyMatchesSpec"
    ref.cmp(s, A, "4.74e-9", ice["e_roll"], 0.002, what="E_roll ice (spec §0)")
    ref.cmp(s, A, "1.18e-9", sil["e_roll"], 0.005, what="E_roll silicate (spec §1.7)")
    ref.cmp(s, A, "4.737410112522892e-09", ice["e_roll"], 1e-12, what="E_roll ice")
    ref.cmp(s, A, "1.184352528130723e-09", sil["e_roll"], 1e-12, what="E_roll silicate")
    ref.cmp(s, A, "2.37e-9", contact(ICE, 0.5)["e_roll"], 0.002, what="E_roll, R_r = a0/2")
    ref.cmp(s, A, "59.2176", 6 * PI ** 2, 0, "digits", what="6 pi^2 (comment)")
    ref.cmp(s, A, "4.73741e-9", ice["e_roll"], 0, "digits", what="E_roll by hand (comment)")

    A = "MonomerMass)"
    ref.cmp(s, A, "5.86e-15", ice["m0"], 0.001, what="m0 ice (spec §12)")
    ref.cmp(s, A, "1.2566370614e-14", sil["m0"], 1e-9, what="m0 silicate")
    ref.cmp(s, A, "1.25664e-14", sil["m0"], 0, "digits", what="m0 silicate (comment)")

    A = "IcePropertiesAgainstIndependentValues"
    ref.cmp(s, A, "5e-6", ice["R"], 4e-16, what="R = a0/2 (DOUBLE_EQ)")
    ref.cmp(s, A, "200.0", ice["w"], 4e-16, what="w = 2 gamma (DOUBLE_EQ)")
    ref.cmp(s, A, "3.733333333333e10", ice["e_star"], 1e-12, what="E* ice")
    ref.cmp(s, A, "1.2371201e-6", ice["a_eq"], 1e-6, what="a_eq ice, closed form")
    # and as the zero of F_JKR (bisection), not from the closed form
    a_zero = bisect(lambda a: jkr_force(a, ice["R"], ice["e_star"], ice["w"]),
                    0.5 * ice["a_eq"], 2 * ice["a_eq"])
    ref.cmp(s, A, "1.2371201e-6", a_zero, 1e-6, what="a_eq ice, zero of F_JKR by bisection")
    dt_form = (9 * PI * ICE["gamma"] * ice["R"] ** 2 / ice["e_star"]) ** (1 / 3)
    ref.cmp(s, A, "1.2371201e-6", dt_form, 1e-6, what="a_eq = (9 pi gamma R^2/E*)^(1/3) (D&T form)")
    ref.cmp(s, A, "4.7123890e-3", ice["f_c"], 1e-6, what="F_c ice")
    ref.cmp(s, A, "1.308837", ice["tabor"], 1e-6, what="mu_T ice, z0 = 0.4 nm")
    ref.cmp(s, A, "2.617674", contact(dict(ICE, z0=2e-8))["tabor"], 1e-6, what="mu_T ice, z0 = 0.2 nm")
    ref.claim(s, A, 0.1 <= ice["tabor"] <= 5.0 and 0.1 <= contact(dict(ICE, z0=2e-8))["tabor"] <= 5.0,
              "ice: not JKR (mu_T <= 5) and not DMT (mu_T >= 0.1) for z0 = 0.2-0.4 nm")

    A = "SilicatePropertiesAgainstIndependentValues"
    ref.cmp(s, A, "2.780352e11", sil["e_star"], 1e-6, what="E* silicate")
    ref.cmp(s, A, "3.9907776e-7", sil["a_eq"], 1e-6, what="a_eq silicate")
    ref.cmp(s, A, "1.1780972e-3", sil["f_c"], 1e-6, what="F_c silicate")
    ref.cmp(s, A, "0.136200", sil["tabor"], 1e-5, what="mu_T silicate, z0 = 0.4 nm")
    ref.cmp(s, A, "0.272400", contact(dict(SIL, z0=2e-8))["tabor"], 1e-5, what="mu_T silicate, z0 = 0.2 nm")
    mu_gamma = (sil["R"] * SIL["gamma"] ** 2 / (sil["e_star"] ** 2 * SIL["z0"] ** 3)) ** (1 / 3)
    ref.cmp(s, A, "0.0858", mu_gamma, 0, "digits", what="mu_T with gamma in place of w (comment)")
    ref.claim(s, A, 0.1 <= sil["tabor"] <= 5.0, "silicate: JKR-DMT transition (0.1 <= mu_T <= 5)")

    A = "HertzAndJkrAgainstIndependentValues"
    a = 0.5 * ice["a_eq"]
    R, es, w = ice["R"], ice["e_star"], ice["w"]
    ref.cmp(s, A, "7.6523311e-8", hertz_delta(a, R), 1e-6, what="Hertz delta at a_eq/2")
    ref.cmp(s, A, "2.3561945e-3", hertz_force(a, R, es), 1e-6, what="Hertz force at a_eq/2")
    ref.cmp(s, A, "-6.7770428e-8", jkr_delta(a, R, es, w), 1e-6, what="JKR delta at a_eq/2")
    ref.cmp(s, A, "-4.3081299e-3", jkr_force(a, R, es, w), 1e-6, what="JKR force at a_eq/2")

    A = "JkrEquilibriumAndPullOff"
    for name, cp in (("ice", ice), ("silicate", sil)):
        f = lambda a: -jkr_force(a, cp["R"], cp["e_star"], cp["w"])  # noqa: E731
        a_min = golden_max(f, 0.1 * cp["a_eq"], cp["a_eq"])
        ref.cmp(s, A, "0.62996", a_min / cp["a_eq"], 2e-5, "abs",
                what=f"{name}: argmin F_JKR / a_eq (golden section)")
        lit = "IcePropertiesAgainstIndependentValues" if name == "ice" else \
            "SilicatePropertiesAgainstIndependentValues"
        ref.cmp(s, lit, "4.7123890e-3" if name == "ice" else "1.1780972e-3", f(a_min), 1e-6,
                what=f"{name}: pull-off = -min F_JKR (golden section)")
        big = 100 * cp["a_eq"]
        ref.claim(s, A, abs(jkr_force(big, cp["R"], cp["e_star"], cp["w"]) /
                            hertz_force(big, cp["R"], cp["e_star"]) - 1) < 1e-2,
                  f"{name}: F_JKR -> F_Hertz within 1% at 100 a_eq", literal="1e-2")

    A = "CombinedModulusAndReducedRadius"
    ref.cmp(s, A, "1.5191190e-11", 1 / combined_modulus(7e10, 0.25, 5.4e11, 0.17), 1e-6,
            what="1/E* ice on silicate")
    ref.cmp(s, A, "1.33929e-11", 0.9375 / 7e10, 0, "digits", what="(1-nu^2)/E ice (comment)")
    ref.cmp(s, A, "1.79833e-12", (1 - 0.17 ** 2) / 5.4e11, 0, "digits", what="(1-nu^2)/E silicate (comment)")
    ref.cmp(s, A, "0.75", 1.0 * 3.0 / (1.0 + 3.0), 0, "abs", what="reduced radius (1, 3)")

    A = "SummaryLine"
    ref.claim(s, A, f"{ice['e_roll']:.2e}" == "4.74e-09", "E_roll prints as 4.74e-09 erg",
              literal="4.74e-09")
    ref.claim(s, A, f"{ice['tabor']:.2f}" == "1.31", "mu_T(ice) prints as 1.31", literal="1.31")
    weak = contact(dict(SIL, gamma=10.0))["tabor"]
    ref.cmp(s, A, "0.0739", weak, 0, "digits", what="mu_T silicate, gamma = 10 (comment)")
    ref.cmp(s, A, "0.1362", sil["tabor"], 0, "digits", what="mu_T silicate (comment)")
    ref.claim(s, A, weak < 0.1, "gamma = 10 silicate is DMT (mu_T < 0.1)", literal="0.0739")
    ref.claim(s, A, contact(dict(ICE, E=1e8))["tabor"] > 5.0, "soft ice (E = 1e8): JKR valid (mu_T > 5)")
    return s


# ===========================================================================================
# test_particle.cpp (and the gas of mmsn_gas.hpp)
# ===========================================================================================
def check_particle(ref):
    s = Source("tests/unit/physics/test_particle.cpp")
    g = gas(5.0)
    A = "GasMatchesSpecTable"
    ref.cmp(s, A, "152.0", g.sigma, 0.005, what="Sigma_g(5 AU)")
    ref.cmp(s, A, "125.0", g.temp, 0.005, what="T(5 AU)")
    ref.cmp(s, A, "665e2", g.cs, 0.005, what="c_s(5 AU)")
    ref.cmp(s, A, "0.0499", g.h / g.r, 0.005, what="H/r(5 AU)")
    ref.cmp(s, A, "1.63e-11", g.rho, 0.005, what="rho_g(5 AU)")
    ref.cmp(s, A, "120.0", g.mfp, 0.01, what="lambda(5 AU)")
    ref.cmp(s, A, "4.04e-3", g.eta, 0.005, what="eta(5 AU)")
    ref.cmp(s, A, "53.9e2", g.vw, 0.005, what="eta v_K")
    ref.cmp(s, A, "271.0", 9 * g.mfp / 4, 0.005, what="9 lambda/4")
    ref.cmp(s, A, "3.9e7", g.re, 0.02, what="Re")
    ref.cmp(s, A, "1.6e-4", g.st_eta, 0.03, what="St_eta")
    ref.cmp(s, A, "2.5e14", ALPHA * g.cs * g.h, 0.02, what="D_g")
    ref.cmp(s, A, "11.2", 2 * PI / g.omega / YR, 0.005, what="P_orb(5 AU) [yr]")

    A = "MakeLocalGasReproducesSpecTable"
    names = ["Sigma_g", "T", "c_s [m/s]", "H/r", "rho_g", "lambda", "eta", "P_orb [yr]"]
    for r_lit in ("1.0, 1700.0", "2.7, 383.0", "5.0, 152.0", "10.0, 53.8", "30.0, 10.3",
                  "100.0, 1.70"):
        try:
            fields, line = s.row(A, "{" + r_lit)
        except LookupError as e:
            ref._report(s, False, "?", A, "table row", str(e))
            continue
        gr = Gas(float(fields[0]))
        mine = [gr.sigma, gr.temp, gr.cs / 100.0, gr.h / gr.r, gr.rho, gr.mfp, gr.eta,
                2 * PI / gr.omega / YR]
        eta_tol = float(fields[9])
        tols = [0.005] * 6 + [eta_tol, 0.012]
        for k in range(8):
            ref.value(s, A, fields[k + 1], float(fields[k + 1]), line, mine[k], tols[k], "rel",
                      f"{names[k]} at {fields[0]} AU")
        ref.cmp(s, A, "53.9e2", gr.vw, 0.002, what=f"eta v_K at {fields[0]} AU (r-independent)")
    g27 = gas(2.7)
    for lit, mine, what in (("383.18", g27.sigma, "Sigma_g"), ("170.4", g27.temp, "T"),
                            ("775.1", g27.cs / 100, "c_s [m/s]"), ("0.04276", g27.h / g27.r, "H/r"),
                            ("8.851e-11", g27.rho, "rho_g"), ("22.12", g27.mfp, "lambda"),
                            ("2.971e-3", g27.eta, "eta"), ("4.436", 2 * PI / g27.omega / YR, "P_orb")):
        ref.cmp(s, A, lit, mine, 0, "digits", what=f"python row 2.7 AU (comment): {what}")

    A = "MonomerMassIce"
    m0 = 4 * PI / 3 * A0 ** 3 * RHO0
    ref.cmp(s, A, "5.86e-15", m0, 0.001, what="m0 (spec §12)")
    ref.cmp(s, A, "5.864306286700947e-15", m0, 1e-12, what="m0")
    ref.cmp(s, A, "5.86431e-15", m0, 0, "digits", what="m0 by hand (comment)")

    A = "RadiusAndMonomerCount"
    ref.cmp(s, A, "0.1", radius(1e9 * m0, 1e-3), 1e-12, what="a(1e9 m0, phi = 1e-3) = 1e4 a0")

    A = "SpecExampleParticles"
    for prefix in ("{1.0, 1e-3", "{1e8, 5e-4", "{1e10, 1e-3"):
        try:
            f, line = s.row(A, prefix)
        except LookupError as e:
            ref._report(s, False, "?", A, "example row", str(e))
            continue
        m, phi = float(f[0]), float(f[1])
        a, st = radius(m, phi), stokes(m, phi, g)
        ref.value(s, A, f[2], float(f[2]), line, a, float(f[4]), "rel", f"a({f[0]} g, {f[1]}) (spec §12)")
        ref.value(s, A, f[3], float(f[3]), line, st, float(f[5]), "rel", f"St({f[0]} g, {f[1]}) (spec §12)")
        ref.value(s, A, f[6], float(f[6]), line, st, 1e-9, "rel", f"St({f[0]} g, {f[1]}), smooth law")
    st_hard = stokes(1e8, 5e-4, g, law="hard")
    st_8 = stokes(1e8, 5e-4, g)
    ref.cmp(s, A, "0.20581", st_hard, 0, "digits", what="St(1e8 g, 5e-4), hard piecewise law (comment)")
    ref.cmp(s, A, "0.75", 100 * (1 - st_8 / st_hard), 0, "digits",
            what="p = 8 law below the hard one [%] (comment)")
    ref.cmp(s, A, "2.2", reynolds_p(radius(1e8, 5e-4), st_8, g), 0, "digits",
            what="Re_p(1e8 g, 5e-4) (comment)")
    ref.cmp(s, A, "0.064", h_dust(st_8, g) / g.h, 0.01, what="h_d/H (spec §12)")
    ref.cmp(s, A, "0.06455927048366601", h_dust(st_8, g) / g.h, 1e-9, what="h_d/H, smooth St")
    ref.cmp(s, A, "0.0645593", h_dust(st_8, g) / g.h, 0, "digits", what="h_d/H (comment)")

    A = "MonomerStokesNumber"
    st_mono = stokes(m0, 1.0, g)
    ref.cmp(s, A, "1.45e-7", st_mono, 0.005, what="monomer St (spec §12)")
    ref.cmp(s, A, "1.4462853858025006e-07", st_mono, 1e-9, what="monomer St")
    ref.cmp(s, A, "1.44629e-7", PI * RHO0 * A0 / (2 * g.sigma), 0, "digits",
            what="pi rho0 a0/(2 Sigma_g) (comment)")
    ref.cmp(s, A, "152.05", g.sigma, 0, "digits", what="Sigma_g (comment)")

    A = "SmoothFactorLimits"
    g_re = lambda x, re: math.exp(ln_g_drag(x, re))  # noqa: E731
    ref.cmp(s, A, "6.4e-6", abs(g_re(1e4, 1e2) / (1e4 / 1e2 ** 0.4) - 1), 0, "digits",
            what="g(1e4, Re 100) / (x Re^-0.4) - 1 (comment)")
    ref.claim(s, A, abs(g_re(1e6, 1e5) / (1e6 / (CD_NEWTON * 1e5)) - 1) < 1e-6,
              "g(1e6, Re 1e5) = x/(0.01833 Re) to 1e-6", literal="1e-6")
    ref.claim(s, A, (1 + 0.73 ** 8) ** 0.125 - 1 < 0.01, "(1 + r^8)^(1/8) - 1 < 1% for r < 0.73",
              literal="0.73")
    ref.claim(s, A, abs(g_re(1.0, 0.0) - 2 ** 0.125) < 1e-12, "g(1, 0) = 2^(1/8)")

    A = "DeepEpsteinMatchesEpstein"
    a = radius(1.0, 1e-3)
    ref.cmp(s, A, "0.020", 4 * a / (9 * g.mfp), 0, "digits", what="x(1 g, 1e-3) (comment)")
    ref.claim(s, A, abs(stokes(1.0, 1e-3, g) / st_epstein(a, 1.4e-3, g) - 1) < 0.01,
              "smooth St = Epstein to 1% at x = 0.02")

    A = "DeepStokesMatchesStokesLaw"
    g1 = gas(1.0)
    a = radius(200.0, 1e-4)
    st = stokes(200.0, 1e-4, g1)
    x = 4 * a / (9 * g1.mfp)
    st_stokes = 2 * 1e-4 * RHO0 * a * a / (9 * g1.nu * g1.rho) * g1.omega
    ref.cmp(s, A, "21.5", x, 0, "digits", what="x(200 g, 1e-4, 1 AU) (comment)")
    ref.claim(s, A, x > 20.0, "x > 20", literal="20.0")
    ref.cmp(s, A, "2.6e-3", reynolds_p(a, st, g1), 0, "digits", what="Re_p (comment)")
    ref.claim(s, A, abs(st / st_stokes - 1) < 0.01, "St = Stokes law to 1%")
    ref.cmp(s, A, "0.00019481003612107102", st, 1e-9, what="St(200 g, 1e-4, 1 AU)")

    A = "AgreesWithIndependentSolutionInEveryRegime"
    re_comment = {"{1.0, 200.0": "2.6e-3", "{1.0, 1e7": "30", "{1.0, 1e12": "1127",
                  "{5.0, 1e8": None, "{30.0, 1e6": None, "{5.0, 1e15": "434", "{0.3, 1e9": None}
    for prefix, re_lit in re_comment.items():
        try:
            f, line = s.row(A, prefix)
        except LookupError as e:
            ref._report(s, False, "?", A, "regime row", str(e))
            continue
        gr = gas(float(f[0]))
        m, phi = float(f[1]), float(f[2])
        st = stokes(m, phi, gr)
        ref.value(s, A, f[3], float(f[3]), line, st, 1e-9, "rel", f"St({f[0]} AU, {f[1]} g, {f[2]})")
        re_p = reynolds_p(radius(m, phi), st, gr)
        if re_lit:
            lit_line = s.lines[line - 1]
            ok = re.search(r"Re_p = " + re.escape(re_lit) + r"(?![\w.])", lit_line)
            ref.value(s, A, re_lit if ok else "nan", float(re_lit), line, re_p, 0, "digits",
                      f"Re_p at {f[0]} AU, {f[1]} g (comment)")
        if prefix == "{0.3, 1e9":
            ref.claim(s, A, re_p > 784 and st < 1,
                      f"0.3 AU, 1e9 g: C_D = 0.44 (Re_p = {re_p:.0f} > 784) at St < 1",
                      literal="0.4023011031152867")
        if prefix == "{30.0, 1e6":
            ref.claim(s, A, 4 * radius(m, phi) / (9 * gr.mfp) < 0.05, "30 AU, 1e6 g: Epstein (x < 0.05)",
                      literal="0.11787145878336643")

    A = "AutoDiffMatchesCentralFiniteDifferences"
    x = 4 * radius(1.2e5, 1e-3) / (9 * g.mfp)
    ref.claim(s, A, abs(math.log(x)) < 0.1, f"(1.2e5 g, 1e-3) is near x = 1 at 5 AU (x = {x:.3f})",
              literal="1.2e5")

    A = "DustScaleHeight"
    ref.cmp(s, A, "0.063571", h_dust(0.21, g) / g.h, 1e-5, what="h_d/H at St = 0.21")
    ref.cmp(s, A, "247.446", 1 + 0.21 / 1e-3 * 1.42 / 1.21, 0, "digits",
            what="1 + (St/alpha)(1+2St)/(1+St) (comment)")

    A = "SoftMaxSoftMinLogistic"
    ref.cmp(s, A, "0.95", float(log_step(10 ** 0.1, 1.0, 0.1)), 1e-12, "abs",
            what="logistic step 0.1 dex above its centre")
    ref.cmp(s, A, "0.05", float(log_step(10 ** -0.1, 1.0, 0.1)), 1e-12, "abs",
            what="logistic step 0.1 dex below its centre")
    return s


# ===========================================================================================
# test_relative_velocity.cpp
# ===========================================================================================
def check_relative_velocity(ref):
    s = Source("tests/unit/physics/test_relative_velocity.cpp")
    g = gas(5.0)
    st_small, m_small, m_target = 1e-4, 1e-12, 1.0  # kStSmall, kMSmall, kMTarget of the test
    dv_ls = lambda st, mode="blend": float(dv_small(st, m_target, st_small, m_small, g, mode))  # noqa: E731
    dv_pr = lambda st, mode="blend": float(dv_pair(st, m_target, g, mode))  # noqa: E731

    A = "BetaValues"
    ref.cmp(s, A, "1.969", beta_oc07(1.0), 5e-4, "abs", what="beta(1) (spec §3.5)")
    ref.cmp(s, A, "2.292", beta_oc07(0.5), 5e-4, "abs", what="beta(0.5) (spec §3.5)")
    ref.cmp(s, A, "2.969", beta_oc07(1e-12), 5e-4, "abs", what="beta(->0) (spec §3.5)")
    ref.cmp(s, A, "128.0", 65 * beta_oc07(1.0), 65e-14, "abs", what="65 beta(1) = 128")
    ref.cmp(s, A, "2.292185592185592", beta_oc07(0.5), 1e-14, "abs", what="beta(0.5)")
    ref.cmp(s, A, "193.0", 65 * beta_oc07(0.0), 65e-14, "abs", what="65 beta(0) = 193")

    A = "ComponentsAgainstIndependentValues"
    parts = [float(v) for v in dv2_parts(0.7, 0.35, 1.0, 0.125, g)]
    for lit, v, what in (("3.9623695521826606e-13", parts[0], "Brownian^2"),
                         ("2895967.2754337443", parts[1], "radial^2"),
                         ("1400291.180722645", parts[2], "azimuthal^2"),
                         ("2526.5037967337134", parts[3], "vertical^2"),
                         ("7071417.075666841", parts[4], "turbulent^2 (blend at St = 0.7)")):
        ref.cmp(s, A, lit, v, 1e-9, what=f"St 0.7/0.35: {what}")
    ref.cmp(s, A, "3371.973018222412", math.sqrt(sum(parts)), 1e-9, what="St 0.7/0.35: total dv")

    A = "BrownianTwoMonomers"
    m0 = 4 * PI / 3 * A0 ** 3 * RHO0
    ref.cmp(s, A, "3.8749215063837723", math.sqrt(float(dv2_parts(1, 1, m0, m0, g)[0])), 1e-9,
            what="dv_B of two ice monomers")

    A = "PairPartnerHasTheMassOfEpsCubed"
    st0 = st_epstein(A0, RHO0, g)
    ref.cmp(s, A, "1.4462853858025024e-07", st0, 1e-12, what="Epstein St of an ice monomer")
    ref.cmp(s, A, "8.21996000391341", float(dv_pair(st0, m0, g)), 1e-9,
            what="dv of a monomer against its pair partner (eps St, eps^3 m)")

    A = "DriftComponentsLimits"
    ref.cmp(s, A, "53.9e2", g.vw, 0.001, what="eta v_K (spec §1.4)")
    t_drift = 5 * AU / (2 * 1.0 * g.vw / 2.0) / YR
    ref.cmp(s, A, "440.0", t_drift, 0.005, what="t_drift(St = 1) [yr] (spec §12)")
    ref.cmp(s, A, "440.09", t_drift, 0, "digits", what="t_drift(St = 1) [yr] (comment)")

    A = "TurbulentRegimes"
    ref.cmp(s, A, "0.006828090772562611", float(dv2_turbulent(1e-6, 5e-7, g)), 1e-9, what="dv_t^2 tight")
    ref.cmp(s, A, "101200.01067429288", float(dv2_turbulent(0.01, 0.005, g)), 1e-9,
            what="dv_t^2 intermediate")
    ref.cmp(s, A, "130281.5203392193", float(dv2_turbulent(100.0, 50.0, g)), 1e-9, what="dv_t^2 heavy")
    for st1, st2 in ((1e-6, 5e-7), (0.01, 0.005), (100.0, 50.0)):
        w_eta, w_one = float(log_step(st1, g.st_eta, BLEND_DEX)), float(log_step(st1, 1.0, BLEND_DEX))
        hard_eta, hard_one = float(st1 >= g.st_eta), float(st1 >= 1.0)
        ok = abs(w_eta - hard_eta) < 1e-12 and abs(w_one - hard_one) < 1e-12
        blend_vs_pure = float(dv2_turbulent(st1, st2, g)) / float(dv2_turbulent(st1, st2, g, mode="hard"))
        ok = ok and abs(blend_vs_pure - 1) < 1e-9
        ref.claim(s, A, ok, f"St {st1:g}/{st2:g}: blend weights < 1e-12 off 0/1, = pure OC07 to 1e-9",
                  literal="1e-12")
    ref.cmp(s, A, "2.3e-5", float(dv2_turbulent(0.01, 0.005, g)) / g.cs ** 2, 0.02,
            what="dv_t^2/c_s^2 ~ 2.3 alpha St (dv_t to 1%)")

    A = "SmallProjectileSpeedsMatchSpec"
    for st_lit, py in (("0.1", "16.650"), ("0.3", "36.792"), ("0.5", "51.953"), ("1.5", "67.462")):
        got = table_row(ref, s, A, "{" + st_lit + ",")
        if got is None:
            continue
        f, line = got
        v = dv_ls(float(f[0]))
        ref.value(s, A, f[1], float(f[1]), line, v, 0.03, "rel", f"dv_ls(St = {f[0]}) (spec §3)")
        ref.value(s, A, f[2], float(f[2]), line, v, 1e-9, "rel", f"dv_ls(St = {f[0]})")
        ref.cmp(s, A, py, v / 100, 0, "digits", what=f"dv_ls(St = {f[0]}) [m/s] (comment)")

    A = "SmallProjectileAtStOne"
    v1 = dv_ls(1.0)
    v_heavy = dv_ls(1.0, "hard")  # St1 >= 1 selects the heavy branch
    v_inter = float(np.sqrt(dv_ls(1.0) ** 2 - float(dv2_turbulent(1.0, st_small, g))
                            + ALPHA * g.cs ** 2 * float(beta_oc07(st_small / 1.0))))
    ref.cmp(s, A, "6843.419116118557", v1, 1e-9, what="dv_ls(St = 1), blended")
    ref.cmp(s, A, "68.434", v1 / 100, 0, "digits", what="dv_ls(St = 1) [m/s] (comment)")
    ref.cmp(s, A, "66.022", v_heavy / 100, 0, "digits", what="unblended (heavy branch) [m/s] (comment)")
    ref.cmp(s, A, "3.7", 100 * (v1 / 6600 - 1), 0, "digits", what="blended above the spec's 66 [%] (comment)")
    ref.cmp(s, A, "66.0", v_heavy / 100, 0, "digits", what="heavy branch at St = 1 [m/s] (comment)")
    ref.claim(s, A, 6602.0 < v1 < 7058.0, "6602 < dv_ls(1) < 7058 cm/s (asserted)", literal="6602.0")
    ref.claim(s, A, abs(v_heavy - 6602.0) < 1, "the lower bound 6602 is the heavy branch at St = 1",
              literal="6602.0")
    # The comment: 7058 is the unblended law at St = 0.990, 7076.4 the intermediate
    # branch's St -> 1- limit.
    ref.cmp(s, A, "7056.7", dv_ls(0.99, "hard"), 0, "digits", what="unblended dv_ls at St = 0.990 (comment)")
    ref.cmp(s, A, "7076.4", v_inter, 0, "digits", what="intermediate branch, St -> 1- (comment)")

    A = "SmallProjectilePlateau"
    for lit, st in (("5879.492998723494", 10.0), ("5786.809029897509", 100.0), ("5780.8711814839435", 1e4)):
        ref.cmp(s, A, lit, dv_ls(st), 1e-9, what=f"dv_ls(St = {st:g})")
    for lit, st in (("58.795", 10.0), ("57.868", 100.0), ("57.809", 1e4)):
        ref.cmp(s, A, lit, dv_ls(st) / 100, 0, "digits", what=f"dv_ls(St = {st:g}) [m/s] (comment)")
    ref.cmp(s, A, "57.808", math.sqrt(g.vw ** 2 + ALPHA * g.cs ** 2) / 100, 0, "digits",
            what="plateau sqrt((eta v_K)^2 + V_g^2) [m/s] (comment)")
    limit = math.sqrt(g.vw ** 2 + ALPHA * g.cs ** 2 / (1 + st_small))
    ref.claim(s, A, abs(dv_ls(1e8) / limit - 1) < 1e-6, "dv_ls(1e8) = plateau to 1e-6", literal="1e-6")
    for st in (10.0, 100.0, 1e4, 1e8):
        ref.claim(s, A, 5750.0 < dv_ls(st) < 6050.0, f"dv_ls(St = {st:g}) in [57.5, 60.5] m/s (spec: 58-60)",
                  literal="5750.0")

    A = "PairSpeedPeak"
    ref.cmp(s, A, "3400.0", dv_pr(0.7), 0.03, what="dv_pair(0.7) (spec §3: ~34 m/s)")
    ref.cmp(s, A, "3371.973018222412", dv_pr(0.7), 1e-9, what="dv_pair(0.7)")
    ref.cmp(s, A, "33.720", dv_pr(0.7) / 100, 0, "digits", what="dv_pair(0.7) [m/s] (comment)")
    st_peak = math.exp(golden_max(lambda u: dv_pr(math.exp(u)), math.log(0.3), math.log(2.0)))
    ref.cmp(s, A, "0.8700482079836537", st_peak, 1e-4, what="St of the peak of dv_pair")
    ref.cmp(s, A, "0.870", st_peak, 0, "digits", what="St of the peak (comment)")
    ref.cmp(s, A, "3521.805423093797", dv_pr(st_peak), 1e-9, what="peak dv_pair")
    ref.cmp(s, A, "35.218", dv_pr(st_peak) / 100, 0, "digits", what="peak dv_pair [m/s] (comment)")
    ref.cmp(s, A, "37.26", dv_pr(1.0 - 1e-12, "hard") / 100, 0, "digits",
            what="unblended dv_pair(St -> 1-) [m/s] (comment)")
    ref.cmp(s, A, "29.87", dv_pr(1.0, "hard") / 100, 0, "digits", what="unblended dv_pair(1) [m/s] (comment)")
    ref.cmp(s, A, "3.5", 100 * (dv_pr(st_peak) / 3400 - 1), 0, "digits",
            what="peak above the spec's 34 m/s [%] (comment)")

    A = "ContinuousAcrossRegimeBoundaries"
    # the sampled log-slopes of the test's scan (ln St in [1e-6, 1e3], step 1e-4)
    ls = np.log(1e-6) + 1e-4 * np.arange(int((np.log(1e3) - np.log(1e-6)) / 1e-4) + 1)
    sts = np.exp(ls)
    lpr = np.log(dv_pair(sts, m_target, g))
    lls = np.log(dv_small(sts, m_target, st_small, m_small, g))
    ref.cmp(s, A, "4.5", np.max(np.abs(np.diff(lpr))) / 1e-4, 0, "digits",
            what="max |d ln dv_pair / d ln St| on the scan (comment)")
    ref.cmp(s, A, "7.4", np.max(np.abs(np.diff(lls))) / 1e-4, 0, "digits",
            what="max |d ln dv_ls / d ln St| on the scan (comment)")
    ref.cmp(s, A, "1.7", dv_ls(st_small), 0, "digits", what="dv_ls at St = St_s = 1e-4 [cm/s] (comment)")
    i_min = int(np.argmin(lls))
    ref.cmp(s, A, "1.60", float(np.exp(lls[i_min])), 0, "digits", what="minimum of dv_ls [cm/s] (comment)")
    ref.cmp(s, A, "9.73e-5", float(sts[i_min]), 0, "digits", what="St of the minimum (comment)")
    return s


# ===========================================================================================
# test_growth_*.cpp (the growth-rate tests, split by law)
# ===========================================================================================
def check_growth(ref):
    s = Source("tests/unit/physics/test_growth_*.cpp",
               "tests/unit/physics/growth_fixture.hpp")
    g = gas(5.0)
    ice = contact(ICE)
    m0, e_roll = ice["m0"], ice["e_roll"]
    thr = 3 * 0.15 * e_roll  # spec §4.2, b = 0.15
    st_mono = stokes(m0, 1.0, g)
    sigma_d = 0.01 * g.sigma  # Z = 0.01 (spec §1.7): kSigmaD

    A = "CompressionSwitchesOnAtThreeBERollOfTheReducedMassEnergy"
    ref.cmp(s, A, "2.131834550635301e-9", thr, 1e-12, what="3 b E_roll of ice (comment)")
    ref.cmp(s, A, "0.923435877716542", math.sqrt(4 * thr / 1e-8), 1e-12,
            what="dv at E_imp = m dv^2/4 = 3 b E_roll, m = 1e-8 g")

    A = "constexpr double kM0"
    ref.cmp(s, A, "5.864306286700947e-15", m0, 1e-12, what="kM0")
    for anchor, lit, mine, tol, what in (
            ("constexpr double kERoll", "4.737410112522892e-09", e_roll, 1e-12, "kERoll"),
            ("constexpr double kERoll", "4.74e-9", e_roll, 0.002, "kERoll (spec)"),
            ("constexpr double kStMono", "1.4462853858025006e-07", st_mono, 1e-12, "kStMono"),
            ("constexpr double kStMono", "1.45e-7", st_mono, 0.005, "kStMono (spec §12)"),
            ("constexpr double kOmega", "1.780976118388187e-08", g.omega, 1e-12, "kOmega"),
            ("constexpr double kSigmaG", "152.0526224699857", g.sigma, 1e-12, "kSigmaG"),
            ("constexpr double kThreshold", "2.131834550635301e-9", thr, 1e-12, "kThreshold = 3 b E_roll")):
        ref.cmp(s, anchor, lit, mine, tol, what=what)

    A = "CoagulationRateMatchesSpecFormula"
    for prefix in ("{1e-10, 1.0", "{1.0, 1e-3", "{1e8, 5e-4", "{1e12, 1e-3"):
        got = table_row(ref, s, A, prefix)
        if got is None:
            continue
        f, line = got
        m, phi = float(f[0]), float(f[1])
        sig = sigma_d if f[2] == "kSigmaD" else float(f[2])
        st_lit = float(f[3])
        tag = f"({f[0]} g, {f[1]})"
        ref.value(s, A, f[3], st_lit, line, stokes(m, phi, g), 1e-9, "rel", f"St{tag}")
        ref.value(s, A, f[4], float(f[4]), line, radius(m, phi), 1e-13, "rel", f"a{tag}")
        ref.value(s, A, f[5], float(f[5]), line, float(h_dust(st_lit, g)), 1e-12, "rel", f"h_d{tag}")
        ref.value(s, A, f[6], float(f[6]), line, k_coag(m, phi, st_lit, sig, g), 1e-12, "rel",
                  f"K = 2 sqrt(pi) a^2 Sigma_d/h_d {tag}")

    # --- erosion E1: St* where dv_ls(St, 1e10 g) against monomers = v_eros = 40 m/s
    A = "FactorIsTanhSwitchOfDvLsOverVEros"
    m_t, phi_t = 1e10, 1e-5
    dvls_t = lambda st: float(dv_small(st, m_t, st_mono, m0, g))  # noqa: E731
    st_star = log_root(lambda st: dvls_t(st) - 4e3, 0.1, 1.0)
    val, line = (None, "?")
    try:
        val, line = s.find(A, "0.3368842767113562")
    except LookupError as e:
        ref._report(s, False, "?", A, "St*", str(e))
    if val is not None:
        # the test asserts S(St*) = 0.5 to 1e-9 with w = 0.01: |dv_ls(St*)/v_eros - 1| < 2e-11
        x_lit = dvls_t(val) / 4e3
        ref._report(s, abs(x_lit - 1) < 2e-11, line, A, "dv_ls(St*) = v_eros",
                    f"python x(St* of the test) - 1 = {x_lit - 1:.1e} (|.| < 2e-11 from "
                    f"|S - 1/2| < 1e-9 at w = 0.01); python St* = {st_star:.16g}", "asserted/input")
    ref.cmp(s, A, "0.33688427671", st_star, 0, "digits", what="St* (comment)")
    ref.claim(s, A, 0.32 <= st_star <= 0.36, "St* in the spec's 0.32-0.36 (§5.2)", literal="0.32-0.36")
    ref.cmp(s, A, "0.328", stokes(m_t, phi_t, g), 0, "digits", what="St(1e10 g, 1e-5) (comment)")
    h = 1e-6
    slope_ls = (math.log(dvls_t(st_star * (1 + h))) - math.log(dvls_t(st_star * (1 - h)))) / \
        (math.log1p(h) - math.log1p(-h))
    ref.cmp(s, A, "0.71", slope_ls, 0, "digits", what="d ln dv_ls / d ln St at St* (comment)")
    s_lo = erosion_s(dvls_t(0.9 * st_star) / 4e3, 0.01)
    s_hi = erosion_s(dvls_t(1.1 * st_star) / 4e3, 0.01)
    ref.claim(s, A, s_lo > 1 - 1e-5 and s_hi < 1e-5, "w = 0.01: S(0.9 St*) > 1 - 1e-5, S(1.1 St*) < 1e-5",
              literal="1e-5")

    # --- erosion E2: K_d and K_s
    A = "GrowthErosionBalance, MatchesSpecFormula"
    h_s = float(h_dust(st_mono, g))
    for prefix in ("{0.1, ", "{0.3368842767113562, ", "{1.0, ", "{100.0, "):
        got = table_row(ref, s, A, prefix)
        if got is None:
            continue
        f, line = got
        st = float(f[0])
        a = radius(m_t, phi_t)
        h_d = float(h_dust(st, g))
        h_bar = math.sqrt(h_d ** 2 + h_s ** 2) / math.sqrt(2)
        ref.value(s, A, f[1], float(f[1]), line, 2 * math.sqrt(PI) * a * a * sigma_d / h_d, 1e-12, "rel",
                  f"K_d(St = {f[0]})")
        ref.value(s, A, f[2], float(f[2]), line, 2 * math.sqrt(PI) * a * a * sigma_d / h_bar, 1e-12, "rel",
                  f"K_s(St = {f[0]}), h_bar = sqrt(h_d^2 + h_s^2)/sqrt 2")

    A = "NetErosionWellAboveVEros"

    def r_s_over_coag(st):
        h_d = float(h_dust(st, g))
        h_bar = math.sqrt(h_d ** 2 + h_s ** 2) / math.sqrt(2)
        return dvls_t(st) * h_d / (float(dv_pair(st, m_t, g)) * h_bar)
    r1 = r_s_over_coag(1.0)
    ref.cmp(s, A, "0.07396515994630538", r1, 1e-9 / 0.95, "abs", what="R_s/R_coag at St = 1")
    ref.cmp(s, A, "0.0740", r1, 0, "digits", what="R_s/R_coag at St = 1 (comment)")
    ref.cmp(s, A, "0.114", r_s_over_coag(st_star), 0, "digits", what="R_s/R_coag at St* (comment)")
    ref.claim(s, A, all(r_s_over_coag(st) < 0.05 for st in (10.0, 30.0, 100.0, 1e3, 1e4)),
              "R_s/R_coag < 0.05 for St > 10 (comment)", literal="0.05 for St > 10")
    ref.cmp(s, A, "1.71", dvls_t(1.0) / 4e3, 0, "digits", what="x = dv_ls/v_eros at St = 1 (comment)")
    ref.cmp(s, A, "0.93", 1 / (1 + r1), 0, "digits", what="f_s above which E2 erodes at St = 1 (comment)")
    ref.cmp(s, A, "-0.02026690", 0.05 - 0.95 * r1, 0, "digits", what="E2/coag at f_s = 0.95 (comment)")
    ref.claim(s, A, erosion_s(dvls_t(1.0) / 4e3, 0.01) < 1e-16, "S = 0 in double at St = 1")
    worst = min(0.9 + 0.1 * r_s_over_coag(st) * (1 - 2 * (1 - erosion_s(dvls_t(st) / 4e3, 0.01)))
                for st in np.exp(np.linspace(np.log(1e-6), np.log(1e4), 400)))
    ref.cmp(s, A, "0.88", worst, 0, "digits",
            what="min over St of E2/coag at f_s = 0.1, eps = 1 ('stays >= 0.88', comment)")

    A = "WithErosionBalanceFragmentsOnlyTheSimilarSizeTerm"
    st1 = 1.0
    dv1 = float(dv_pair(st1, m_t, g))
    coag = k_coag(m_t, phi_t, st1, sigma_d, g) * dv1
    e2 = 0.05 - 0.95 * r1
    ff = frag_factor(dv1, 1e3)
    # The comment's g/s numbers (measured on the C++ when the bug was found, commit
    # 9345489) are 1.35% below these; they fit Sigma_d = 1.5 g cm^-2 instead of the test's
    # kSigmaD = 0.01 Sigma_g = 1.5205 to their digits: a comment-level imprecision, noted.
    # The dimensionless ratios they imply (F_frag, the E2 factor) are checked.
    ref.cmp(s, A, "-481", -11.6 * ff / e2, 0.01,
            what="-11.6 x F_frag / (E2 factor) (comment; Sigma_d-free ratio, 3 digits: 1%)")
    ref.cmp(s, A, "+9.75", -11.6 * ff, 0.01,
            what="-11.6 x F_frag (comment; Sigma_d-free ratio, 3 digits: 1%)")
    ref.note(s, A, "-481", coag * ff,
             f"comment '+9.75 g/s here against -481 and -11.6 g/s alone': at the test's state "
             f"(kSigmaD = {sigma_d:.4f}) python gives {coag * ff * e2:+.2f}, {coag * ff:.1f}, "
             f"{coag * e2:.2f} g/s, "
             f"1.35% more; with Sigma_d = 1.5 it gives {coag * ff * e2 * 1.5 / sigma_d:+.2f}, "
             f"{coag * ff * 1.5 / sigma_d:.1f}, {coag * e2 * 1.5 / sigma_d:.2f} (the comment's digits); "
             f"their ratios agree with python")

    A = "GrowthFragmentation, FactorAndLimits"
    st_slow, st_fast = stokes(1.0, 1e-3, g), stokes(1e8, 5e-4, g)
    ref.cmp(s, A, "8.020136923798523e-05", st_slow, 1e-9, what="St(1 g, 1e-3)")
    ref.cmp(s, A, "0.20427797089107294", st_fast, 1e-9, what="St(1e8 g, 5e-4)")
    dv_slow, dv_fast = float(dv_pair(st_slow, 1.0, g)), float(dv_pair(st_fast, 1e8, g))
    ref.cmp(s, A, "5.84", dv_slow, 0, "digits", what="dv(1 g, 1e-3) [cm/s] (comment)")
    ref.cmp(s, A, "17.8", dv_fast / 100, 0, "digits", what="dv(1e8 g, 5e-4) [m/s] (comment)")
    ref.cmp(s, A, "1.9e-6", 1 - frag_factor(dv_slow, 6e3), 0, "digits", what="1 - F(slow, 60 m/s) (comment)")
    ref.claim(s, A, abs(frag_factor(dv_slow, 6e3) - 1) < 1e-5, "F(slow, 60 m/s) = 1 to 1e-5", literal="1e-5")
    ref.cmp(s, A, "0.8385", frag_factor(dv_fast, 6e3), 0, "digits", what="F(fast, 60 m/s) (comment)")
    ref.cmp(s, A, "-0.99369", frag_factor(dv_fast, 1e2), 0, "digits", what="F(fast, 1 m/s) (comment)")
    ref.claim(s, A, frag_factor(dv_fast, 1e2) < -0.99, "F(fast, 1 m/s) < -0.99", literal="-0.99")
    ref.cmp(s, A, "6.3e-7", frag_factor(dv_fast, 1.0) + 1, 0, "digits", what="F(fast, 1 cm/s) + 1 (comment)")

    A = "HitAndStickAndCompressionSlopes"
    ref.cmp(s, A, "120.42", g.mfp, 0, "digits", what="lambda(5 AU) (comment)")
    ref.cmp(s, A, "2.1318e-9", thr, 0, "digits", what="3 b E_roll (comment)")
    ref.cmp(s, A, "4.7374e-9", e_roll, 0, "digits", what="E_roll (comment)")
    cases = (("{1e-12, 1e-2", "4.6e-5", None, None, "hs"),
             ("{1.0, 1e-3", "4e9", "0.020", "8e-5", "ep"),
             ("{1e12, 1e-3", "7e25", None, "26.7", "heavy"),
             ("{1e9, 1e-6", "9e22", "205", "0.062", "stokes"))
    for prefix, e_lit, x_lit, st_lit, regime in cases:
        got = particle_row(ref, s, A, prefix, g)
        if got is None:
            continue
        f, line, m, phi, st = got
        e_ratio = 0.25 * m * float(dv_pair(float(f[2]), m, g)) ** 2 / thr
        x = 4 * radius(m, phi) / (9 * g.mfp)
        ref.cmp(s, A, e_lit, e_ratio, 0, "digits", what=f"E_imp/(3 b E_roll) at {f[0]} g (comment)")
        if x_lit:
            ref.cmp(s, A, x_lit, x, 0, "digits", what=f"x = 4a/(9 lambda) at {f[0]} g (comment)")
        if st_lit:
            ref.cmp(s, A, st_lit, st, 0, "digits", what=f"St at {f[0]} g (comment)")
        ok = {"hs": e_ratio < 1e-4,
              "ep": e_ratio > 1e9 and x < 0.1 and st < 0.1,
              "heavy": e_ratio > 1e9 and st > 10,
              "stokes": e_ratio > 1e9 and x > 10 and st < 0.1}[regime]
        slope = {"hs": "-0.58", "ep": "-1/8", "heavy": "-1/5", "stokes": "0"}[regime]
        ref._report(s, ok, line, A, f"regime of ({f[0]} g, {f[1]})",
                    f"E_imp/thr = {e_ratio:.2g}, x = {x:.3g}, St = {st:.3g}: deep in the s = {slope} "
                    f"regime of spec §4.3 ({'holds' if ok else 'FAILS'})")

    A = "CompressionSlopeFollowsEpsteinDragLaw"
    ref.cmp(s, A, "8.020136923798508e-04", stokes(1e9, 1e-6, g, law="epstein"), 1e-12,
            what="Epstein St(1e9 g, 1e-6)")
    ref.cmp(s, A, "554.5", radius(1e9, 1e-6) / 100, 0, "digits", what="a(1e9 g, 1e-6) [m] (comment)")
    ref.cmp(s, A, "205", 4 * radius(1e9, 1e-6) / (9 * g.mfp), 0, "digits", what="x (comment)")

    A = "NoChangeWhileLosingMass"
    ref.cmp(s, A, "0.20427797089107294", st_fast, 1e-9, what="St(1e8 g, 5e-4)")
    ref.cmp(s, A, "17.8", dv_fast / 100, 0, "digits", what="dv [m/s] (comment)")

    A = "GrowthTurbulence, Vg2FactorScalesOnlyTheTurbulentTerm"
    ref.cmp(s, A, "0.20427797089107294", st_fast, 1e-9, what="St(1e8 g, 5e-4)")
    ref.claim(s, A, float(dv2_turbulent(st_fast, 0.5 * st_fast, g)) > 0.5 * dv_fast ** 2,
              "turbulence dominates dv^2 at (1e8 g, 5e-4)")

    # --- compaction floors (spec §4.3)
    fgas = lambda m, st: phi_gas(m, st, g, m0, e_roll)  # noqa: E731
    fgrav = lambda m: phi_grav(m, m0, e_roll)  # noqa: E731

    def t_grow_omega(m, phi, st):
        return m / (k_coag(m, phi, st, sigma_d, g) * float(dv_pair(st, m, g))) * g.omega

    A = "PushFarBelowFloorIsLogDistanceOverRelaxationTime"
    for prefix, what in (('{"gas", ', "gas"), ('{"gas+grav"', "gas+grav"),
                         ('{"gas, fast growth"', "gas, fast"),
                         ('{"grav", ', "grav"), ('{"grav+gas"', "grav+gas")):
        got = table_row(ref, s, A, prefix)
        if got is None:
            continue
        f, line = got
        m, phi, st_lit = float(f[1]), float(f[2]), float(f[3])
        gas_on, grav_on = f[4] == "true", f[5] == "true"
        ref.value(s, A, f[3], st_lit, line, stokes(m, phi, g), 1e-9, "rel", f"{what}: St({f[1]} g, {f[2]})")
        fl_gas, fl_grav = fgas(m, st_lit), fgrav(m)
        floor = max(fl_gas if gas_on else 0, fl_grav if grav_on else 0)
        ref.value(s, A, f[6], float(f[6]), line, floor, 1e-9, "rel", f"{what}: floor (spec §4.3)")
        if gas_on and grav_on:
            ref._report(s, max(fl_gas, fl_grav) > 20 * min(fl_gas, fl_grav), line, A, f"{what}: floors apart",
                        f"phi_gas = {fl_gas:.3g}, phi_grav = {fl_grav:.3g} (> 20x apart)")
        tg = t_grow_omega(m, phi, st_lit)
        shorter = f[7] == "true"
        ref._report(s, (tg < 0.1 if shorter else 10 < tg < 100) and math.log(floor / phi) > 2,
                    line, A, f"{what}: regime",
                    f"t_grow Omega = {tg:.3g} ({'< 0.1' if shorter else '10-100'}), "
                    f"z = ln(floor/phi) = {math.log(floor / phi):.2f} > 2")
    st_g = float(s.row(A, '{"gas", ')[0][3])
    for lit, mine, what in (("7.62e-5", st_g, "St(1e4 g, 1e-6)"),
                            ("4.0e-7", fgrav(1e4), "phi_grav(1e4 g)"),
                            ("1.7279e-10", stokes(1e-9, 1e-7, g), "St(1e-9 g, 1e-7)"),
                            ("205.9", stokes(1e15, 1e-4, g), "St(1e15 g, 1e-4)"),
                            ("3.8e-4", fgas(1e15, stokes(1e15, 1e-4, g)), "phi_gas(1e15 g)")):
        ref.cmp(s, A, lit, mine, 0, "digits", what=f"{what} (comment)")
    for lit, m, phi in (("15", 1e4, 1e-6), ("0.043", 1e-9, 1e-7), ("52", 1e15, 1e-4)):
        ref.cmp(s, A, lit, t_grow_omega(m, phi, stokes(m, phi, g)), 0, "digits",
                what=f"t_grow Omega at ({m:g} g, {phi:g}) (comment)")

    A = "RelaxationCappedAtHundredOrbitsWhereGrowthIsSlow"
    ref.cmp(s, A, "0.00013300598760858056", fgas(1e4, st_g), 1e-9, what="phi_gas(1e4 g) at St(1e4 g, 1e-6)")
    ref.cmp(s, A, "7.618670735964675e-05", stokes(1e4, 1e-6, g), 1e-9, what="St(1e4 g, 1e-6)")
    ref.cmp(s, A, "1.5e6", 1e5 * t_grow_omega(1e4, 1e-6, st_g), 0.05,
            what="t_grow Omega at f_grow = 1e-5 (comment, 2 digits)")

    A = "LittleLeakAboveFloorWhereGrowthIsSlow"
    floor = fgas(1e4, st_g)
    ref.cmp(s, A, "0.00013300598760858056", floor, 1e-9, what="phi_gas(1e4 g)")
    phi = 1.08 * floor
    # The test passes St = 7.6187e-5, the St of (1e4 g, phi = 1e-6), with phi = 1.08
    # floor: checked as the number it is; the comment numbers below follow from that
    # state. The St of (1e4 g, 1.08 floor) itself is 4.87e-4 (see the note).
    st_used = st_g
    ref.cmp(s, A, "7.618670735964675e-05", stokes(1e4, 1e-6, g), 1e-9, what="St passed (= St(1e4 g, 1e-6))")
    tg = t_grow_omega(1e4, phi, st_used)
    z = math.log(1 / 1.08)
    ref.cmp(s, A, "-0.077", z, 0, "digits", what="z (comment)")
    ref.cmp(s, A, "400", tg, 0.25, what="t_grow Omega at the state passed (comment '~ 400', 25%)")
    ref.claim(s, A, tg > 200.0, f"t_grow Omega > 200 (the cap binds; python {tg:.0f})", literal="200.0")
    # the test's own written-out t_relax: 0.03 soft_min_8(t_grow, 100/Omega) (code choice,
    # see the module docstring); growth factor 0.5 (1 + sqrt(1 + 1e-6))
    dlnm = (1 / tg) * 0.5 * (1 + math.sqrt(1 + 1e-6))
    t_relax = 0.03 * (dlnm ** 8 + (1 / 100.0) ** 8) ** (-1 / 8)  # in units of 1/Omega
    push = softplus(z, 100.0) / t_relax
    decline = 0.125 * dlnm
    ref.claim(s, A, 2.5 < t_relax < 3.5, f"t_relax ~ 3/Omega (python {t_relax:.3f}/Omega)", literal="3/Omega")
    ref.cmp(s, A, "1.5e-6", push, 0.1, what="push [Omega] (comment '~1.5e-6 Omega', 10%)")
    ref.cmp(s, A, "3e-4", decline, 0.2, what="decline 1/8 d ln m/dt [Omega] (comment '~3e-4 Omega', 20%)")
    e_ratio = 0.25 * 1e4 * float(dv_pair(st_used, 1e4, g)) ** 2 / thr
    ref.claim(s, A, push < 0.1 * decline and 300 * push > decline and e_ratio > 100
              and 4 * radius(1e4, phi) / (9 * g.mfp) < 1 and st_used < 0.1,
              f"push < 0.1 x decline < 300 x push (compression, Epstein side: x = "
              f"{4 * radius(1e4, phi) / (9 * g.mfp):.2f}; s ~ -1/8): push/decline = {push / decline:.3g}",
              literal="300.0")
    st_self = stokes(1e4, phi, g)
    ref.note(s, A, "7.618670735964675e-05", st_self,
             f"the test evaluates phi = 1.08 floor = {phi:.4g} with St = {st_used:.4g}, "
             f"the St of phi = 1e-6; "
             f"the St of (1e4 g, {phi:.3g}) is {st_self:.4g} (python), where t_grow Omega = "
             f"{t_grow_omega(1e4, phi, st_self):.1f}, not ~400: the cap does not bind at the "
             f"self-consistent state (particle_rates takes St as an argument, so the test's "
             f"algebra holds; its scenario 'where growth is slow' is not that of this particle)")

    A = "NegligibleWellAboveFloor"
    for prefix, flit, fmine, what in (("{1e4, 4e-4", "1.330e-4", None, "phi_gas(1e4 g)"),
                                      ("{1e15, 3e-2", "1.013e-2", fgrav(1e15), "phi_grav(1e15 g)"),
                                      ("{1e-12, 1e-2", None, None, "")):
        got = particle_row(ref, s, A, prefix, g)
        if got is None:
            continue
        f, line, m, phi, st = got
        floor = max(fgas(m, st), fgrav(m))
        if flit:
            ref.cmp(s, A, flit, fmine if fmine is not None else fgas(m, st), 0, "digits",
                    what=f"{what} (comment)")
        ref._report(s, math.log(floor / phi) < -1.0, line, A, f"({f[0]} g, {f[1]}) well above the floor",
                    f"z = ln(floor/phi) = {math.log(floor / phi):.2f} < -1")
    ref.cmp(s, A, "9.4e-5", fgas(1e15, stokes(1e15, 3e-2, g)), 0, "digits",
            what="phi_gas(1e15 g, 3e-2) (comment)")
    ref.cmp(s, A, "-1.1", math.log(fgas(1e4, stokes(1e4, 4e-4, g)) / 4e-4), 0, "digits",
            what="z at (1e4 g, 4e-4) (comment)")

    A = "SpecDerivedMagnitudes"
    for prefix, gas_floor in (('{"phi_gas(1e4 g)"', True), ('{"phi_gas(1e10 g)"', True),
                              ('{"phi_gas(1e18 g)"', True), ('{"phi_grav(1e15 g)"', False),
                              ('{"phi_grav(1e18 g)"', False)):
        got = table_row(ref, s, A, prefix)
        if got is None:
            continue
        f, line = got
        m, phi_f, st_lit = float(f[1]), float(f[2]), float(f[3])
        lo, hi = float(f[5]), float(f[6])
        if gas_floor:
            # self-consistent state: phi = phi_gas(m, St(m, phi)) (fixed point, bisection)
            phi_sc = log_root(lambda p: math.log(fgas(m, stokes(m, p, g)) / p), 1e-8, 0.5)
            ref.value(s, A, f[2], phi_f, line, phi_sc, 1e-9, "rel", f"{f[0]}: self-consistent phi_gas")
            ref.value(s, A, f[3], st_lit, line, stokes(m, phi_sc, g), 1e-9, "rel", f"{f[0]}: St(m, phi_gas)")
            mine = fgas(m, st_lit)
        else:
            mine = fgrav(m)
            ref.value(s, A, f[2], phi_f, line, mine, 1e-9, "rel", f"{f[0]}")
            # St of these rows is not that of the self-consistent state the comment names:
            # it is St(m, 1e-4) and St(m, 1e-5); the floor does not depend on St.
            phi_used = 1e-4 if m == 1e15 else 1e-5
            ref.value(s, A, f[3], st_lit, line, stokes(m, phi_used, g), 1e-9, "rel",
                      f"{f[0]}: St(m, {phi_used:g}) (the St this row passes)")
        ref._report(s, lo < mine < hi, line, A, f"{f[0]} in the spec band",
                    f"{lo:g} < {mine:.4g} < {hi:g} ({'holds' if lo < mine < hi else 'FAILS'})")
    # the spec's "phi_gas ~ 1e-2 at 1e18 g" against its own formula (C_D = 0.44 limit)
    closed = (1.32 * m0 * g.rho * g.vw ** 2 / (8 * PI * e_roll * RHO0)) ** (1 / 3)
    ref.cmp(s, A, "2.80e-4", closed, 0, "digits", what="phi_gas(1e18 g), C_D = 0.44 closed form (comment)")
    ref.cmp(s, A, "2.80e-4", fgas(1e18, stokes(1e18, 2.8e-4, g)), 0, "digits",
            what="phi_gas(1e18 g), formula (comment)")

    A = "RememberedLogsFollowTheSpeciesAndOptions"
    ref.cmp(s, A, "0.40", fgrav(1e19), 0, "digits", what="phi_grav(1e19 g) (comment)")

    A = "PhiRateIsSmoothWhereGrowthTurnsToLoss"
    st_c = stokes(1e4, 1.0, g)
    ref.cmp(s, A, "0.17278861207467963", st_c, 1e-9, what="St(1e4 g, phi = 1)")
    ref.cmp(s, A, "11.9", radius(1e4, 1.0), 0, "digits", what="a(1e4 g, 1) [cm] (comment)")
    ref.cmp(s, A, "0.044", 4 * radius(1e4, 1.0) / (9 * g.mfp), 0, "digits", what="x (comment)")
    h = 1e-5
    dlnv = (math.log(float(dv_pair(st_c * math.exp(h), 1e4, g))) -
            math.log(float(dv_pair(st_c * math.exp(-h), 1e4, g)))) / (2 * h)
    ref.cmp(s, A, "0.6236652407842769", dlnv, 1e-6, what="d ln dv / d ln St at fixed m (central difference)")

    A = "GrowthAutoDiff, MatchesCentralFiniteDifferences"
    targets = (
        ("2.16266531069291e-07", "E_imp = 3 b E_roll, phi = 1e-2",
         lambda m: math.log(0.25 * m * float(dv_pair(stokes(m, 1e-2, g), m, g)) ** 2 / thr), 1e-12, 1e-3),
        ("11665.648182477757", "x = 4a/(9 lambda) = 1, phi = 1e-4",
         lambda m: math.log(4 * radius(m, 1e-4) / (9 * g.mfp)), 1.0, 1e8),
        ("2296877226.4092894", "St = 1, phi = 1e-3",
         lambda m: math.log(stokes(m, 1e-3, g)), 1e6, 1e12),
        ("1.2580197071079174e+16", "St = 1e4, phi = 1e-2",
         lambda m: math.log(stokes(m, 1e-2, g) / 1e4), 1e12, 1e20),
        ("10708412973.512157", "dv_ls = v_eros (E1 x = 1), phi = 1e-5",
         lambda m: math.log(float(dv_small(stokes(m, 1e-5, g), m, st_mono, m0, g)) / 4e3), 1e8, 1e12))
    for lit, what, fun, lo, hi in targets:
        m_sw = log_root(fun, lo, hi)
        ref.cmp(s, A, lit, m_sw, 1e-8, what=f"switch mass: {what} (bisection in ln m)")
    x098 = float(dv_small(stokes(1e10, 1e-5, g), 1e10, st_mono, m0, g)) / 4e3
    ref.cmp(s, A, "0.98", x098, 0, "digits", what="E1 x at (1e10 g, 1e-5) (case name)")
    bend = math.log(fgas(1e4, stokes(1e4, 1.3367e-4, g)) / 1.3367e-4)
    ref.claim(s, A, abs(100 * bend) < 1,
              f"(1e4 g, 1.3367e-4) sits in the softplus_100 bend (100 z = {100 * bend:.2f})",
              literal="1.3367e-4")

    A = "RatesHaveNoJumpInMass"
    sts = np.exp(np.linspace(np.log(1e-8), np.log(1e4), 4000))
    dv_max = float(np.max(dv_pair(sts, 1e30, g)))  # the Brownian term is nil at large m
    ref.claim(s, A, dv_max < 6e3,
              f"dv_pair never reaches the 60 m/s default at 5 AU (max {dv_max / 100:.1f} m/s)",
              literal="the 60 m/s default is never reached")
    ref.cmp(s, A, "12.8", math.log(19) / (0.1 * math.log(10)), 0, "digits",
            what="logistic k for 0.1 dex (comment)")

    A = "RatesHaveNoJumpAcrossPhiBounce"
    ref.cmp(s, A, "25.6", math.log(19) / (0.05 * math.log(10)), 0, "digits",
            what="logistic k for 0.05 dex (comment)")
    return s


NOT_COVERED = """\
Not covered: properties of the C++ (round-off, continuity, AutoDiff tests), the
particle_rates() ratios whose expectations the tests compute at run time from the C++
dv (their hard-coded inputs are covered), the compaction push (the code's t_relax), the
spec §0 material constants. Details: the module docstring.
"""


def main():
    parse_args()  # --exe, --workdir: accepted, unused (nothing is run)
    c = Checks()
    ref = Ref(c)
    sources = [check_contact(ref), check_particle(ref), check_relative_velocity(ref), check_growth(ref)]
    print()
    for src in sources:
        n = src.count
        print(f"{src.name}: {sum(n.values())} checks: {n['asserted/input']} numbers asserted in or "
              f"passed by the test, {n['comment']} numbers quoted in its comments, {n['claim']} claims")
    print(NOT_COVERED)
    if NOTES:
        print("Notes (comment-level discrepancies, explained, not failed):")
        for n in NOTES:
            print("  " + n)
    print(f"run time {time.time() - T_START:.1f} s")
    c.finish()


if __name__ == "__main__":
    main()
