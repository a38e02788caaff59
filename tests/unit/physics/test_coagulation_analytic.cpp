//! The one-cell Smoluchowski engine (physics/coagulation, spec §15.2, §15.5) against the
//! exact solutions of the constant, additive and product kernels for an exponential
//! initial distribution n(x, 0) = e^-x (x = m / <m>_0, N_0 = M_1 = 1), integrated with
//! CVODE BDF and the engine's dense analytic Jacobian:
//!   K = 1:     n = (2/(2+t))^2 exp(-2x/(2+t))                      (Smoluchowski 1916)
//!   K = x + y: n = (1-T) e^-(1+T)x sum_k (T x^2)^k / (k!(k+1)!),  T = 1 - e^-t
//!              (Golovin 1963; Scott 1968: the series is I_1(2x sqrt T)/(x sqrt T))
//!   K = x y:   n = e^-(1+t)x sum_k (t x^3)^k / ((k+1)!(2k+1)!),  t < 1/2 (gelation)
//!              (Scott 1968; derived here by Lagrange inversion of the Laplace transform)
//! Moments: M_0 = 2/(2+t), e^-t, 1 - t/2 and M_2 = 2 + t, 2e^(2t), 2/(1-2t).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/smoluchowski.hpp"
#include "tests/unit/support/dense_cvode.hpp"

