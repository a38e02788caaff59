//! The one-cell coagulation engine (physics/coagulation, spec §15.2-§15.3): its
//! analytic Jacobian against finite differences, mass and the volume measure conserved
//! by the two-bin split and by fragmentation, the porosity rules' equal-mass limits
//! (spec §4.3 slopes), and the disk's kernel on the MMSN gas through the laws of
//! physics/drag.hpp and physics/relative_velocity.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "physics/coagulation/cell_coefficients.hpp"
#include "physics/coagulation/collision_kernel.hpp"
#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/porosity.hpp"
#include "physics/coagulation/smoluchowski.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/particle.hpp"
#include "tests/unit/support/coagulation_checks.hpp"
#include "tests/unit/support/dense_cvode.hpp"
#include "tests/unit/support/ice_cell_model.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

namespace panoptic::physics::coagulation {
namespace {

//! A smooth, symmetric, positive kernel with some structure, and a state spread over
//! the grid, for the Jacobian and conservation checks.
CellCoefficients synthetic_cell(const Smoluchowski& eng, bool frag, bool porous) {
  const int n = eng.size();
  const auto& m = eng.grid().m;
  CellCoefficients c;
  c.kernel.resize(static_cast<std::size_t>(n) * n);
  if (frag) c.p_frag.resize(static_cast<std::size_t>(n) * n);
  if (porous) c.ln_u_ratio.resize(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::size_t ij = static_cast<std::size_t>(i) * n + j;
      const double s = std::cbrt(m[i]) + std::cbrt(m[j]);
      c.kernel[ij] = s * s * (1.3 + 0.5 * std::sin(0.7 * (i + j)));
      if (frag) c.p_frag[ij] = 0.5 + 0.45 * std::cos(0.3 * (i + j) + 0.1 * i * j);
      if (porous) c.ln_u_ratio[ij] = 0.3 * std::sin(0.2 * i - 0.5 * j);
    }
  if (porous) {
    c.ln_phi_floor.resize(n);
    c.relax_rate.resize(n);
    for (int k = 0; k < n; ++k) {
      c.ln_phi_floor[k] = -2.0 - 0.05 * k;  // crosses the state's ln phi
      c.relax_rate[k] = 0.2 + 0.01 * k;
    }
  }
  return c;
}

std::vector<double> synthetic_sigma(int n) {
  std::vector<double> s(n);
  for (int k = 0; k < n; ++k)
    s[k] = std::exp(-0.5 * std::pow((k - 0.4 * n) / 6.0, 2)) + 1e-3;
  return s;
}
// u_k = psi_k/sigma_k from e^0.1 up: off the kink of bin_porosity at u = 1 (phi <= 1)
std::vector<double> synthetic_psi(const std::vector<double>& sigma) {
  std::vector<double> p(sigma.size());
  for (std::size_t k = 0; k < p.size(); ++k) p[k] = sigma[k] * std::exp(0.1 + 0.15 * k);
  return p;
}

//! (sigma, psi) of synthetic_sigma and synthetic_psi.
std::vector<double> synthetic_state(const Smoluchowski& eng) {
  std::vector<double> y = synthetic_sigma(eng.size());
  const auto psi = synthetic_psi(y);
  y.insert(y.end(), psi.begin(), psi.end());
  return y;
}

TEST(CoagulationEngine, JacobianMatchesFiniteDifferencesCompact) {
  const Smoluchowski eng(MassGrid(1.0, 1e6, 5.0));  // 31 bins; cratering beyond 5 bins
  const auto sigma = synthetic_sigma(eng.size());
  EXPECT_LT(jacobian_error(eng, synthetic_cell(eng, false, false), sigma, false), 1e-7);
  EXPECT_LT(jacobian_error(eng, synthetic_cell(eng, true, false), sigma, false), 1e-7);
}

TEST(CoagulationEngine, JacobianMatchesFiniteDifferencesPorous) {
  // K, p, d and the floors held fixed (the engine's Jacobian is exact for them)
  const Smoluchowski eng(MassGrid(1.0, 1e6, 5.0));
  EXPECT_LT(
      jacobian_error(eng, synthetic_cell(eng, true, true), synthetic_state(eng), true),
      1e-7);
}

// A state off the physical cone psi >= sigma >= 0 that integration error makes in nearly
// empty bins, away from bin_porosity's kinks: psi < 0 < sigma (u = |psi|/sigma), 0 < psi
// < sigma (u held at 1), and sigma, psi < 0 with |psi| > |sigma|, among bins inside it.
std::vector<double> state_off_the_cone(const std::vector<double>& sigma,
                                       const std::vector<double>& psi) {
  const int n = static_cast<int>(sigma.size());
  std::vector<double> y = sigma;
  y.insert(y.end(), psi.begin(), psi.end());
  for (int k = 0; k < n; ++k) {
    if (k % 4 == 1) y[n + k] = -2.5 * sigma[k];
    if (k % 4 == 2) y[n + k] = 0.4 * sigma[k];
    if (k % 4 == 3 && k < n / 2) {
      y[k] = -0.5 * sigma[k];
      y[n + k] = -1.5 * sigma[k];
    }
  }
  return y;
}

// synthetic coefficients that move with the bins' u (bin_porosity): K_ij ∝ exp(g_i dln
// u_i + g_j dln u_j), p_ij and d_ij linear in ln u; the right-hand side rebuilt from the
// state at each difference, the Jacobian fed the derivatives
double synthetic_full_jacobian_error(const Smoluchowski& eng,
                                     const std::vector<double>& y) {
  const int n = eng.size();
  auto ln_u = [&](const std::vector<double>& yy, int k) {
    return std::log(bin_porosity(yy[k], yy[n + k], kTinyEmptyScale).u);
  };
  std::vector<double> ln_u0(n);
  for (int k = 0; k < n; ++k) ln_u0[k] = ln_u(y, k);
  auto coefficients = [&](const std::vector<double>& yy) {
    CellCoefficients c = synthetic_cell(eng, true, true);
    c.dlnk_dlnu.resize(static_cast<std::size_t>(n) * n);
    c.dp_dlnu.resize(static_cast<std::size_t>(n) * n);
    c.dd_dlnu_i.assign(static_cast<std::size_t>(n) * n, 0.0);
    c.dd_dlnu_j.assign(static_cast<std::size_t>(n) * n, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const std::size_t ij = static_cast<std::size_t>(i) * n + j;
        const double li = ln_u(yy, i) - ln_u0[i];
        const double lj = ln_u(yy, j) - ln_u0[j];
        const double gi = 0.3 + 0.01 * i, gj = 0.3 + 0.01 * j;
        c.kernel[ij] *= std::exp(i == j ? (gi + gj) * li : gi * li + gj * lj);
        c.dlnk_dlnu[ij] = i == j ? gi + gj : gi;
        c.p_frag[ij] = 0.5 + 0.3 * std::sin(i + j) + 0.1 * (i == j ? li : li + lj);
        c.dp_dlnu[ij] = 0.1;
        const int hi = std::max(i, j), lo = std::min(i, j);
        c.ln_u_ratio[ij] +=
            0.2 * (ln_u(yy, hi) - ln_u0[hi]) + 0.1 * (ln_u(yy, lo) - ln_u0[lo]);
        if (i >= j) {
          c.dd_dlnu_i[ij] = i == j ? 0.3 : 0.2;
          c.dd_dlnu_j[ij] = i == j ? 0.0 : 0.1;
        }
      }
    c.ln_phi_floor.clear();
    c.relax_rate.clear();
    return c;
  };
  return full_jacobian_error(eng, coefficients, y);
}

TEST(CoagulationEngine, JacobianFollowsTheCoefficientsThroughPorosity) {
  const Smoluchowski eng(MassGrid(1.0, 1e6, 5.0));
  EXPECT_LT(synthetic_full_jacobian_error(eng, synthetic_state(eng)), 1e-7);  // 3.7e-10
}

TEST(CoagulationEngine, JacobianMatchesFiniteDifferencesOffThePhysicalCone) {
  // bins whose psi has the wrong sign or is below sigma carry their own (signed) volume:
  // the Jacobian follows that booking and the voids at the bins' u, with K, p, d fixed
  // and with them moving through u
  const Smoluchowski eng(MassGrid(1.0, 1e6, 5.0));
  const auto sigma = synthetic_sigma(eng.size());
  const auto y = state_off_the_cone(sigma, synthetic_psi(sigma));
  EXPECT_LT(jacobian_error(eng, synthetic_cell(eng, true, true), y, true), 1e-7);
  EXPECT_LT(synthetic_full_jacobian_error(eng, y), 1e-7);
}

TEST(CoagulationEngine, ABinLosesVolumeInProportionToItsMassForEitherSignOfPsi) {
  // bin 0 gains nothing by sticking (m_0 + m_0 > m_1 at 5 bins per decade): its psi must
  // leave at its mass's fractional rate whatever its sign or its u, so that a psi below
  // zero decays (the rule u |psi|/sigma per unit mass made psi < 0 grow at that rate);
  // with sigma_0 = 0 its orphan volume leaves at the same rate, continuously
  const Smoluchowski eng(MassGrid(1.0, 1e6, 5.0));
  const int n = eng.size();
  auto c = synthetic_cell(eng, false, true);
  c.ln_phi_floor.clear();
  c.relax_rate.clear();
  auto sigma = synthetic_sigma(n);
  auto psi = synthetic_psi(sigma);
  std::vector<double> ds(n), dp(n);
  eng.rhs(c, sigma, psi, ds, dp);
  const double rate = ds[0] / sigma[0];  // d ln sigma_0 / dt < 0
  ASSERT_LT(rate, 0.0);
  for (const double ratio : {3.0, 0.4, -2.5}) {  // psi_0/sigma_0: u = 3, held at 1, |.|
    psi[0] = ratio * sigma[0];
    eng.rhs(c, sigma, psi, ds, dp);
    EXPECT_NEAR(dp[0] / psi[0], rate, 1e-14 * std::abs(rate))
        << "psi_0/sigma_0 " << ratio;
  }
  // the limit sigma_0 -> 0 (no self-collisions of bin 0 left)
  sigma[0] *= 1e-20;
  eng.rhs(c, sigma, psi, ds, dp);
  const double rate_empty = ds[0] / sigma[0];
  sigma[0] = 0.0;
  eng.rhs(c, sigma, psi, ds, dp);
  EXPECT_NEAR(dp[0] / psi[0], rate_empty, 1e-14 * std::abs(rate_empty));
}

TEST(CoagulationEngine, PorousJacobianOfTheDiskCellMatchesFullDifferences) {
  // the builder's coefficients (kernel, fragmentation, product porosity, floors) rebuilt
  // from the state at each difference: the engine's Jacobian with the builder's
  // derivatives follows all of them (measured: 2.3e-7 here; 1.3e-7 at 120 bins on the
  // state of bench_coagulation, where holding the coefficients fixed gives 0.21, and
  // 0.28 with fragmentation)
  const LocalGas gas = mmsn_gas(5.0);
  const CellModel model = testing::ice_cell_model(
      {.fragmentation = true, .cratering = true, .v_frag = 100.0, .v_eros = 100.0});
  const Smoluchowski eng(MassGrid(1e-12, 1e4, 4.0));
  const int n = eng.size();
  std::vector<double> y(2 * n);
  for (int k = 0; k < n; ++k) {
    const double mk = eng.grid().m[k];
    y[k] = 1e-3 * std::pow(mk / 1e-12, 1.0 / 6.0) * std::exp(-mk / 1e2) + 1e-12;
    y[n + k] = y[k] * std::exp(0.1 * (k + 1));  // u > 1: off bin_porosity's kink
  }
  auto coefficients = [&](const std::vector<double>& yy) {
    return cell_coefficients(eng, std::span<const double>(yy.data(), n),
                             std::span<const double>(yy.data() + n, n), gas, model, true);
  };
  EXPECT_LT(full_jacobian_error(eng, coefficients, y), 1e-5);
}

TEST(CoagulationEngine, MassConservedToRoundOff) {
  // sticking, fragmentation and cratering, with pairs 30 decades apart, where m_i + m_j
  // rounds to m_i (Brauer et al. 2008, A.2)
  const Smoluchowski eng(MassGrid(1e-15, 1e15, 7.0));
  const int n = eng.size();
  std::vector<double> sigma(n, 1.0);
  EXPECT_LT(imbalance(eng, synthetic_cell(eng, false, false), sigma, {}).first, 1e-14);
  EXPECT_LT(imbalance(eng, synthetic_cell(eng, true, false), sigma, {}).first, 1e-14);
  // integrated: sticking + fragmentation + cratering over many collision times
  const Smoluchowski small(MassGrid(1.0, 1e6, 5.0));
  const auto c = synthetic_cell(small, true, false);
  std::vector<double> y = synthetic_sigma(small.size());
  double m1 = 0.0;
  for (double v : y) m1 += v;
  testing::DenseOde ode{[&](double, std::span<const double> s, std::span<double> d) {
                          small.rhs(c, s, {}, d, {});
                        },
                        [&](double, std::span<const double> s, std::span<double> j) {
                          small.jacobian(c, s, {}, j);
                        }};
  testing::integrate_dense(ode, 0.0, 10.0, y, 1e-8, 1e-20);
  double m1_end = 0.0;
  for (double v : y) m1_end += v;
  EXPECT_LT(std::abs(m1_end / m1 - 1.0), 1e-12);
}

TEST(CoagulationEngine, VolumeMeasureBookedBySplitAndKeptByFragments) {
  const Smoluchowski eng(MassGrid(1e-15, 1e15, 7.0));
  const int n = eng.size();
  const auto& m = eng.grid().m;
  std::vector<double> sigma(n), psi(n), u(n);
  for (int k = 0; k < n; ++k) {
    sigma[k] = 1.0;
    u[k] = std::exp(0.05 * k);
    psi[k] = sigma[k] * u[k];
  }
  // sticking whose product has the partners' summed volume, m_p u_p = m_i u_i + m_j u_j:
  // sum psi changes by the split's extension of each product's step alone, booked
  // exactly (sticking_volume_gain, coagulation_checks.hpp)
  auto c = synthetic_cell(eng, false, true);
  c.ln_phi_floor.clear();
  c.relax_rate.clear();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      c.ln_u_ratio[static_cast<std::size_t>(i) * n + j] =
          std::log1p(m[j] * u[j] / (m[i] * u[i])) - std::log1p(m[j] / m[i]);
    }
  EXPECT_LT(imbalance(eng, c, sigma, psi).first, 1e-14);
  const VolumeRates on = volume_rates(eng, c, sigma, psi);
  const double split = sticking_volume_gain(eng, c, sigma, psi);
  std::printf("the split adds %.2e of sum |dpsi|; booked to %.1e\n", split / on.abs,
              std::abs(on.sum - split) / on.abs);
  EXPECT_GT(std::abs(split), 1e-6 * on.abs);  // the split's volume is there
  EXPECT_LT(std::abs(on.sum - split), 1e-13 * on.abs);
  // off the physical cone (psi of the wrong sign, or below sigma) the partners carry
  // their own signed volume and the products add the voids at the bins' u: zero here
  std::vector<double> psi_off = psi;
  for (int k = 1; k < n; k += 3) psi_off[k] = (k % 2 == 0 ? 0.4 : -2.5) * sigma[k];
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      const double ui = bin_porosity(sigma[i], psi_off[i], kTinyEmptyScale).u;
      const double uj = bin_porosity(sigma[j], psi_off[j], kTinyEmptyScale).u;
      c.ln_u_ratio[static_cast<std::size_t>(i) * n + j] =
          std::log1p(m[j] * uj / (m[i] * ui)) - std::log1p(m[j] / m[i]);
    }
  const VolumeRates off = volume_rates(eng, c, sigma, psi_off);
  // the partners carry their own signed volume, the voids at the bins' u are zero: the
  // split's factor alone
  const double split_off = sticking_volume_gain(eng, c, sigma, psi_off);
  EXPECT_LT(std::abs(off.sum - split_off), 1e-13 * off.abs);
  // fragmentation and cratering only: fragments and remnants keep their parents' volume
  auto f = synthetic_cell(eng, true, true);
  f.ln_phi_floor.clear();
  f.relax_rate.clear();
  for (auto& p : f.p_frag) p = 1.0;
  EXPECT_LT(imbalance(eng, f, sigma, psi).second, 1e-14);
  EXPECT_LT(imbalance(eng, f, sigma, psi_off).second, 1e-14);
}

