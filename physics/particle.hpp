#pragma once
//! Properties of the mass-dominating dust particle of a cell (spec §2): monomer mass,
//! radius from (m, phi), Stokes number (Epstein, and the smooth Epstein-Stokes-Reynolds
//! law), dust scale height and midplane dust density; plus the smooth switches (soft-max,
//! soft-min, logistic step) used by every regime change in physics/. Sources: Epstein
//! (1924) and Stokes drag; Weidenschilling (1977) C_D(Re_p); the smooth form of
//! DiscEvolution (Booth et al., porous_dust.py); Nakagawa, Sekiya & Hayashi (1986) for
//! the particle-gas speed; Youdin & Lithwick (2007) for h_d; Okuzumi et al. (2012) for
//! their use.
//!
//! Every function is a template on the scalar type T, so that it can be evaluated with
//! double and with Eigen::AutoDiffScalar (exact Jacobians). Rules for T code in this
//! file: unqualified sqrt/exp/log/pow after `using std::...` (ADL finds Eigen's
//! overloads), every intermediate is stored in a named T (never `auto`: Eigen's AutoDiff
//! expressions reference temporaries), and no std::max/std::min on T (their derivative
//! jumps): use soft_max/soft_min/logistic. The gas is a LocalGasT<G>
//! (physics/local_gas.hpp): G = double, or AD where the Jacobian differentiates an
//! evolving Sigma_g; quantities derived from its density-dependent fields are G, never
//! double.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "physics/local_gas.hpp"
#include "src/autodiff.hpp"
#include "src/units.hpp"