namespace panoptic::physics::coagulation {
namespace {

//! ln sum_k exp(lt(k)) of a series of positive terms that rise and then fall.
double log_series(const std::function<double(int)>& lt) {
  std::vector<double> terms;
  double peak = -1e300;
  for (int k = 0; k < 100000; ++k) {
    const double l = lt(k);
    terms.push_back(l);
    peak = std::max(peak, l);
    if (k > 5 && l < peak - 60.0 && l < terms[k - 1]) break;
  }
  double s = 0.0;
  for (double l : terms) s += std::exp(l - peak);
  return peak + std::log(s);
}

enum class Kernel { kConstant, kAdditive, kProduct };

double exact_n(Kernel kind, double x, double t) {
  switch (kind) {
    case Kernel::kConstant: {
      const double c = 2.0 / (2.0 + t);
      return c * c * std::exp(-c * x);
    }
    case Kernel::kAdditive: {
      const double tau = -std::expm1(-t);
      const double lq = std::log(tau * x * x);
      const double ls = log_series(
          [&](int k) { return k * lq - std::lgamma(k + 1.0) - std::lgamma(k + 2.0); });
      return (1.0 - tau) * std::exp(ls - (1.0 + tau) * x);
    }
    case Kernel::kProduct: {
      const double lq = std::log(t * x * x * x);
      const double ls = log_series([&](int k) {
        return k * lq - std::lgamma(k + 2.0) - std::lgamma(2.0 * k + 2.0);
      });
      return std::exp(ls - (1.0 + t) * x);
    }
  }
  return 0.0;
}

double exact_m0(Kernel kind, double t) {
  if (kind == Kernel::kConstant) return 2.0 / (2.0 + t);
  if (kind == Kernel::kAdditive) return std::exp(-t);
  return 1.0 - 0.5 * t;
}
double exact_m2(Kernel kind, double t) {
  if (kind == Kernel::kConstant) return 2.0 + t;
  if (kind == Kernel::kAdditive) return 2.0 * std::exp(2.0 * t);
  return 2.0 / (1.0 - 2.0 * t);
}

struct Errors {
  double m0 = 0.0;    //!< |M_0 / exact - 1|
  double m2 = 0.0;    //!< |M_2 / exact - 1|
  double dist = 0.0;  //!< sum_k |sigma_k - x_k^2 n(x_k) dlnm| (L1, mass fraction)
  double mass = 0.0;  //!< |M_1(t) / M_1(0) - 1|
  long steps = 0;
};

Errors run(Kernel kind, double t_end, double bpd, double x_max = 1e4) {
  const MassGrid grid(1e-6, x_max, bpd);
  const Smoluchowski engine(grid);
  const int n = grid.size();
  const auto& m = grid.m;
  CellCoefficients c;
  c.kernel.resize(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      c.kernel[static_cast<std::size_t>(i) * n + j] = kind == Kernel::kConstant ? 1.0
                                                      : kind == Kernel::kAdditive
                                                          ? m[i] + m[j]
                                                          : m[i] * m[j];
  std::vector<double> y(n);
  double m1_start = 0.0;
  for (int k = 0; k < n; ++k) {
    y[k] = m[k] * m[k] * std::exp(-m[k]) * grid.dlnm;  // mass per bin of n = e^-x
    m1_start += y[k];
  }
  testing::DenseOde ode{[&](double, std::span<const double> s, std::span<double> ds) {
                          engine.rhs(c, s, {}, ds, {});
                        },
                        [&](double, std::span<const double> s, std::span<double> jac) {
                          engine.jacobian(c, s, {}, jac);
                        }};
  Errors e;
  e.steps = testing::integrate_dense(ode, 0.0, t_end, y, 1e-9, 1e-22).steps;
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  for (int k = 0; k < n; ++k) {
    m0 += y[k] / m[k];
    m1 += y[k];
    m2 += y[k] * m[k];
    const double exact = m[k] * m[k] * exact_n(kind, m[k], t_end) * grid.dlnm;
    e.dist += std::abs(y[k] - exact);
  }
  e.m0 = std::abs(m0 / exact_m0(kind, t_end) - 1.0);
  e.m2 = std::abs(m2 / exact_m2(kind, t_end) - 1.0);
  e.mass = std::abs(m1 / m1_start - 1.0);
  return e;
}

//! Errors at 5, 10 and 20 bins per decade, printed, with the observed orders.
std::vector<Errors> convergence(Kernel kind, double t_end, const char* name) {
  std::vector<Errors> out;
  for (double bpd : {5.0, 10.0, 20.0}) {
    out.push_back(run(kind, t_end, bpd));
    const Errors& e = out.back();
    std::printf("%s bpd %4.0f: M0 %.3e  M2 %.3e  L1 %.3e  mass %.1e  steps %ld\n", name,
                bpd, e.m0, e.m2, e.dist, e.mass, e.steps);
  }
  for (std::size_t r = 1; r < out.size(); ++r)
    std::printf("%s order %zu: M0 %.2f  M2 %.2f  L1 %.2f\n", name, r,
                std::log2(out[r - 1].m0 / out[r].m0),
                std::log2(out[r - 1].m2 / out[r].m2),
                std::log2(out[r - 1].dist / out[r].dist));
  return out;
}

double order(double coarse, double fine) { return std::log2(coarse / fine); }

TEST(CoagulationAnalytic, ExactSolutionsOfTheInitialState) {
  // the exact solutions at t = 0 are e^-x, and their moments those of the code's
  // formulas (a check of the test's own reference)
  for (Kernel k : {Kernel::kConstant, Kernel::kAdditive, Kernel::kProduct}) {
    EXPECT_NEAR(exact_n(k, 2.5, 1e-12), std::exp(-2.5), 1e-10);
    EXPECT_DOUBLE_EQ(exact_m0(k, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(exact_m2(k, 0.0), 2.0);
  }
  // Golovin's series against the Bessel form (1-T) e^-(1+T)x I_1(2x sqrt T)/(x sqrt T)
  const double t = 1.0, x = 3.0, tau = -std::expm1(-t);
  const double bessel = (1.0 - tau) * std::exp(-(1.0 + tau) * x) *
                        std::cyl_bessel_i(1.0, 2.0 * x * std::sqrt(tau)) /
                        (x * std::sqrt(tau));
  EXPECT_NEAR(exact_n(Kernel::kAdditive, x, t) / bessel, 1.0, 1e-12);
}

//! The two-bin split conserves number and mass per collision, so for these kernels the
//! discrete M_0 obeys the exact moment equation (dM_0/dt = -K M_0^2/2, -M_0 M_1,
//! -M_1^2/2): its error is the integrator's, at any resolution. M_2 and the distribution
//! (L1 error of the mass per bin, as a fraction of M_1) converge at second order in the
//! bin width. Asserted: mass to 1e-12, M_0 to 1e-5, and order > 1.8 from 10 to 20 bins
//! per decade.
void expect_second_order(const std::vector<Errors>& e) {
  for (const auto& r : e) {
    EXPECT_LT(r.mass, 1e-12);
    EXPECT_LT(r.m0, 1e-5);
  }
  EXPECT_GT(order(e[1].m2, e[2].m2), 1.8);
  EXPECT_GT(order(e[1].dist, e[2].dist), 1.8);
}

// Measured (CVODE rtol 1e-9), errors at 5 / 10 / 20 bins per decade:
//   M_2: 1.02e-1, 2.42e-2, 6.05e-3 (orders 2.08, 2.00); L1: 8.64e-2, 2.43e-2, 6.32e-3
//   (1.83, 1.94); M_0 < 1e-7; mass < 2e-15.
TEST(CoagulationAnalytic, ConstantKernelConverges) {
  expect_second_order(convergence(Kernel::kConstant, 20.0, "constant"));
}

// Measured: M_2: 3.62e-1, 8.32e-2, 2.14e-2 (orders 2.12, 1.96); L1: 1.02e-1, 3.12e-2,
// 8.66e-3 (1.71, 1.85); M_0 < 1e-6; mass < 7e-15.
TEST(CoagulationAnalytic, AdditiveKernelConverges) {
  expect_second_order(convergence(Kernel::kAdditive, 1.0, "additive"));
}

// t = 0.2, before gelation at t = 1/2 (M_2 = 2/(1-2t)). Measured: M_2: 8.25e-2, 1.81e-2,
// 4.39e-3 (orders 2.19, 2.04); L1: 2.33e-2, 5.92e-3, 1.51e-3 (1.97, 1.98); mass < 1e-15.
TEST(CoagulationAnalytic, ProductKernelConvergesBeforeGelation) {
  expect_second_order(convergence(Kernel::kProduct, 0.2, "product"));
}

}  // namespace
}  // namespace panoptic::physics::coagulation
