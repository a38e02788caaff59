//! Erosion by small projectiles in the one-cell coagulation engine (Krijt et al. 2015;
//! spec §5.1, §15.2; physics/coagulation/cell_coefficients.hpp outcome_switches): a
//! target bin bombarded by a projectile bin loses eps_eros m_j per collision above
//! v_eros and gains m_j below it, at the rate of the kernel written out by hand; the
//! fragments and the remnant keep their parents' volume; a closed box conserves mass to
//! round-off; the Jacobian against finite differences, compact and porous.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/coagulation/cell_coefficients.hpp"
#include "physics/coagulation/collision_kernel.hpp"
#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/smoluchowski.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"
#include "tests/unit/support/coagulation_checks.hpp"
#include "tests/unit/support/dense_cvode.hpp"
#include "tests/unit/support/ice_cell_model.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

namespace panoptic::physics::coagulation {
namespace {

constexpr double kEps = 2.0;     // eps_eros: 2, so that DustPy's 1 would fail
constexpr double kWidth = 0.01;  // erosion.width's default

//! The erosion switches at v_eros [cm s^-1], fragmentation optionally at v_frag.
OutcomeSwitches erosion_switches(double v_eros, bool fragmentation = false,
                                 double v_frag = 1e300) {
  OutcomeSwitches s;
  s.fragmentation = fragmentation;
  s.cratering = true;
  s.v_frag = v_frag;
  s.v_eros = v_eros;
  s.w_eros = kWidth;
  return s;
}

//! Icy compact bins from the monomer to 1e3 g, 7 per decade, eroding with kEps.
Smoluchowski ice_engine(const CellModel& model, double m_max = 1e3, double bpd = 7.0) {
  return Smoluchowski(MassGrid(model.species.m0, m_max, bpd), {10.0, kEps, -11.0 / 6.0});
}

TEST(CoagulationErosion, SwitchesOfTheScene) {
  // erosion off: DustPy's cratering at v_frag, Maxwell-Boltzmann (bit for bit as before)
  GrowthOptions o;
  o.fragmentation = true;
  Species sp;
  sp.v_frag = 100.0;
  OutcomeSwitches s = outcome_switches(o, sp);
  EXPECT_TRUE(s.fragmentation && s.cratering);
  EXPECT_EQ(s.v_eros, 100.0);
  EXPECT_EQ(s.w_eros, 0.0);
  EXPECT_EQ(fragmentation_model(o).excavated_mass, 1.0);
  // erosion on (either model), fragmentation off or a species that does not fragment:
  // the unequal pairs erode at v_eros with the smooth step, the others stick
  for (ErosionModel e : {ErosionModel::kHalt, ErosionModel::kBalance}) {
    o.erosion = e;
    o.fragmentation = false;
    o.v_eros = 2e3;
    o.w_eros = 0.02;
    o.eps_eros = 3.0;
    s = outcome_switches(o, sp);
    EXPECT_FALSE(s.fragmentation);
    EXPECT_TRUE(s.cratering);
    EXPECT_EQ(s.v_eros, 2e3);
    EXPECT_EQ(s.w_eros, 0.02);
    EXPECT_EQ(fragmentation_model(o).excavated_mass, 3.0);
  }
  // the step: S(x) of spec §5.2, 1/2 at v_eros, 1 - 1/2 (1 - tanh(1)) one width above
  EXPECT_EQ(pair_loss_probability(2e3, true, s), 0.5);
  EXPECT_NEAR(pair_loss_probability(2e3 * 1.02, true, s), 0.5 * (1.0 + std::tanh(1.0)),
              1e-15);
  EXPECT_EQ(pair_loss_probability(1e3, true, s), 0.0);
  EXPECT_EQ(pair_loss_probability(4e3, true, s), 1.0);
  EXPECT_EQ(pair_loss_probability(1e9, false, s), 0.0);  // similar pairs stick
}

TEST(CoagulationErosion, TargetLosesEpsTimesTheProjectileAboveVerosAndGainsBelow) {
  // MMSN gas at 5 au, a 1 g target bin and a 1e-6 g projectile bin (six decades apart),
  // nothing else: the target's bins (i - 1 for the remnant, i and up for sticking and
  // its self-collisions) change by (1 - p) m_j R - p eps m_j R, R = K_ij n_i n_j
  const LocalGas gas = mmsn_gas(5.0);
  CellModel model = testing::ice_cell_model();
  const Smoluchowski eng = ice_engine(model);
  const int n = eng.size();
  const auto& m = eng.grid().m;
  const double rho0 = model.species.rho0;
  const int i = static_cast<int>(std::lround(std::log10(1.0 / m[0]) * 7.0));
  const int j = i - 42;
  ASSERT_GT(i - j, eng.crater_bins());
  // the kernel by hand from the spec's laws (§2 radius, St, h_d; §3 dv; §15.2 K)
  const double a_i = radius(m[i], 1.0, rho0), a_j = radius(m[j], 1.0, rho0);
  const double st_i = stokes_number_of_radius(a_i, 1.0, rho0, gas, DragLaw::kStokesRe);
  const double st_j = stokes_number_of_radius(a_j, 1.0, rho0, gas, DragLaw::kStokesRe);
  const double h_i = dust_scale_height(st_i, gas), h_j = dust_scale_height(st_j, gas);
  const double dv = dv_total(st_i, st_j, m[i], m[j], gas, TurbulenceModel{});
  const double k_ij = units::kPi * (a_i + a_j) * (a_i + a_j) * dv /
                      std::sqrt(2.0 * units::kPi * (h_i * h_i + h_j * h_j));
  std::vector<double> sigma(n, 0.0), ds(n);
  sigma[i] = 1e-2;
  sigma[j] = 1e-3;
  const double rate = k_ij * (sigma[i] / m[i]) * (sigma[j] / m[j]);
  std::printf("dv(1 g, 1e-6 g) = %.1f cm/s, R = %.3e cm^-2 s^-1\n", dv, rate);
  // v_eros below, at and above the pair's speed: p = 1, 1/2, 0
  for (const auto& [x, p] : {std::pair{1.25, 1.0}, {1.0, 0.5}, {0.8, 0.0}}) {
    model.outcomes = erosion_switches(dv / x);
    const CellCoefficients c = cell_coefficients(eng, sigma, {}, gas, model);
    ASSERT_EQ(c.p_frag[static_cast<std::size_t>(i) * n + j], p);
    eng.rhs(c, sigma, {}, ds, {});
    double target = 0.0, below = 0.0;
    for (int k = i - 1; k < n; ++k) target += ds[k];
    for (int k = 0; k < j; ++k) below += ds[k];
    const double expected = (1.0 - p) * m[j] * rate - p * kEps * m[j] * rate;
    EXPECT_NEAR(target / (m[j] * rate), expected / (m[j] * rate), 1e-12) << "x = " << x;
    // the fragments: (1 + eps) m_j per collision as n(m) ∝ m^-11/6 over the bins <= j
    // (mass per bin ∝ m^(1/6)); bins below j receive nothing else
    double z = 0.0;
    for (int k = 0; k <= j; ++k) z += std::pow(m[k] / m[0], 1.0 / 6.0);
    const double w_j = std::pow(m[j] / m[0], 1.0 / 6.0);
    EXPECT_NEAR(below / (m[j] * rate), p * (1.0 + kEps) * (z - w_j) / z, 1e-12);
    if (p == 1.0) {
      EXPECT_NEAR(ds[3] / ds[2], std::pow(m[3] / m[2], 1.0 / 6.0), 1e-12);
    }
  }
}

TEST(CoagulationErosion, FragmentsAndRemnantKeepTheirParentsVolumeUpToTheCeiling) {
  // porous target (u = 50) and projectile (u = 3) eroding (p = 1): the remnant has the
  // target's u, the fragments the mass-weighted u of the projectile and the excavated
  // mass, (u_j + eps u_i) / (1 + eps) (spec §15.3), in each bin k capped by the smooth
  // minimum with the fluffiest u of its mass, (m_k / m0)^(log2(2.99) - 1) (porosity.hpp)
  CellModel model = testing::ice_cell_model(erosion_switches(1e-3));
  model.growth.gas_compaction = false;
  model.growth.self_gravity = false;
  const Smoluchowski eng = ice_engine(model);
  const int n = eng.size(), i = 80, j = 30;
  std::vector<double> sigma(n, 0.0), psi(n, 0.0), ds(n), dp(n);
  sigma[i] = 1e-2;
  sigma[j] = 1e-3;
  psi[i] = 50.0 * sigma[i];
  psi[j] = 3.0 * sigma[j];
  const CellCoefficients c = cell_coefficients(eng, sigma, psi, mmsn_gas(5.0), model);
  ASSERT_EQ(c.p_frag[static_cast<std::size_t>(i) * n + j], 1.0);
  eng.rhs(c, sigma, psi, ds, dp);
  ASSERT_GT(ds[i - 1], 0.0);
  EXPECT_NEAR(dp[i - 1] / ds[i - 1], 50.0, 1e-12 * 50.0);
  const double u_frag = (3.0 + kEps * 50.0) / (1.0 + kEps);
  const auto& m = eng.grid().m;
  int capped = 0, free = 0;
  for (int k = 0; k < j; ++k) {
    const double ceiling = std::pow(m[k] / model.species.m0, std::log2(2.99) - 1.0);
    const double expected = std::pow(std::pow(u_frag, -8.0) + std::pow(ceiling, -8.0),
                                     -1.0 / 8.0);  // soft_min, p = 8
    EXPECT_NEAR(dp[k] / ds[k], expected, 1e-12 * expected) << "bin " << k;
    capped += ceiling < 0.5 * u_frag;
    free += ceiling > 2.0 * u_frag;
  }
  EXPECT_GT(capped, 3);  // both regimes are met
  EXPECT_GT(free, 3);
}

TEST(CoagulationErosion, ClosedBoxConservesMassAndBooksTheVolume) {
  // compact, 5 au MMSN, bins to 100 g: erosion at 1 m/s (eps 2), fragmentation at 5 m/s,
  // from an MRN-like spread to 1e-2 g, 300 yr of CVODE with the engine's Jacobian
  const LocalGas gas = mmsn_gas(5.0);
  CellModel model = testing::ice_cell_model(erosion_switches(1e2, true, 5e2));
  const Smoluchowski eng = ice_engine(model, 1e2, 5.0);
  const int n = eng.size();
  const auto& m = eng.grid().m;
  std::vector<double> y(n, 0.0);
  double m1 = 0.0;
  for (int k = 0; k < n && m[k] < 1e-2; ++k) {
    y[k] = 1e-3 * std::pow(m[k] / m[0], 1.0 / 6.0);
    m1 += y[k];
  }
  const CellCoefficients c = cell_coefficients(eng, y, {}, gas, model);
  // erosion acts: the eroding pairs' share of the collision mass rate at the start
  double eroding = 0.0, all = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      const std::size_t ij = static_cast<std::size_t>(i) * n + j;
      const double r = c.kernel[ij] * y[i] * y[j] / m[i];
      all += r;
      if (i - j > eng.crater_bins()) eroding += c.p_frag[ij] * r;
    }
  testing::DenseOde ode{[&](double, std::span<const double> s, std::span<double> d) {
                          eng.rhs(c, s, {}, d, {});
                        },
                        [&](double, std::span<const double> s, std::span<double> jac) {
                          eng.jacobian(c, s, {}, jac);
                        }};
  const auto res = testing::integrate_dense(ode, 0.0, 300.0 * units::kYr, y, 1e-8, 1e-20);
  double m1_end = 0.0;
  for (double v : y) m1_end += v;
  std::printf("eroding share of the collision rate %.2e; %ld steps; mass error %.1e\n",
              eroding / all, res.steps, m1_end / m1 - 1.0);
  EXPECT_GT(eroding, 1e-3 * all);
  EXPECT_LT(std::abs(m1_end / m1 - 1.0), 1e-13);

