// The size-distribution mode on the grid (spec §15; physics/modules/size_distribution.*):
// its Jacobian against finite differences on the whole grid, the mass budget (rates and
// a run), one bin without coagulation against the single-size transport of the same St,
// the mass-weighted mean mass beside the mass-dominating bin, and the scene combinations
// it refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/modules/dust_transport.hpp"
#include "physics/modules/size_distribution.hpp"
#include "src/core/units.hpp"
#include "src/model/scene_validation.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "tests/unit/support/config_error.hpp"
#include "tests/unit/support/evolved_state.hpp"
#include "tests/unit/support/jacobian_check.hpp"

namespace panoptic {
namespace {

const std::string kSmall =
    std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml";

Config small_scene(const std::vector<std::string>& sets = {}) {
  return load_scene(kSmall, sets);
}

void expect_jacobian_exact(const std::vector<std::string>& sets, const char* label) {
  Simulation sim(small_scene(sets));
  const auto& L = sim.model().layout();
  for (unsigned seed : {1u, 2u}) {
    const auto c = testing::compare_with_fd(sim, testing::perturbed_state(sim, seed));
    std::printf(
        "%s, seed %u: row-scaled error %.2e, entry error %.2e, %ld FD non-zeros\n", label,
        seed, c.max_rel_err, c.max_entry_err, c.nnz_fd);
    EXPECT_LT(c.max_rel_err, 1e-7) << label << ": worst d(" << L.describe(c.worst_row)
                                   << ")/d(" << L.describe(c.worst_col) << "): analytic "
                                   << c.worst_analytic << ", FD " << c.worst_fd;
    EXPECT_LT(c.max_entry_err, 1e-4) << label << ": d(" << L.describe(c.entry_row)
                                     << ")/d(" << L.describe(c.entry_col) << ")";
    EXPECT_EQ(c.outside_pattern, 0) << label;
    // the dense coagulation blocks are there (12 cells x 50 x 50 in all)
    EXPECT_GT(c.nnz_fd, 12 * 50 * 40) << label;
  }
}

// Coagulation (sticking, fragmentation, cratering), drift, diffusion and the viscous gas
// at once, on states perturbed by +-30 % per component (every bin filled).
TEST(SizeDistribution, JacobianMatchesFiniteDifferences) {
  expect_jacobian_exact({}, "distribution, evolving gas");
}

// Porosity on the track (porosity.bins = "track", with the snow line): the bins' St and
// coefficients are the track's, constants of the state as the compact ones, so the
// Jacobian stays exact.
TEST(SizeDistribution, JacobianMatchesFiniteDifferencesOnTheTrack) {
  expect_jacobian_exact(
      {"porosity.enabled=true", "porosity.bins=\"track\"", "snowline.enabled=true"},
      "distribution, porosity on the track, snow line");
}

// The limited advection's far upwind cell, per bin.
TEST(SizeDistribution, JacobianMatchesFiniteDifferencesVanLeer) {
  expect_jacobian_exact({"transport.advection=\"van_leer\"", "gas.evolve=false"},
                        "distribution, van Leer, static gas");
}

// A size distribution grown from monomers holds bins of 1e-250 g cm^-2 and less, down to
// 5e-324 (the porous MMSN at 7 per decade, van Leer, after 0.5 yr: 393 of 3 980). The
// limiter's slopes there differ by as little, and a derivative taken through 1/(a + b)
// overflows: that run stopped at 0.004 yr on a NaN Jacobian entry. Every entry must stay
// finite.
TEST(SizeDistribution, VanLeerJacobianStaysFiniteOnNearlyEmptyBins) {
  for (const char* porous : {"porosity.enabled=false", "porosity.enabled=true"}) {
    Simulation sim(
        small_scene({"transport.advection=\"van_leer\"", "gas.evolve=false", porous}));
    const auto* d = sim.distribution();
    const auto& L = sim.model().layout();
    auto y = testing::perturbed_state(sim, 1);
    for (int i = 0; i < sim.grid().n_cells(); ++i)
      for (int j = 0; j < d->cell_vars(); ++j)
        if (j % d->n_bins() >= d->n_bins() / 2)
          y[L.index(i, d->bin_slot(0) + j)] *= 1e-310;
    std::vector<double> values(sim.model().pattern().nnz());
    sim.model().jacobian(0.0, y, values);
    long bad = 0, first = -1;
    for (long p = 0; p < static_cast<long>(values.size()); ++p)
      if (!std::isfinite(values[p]) && bad++ == 0) first = p;
    EXPECT_EQ(bad, 0) << porous << ": first at position " << first;
  }
}

// The snow face's flows into the inner cell's bins and m_sublimated, with the silicate
// species inside (spec §6.3, §15.4).
TEST(SizeDistribution, JacobianMatchesFiniteDifferencesSnowLine) {
  expect_jacobian_exact({"snowline.enabled=true"}, "distribution, snow line");
  expect_jacobian_exact({"snowline.enabled=true", "transport.advection=\"van_leer\""},
                        "distribution, snow line, van Leer");
}

// The budget terms' rates cancel (coagulation moves mass between bins only; the transport
// books what leaves through r_in), and a run keeps the budget to round-off.
TEST(SizeDistribution, MassBudgetCloses) {
  Simulation sim(small_scene());
  const std::vector<double> y = evolved_state(sim, 3000.0);
  std::vector<double> ydot(y.size());
  sim.model().rhs(3000.0 * units::kYr, y, ydot);
  const auto rates = sim.budget_masses(ydot);  // linear terms: d(mass)/dt = mass(ydot)
  double sum = 0.0, scale = 0.0, out = 0.0;
  for (std::size_t k = 0; k < rates.size(); ++k) {
    sum += rates[k];
    scale += std::abs(rates[k]);
    if (sim.budget_terms()[k].name == "m_out_inner") out = rates[k];
  }
  std::printf(
      "|sum of the rates| / sum of |rates| = %.1e; budget error after 3000 yr %.1e\n",
      std::abs(sum) / scale, sim.budget_error(y));
  EXPECT_GT(out, 1e3 * 1e-12 * scale) << "no dust leaves: the check would not see it";
  EXPECT_LT(std::abs(sum), 1e-12 * scale);
  EXPECT_LT(sim.budget_error(y), 1e-10);
  // coagulation moved the mass up the grid: the mass-dominating bin is no longer MRN's
  const auto* dist = sim.distribution();
  ASSERT_NE(dist, nullptr);
  EXPECT_GT(dist->dominant_bin(0, y), 10);
}

// One bin without coagulation is the single-size transport of the same St: the same flux
// operator, boundaries and booking. A power-law gas disk with Epstein drag gives the bin
// St ∝ Sigma_g^-1 ∝ r^p, which the single-size scene prescribes as transport.St and
// St_slope. `sets` go to both scenes; with the snow line the budgets' m_sublimated are
// compared too.
void expect_one_bin_is_single_size(const std::vector<std::string>& sets) {
  std::vector<std::string> common{"disk.model=\"powerlaw\"", "disk.p=1.0",
                                  "gas.evolve=false", "growth.enabled=false",
                                  "fragmentation.enabled=false"};
  common.insert(common.end(), sets.begin(), sets.end());
  std::vector<std::string> dist_sets = common;
  for (const char* s : {"growth.drag_law=\"epstein\"", "model.init=\"monomers\"",
                        "model.m_min_g=100.0", "model.m_max_g=1000.0"})
    dist_sets.push_back(s);
  Simulation dist(small_scene(dist_sets));
  const auto y_dist0 = dist.initial_state();
  const double st0 = dist.distribution()->dominant_st(y_dist0)[0];
  const double r0_au = dist.grid().r_c(0) / units::kAu;
  char st_set[64];
  std::snprintf(st_set, sizeof st_set, "transport.St=%.17g", st0 / r0_au);
  std::vector<std::string> single_sets = common;
  for (const char* s : {"model.kind=\"single_size\"", "transport.St_slope=1.0"})
    single_sets.push_back(s);
  single_sets.push_back(st_set);
  Simulation single(small_scene(single_sets));
  ASSERT_GT(st0, 1e-3);  // drift matters

  const auto& Ld = dist.model().layout();
  const auto& Ls = single.model().layout();
  const int n = dist.grid().n_cells(), bin0 = dist.distribution()->bin_slot(0);
  const int sd = single.transport().sigma_slot();
  std::vector<double> fd(y_dist0.size()), fs(Ls.size());
  dist.model().rhs(0.0, y_dist0, fd);
  single.model().rhs(0.0, single.initial_state(), fs);
  double scale = 0.0, diff = 0.0;
  for (int i = 0; i < n; ++i) {
    scale = std::max(scale, std::abs(fs[Ls.index(i, sd)]));
    diff = std::max(diff, std::abs(fd[Ld.index(i, bin0)] - fs[Ls.index(i, sd)]));
  }
  std::printf("d sigma/dt: max |distribution - single size| / max |single| = %.1e\n",
              diff / scale);
  EXPECT_LT(diff, 1e-12 * scale);
  // the booked masses, in grams per second (each run's unit is its initial dust mass)
  const auto rates_d = dist.budget_masses(fd), rates_s = single.budget_masses(fs);
  ASSERT_EQ(rates_d.size(), rates_s.size());
  for (std::size_t t = 0; t < rates_d.size(); ++t)
    if (dist.budget_terms()[t].name != "m_dust") {
      EXPECT_NEAR(rates_d[t], rates_s[t], 1e-12 * std::abs(rates_s[t]))
          << dist.budget_terms()[t].name;
    }

  // and integrated: 3 000 yr, the profiles and the mass through r_in
  const auto yd = evolved_state(dist, 3000.0), ys = evolved_state(single, 3000.0);
  double worst = 0.0, peak = 0.0;
  for (int i = 0; i < n; ++i) {
    peak = std::max(peak, ys[Ls.index(i, sd)]);
    worst = std::max(worst, std::abs(yd[Ld.index(i, bin0)] - ys[Ls.index(i, sd)]));
  }
  const double out_d = dist.distribution()->mass_out(yd);
  const double out_s = single.transport().mass_out(ys);
  std::printf("after 3000 yr: max |Delta sigma| / max sigma = %.1e, m_out %.6e vs %.6e\n",
              worst / peak, out_d, out_s);
  EXPECT_LT(worst, 1e-5 * peak);
  EXPECT_GT(out_s, 0.0);
  EXPECT_NEAR(out_d / out_s, 1.0, 1e-5);
  const double sub_d = dist.distribution()->mass_sublimated(yd);
  const double sub_s = single.transport().mass_sublimated(ys);
  std::printf("m_sublimated %.6e vs %.6e\n", sub_d, sub_s);
  EXPECT_NEAR(sub_d, sub_s, 1e-5 * std::abs(sub_s));
}

TEST(SizeDistribution, OneBinWithoutGrowthIsTheSingleSizeTransport) {
  expect_one_bin_is_single_size({});
}

// The same at the snow line (spec §6.3): the ice of the one bin sublimates as the
// single-size model's Sigma_d does. The bin's mass 100 g lies at the bottom of the grid,
// so its (1 - f_ice) m stays in it (MassGrid::split_mass): one bin still. The silicates
// take the ice's density so that the bin's St is the prescribed power law across it.
TEST(SizeDistribution, OneBinAtTheSnowLineIsTheSingleSizeTransport) {
  expect_one_bin_is_single_size({"snowline.enabled=true", "material.sil_rho0=1.67"});
}

// A bulk and a tail (tests/bench/results/porous_mmsn.md, "Why the distribution grows
// unlike the single size"): the snapshots' m is the bin holding the most mass, m_mean
// the mass-weighted mean sum sigma_k m_k / sum sigma_k.
TEST(SizeDistribution, MeanMassIsTheMassWeightedMeanOfTheBins) {
  const Simulation sim(small_scene());
  const auto* d = sim.distribution();
  const auto& L = sim.model().layout();
  const std::vector<double>& m = d->engine().grid().m;
  const int bulk = 10, tail = 40, cell = 3;
  auto y = sim.initial_state();
  for (int i = 0; i < sim.grid().n_cells(); ++i)
    for (int j = 0; j < d->cell_vars(); ++j) y[L.index(i, d->bin_slot(0) + j)] = 0.0;
  y[L.index(cell, d->bin_slot(bulk))] = 0.7;
  y[L.index(cell, d->bin_slot(tail))] = 0.2;
  const OutputField* mean = nullptr;
  const OutputField* dominant = nullptr;
  const auto fields = d->output_fields();
  for (const OutputField& f : fields) {
    if (f.name == "m_mean") mean = &f;
    if (f.name == "m") dominant = &f;
  }
  ASSERT_NE(mean, nullptr);
  ASSERT_NE(dominant, nullptr);
  EXPECT_EQ(mean->units, "g");
  const std::vector<double> got = mean->fill(y);
  ASSERT_EQ(got.size(), static_cast<std::size_t>(sim.grid().n_cells()));
  const double want = (0.7 * m[bulk] + 0.2 * m[tail]) / 0.9;
  EXPECT_NEAR(got[cell], want, 1e-14 * want);
  EXPECT_GT(got[cell], 1e7 * m[bulk]);  // the tail's moment, far above the bulk's bin
  EXPECT_EQ(dominant->fill(y)[cell], m[bulk]);
  EXPECT_EQ(got[cell + 1], 0.0);  // a cell without dust
}

TEST(SizeDistribution, RefusesWhatItDoesNotCarryYet) {
  EXPECT_NO_THROW(validate_scene(small_scene({"snowline.enabled=true"})));
  for (const auto& [set, key] : std::vector<std::pair<std::string, std::string>>{
           {"bouncing.enabled=true", "bouncing.enabled"}}) {
    const std::string msg =
        config_error_message([&] { validate_scene(small_scene({set})); }, set);
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
    EXPECT_NE(msg.find("not supported with model.kind = \"distribution\" yet"),
              std::string::npos)
        << msg;
  }
  const std::string msg = config_error_message(
      [] { validate_scene(small_scene({"model.m_min_g=1e3"})); }, "m_min_g > m_max_g");
  EXPECT_NE(msg.find("model.m_min_g"), std::string::npos) << msg;
}

}  // namespace
}  // namespace panoptic
