//! The porous one-cell engine in time (physics/coagulation, spec §15.3): icy monomers on
//! the MMSN gas at 5 au grow by hit-and-stick (Brownian motion, then turbulence) with
//! every coefficient rebuilt from the state at each right-hand side, CVODE BDF with the
//! engine's dense Jacobian and the coefficients' derivatives by the porosity. Okuzumi et
//! al. (2012) find fractal aggregates: internal densities far below the monomers'.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "physics/coagulation/cell_coefficients.hpp"
#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/smoluchowski.hpp"
#include "physics/compaction.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/particle.hpp"
#include "tests/unit/support/coagulation_checks.hpp"
#include "tests/unit/support/dense_cvode.hpp"
#include "tests/unit/support/ice_cell_model.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

namespace panoptic::physics::coagulation {
namespace {

TEST(CoagulationPorous, MonomersGrowIntoFluffyAggregates) {
  const LocalGas gas = mmsn_gas(5.0);
  const CellModel model = testing::ice_cell_model();
  const Smoluchowski eng(MassGrid(model.species.m0, 1e-5, 7.0));
  const int n = eng.size();
  const auto& m = eng.grid().m;
  const double sigma_d = 0.01 * gas.sigma_g;
  std::vector<double> y(2 * n, 0.0);
  y[0] = sigma_d;  // monomers, phi = 1
  y[n] = sigma_d;
  CellCoefficients c;
  testing::DenseOde ode{[&](double, std::span<const double> s, std::span<double> d) {
                          const std::span<const double> sig = s.first(n),
                                                        psi = s.subspan(n);
                          c = cell_coefficients(eng, sig, psi, gas, model);
                          eng.rhs(c, sig, psi, d.first(n), d.subspan(n));
                        },
                        [&](double, std::span<const double> s, std::span<double> j) {
                          eng.jacobian(c, s.first(n), s.subspan(n), j);
                        }};
  const auto res = testing::integrate_dense(ode, 0.0, 100.0 * units::kYr, y, 1e-5, 1e-25);
  double m1 = 0.0, best = 0.0;
  int peak = 0;
  for (int k = 0; k < n; ++k) {
    m1 += y[k];
    if (y[k] > best) {
      best = y[k];
      peak = k;
    }
  }
  const double phi_peak = y[peak] / y[n + peak];
  std::printf("steps %ld, peak bin %d: m = %.3g g, phi = %.3g, ln phi / ln N = %.3f\n",
              res.steps, peak, m[peak], phi_peak,
              std::log(phi_peak) / std::log(m[peak] / m[0]));
  EXPECT_LT(std::abs(m1 / sigma_d - 1.0), 1e-12);
  // Measured: 1 069 steps; the mass-dominating bin 3.0e-10 g (5e4 monomers) with phi =
  // 3.0e-3: ln phi / ln N = -0.536, between the equal-mass hit-and-stick slope -0.58 and
  // the fractal dimension 2 of -1/2 (spec §4.3), as unequal partners add less void.
  EXPECT_GT(m[peak], 1e4 * m[0]);
  const double slope = std::log(phi_peak) / std::log(m[peak] / m[0]);
  EXPECT_GT(slope, -0.58);
  EXPECT_LT(slope, -0.45);
  // every bin from 1e-11 g up that holds 1e-3 of the mass is below 0.1 g cm^-3
  for (int k = 0; k < n; ++k)
    if (m[k] > 1e-11 && y[k] > 1e-3 * sigma_d) {
      EXPECT_LT(y[k] / y[n + k] * model.species.rho0, 0.1) << "bin " << k;
    }
}

//! A fluffy disk cell: icy monomers on the MMSN gas at 5 au, bins up to 1e3 g (3.5 per
//! decade), y = (sigma_k, psi_k): sigma_k a power law cut off at 1e-2 g, phi from
//! e^-0.1 down (psi_k = sigma_k e^(0.5 k + 0.1)).
struct FluffyCell {
  LocalGas gas = mmsn_gas(5.0);
  CellModel model = testing::ice_cell_model();
  Smoluchowski eng{MassGrid(model.species.m0, 1e3, 3.5)};
  int n = eng.size();
  std::vector<double> y = state(eng.grid().m);