  // porous, floors off, u spread over 1 .. 1e3: sum psi changes by the sticking
  // products' volume only, mass by nothing
  model.growth.gas_compaction = false;
  model.growth.self_gravity = false;
  std::vector<double> sigma(n), psi(n);
  for (int k = 0; k < n; ++k) {
    sigma[k] = 1e-3 * std::exp(-0.02 * k);
    psi[k] = sigma[k] * std::pow(10.0, 3.0 * std::sin(0.37 * k) * std::sin(0.37 * k));
  }
  const CellCoefficients cp = cell_coefficients(eng, sigma, psi, gas, model);
  const double mass = imbalance(eng, cp, sigma, psi).first;
  const VolumeRates capped = volume_rates(eng, cp, sigma, psi);
  const double gain = sticking_volume_gain(eng, cp, sigma, psi);
  // fragments that keep their parents' volume (the ceiling off): psi booked exactly
  CellCoefficients uncapped = cp;
  uncapped.fragment_u_cap.clear();
  const VolumeRates kept = volume_rates(eng, uncapped, sigma, psi);
  std::printf(
      "porous: mass imbalance %.1e, volume %.1e of sum |dpsi|; the ceiling "
      "removes %.1e of it\n",
      mass, std::abs(kept.sum - gain) / capped.abs, (kept.sum - capped.sum) / capped.abs);
  EXPECT_LT(mass, 1e-14);
  EXPECT_LT(std::abs(kept.sum - gain), 1e-13 * capped.abs);
  // the ceiling only removes fragment volume, and leaves the mass rates as they are
  EXPECT_GT(kept.sum - capped.sum, 0.0);
  std::vector<double> ds(n), ds_free(n), dp(n);
  eng.rhs(cp, sigma, psi, ds, dp);
  eng.rhs(uncapped, sigma, psi, ds_free, dp);
  EXPECT_EQ(ds, ds_free);
}

TEST(CoagulationErosion, JacobianMatchesFiniteDifferences) {
  // compact: the coefficients are the gas's, the Jacobian exact
  const LocalGas gas = mmsn_gas(5.0);
  CellModel model = testing::ice_cell_model(erosion_switches(30.0, true, 100.0));
  const Smoluchowski eng = ice_engine(model, 1e4, 4.0);
  const int n = eng.size();
  std::vector<double> y(2 * n);
  for (int k = 0; k < n; ++k) {
    const double mk = eng.grid().m[k];
    y[k] = 1e-3 * std::pow(mk / eng.grid().m[0], 1.0 / 6.0) * std::exp(-mk / 1e2) + 1e-12;
    y[n + k] = y[k] * std::exp(0.1 * k);
  }
  const std::vector<double> sigma(y.begin(), y.begin() + n);
  const CellCoefficients c = cell_coefficients(eng, sigma, {}, gas, model);
  int eroding = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; i - j > eng.crater_bins(); ++j)
      eroding += c.p_frag[static_cast<std::size_t>(i) * n + j] > 0.5;
  EXPECT_GT(eroding, 20);
  // d/d ln sigma_j: the central differences' round-off in the nearly empty bins (1e-12)
  // would swamp a plain comparison
  std::vector<double> jac(static_cast<std::size_t>(n) * n);
  eng.jacobian(c, sigma, {}, jac);
  auto f = [&](const std::vector<double>& s) {
    std::vector<double> out(n);
    eng.rhs(c, s, {}, out, {});
    return out;
  };
  const FdComparison d = compare_with_differences(f, jac, sigma, true);
  const double compact = d.err / d.max_fd;
  // porous: every coefficient rebuilt from the state at each difference, the Jacobian
  // fed the builder's derivatives by ln u (the erosion step's among them)
  auto coefficients = [&](const std::vector<double>& yy) {
    return cell_coefficients(eng, std::span<const double>(yy.data(), n),
                             std::span<const double>(yy.data() + n, n), gas, model, true);
  };
  const double porous = full_jacobian_error(eng, coefficients, y);
  std::printf("compact %.1e, porous %.1e (%d eroding pairs)\n", compact, porous, eroding);
  EXPECT_LT(compact, 1e-7);
  EXPECT_LT(porous, 1e-5);
}

}  // namespace
}  // namespace panoptic::physics::coagulation
