#pragma once
//! Smooth switches, and the math they are built from, for every regime change in
//! physics/: p-norm soft-max and soft-min (also in logarithms), tanh and logistic steps
//! (log_step: logistic in ln x), softplus and a smooth positive part, and the p-th
//! powers and roots, log1p and cbrt in their AutoDiff forms. A hard max() or if() on the
//! state would put a kink into the right-hand side, which stalls CVODE's Newton
//! iteration (spec §6.4). Templates on the scalar type T: double, or
//! Eigen::AutoDiffScalar for exact Jacobians (rules for T code: physics/particle.hpp).
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "src/core/autodiff.hpp"

namespace panoptic::physics {

//! p of the p-norm soft-max (spec §2) [-].
inline constexpr double kSoftMaxPower = 8.0;

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
//! relaxation cap), and the root is the costliest part of the smooth switches.
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

//! Softplus with sharpness k: ln(1 + e^(k z))/k, = z for k z >> 1, -> 0 for k z << -1.
template <class T>
T softplus(const T& z, double k) {
  using std::exp;
  using std::log;
  const double kz = k * value_of(z);
  if (kz > 30.0) return z;
  // Far below the bend exp(k z) underflows, and libm's underflow path is slow (3% of the
  // fiducial run's time went to it): softplus < 1e-300 there, so it is 0.
  if (kz < -690.0) return T(0.0);
  return log(1.0 + exp(k * z)) / k;
}

//! Smooth positive part of x (scale-free: exact away from a band of width `delta`).
template <class T>
T positive_part(const T& x, double delta) {
  using std::sqrt;
  return 0.5 * (x + sqrt(x * x + delta * delta));
}

}  // namespace panoptic::physics