  static std::vector<double> state(const std::vector<double>& m) {
    const std::size_t n = m.size();
    std::vector<double> y(2 * n);
    for (std::size_t k = 0; k < n; ++k) {
      y[k] = 1e-2 * std::pow(m[k] / m[0], 0.1) * std::exp(-m[k] / 1e-2) + 1e-10;
      y[n + k] = y[k] * std::exp(0.5 * static_cast<double>(k) + 0.1);
    }
    return y;
  }
};

// The compaction floors' push T_k = -psi_k softplus(ln floor_k + ln u_k) r_k (spec §4.4,
// §15.3) on a disk cell whose bins sit at their floors: the Jacobian follows ln floor_k
// through St_k(u_k) and r_k through t_grow = m_k / sum_{j <= k} K_kj sigma_j (every such
// sigma_j, and u_j through K_kj). Without those two derivatives the same check fails.
TEST(CoagulationPorous, JacobianFollowsTheFloorsAndTheirRelaxationRates) {
  FluffyCell cell;
  const LocalGas& gas = cell.gas;
  const CellModel& model = cell.model;
  const Smoluchowski& eng = cell.eng;
  const int n = cell.n;
  std::vector<double>& y = cell.y;
  auto coefficients = [&](const std::vector<double>& yy) {
    return cell_coefficients(eng, std::span<const double>(yy.data(), n),
                             std::span<const double>(yy.data() + n, n), gas, model, true);
  };
  // every bin 0.02 below its floor in ln phi (its push on), u >= 1
  const CellCoefficients c0 = coefficients(y);
  for (int k = 0; k < n; ++k)
    y[n + k] = y[k] * std::max(1.0, std::exp(0.02 - c0.ln_phi_floor[k]));
  const double with = full_jacobian_error(eng, coefficients, y);
  const double without =
      full_jacobian_error(eng, coefficients, y, [](CellCoefficients& c) {
        c.dlnfloor_dlnu.clear();
        c.drelax_dgrowth.clear();
      });
  std::printf("floors at their push: error %.2e with their derivatives, %.2e without\n",
              with, without);
  // measured 6.4e-9 and 1.3e-2 (of the largest entry |J_fd y_j| of the block); the 6.4e-9
  // is the coefficients' forward differences (kLnUStep 1e-6; 6.4e-8 at 1e-5), the same
  // at a check step of 1e-6 and 1e-7
  EXPECT_LT(with, 1e-7);
  EXPECT_GT(without, 1e-4);
}

// A bin's floor relaxation rate r_k = 1 / (kRelaxFraction soft_min(t_grow, kRelaxCapOmega
// / Omega)) takes t_grow from the bin's own growth: its sticking gain per unit mass from
// partners no more massive than itself, m_k / sum_{j <= k} K_kj sigma_j
// (cell_coefficients). More mass in larger bins leaves it as it is; more in smaller bins
// shortens it.
TEST(CoagulationPorous, FloorRelaxationCountsTheBinsOwnGrowthOnly) {
  FluffyCell cell;
  const int n = cell.n;
  const auto& m = cell.eng.grid().m;
  auto coefficients = [&](const std::vector<double>& yy) {
    return cell_coefficients(cell.eng, std::span<const double>(yy.data(), n),
                             std::span<const double>(yy.data() + n, n), cell.gas,
                             cell.model);
  };
  const int k = n / 2;
  const CellCoefficients c0 = coefficients(cell.y);
  ASSERT_EQ(c0.relax_rate.size(), static_cast<std::size_t>(n));
  double growth = 0.0;
  for (int j = 0; j <= k; ++j)
    growth += c0.kernel[static_cast<std::size_t>(k) * n + j] * cell.y[j] / m[k];
  const double t_cap = kRelaxCapOmega / cell.gas.omega_k;
  const double expected =
      1.0 / (kRelaxFraction *
             std::pow(std::pow(growth, 8.0) + std::pow(t_cap, -8.0), -1.0 / 8.0));
  std::printf("bin %d: t_grow Omega %.3g, r_k %.6e s^-1 (expected %.6e)\n", k,
              cell.gas.omega_k / growth, c0.relax_rate[k], expected);
  EXPECT_NEAR(c0.relax_rate[k] / expected, 1.0, 1e-12);
  // 100x the mass in every larger bin, at the same u: r_k unchanged to the bit
  std::vector<double> y = cell.y;
  for (int j = k + 1; j < n; ++j) {
    y[j] *= 100.0;
    y[n + j] *= 100.0;
  }
  EXPECT_EQ(coefficients(y).relax_rate[k], c0.relax_rate[k]);
  // 100x the mass in every smaller bin: a faster relaxation
  y = cell.y;
  for (int j = 0; j < k; ++j) {
    y[j] *= 100.0;
    y[n + j] *= 100.0;
  }
  EXPECT_GT(coefficients(y).relax_rate[k], 10.0 * c0.relax_rate[k]);
}

//! The fluffy cell fragmenting and cratering at 1 cm/s: its pairs collide at well below
//! 1 m/s, and at this threshold 356 of its pairs (k, j <= k) have 0.01 < p_kj < 0.99
//! (the tests check a formula, not a material).
FluffyCell fragmenting_fluffy_cell() {
  FluffyCell cell;
  OutcomeSwitches& s = cell.model.outcomes;
  s.fragmentation = true;
  s.v_frag = 1e0;
  s.cratering = true;
  s.v_eros = 1e0;
  return cell;
}

// With fragmentation and cratering, t_grow counts the collisions that stick: r_k from
// sum_{j <= k} K_kj (1 - p_kj) sigma_j / m_k (cell_coefficients; net of the losses, as
// the single size's t_grow, physics/growth_rates.hpp). A bin whose partners mostly
// fragment it relaxes more slowly than the same bin with every pair sticking.
TEST(CoagulationPorous, FloorRelaxationCountsTheStickingCollisionsOnly) {
  FluffyCell cell = fragmenting_fluffy_cell();
  const int n = cell.n;
  const auto& m = cell.eng.grid().m;
  auto coefficients = [&](const CellModel& model) {
    return cell_coefficients(cell.eng, std::span<const double>(cell.y.data(), n),
                             std::span<const double>(cell.y.data() + n, n), cell.gas,
                             model);
  };
  const CellCoefficients c = coefficients(cell.model);
  CellModel sticking = cell.model;
  sticking.outcomes = {};
  const CellCoefficients c_stick = coefficients(sticking);
  const double t_cap = kRelaxCapOmega / cell.gas.omega_k;
  int slower = 0;
  for (int k = 0; k < n; ++k) {
    double growth = 0.0, lost = 0.0;
    for (int j = 0; j <= k; ++j) {
      const std::size_t kj = static_cast<std::size_t>(k) * n + j;
      const double rate = c.kernel[kj] * cell.y[j] / m[k];
      growth += rate * (1.0 - c.p_frag[kj]);
      lost += rate * c.p_frag[kj];
    }
    const double expected =
        1.0 / (kRelaxFraction *
               std::pow(std::pow(growth, 8.0) + std::pow(t_cap, -8.0), -1.0 / 8.0));
    EXPECT_NEAR(c.relax_rate[k] / expected, 1.0, 1e-12) << "bin " << k;
    // where most of the bin's collisions are losses and growth sets t_relax (not the cap)
    if (lost > growth && growth * t_cap > 10.0) {
      EXPECT_LT(c.relax_rate[k], 0.9 * c_stick.relax_rate[k]) << "bin " << k;
      ++slower;
    }
  }
  std::printf("%d bins checked, %d of them relax more slowly for their losses\n", n,
              slower);
  EXPECT_GT(slower, 2);
}

// The floors' push with fragmentation and cratering: the Jacobian follows r_k through
// the sticking collisions K_kj (1 - p_kj). Measured: 1.2e-8, against 8.6e-2 with the
// derivatives of r_k through K_kj alone (the rule before). The terms of p_kj by u_k and
// u_j are below this check's resolution here (1.2e-8 without them as well).
TEST(CoagulationPorous, JacobianFollowsTheFloorsOfAFragmentingCell) {
  FluffyCell cell = fragmenting_fluffy_cell();
  const int n = cell.n;
  std::vector<double>& y = cell.y;
  auto coefficients = [&](const std::vector<double>& yy) {
    return cell_coefficients(cell.eng, std::span<const double>(yy.data(), n),
                             std::span<const double>(yy.data() + n, n), cell.gas,
                             cell.model, true);
  };
  const CellCoefficients c0 = coefficients(y);
  int partial = 0;  // pairs (k, j <= k) whose outcome is neither sure sticking nor loss
  for (int k = 0; k < n; ++k)
    for (int j = 0; j <= k; ++j) {
      const double p = c0.p_frag[static_cast<std::size_t>(k) * n + j];
      partial += p > 0.01 && p < 0.99;
    }
  for (int k = 0; k < n; ++k)
    y[n + k] = y[k] * std::max(1.0, std::exp(0.02 - c0.ln_phi_floor[k]));
  const double err = full_jacobian_error(cell.eng, coefficients, y);
  std::printf("%d pairs with 0.01 < p < 0.99; floors at their push: error %.2e\n",
              partial, err);
  EXPECT_GT(partial, 10);
  EXPECT_LT(err, 1e-7);
}

//! Every vector of CellCoefficients, for comparisons member by member.
constexpr std::array<std::vector<double> CellCoefficients::*, 12> kCoefficientVectors = {
    &CellCoefficients::kernel,         &CellCoefficients::p_frag,
    &CellCoefficients::dlnk_dlnu,      &CellCoefficients::dp_dlnu,
    &CellCoefficients::ln_u_ratio,     &CellCoefficients::dd_dlnu_i,
    &CellCoefficients::dd_dlnu_j,      &CellCoefficients::ln_phi_floor,
    &CellCoefficients::dlnfloor_dlnu,  &CellCoefficients::relax_rate,
    &CellCoefficients::drelax_dgrowth, &CellCoefficients::fragment_u_cap};

// The porous Jacobian's perturbed bins (radius and St at u e^kLnUStep), given by a caller
// that has them (the distribution module, for its d St / d ln u), are the ones
// cell_coefficients uses: the same bits as its own, and other bins change the result.
TEST(CoagulationPorous, CoefficientsUseTheCallersPerturbedBins) {
  const FluffyCell cell;
  const CellModel& model = cell.model;
  const int n = cell.n;
  const auto& m = cell.eng.grid().m;
  const std::span<const double> sigma(cell.y.data(), n), psi(cell.y.data() + n, n);
  std::vector<double> phi(n);
  for (int k = 0; k < n; ++k)
    phi[k] = bin_porosity(sigma[k], psi[k], model.empty_scale).phi();
  const double rho0 = model.species.rho0;
  const DragLaw drag = model.growth.drag;
  auto coefficients = [&](const PerturbedBins* perturbed) {
    return cell_coefficients(cell.eng, sigma, psi, cell.gas, model, true, nullptr, {},
                             perturbed);
  };
  PerturbedBins same, compact;
  perturbed_bins(m, phi, rho0, cell.gas, drag, same);
  perturbed_bins(m, std::vector<double>(n, 1.0), rho0, cell.gas, drag, compact);
  const CellCoefficients own = coefficients(nullptr), given = coefficients(&same),
                         other = coefficients(&compact);
  for (const auto member : kCoefficientVectors) EXPECT_TRUE(own.*member == given.*member);
  EXPECT_FALSE(own.dlnk_dlnu == other.dlnk_dlnu);
  EXPECT_FALSE(own.dlnfloor_dlnu == other.dlnfloor_dlnu);
}

// A cell's workspace keeps tables of the grid, the gas and the monomers from call to call
// (CoefficientWorkspace): after serving another gas, state and monomer mass it gives the
// coefficients of a fresh call bit for bit, the fragments' ceiling that of the cell's own
// monomers.
TEST(CoagulationPorous, AReusedWorkspaceGivesTheCoefficientsOfAFreshOne) {
  const FluffyCell cell;
  CellModel model = cell.model;
  model.outcomes = {
      .fragmentation = true, .cratering = true, .v_frag = 100.0, .v_eros = 100.0};
  const int n = cell.n;
  const std::span<const double> sigma(cell.y.data(), n);
  // the upper half compact (u = 1): their pairs from the workspace's CompactPairTable
  std::vector<double> psi(cell.y.begin() + n, cell.y.end());
  std::copy(sigma.begin() + n / 2, sigma.end(), psi.begin() + n / 2);
  CellModel other = model;
  other.species.m0 *= 8.0;
  const std::vector<double> compact(sigma.begin(), sigma.end());
  for (const bool derivatives : {false, true}) {
    CoefficientWorkspace ws;
    CellCoefficients c = cell_coefficients(cell.eng, sigma, compact, mmsn_gas(2.0), other,
                                           !derivatives, &ws);
    c = cell_coefficients(cell.eng, sigma, psi, cell.gas, model, derivatives, &ws,
                          std::move(c));
    const CellCoefficients fresh =
        cell_coefficients(cell.eng, sigma, psi, cell.gas, model, derivatives);
    for (const auto member : kCoefficientVectors)
      EXPECT_TRUE(c.*member == fresh.*member) << "derivatives " << derivatives;
    ASSERT_EQ(c.fragment_u_cap.size(), static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k)
      EXPECT_EQ(c.fragment_u_cap[k],
                fragment_u_ceiling(cell.eng.grid().m[k], model.species.m0));
    EXPECT_GT(c.fragment_u_cap[n - 1], 1.0);
  }
}

// Pairs of two compact bins (u = 1 exactly: here psi_k = sigma_k in the upper half of the
// bins) take their coefficients from the workspace's CompactPairTable: the bits of the
// compact cell's kernel and loss probabilities, and of the product rule at u = 1 on the
// compact bins' speeds and compression slopes. A pair with a fluffy bin differs.
TEST(CoagulationPorous, PairsOfCompactBinsHaveTheCompactCellsCoefficients) {
  const FluffyCell cell;
  CellModel model = cell.model;
  model.outcomes = {
      .fragmentation = true, .cratering = true, .v_frag = 100.0, .v_eros = 100.0};
  const int n = cell.n, half = n / 2;
  const auto& m = cell.eng.grid().m;
  const std::span<const double> sigma(cell.y.data(), n);
  std::vector<double> psi(cell.y.begin() + n, cell.y.end());
  std::copy(sigma.begin() + half, sigma.end(), psi.begin() + half);
  const CellCoefficients porous =
      cell_coefficients(cell.eng, sigma, psi, cell.gas, model, true);
  const CellCoefficients compact =
      cell_coefficients(cell.eng, sigma, {}, cell.gas, model);
  const std::vector<double> ones(n, 1.0);
  const BinProperties bins = bin_properties(cell.eng.grid(), ones, model.species.rho0,
                                            cell.gas, model.growth.drag);
  const std::vector<double> dv =
      pair_speeds(cell.eng.grid(), bins, cell.gas, model.growth.turbulence);
  const double e_threshold = 3.0 * model.growth.b * model.species.e_roll;
  for (int i = half; i < n; ++i) {
    const double s_c =
        compression_slope_of_target(bins.a[i], bins.St[i], cell.gas, model.growth.drag);
    for (int j = half; j <= i; ++j) {
      const std::size_t ij = static_cast<std::size_t>(i) * n + j;
      const std::size_t ji = static_cast<std::size_t>(j) * n + i;
      EXPECT_EQ(porous.kernel[ij], compact.kernel[ij]) << i << " " << j;
      EXPECT_EQ(porous.kernel[ji], compact.kernel[ji]) << i << " " << j;
      EXPECT_EQ(porous.p_frag[ij], compact.p_frag[ij]) << i << " " << j;
      EXPECT_EQ(porous.ln_u_ratio[ij],
                product_ln_u_ratio(m[i], 1.0, m[j], 1.0,
                                   impact_energy(m[i], m[j], dv[ij]), e_threshold, s_c))
          << i << " " << j;
    }
  }
  const std::size_t mixed = static_cast<std::size_t>(half) * n + half - 1;
  EXPECT_NE(porous.kernel[mixed], compact.kernel[mixed]);
}

}  // namespace
}  // namespace panoptic::physics::coagulation