TEST(CoagulationEngine, OutcomesOfOnePairAreDustPys) {
  // one pair at a time (all other bins empty), p = 1: DustPy's outcome model
  const Smoluchowski eng(MassGrid(1.0, 1e8, 7.0));
  const int n = eng.size();
  const auto& m = eng.grid().m;
  EXPECT_EQ(eng.crater_bins(), 7);  // mass ratio 10 at 7 bins per decade
  CellCoefficients c;
  c.p_frag.assign(static_cast<std::size_t>(n) * n, 1.0);
  // K = 1 for the pair (a, b) only (no self-collisions)
  auto only_pair = [&](int a, int b) {
    c.kernel.assign(static_cast<std::size_t>(n) * n, 0.0);
    c.kernel[static_cast<std::size_t>(a) * n + b] = 1.0;
    c.kernel[static_cast<std::size_t>(b) * n + a] = 1.0;
  };
  std::vector<double> sigma(n, 0.0), ds(n);
  // cratering: target bin 40, projectile bin 20 (ratio 1e20/7): R = n_i n_j = 1
  const int i = 40, j = 20;
  only_pair(i, j);
  sigma[i] = m[i];
  sigma[j] = m[j];
  eng.rhs(c, sigma, {}, ds, {});
  // the target loses eps_c m_j = m_j (remnant split between bins i-1 and i)
  EXPECT_NEAR(ds[i] + ds[i - 1], -m[j], 1e-12 * m[j]);
  EXPECT_LT(ds[i], 0.0);
  EXPECT_GT(ds[i - 1], 0.0);
  // the projectile's bin loses m_j and fragments of 2 m_j spread over bins <= j as
  // m^(1/6) (n ∝ m^-11/6)
  double frag = 0.0;
  for (int k = 0; k <= j; ++k) frag += ds[k];
  EXPECT_NEAR(frag, -m[j] + 2.0 * m[j], 1e-12 * m[j]);
  EXPECT_NEAR(ds[5] / ds[4], std::pow(m[5] / m[4], 1.0 / 6.0), 1e-12);
  for (int k = j + 1; k < i - 1; ++k) EXPECT_EQ(ds[k], 0.0);
  // full fragmentation of bins 30 and 25: all of m_30 + m_25 into bins <= 30
  std::fill(sigma.begin(), sigma.end(), 0.0);
  sigma[30] = m[30];
  sigma[25] = m[25];
  only_pair(30, 25);
  eng.rhs(c, sigma, {}, ds, {});
  double total = 0.0;
  for (int k = 0; k < n; ++k) total += ds[k];
  EXPECT_NEAR(total, 0.0, 1e-13 * m[30]);
  for (int k = 31; k < n; ++k) EXPECT_EQ(ds[k], 0.0);
  EXPECT_NEAR((ds[10] / ds[3]), std::pow(m[10] / m[3], 1.0 / 6.0), 1e-12);
  // sticking (p = 0) of bins 30 and 25: number and mass conserved, product in 30, 31
  std::fill(c.p_frag.begin(), c.p_frag.end(), 0.0);
  eng.rhs(c, sigma, {}, ds, {});
  double num = 0.0;
  for (int k = 0; k < n; ++k) num += ds[k] / m[k];
  EXPECT_NEAR(num, -1.0, 1e-13);  // two particles become one at rate R = 1
  EXPECT_NEAR(ds[30] + ds[31], m[25], 1e-12 * m[30]);
  EXPECT_NEAR(ds[25], -m[25], 1e-12 * m[25]);
}