namespace panoptic::physics {

//! p of the p-norm soft-max (spec §2) [-].
inline constexpr double kSoftMaxPower = 8.0;
//! Newton steps on ln St in stokes_number() (5 reach round-off) [-].
inline constexpr int kDragIterations = 6;
//! Re_p below which f_Re = (1 + Re_p^(0.4 p) + (0.01833 Re_p)^p)^(1/p) is 1 to round-off:
//! Re_p^3.2 < 1e-16 [-].
inline constexpr double kReNegligible = 1e-5;
//! ln kReNegligible.
inline constexpr double kLnReNegligible = -11.512925464970229;
//! C_D = 0.44 written as 24/Re_p times (this constant * Re_p) (Weidenschilling 1977) [-].
inline constexpr double kCdNewton = 0.44 / 24.0;

//! Drag law of spec §9 (`drag.law`).
enum class DragLaw {
  kEpstein,   //!< Epstein drag at every size
  kStokesRe,  //!< smooth Epstein-Stokes-Reynolds law (default)
};

// ---------------------------------------------------------------------------------------------
// Smooth switches
// ---------------------------------------------------------------------------------------------

//! log2(p) when p is 2, 4, ..., 64, else 0.
inline int power_of_two_exponent(double p) {
  for (int k = 1; k <= 6; ++k)
    if (p == double(1 << k)) return k;
  return 0;
}

//! The plain derivative vector of an AutoDiff type whose derivatives may be an Eigen
//! expression (AutoDiff arithmetic returns those).
template <class D>
using PlainDerivatives = typename Eigen::internal::remove_all<D>::type::PlainObject;

//! Cube root and log(1 + x) for double and for AutoDiff (Eigen's AutoDiff has neither):
//! the value from libm, the derivative by the chain rule. cbrt is about twice as fast as
//! pow(x, 1/3); log1p keeps the precision of log(1 + x) for x below the round-off of 1.
inline double cbrt_of(double x) { return std::cbrt(x); }
template <class D>
Eigen::AutoDiffScalar<PlainDerivatives<D>> cbrt_of(const Eigen::AutoDiffScalar<D>& x) {
  const double c = std::cbrt(x.value());
  return Eigen::AutoDiffScalar<PlainDerivatives<D>>(
      c, PlainDerivatives<D>(x.derivatives() * (c / (3.0 * x.value()))));
}
inline double log1p_of(double x) { return std::log1p(x); }
template <class D>
Eigen::AutoDiffScalar<PlainDerivatives<D>> log1p_of(const Eigen::AutoDiffScalar<D>& x) {
  return Eigen::AutoDiffScalar<PlainDerivatives<D>>(
      std::log1p(x.value()),
      PlainDerivatives<D>(x.derivatives() * (1.0 / (1.0 + x.value()))));
}

//! log(1 + y) for y >= 0, with the series where it is exact to round-off: y - y^2/2 for
//! y < 1e-8 (next term y^3/3 < 3.4e-17 y) and ln y + 1/y for y > 1e8 (next term
//! 1/(2 y^2) < 3e-18 of the result). The drag solve takes ln(1 + (x/f_Re)^p) of grains
//! that are mostly deep in one regime, and log1p costs more than log.
template <class T>
T log1p_nonneg(const T& y) {
  using std::log;
  const double v = value_of(y);
  if (v < 1e-8) return y - 0.5 * y * y;
  if (v > 1e8) return log(y) + 1.0 / y;
  return log1p_of(y);
}

//! x^p. For p a power of two by repeated squaring: exact to round-off and an order of
//! magnitude cheaper than pow(), which dominated the cost of the smooth switches.
template <class T>
T power_p(const T& x, double p) {
  using std::pow;
  const int k = power_of_two_exponent(p);
  if (k == 0) return pow(x, p);
  T y = x;
  for (int i = 0; i < k; ++i) y = y * y;
  return y;
}

//! x^(1/p), by repeated square roots when p is a power of two (see power_p).
template <class T>
T root_p(const T& x, double p) {
  using std::pow;
  using std::sqrt;
  const int k = power_of_two_exponent(p);
  if (k == 0) return pow(x, 1.0 / p);
  T y = x;
  for (int i = 0; i < k; ++i) y = sqrt(y);
  return y;
}

//! Smooth maximum of two positive numbers, the p-norm (a^p + b^p)^(1/p) [units of a, b].
//! It exceeds max(a, b) by at most the factor 2^(1/p) (at a = b; 9% for p = 8), and
//! by (1/p) (min/max)^p elsewhere (< 1% once the arguments differ by 1.35x, p = 8).
//! Evaluated as max * (1 + (min/max)^p)^(1/p) so that it cannot overflow; both
//! branches are the same symmetric function, so the comparison introduces no jump in
//! value or derivative.
//! Where (min/max)^p < 1e-8 the root is taken as 1 + r^p/p, its Taylor series to
//! O(r^2p) < 1e-16 (below round-off), which skips the p-th root: most calls compare
//! quantities decades apart (the drag regime of a small grain, t_grow against the
//! relaxation cap), and the root was the costliest part of the smooth switches.
template <class T>
T soft_max(const T& a, const T& b, double p = kSoftMaxPower) {
  const bool a_larger = a >= b;
  const T& hi = a_larger ? a : b;
  const T r = (a_larger ? b : a) / hi;
  const T rp = power_p<T>(r, p);
  if (value_of(rp) < 1e-8) return hi * (1.0 + rp / p);
  return hi * root_p<T>(1.0 + rp, p);
}

//! Smooth minimum of two positive numbers, (a^-p + b^-p)^(-1/p) = a b / soft_max(a, b)
//! [units of a, b]; below min(a, b) by at most the factor 2^(-1/p).
template <class T>
T soft_min(const T& a, const T& b, double p = kSoftMaxPower) {
  const T hi = soft_max(a, b, p);
  return a * b / hi;
}

//! soft_max() from the logarithms of its arguments: ln soft_max(e^la, e^lb) = hi +
//! log1p(exp(-p |la - lb|)) / p, hi = max(la, lb) [ln of the units of a, b]. For laws
//! that are power laws (products of pow()) the logs cost less than the powers. Where
//! p |la - lb| > 40 the correction (< 5e-19) is below round-off and hi is returned
//! without calling exp.
template <class T>
T ln_soft_max(const T& la, const T& lb, double p = kSoftMaxPower) {
  using std::exp;
  const bool a_larger = value_of(la) >= value_of(lb);
  const T& hi = a_larger ? la : lb;
  const T d = (a_larger ? lb : la) - hi;  // <= 0
  if (p * value_of(d) < -40.0) return hi;
  return hi + log1p_of(exp(p * d)) / p;
}

//! soft_min() from the logarithms of its arguments: ln soft_min(e^la, e^lb) = lo -
//! log1p(exp(-p |la - lb|)) / p, lo = min(la, lb) (soft_min = a b / soft_max), i.e.
//! -ln_soft_max(-la, -lb) (negation is exact, so the two agree bit for bit).
template <class T>
T ln_soft_min(const T& la, const T& lb, double p = kSoftMaxPower) {
  const T neg_a = -la;
  const T neg_b = -lb;
  return -ln_soft_max(neg_a, neg_b, p);
}

//! Step (1 + tanh z) / 2 in [0, 1] [-]. For |z| > 20 tanh(z) is +-1 in double (1 - |tanh|
//! = 2 e^(-2|z|) < 1e-17, below half an ulp of 1), so the step is exactly 1 or 0; that is
//! returned without calling tanh (the same bits).
template <class T>
T tanh_step(const T& z) {
  using std::tanh;
  const double v = value_of(z);
  if (v > 20.0) return T(1.0);
  if (v < -20.0) return T(0.0);
  return 0.5 * (1.0 + tanh(z));
}

//! |k z| beyond which the logistic step is 0 or 1 to round-off: for k z > 37,
//! exp(-k z) < 8.5e-17 is below half an ulp of 1, so 1 / (1 + exp(-k z)) is exactly 1 in
//! double; for k z < -37 the step is below 8.5e-17 and is returned as 0.
inline constexpr double kLogisticSaturation = 37.0;

//! Logistic step 1 / (1 + exp(-k z)) in (0, 1) [-]; written in the form that never
//! evaluates exp of a large positive number (no inf, no NaN derivative). Saturated
//! (kLogisticSaturation) it returns 1 or 0 without calling exp.
template <class T>
T logistic_step(const T& z, double k) {
  using std::exp;
  const double kz = k * value_of(z);
  if (kz > kLogisticSaturation) return T(1.0);
  if (kz < -kLogisticSaturation) return T(0.0);
  if (kz >= 0.0) {
    const T e = exp(-k * z);
    return T(1.0) / (T(1.0) + e);
  }
  const T e = exp(k * z);
  return e / (T(1.0) + e);
}

//! floor(log2 x) of a finite double x > 0, read from its exponent bits (-1023 for
//! subnormals, which lie below 2^-1022); no libm call.
inline int binary_exponent(double x) {
  return static_cast<int>((std::bit_cast<std::uint64_t>(x) >> 52) & 0x7ff) - 1023;
}

//! Smooth step in ln x centred on x0: 0.5 at x = x0, 0.05 at x0 * 10^(-w) and 0.95 at
//! x0 * 10^(+w), w = half_width_dex (spec §3.5, "logistic in ln St over +-0.1 dex") [-].
//! Equivalent to 1 / (1 + (x0/x)^k) with k = ln 19 / (w ln 10) (k = 12.8 for w = 0.1).
//! Most calls are far from x0 (a grain's St against 10 or against 0.01), where the step
//! is saturated: that is decided from the binary exponent of x/x0, so those calls cost
//! neither the log nor the exp (together 9 of each per cell and right-hand side on the
//! fiducial scene).
template <class T, class X0>
T log_step(const T& x, const X0& x0, double half_width_dex) {
  using std::log;
  const double k = std::log(19.0) / (half_width_dex * std::log(10.0));
  const double r = value_of(x) / value_of(x0);
  if (r > 0.0 && r <= std::numeric_limits<double>::max()) {
    // log2 r lies in [e, e + 1)
    const int e = binary_exponent(r);
    const double kln2 = k * std::numbers::ln2;
    if (e * kln2 > kLogisticSaturation) return T(1.0);
    if ((e + 1) * kln2 < -kLogisticSaturation) return T(0.0);
  }
  const T z = log(x / x0);
  return logistic_step(z, k);
}

// ---------------------------------------------------------------------------------------------
// Particle structure (spec §2)
// ---------------------------------------------------------------------------------------------

//! Monomer mass m0 = (4 pi / 3) a0^3 rho0 (spec §2) [g]; a0 [cm], rho0 [g cm^-3].
template <class T>
T monomer_mass(const T& a0, const T& rho0) {
  return (4.0 * units::kPi / 3.0) * a0 * a0 * a0 * rho0;
}

//! Internal (aggregate) density rho_int = phi rho0 (spec §2) [g cm^-3].
template <class T>
T internal_density(const T& phi, double rho0) {
  return phi * rho0;
}

//! Aggregate radius a = (3 m / (4 pi rho0 phi))^(1/3) (spec §2) [cm]; m [g], phi [-].
template <class T>
T radius(const T& m, const T& phi, double rho0) {
  const T v = 3.0 * m / (4.0 * units::kPi * rho0 * phi);
  return cbrt_of(v);
}

//! Number of monomers N = m / m0 (spec §2) [-].
template <class T>
T monomer_count(const T& m, double m0) {
  return m / m0;
}

// ---------------------------------------------------------------------------------------------
// Drag (spec §2)
// ---------------------------------------------------------------------------------------------

//! Epstein Stokes number St = t_s Omega_K with t_s = rho_int a / (rho_g v_th) (spec §2;
//! Epstein 1924). At the midplane this equals pi rho_int a / (2 Sigma_g) [-].
template <class T, class G>
T stokes_epstein(const T& a, const T& rho_int, const LocalGasT<G>& gas) {
  return rho_int * a * (gas.omega_k / (gas.rho_g * gas.v_th));
}

//! x = 4 a / (9 lambda): Stokes/Epstein stopping-time ratio at Re_p < 1 (spec §2) [-].
//! t_Stokes = 2 rho_int a^2 / (9 nu_mol rho_g) = x t_Epstein when nu_mol = v_th lambda
//! / 2.
template <class T, class G>
T knudsen_ratio(const T& a, const LocalGasT<G>& gas) {
  return 4.0 * a / (9.0 * gas.mfp);
}

//! Laminar particle-gas speed dv_pg = eta v_K St sqrt(4 + St^2) / (1 + St^2) (spec §2;
//! Nakagawa, Sekiya & Hayashi 1986 radial and azimuthal drift combined) [cm s^-1].
template <class T, class G>
T gas_drift_speed(const T& St, const LocalGasT<G>& gas) {
  using std::sqrt;
  const T st2 = St * St;
  const T shape = St * sqrt(4.0 + st2) / (1.0 + st2);
  // the speed, |eta| v_K: where the pressure rises outward (eta < 0, the inner side of a
  // pressure maximum, or a surface density rising with r) the particle drifts outward
  // as fast, and the drag laws and the gas-compaction floor take logs of this speed
  return std::abs(gas.headwind()) * shape;
}

//! Log-slope of gas_drift_speed(): d ln(dv_pg) / d ln St =
//! 1 + St^2/(4 + St^2) - 2 St^2/(1 + St^2), in [-0.115, 1] [-].
template <class T>
T gas_drift_speed_log_slope(const T& St) {
  const T st2 = St * St;
  return 1.0 + st2 / (4.0 + st2) - 2.0 * st2 / (1.0 + st2);
}

//! Particle Reynolds number Re_p = 2 a dv_pg / nu_mol (spec §2) [-].
template <class T, class G>
T particle_reynolds(const T& a, const T& dv_pg, const LocalGasT<G>& gas) {
  return 2.0 * a * dv_pg / gas.nu_mol;
}

//! Smooth C_D(Re_p) correction f_Re of spec §2, with p = kSoftMaxPower:
//!   f_Re = (1 + Re_p^(0.4 p) + (0.01833 Re_p)^p)^(1/p)
//!        ~ max(1, Re_p^0.4, 0.01833 Re_p).
//! The three branches are Weidenschilling's (1977) C_D = 24/Re_p, 24 Re_p^-0.6, 0.44
//! written as t_s = t_Stokes / f_Re. Written with Re_p^(0.4 p) = Re_p^3.2 (not
//! (Re_p^0.4)^p) so that Re_p = 0 (no headwind) has a finite derivative [-].
template <class T>
T reynolds_correction(const T& re_p) {
  using std::pow;
  const double p = kSoftMaxPower;
  const T fp = 1.0 + pow(re_p, 0.4 * p) + power_p<T>(kCdNewton * re_p, p);
  return root_p<T>(fp, p);
}

//! d ln f_Re / d ln Re_p = (0.4 Re_p^(0.4p) + (0.01833 Re_p)^p) / f_Re^p [-].
template <class T>
T reynolds_correction_log_slope(const T& re_p) {
  using std::pow;
  const double p = kSoftMaxPower;
  const T b = pow(re_p, 0.4 * p);
  const T c = power_p<T>(kCdNewton * re_p, p);
  return (0.4 * b + c) / (1.0 + b + c);
}

//! Drag-regime factor g = St / St_Epstein of spec §2 (DiscEvolution form, smoothed):
//!   g(x, Re_p) = soft_max(1, x / f_Re(Re_p)) = (1 + (x/f_Re)^p)^(1/p),  p = 8.
//! Limits: g -> 1 (Epstein) for x << 1; g -> x (Stokes, Re_p < 1), x Re_p^-0.4, or
//! x / (0.01833 Re_p) (C_D = 0.44) for x >> f_Re. The hard max() of DiscEvolution
//! (`where(x < 1, 1, x/f)`) has a kink at every regime boundary, which stalls CVODE's
//! Newton iteration (spec §6.4); the p-norm is C-infinity, within 1% of the hard law once
//! the two competing branches differ by more than 35%, and at most 9% (2^(1/8)) above it
//! exactly at a boundary, well inside the uncertainty of the drag law there [-].
template <class T>
T drag_regime_factor(const T& x, const T& re_p) {
  const T f = reynolds_correction(re_p);
  const T y = x / f;
  return soft_max(T(1.0), y);
}

//! Stokes number of an aggregate of mass m [g] and filling factor phi [-] made of
//! monomers of density rho0 [g cm^-3], spec §2 [-].
//!
//! kEpstein: St = St_Ep. kStokesRe: St = St_Ep g(x, Re_p(St)), implicit because
//! Re_p = 2 a dv_pg(St) / nu_mol. Plain fixed-point (Picard) iteration St <- St_Ep g(...)
//! does not converge where C_D = 0.44 and St < 1: there St_Ep g ~ 1/dv_pg ~ 1/St, a map
//! with slope -1 in ln St that oscillates forever (5 Picard steps leave 1-2% errors at
//! 1-5 au and up to a factor e^4 for fluffy km bodies at 0.3 au). We therefore iterate
//! the Newton map of
//!   G(u) = u - ln(St_Ep g(x, Re_p(e^u))),  u = ln St,
//!   u <- u - G(u) / G'(u),   G' = 1 - (dln g/dln f)(dln f/dln Re)(dln dv_pg/dln St),
//! with analytic slopes (G' lies in [0.88, 2], so the step is always well defined),
//! starting from the smaller of the Re_p = 0 law u0 = ln(St_Ep soft_max(1, x)) and the
//! hard-branch solution (below). A bounded number of steps keeps the result a
//! deterministic function of (m, phi), smooth to round-off, whose AutoDiff derivative
//! converges to the implicit-function derivative (the Newton map is flat at its fixed
//! point). No call of the fiducial run took more than four steps; we allow 6.
//! stokes_number_of_radius() is the same law for a known radius a = radius(m, phi, rho0)
//! (the growth model's St cache keeps a for the rates; the same bits).
template <class T, class G>
T stokes_number_of_radius(const T& a, const T& phi, double rho0, const LocalGasT<G>& gas,
                          DragLaw law = DragLaw::kStokesRe,
                          int iterations = kDragIterations) {
  using std::exp;
  using std::log;
  using std::pow;
  const T rho_int = internal_density(phi, rho0);
  const T st_ep = stokes_epstein(a, rho_int, gas);  // spec §2; Epstein (1924)
  if (law == DragLaw::kEpstein) return st_ep;

  const double p = kSoftMaxPower;
  const T x = knudsen_ratio(a, gas);
  // A grain inside the Epstein regime (x < 0.01: ln g < x^8/8 = 1.25e-17 for any Re_p,
  // since f_Re >= 1, below half an ulp of 1) has St = St_Ep to round-off: the Newton
  // solve would return exp(ln St_Ep).
  if (value_of(x) < 1e-2) return st_ep;
  const T ln_st_ep = log(st_ep);
  // g = soft_max(1, x / f_Re) = (1 + y^p)^(1/p) with y^p = x^p / f_Re^p, so ln g =
  // log1p(x^p / f_Re^p) / p: no p-th root, no soft_max (drag_regime_factor() is the same
  // function; x < 3e38 in any disk, so x^p is finite).
  const T xp = power_p<T>(x, p);
  T u = ln_st_ep + log1p_nonneg(xp) / p;  // the Re_p = 0 law
  // Re_p = K shape(St) with K = 2 a eta v_K / nu_mol and shape = St sqrt(4 + St^2) / (1 +
  // St^2) <= min(2 St, 1.12) (gas_drift_speed).
  const T ln_k = log(2.0 * a * (std::abs(gas.headwind()) / gas.nu_mol));  // |eta| v_K
  // Re_p < kReNegligible at the Re_p = 0 law (bounded with shape <= 2 St) makes f_Re^p =
  // 1 + Re_p^3.2 + ... equal to 1 to round-off: that law solves G(u) = 0, and St is its
  // value without a Newton step (no pow; most grains before the drift barrier).
  if (value_of(ln_k) + std::numbers::ln2 + value_of(u) < kLnReNegligible) return exp(u);
  // First guess where Re_p matters: the hard-max law f_Re = max(1, Re_p^0.4, 0.01833
  // Re_p) with shape = min(2 St, 1), solved in closed form on each branch (St
  // f_i(Re_p(St)) = St_Ep x rises with St, so the solution is the least of the branch
  // solutions, and each branch's is the larger of its small- and large-St solutions);
  // never above the Re_p = 0 law. On the fiducial run it was at most 0.17 in ln St from
  // the smooth law's root (the p-norm corners and the shape), where the Re_p = 0 law was
  // up to 3.1 off: the Newton solve below takes 2.9 steps on average instead of 4.1.
  {
    const T ln_sx = ln_st_ep + log(x);  // f_Re = 1 (Stokes)
    const double ln2 = std::numbers::ln2;
    const T b_small = (ln_sx - 0.4 * (ln_k + ln2)) / 1.4;  // f_Re = Re_p^0.4
    const T b_large = ln_sx - 0.4 * ln_k;
    const T c_small = 0.5 * (ln_sx - std::log(2.0 * kCdNewton) - ln_k);  // 0.01833 Re_p
    const T c_large = ln_sx - std::log(kCdNewton) - ln_k;
    const T& b = value_of(b_small) > value_of(b_large) ? b_small : b_large;
    const T& c = value_of(c_small) > value_of(c_large) ? c_small : c_large;
    const T& bc = value_of(b) < value_of(c) ? b : c;
    const T& guess = value_of(bc) > value_of(ln_st_ep) ? bc : ln_st_ep;
    if (value_of(guess) < value_of(u)) u = guess;
  }
  for (int it = 0; it < iterations; ++it) {
    const T st = exp(u);
    const T dv = gas_drift_speed(st, gas);
    const T re_p = particle_reynolds(a, dv, gas);
    // f_Re and its log-slope share Re_p^(0.4 p) and (0.01833 Re_p)^p: computed once
    // (the same expressions as reynolds_correction() and its _log_slope()).
    const T b = pow(re_p, 0.4 * p);
    const T c = power_p<T>(kCdNewton * re_p, p);
    const T fp = 1.0 + b + c;              // f_Re^p
    const T yp = xp / fp;                  // (x / f_Re)^p
    const T dlng_dlnf = -yp / (1.0 + yp);  // d ln g / d ln f for g = (1 + (x/f)^p)^(1/p)
    const T dlnf_dlnre = (0.4 * b + c) / fp;
    const T slope = dlng_dlnf * dlnf_dlnre * gas_drift_speed_log_slope(st);
    const T residual = u - ln_st_ep - log1p_nonneg(yp) / p;  // G(u)
    u = u - residual / (1.0 - slope);
    // Once |G| < 1e-8 this Newton step leaves an error ~|G''/2G'| G^2 < 1e-16 in u
    // (quadratic convergence; over 0.05-300 au, 1e-15 < m < 1e23 g, 1e-6 < phi < 1 the
    // result differs from one converged to |G| < 1e-14 by < 2e-15 (1 + |u|)), and the AD
    // derivative is converged to ~|G| (the Newton map is flat at its fixed point), so
    // stop. The test is on the value, so double and AD stop at the same step and agree
    // bit for bit.
    if (std::abs(value_of(residual)) < 1e-8) break;
  }
  return exp(u);
}

//! Stokes number of an aggregate of mass m [g] and filling factor phi (above).
template <class T, class G>
T stokes_number(const T& m, const T& phi, double rho0, const LocalGasT<G>& gas,
                DragLaw law = DragLaw::kStokesRe, int iterations = kDragIterations) {
  return stokes_number_of_radius(radius(m, phi, rho0), phi, rho0, gas, law, iterations);
}

// ---------------------------------------------------------------------------------------------
// Vertical structure (spec §2)
// ---------------------------------------------------------------------------------------------

//! Dust scale height h_d = H [1 + (St/alpha)(1 + 2 St)/(1 + St)]^(-1/2) (spec §2; Youdin
//! & Lithwick 2007 with Sc = 1, as used by Okuzumi et al. 2012) [cm].
template <class T, class G>
T dust_scale_height(const T& St, const LocalGasT<G>& gas) {
  using std::sqrt;
  const T settling = (St / gas.alpha) * (1.0 + 2.0 * St) / (1.0 + St);
  return gas.h_g / sqrt(1.0 + settling);
}

//! Midplane dust density rho_d = Sigma_d / (sqrt(2 pi) h_d) (spec §2) [g cm^-3];
//! sigma_d [g cm^-2], h_d [cm].
template <class T>
T midplane_dust_density(const T& sigma_d, const T& h_d) {
  return sigma_d / (std::sqrt(2.0 * units::kPi) * h_d);
}

//! Midplane dust-to-gas ratio eps_mid = rho_d / rho_g (spec §2) [-].
template <class T, class G>
T midplane_dust_to_gas(const T& sigma_d, const T& h_d, const LocalGasT<G>& gas) {
  return midplane_dust_density(sigma_d, h_d) / gas.rho_g;
}

}  // namespace panoptic::physics
