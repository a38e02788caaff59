// Porous bins on the grid (spec §15.1, §15.3, §15.4; physics/modules/size_distribution.*
// with growth.porosity): psi_k is the tracer moment of sigma_k under transport, the
// coagulation conserves mass and books the volume of every sticking product exactly,
// the Jacobian (the engine's with the coefficients' derivatives by ln u, and the face
// flows through St) against finite differences, and a run that keeps its budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "physics/modules/size_distribution.hpp"
#include "src/core/units.hpp"
#include "src/model/scene_validation.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "tests/unit/support/coagulation_checks.hpp"
#include "tests/unit/support/jacobian_check.hpp"

namespace panoptic {
namespace {

const std::string kSmall =
    std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml";

// The small distribution scene with porous ice aggregates on 3.5 bins per decade to
// 1e-4 g (29 bins), so that the dense finite-difference Jacobian stays cheap.
Config porous_scene(std::vector<std::string> sets = {}) {
  for (const char* s : {"porosity.enabled=true", "model.m_max_g=1e-4"})
    sets.insert(sets.begin(), s);
  return load_scene(kSmall, sets);
}

// A state with every bin filled (+-30 % per component around the initial state) and psi
// = u sigma, u from `u_of(cell, bin)`.
template <class U>
std::vector<double> porous_state(const Simulation& sim, U u_of) {
  auto y = testing::perturbed_state(sim, 7);
  const auto& L = sim.model().layout();
  const auto* d = sim.distribution();
  for (int i = 0; i < sim.grid().n_cells(); ++i)
    for (int k = 0; k < d->n_bins(); ++k)
      y[L.index(i, d->psi_slot(k))] = u_of(i, k) * y[L.index(i, d->bin_slot(k))];
  return y;
}

TEST(SizeDistributionPorous, AcceptedAndRegistersPsi) {
  EXPECT_NO_THROW(validate_scene(porous_scene()));
  Simulation sim(porous_scene());
  const auto* d = sim.distribution();
  ASSERT_NE(d, nullptr);
  ASSERT_TRUE(d->porous());
  EXPECT_EQ(d->cell_vars(), 2 * d->n_bins());
  // compact at the start: psi_k = sigma_k
  const auto y = sim.initial_state();
  const auto& L = sim.model().layout();
  for (int k = 0; k < d->n_bins(); ++k)
    EXPECT_EQ(y[L.index(3, d->psi_slot(k))], y[L.index(3, d->bin_slot(k))]);
}

// A bin's u is resolved where its mass is (physics/coagulation/porosity.hpp): the
// empty-bin scale e is the bins' absolute tolerance, solver.atol_sigma times their scale
// (by default 1e-10 in a porous distribution), so a bin at e with psi = 3 sigma has u =
// (3 e + e)/(e + e) = 2, one at 100 e has (300 + 1)/(100 + 1), and both move with the
// tolerance.
TEST(SizeDistributionPorous, EmptyBinScaleIsTheBinsAbsoluteTolerance) {
  for (const auto& [sets, atol] : {std::pair<std::vector<std::string>, double>{{}, 1e-10},
                                   {{"solver.atol_sigma=1e-8"}, 1e-8}}) {
    Simulation sim(porous_scene(sets));
    const auto* d = sim.distribution();
    const auto& L = sim.model().layout();
    const double e = atol * L.cell_var(d->bin_slot(0)).abs_scale;
    auto y = sim.initial_state();
    const int cell = 2, k = 5;
    for (const double n : {1.0, 100.0}) {
      y[L.index(cell, d->bin_slot(k))] = n * e;
      y[L.index(cell, d->psi_slot(k))] = 3.0 * n * e;
      EXPECT_NEAR(1.0 / d->phi(cell, k, y), (3.0 * n + 1.0) / (n + 1.0), 1e-9)
          << "atol_sigma " << atol << ", sigma_k = " << n << " e";
    }
  }
}

// psi/sigma uniform: the transport moves psi_k exactly as u sigma_k (the same face terms
// and a flux operator linear and, limited, homogeneous of degree one in the
// transported quantity), to round-off, for first-order and van Leer advection.
TEST(SizeDistributionPorous, UniformPorosityStaysUniformUnderTransport) {
  for (const char* scheme : {"\"upwind\"", "\"van_leer\""}) {
    Simulation sim(porous_scene({std::string("transport.advection=") + scheme}));
    const double u = 37.0;
    const auto y = porous_state(sim, [u](int, int) { return u; });
    std::vector<double> ydot(y.size(), 0.0);
    const auto* d = sim.distribution();
    d->add_transport(y, ydot);
    const auto& L = sim.model().layout();
    double worst = 0.0, scale = 0.0;
    for (int i = 0; i < sim.grid().n_cells(); ++i)
      for (int k = 0; k < d->n_bins(); ++k) {
        const double ds = ydot[L.index(i, d->bin_slot(k))];
        const double dp = ydot[L.index(i, d->psi_slot(k))];
        scale = std::max(scale, std::abs(u * ds));
        worst = std::max(worst, std::abs(dp - u * ds));
      }
    std::printf("%s: max |dpsi/dt - u dsigma/dt| / max |u dsigma/dt| = %.1e\n", scheme,
                worst / scale);
    EXPECT_GT(scale, 0.0);
    EXPECT_LT(worst, 1e-13 * scale) << scheme;
  }
}

// Closed box (no drift, no diffusion, static gas; floors off): per cell the coagulation
// moves mass between bins only, and changes sum_k psi_k by exactly the volume the
// sticking products gain, sum over pairs of (1 - p) R_ij [(m_i + m_j) u_i e^d_ij - m_i
// u_i
// - m_j u_j] (products inside the grid; fragments keep their parents' volume), computed
// here from the coefficients independently of the engine's two-bin split.
TEST(SizeDistributionPorous, CoagulationConservesMassAndBooksTheVolume) {
  Simulation sim(porous_scene({"transport.drift=false", "transport.diffusion=false",
                               "gas.evolve=false", "porosity.gas_compaction=false",
                               "porosity.self_gravity=false"}));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> log_u(0.0, 4.0);
  std::vector<double> u_table(12 * 100);
  for (double& v : u_table) v = std::pow(10.0, log_u(rng));
  const auto* d = sim.distribution();
  const int nb = d->n_bins();
  const auto y = porous_state(sim, [&](int i, int k) { return u_table[i * nb + k]; });
  std::vector<double> ydot(y.size(), 0.0);
  sim.model().rhs(0.0, y, ydot);
  const auto& L = sim.model().layout();
  double worst_mass = 0.0, worst_volume = 0.0, ceiling_share = 0.0;
  for (int i = 0; i < sim.grid().n_cells(); ++i) {
    const auto c = d->coefficients(i, y);
    double dm = 0.0, dm_abs = 0.0, dv = 0.0, dv_abs = 0.0;
    for (int k = 0; k < nb; ++k) {
      dm += ydot[L.index(i, d->bin_slot(k))];
      dm_abs += std::abs(ydot[L.index(i, d->bin_slot(k))]);
      dv += ydot[L.index(i, d->psi_slot(k))];
      dv_abs += std::abs(ydot[L.index(i, d->psi_slot(k))]);
    }
    // the engine with fragments that keep their parents' volume books exactly the
    // sticking gain; the fragment ceiling (porosity.hpp) only removes volume
    std::vector<double> s(nb), p(nb);
    for (int k = 0; k < nb; ++k) {
      s[k] = y[L.index(i, d->bin_slot(k))];
      p[k] = y[L.index(i, d->psi_slot(k))];
    }
    const double gain = physics::coagulation::sticking_volume_gain(d->engine(), c, s, p);
    auto free_fragments = c;
    free_fragments.fragment_u_cap.clear();
    const double dv_free =
        physics::coagulation::volume_rates(d->engine(), free_fragments, s, p).sum;
    worst_mass = std::max(worst_mass, std::abs(dm) / dm_abs);
    worst_volume = std::max(worst_volume, std::abs(dv_free - gain) / dv_abs);
    EXPECT_GE(dv_free - dv, -1e-15 * dv_abs) << "cell " << i;  // 0 where none fragment
    ceiling_share = std::max(ceiling_share, (dv_free - dv) / dv_abs);
  }
  std::printf(
      "closed box: |sum dsigma/dt| / sum |dsigma/dt| <= %.1e, |sum dpsi/dt - "
      "volume gain| / sum |dpsi/dt| <= %.1e with fragments keeping their parents' "
      "volume; the ceiling removes up to %.1e\n",
      worst_mass, worst_volume, ceiling_share);
  EXPECT_LT(worst_mass, 1e-12);
  EXPECT_LT(worst_volume, 1e-12);
  EXPECT_GT(ceiling_share, 1e-6);  // the state's fragments meet the ceiling
}

// The assembled Jacobian against central differences of the right-hand side with every
// coefficient rebuilt, on states with every bin filled and porosities spread over 1 ..
// 1e4: coagulation (sticking, fragmentation, cratering, the floors), drift and diffusion
// with St(phi), the viscous gas. Measured: row-scaled error 2.2e-5, entry error 1.9e-3,
// both in the coagulation blocks: the coefficients' derivatives by ln u are forward
// differences of 1e-6 (cell_coefficients; the floors' levels and relaxation rates are
// followed, CoagulationPorous.JacobianFollowsTheFloorsAndTheirRelaxationRates). `sets`
// change the scene.
void expect_porous_jacobian(const std::vector<std::string>& sets) {
  Simulation sim(porous_scene(sets));
  const auto& L = sim.model().layout();
  const int nb = sim.distribution()->n_bins();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> log_u(0.0, 4.0);
  std::vector<double> u_table(12 * 100);
  for (double& v : u_table) v = std::pow(10.0, log_u(rng));
  const auto y = porous_state(sim, [&](int i, int k) { return u_table[i * nb + k]; });
  const auto c = testing::compare_with_fd(sim, y);
  std::printf("porous: row-scaled error %.2e, entry error %.2e, %ld FD non-zeros\n",
              c.max_rel_err, c.max_entry_err, c.nnz_fd);
  EXPECT_LT(c.max_rel_err, 1e-4)
      << "worst d(" << L.describe(c.worst_row) << ")/d(" << L.describe(c.worst_col)
      << "): analytic " << c.worst_analytic << ", FD " << c.worst_fd;
  EXPECT_LT(c.max_entry_err, 1e-2)
      << "d(" << L.describe(c.entry_row) << ")/d(" << L.describe(c.entry_col) << ")";
  EXPECT_EQ(c.outside_pattern, 0);
  // the dense 2N x 2N coagulation blocks are there
  EXPECT_GT(c.nnz_fd, 12 * (2 * nb) * (2 * nb) / 2);
}

TEST(SizeDistributionPorous, JacobianMatchesFiniteDifferences) {
  expect_porous_jacobian({});
}

// With the snow line: psi_k follows sigma_k over the two bins of (1 - f_ice) m_k, and
// the silicate cell's coefficients (spec §6.3, §15.4).
TEST(SizeDistributionPorous, JacobianMatchesFiniteDifferencesSnowLine) {
  expect_porous_jacobian({"snowline.enabled=true"});
}

// A run from compact MRN dust: Newton converges with this Jacobian, the mass budget
// closes, and the aggregates grow porous (phi of the mass-dominating bin well below 1);
// with psi_k per bin, and with porosity on the track (porosity.bins = "track",
// tests/unit/physics/test_porosity_track.cpp).
TEST(SizeDistributionPorous, RunKeepsTheBudgetAndGrowsFluffy) {
  for (const char* bins : {"porosity.bins=\"evolved\"", "porosity.bins=\"track\""}) {
    Simulation sim(porous_scene({"output.t_end_yr=300.0", bins}));
    CvodeIntegrator cvode(sim.model(), 0.0, sim.initial_state(),
                          sim.integrator_options());
    cvode.advance_to(300.0 * units::kYr);
    const std::vector<double> y(cvode.state().begin(), cvode.state().end());
    const auto st = cvode.stats();
    const auto* d = sim.distribution();
    const int i = 5, k = d->dominant_bin(i, y);
    std::printf(
        "%s, 300 yr: %ld steps, %ld Newton iterations, %ld convergence failures, %ld "
        "Jacobians; budget error %.1e; cell %d: bin %d (m = %.2e g), phi = %.2e\n",
        bins, st.nst, st.nni, st.nncf, st.nje, sim.budget_error(y), i, k,
        d->mass_grid().m[k], d->phi(i, k, y));
    EXPECT_LT(sim.budget_error(y), 1e-10) << bins;
    EXPECT_LT(st.nncf, st.nst / 4) << bins;
    EXPECT_LT(d->phi(i, k, y), 0.5) << bins;
  }
}

}  // namespace
}  // namespace panoptic