TEST(CoagulationPorosity, EqualMassLimitsAreTheSpecSlopes) {
  // spec §4.3: hit-and-stick V_{1+2} = 2.99 V_1 -> d ln phi / d ln m = 1 - log2(2.99)
  const double m = 1e-10, u = 37.0;
  const double s_hs = -ln_u_ratio_hit_and_stick(m, u, m, u) / std::log(2.0);
  EXPECT_NEAR(s_hs, 1.0 - std::log2(2.99), 1e-7);
  EXPECT_NEAR(s_hs, -0.580, 5e-4);
  // compression: the slope of the target's regime, reached 0.1 dex above 3 b E_roll
  for (double s_c : {-0.125, 0.0, -0.2}) {
    const double d = product_ln_u_ratio(m, u, m, u, 1e3, 1.0, s_c);
    EXPECT_NEAR(-d / std::log(2.0), s_c, 1e-12);
  }
  // below the threshold: hit-and-stick
  EXPECT_NEAR(-product_ln_u_ratio(m, u, m, u, 1e-3, 1.0, -0.125) / std::log(2.0), s_hs,
              1e-12);
  // the regime slopes of spec §4.3 (MMSN 5 au, lambda = 120 cm): Epstein St < 1,
  // Stokes St < 1, St > 1
  const LocalGas gas = mmsn_gas(5.0);
  EXPECT_NEAR(compression_slope_of_target(1.0, 1e-3, gas, DragLaw::kStokesRe), -0.125,
              1e-12);
  EXPECT_NEAR(compression_slope_of_target(1e5, 1e-2, gas, DragLaw::kStokesRe), 0.0,
              1e-12);
  EXPECT_NEAR(compression_slope_of_target(1e5, 1e2, gas, DragLaw::kStokesRe), -0.2,
              1e-12);
  // a small projectile of the same porosity adds its volume and a void of 6.94 V_2
  // (the soft-min takes 4e-4 off the cap where the uncapped void is 14.5 V_2)
  const double r = 1e-6;
  EXPECT_NEAR(ln_u_ratio_hit_and_stick(m, u, r * m, u) / r, kVoidCap, 5e-3);
  // reduced-mass impact energy
  EXPECT_DOUBLE_EQ(impact_energy(2.0, 2.0, 3.0), 0.5 * 1.0 * 9.0);
}

TEST(CoagulationKernel, DiskKernelFromTheSpecLawsOnMmsnGas) {
  // icy monomers at 5 au (spec §12: m0 = 5.86e-15 g), compact bins to 1 kg
  const LocalGas gas = mmsn_gas(5.0);
  const MonomerMaterial ice = ice_material();
  const double m0 = monomer_mass(ice.a0, ice.rho0);
  EXPECT_NEAR(m0, 5.86e-15, 0.01e-15);
  const MassGrid grid(m0, 1e3, 7.0);
  const int n = grid.size();
  const std::vector<double> phi(n, 1.0);
  const BinProperties b = bin_properties(grid, phi, ice.rho0, gas);
  EXPECT_NEAR(b.St[0], 1.45e-7, 0.01e-7);  // spec §12: monomer St at 5 au
  const auto dv = pair_speeds(grid, b, gas);
  const auto k = collision_kernel(
      b.a, b.h_d, [&](int i, int j) { return dv[static_cast<std::size_t>(i) * n + j]; });
  // monomer pair: Brownian motion dominates, dv = sqrt(16 k_B T / (pi m0))
  const double dv_b =
      std::sqrt(16.0 * units::kBoltzmann * gas.temperature / (units::kPi * m0));
  EXPECT_NEAR(dv[0] / dv_b, 1.0, 1e-3);
  // K_00 by hand: pi (2 a0)^2 dv / sqrt(2 pi 2 h^2)
  const double h = dust_scale_height(b.St[0], gas);
  EXPECT_NEAR(k[0] / (units::kPi * 4.0 * ice.a0 * ice.a0 * dv[0] /
                      std::sqrt(4.0 * units::kPi * h * h)),
              1.0, 1e-12);
  // the pair (m, m/8) of the single-size model (eps = 1/2, spec §3): 1 g against the
  // bin nearest 1/8 g, against dv_total of the same Stokes numbers
  const int i = static_cast<int>(std::lround(std::log10(1.0 / m0) * 7.0));
  const int j = i - static_cast<int>(std::lround(std::log10(8.0) * 7.0));
  EXPECT_DOUBLE_EQ(dv[static_cast<std::size_t>(i) * n + j],
                   dv_total(b.St[i], b.St[j], grid.m[i], grid.m[j], gas));
  for (int a = 0; a < n; ++a)
    for (int c = 0; c < a; ++c)
      ASSERT_EQ(k[static_cast<std::size_t>(a) * n + c],
                k[static_cast<std::size_t>(c) * n + a]);

  // monomers coagulate for 100 yr: mass conserved, the mean mass grows
  const Smoluchowski eng(grid);
  CellCoefficients c;
  c.kernel = k;
  std::vector<double> y(n, 0.0);
  y[0] = 0.01 * gas.sigma_g;
  testing::DenseOde ode{[&](double, std::span<const double> s, std::span<double> d) {
                          eng.rhs(c, s, {}, d, {});
                        },
                        [&](double, std::span<const double> s, std::span<double> jj) {
                          eng.jacobian(c, s, {}, jj);
                        }};
  testing::integrate_dense(ode, 0.0, 100.0 * units::kYr, y, 1e-8, 1e-30);
  double m1 = 0.0, m0_num = 0.0;
  for (int q = 0; q < n; ++q) {
    m1 += y[q];
    m0_num += y[q] / grid.m[q];
  }
  EXPECT_LT(std::abs(m1 / (0.01 * gas.sigma_g) - 1.0), 1e-12);
  EXPECT_GT(m1 / m0_num, 10.0 * m0);
}

TEST(CoagulationKernel, FragmentationProbabilityIsDustPys) {
  EXPECT_EQ(fragmentation_probability(0.0, 100.0), 0.0);
  EXPECT_NEAR(fragmentation_probability(94.53763912, 100.0), 0.5, 1e-9);
  EXPECT_GT(fragmentation_probability(1e4, 100.0), 0.9998);
  EXPECT_LT(fragmentation_probability(10.0, 100.0), 1e-60);
}

TEST(CoagulationKernel, PorousCellCoefficients) {
  // the porous builder: floors from physics/compaction.hpp per bin, product porosity
  // per pair; the engine's right-hand side conserves mass with them
  const LocalGas gas = mmsn_gas(5.0);
  const CellModel model = testing::ice_cell_model(
      {.fragmentation = true, .cratering = true, .v_frag = 6e3, .v_eros = 4e3});
  const Smoluchowski eng(MassGrid(model.species.m0, 1e3, 7.0));
  const int n = eng.size();
  std::vector<double> sigma(n), psi(n);
  for (int k = 0; k < n; ++k) {
    sigma[k] = 1e-3 * std::exp(-0.01 * k);
    psi[k] = sigma[k] * std::exp(0.1 * k);  // phi falls with mass
  }
  const CellCoefficients c = cell_coefficients(eng, sigma, psi, gas, model);
  ASSERT_EQ(c.ln_phi_floor.size(), static_cast<std::size_t>(n));
  // the gas floor of a 1e-3 g aggregate lies far below 1 and below phi_max
  for (int k = 0; k < n; ++k) EXPECT_LT(c.ln_phi_floor[k], std::log(0.5) + 1e-12);
  const auto [mass, vol] = imbalance(eng, c, sigma, psi);
  EXPECT_LT(mass, 1e-14);
  (void)vol;  // hit-and-stick creates voids, compression and the floors remove volume
}

}  // namespace
}  // namespace panoptic::physics::coagulation
