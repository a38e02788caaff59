// Erosion by small projectiles (Krijt et al. 2015; spec §5.1, §15.2) in the
// size-distribution mode on the grid: either erosion.model selects the rule on the pairs
// of bins, and the run says so; eps_eros at or above the mass ratio is refused; the
// Jacobian with erosion against finite differences; a run keeps its budget, and erosion
// below the fragmentation speed leaves more mass in the small bins than DustPy's
// cratering alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/modules/size_distribution.hpp"
#include "src/model/scene_validation.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "tests/unit/support/config_error.hpp"
#include "tests/unit/support/evolved_state.hpp"
#include "tests/unit/support/jacobian_check.hpp"

namespace panoptic {
namespace {

// The small distribution scene (fragmentation and cratering at 1 m/s) with erosion at
// 0.3 m/s.
Config eroding_scene(std::vector<std::string> sets = {}) {
  for (const char* s : {"erosion.model=\"halt\"", "erosion.v_eros_m_s=0.3"})
    sets.insert(sets.begin(), s);
  return load_scene(
      std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml", sets);
}

TEST(SizeDistributionErosion, EitherModelIsTheRuleOnPairsAndTheRunSaysSo) {
  for (const char* model : {"\"halt\"", "\"balance\""}) {
    const Config cfg = eroding_scene({std::string("erosion.model=") + model});
    EXPECT_NO_THROW(validate_scene(cfg)) << model;
    const std::string summary = Simulation(cfg).summary();
    EXPECT_NE(summary.find("Krijt et al. (2015) rule on the pairs of bins"),
              std::string::npos)
        << summary;
    EXPECT_NE(summary.find(std::string("erosion.model = ") + model), std::string::npos);
  }
  const std::string msg = config_error_message(
      [] { validate_scene(eroding_scene({"erosion.eps_eros=10.0"})); }, "eps_eros = 10");
  EXPECT_NE(msg.find("erosion.eps_eros"), std::string::npos) << msg;
  EXPECT_NE(msg.find("must be < 10"), std::string::npos) << msg;
}

// Coagulation with erosion (unequal pairs) and fragmentation (the others), drift,
// diffusion and the viscous gas, on states perturbed by +-30 % per component.
TEST(SizeDistributionErosion, JacobianMatchesFiniteDifferences) {
  Simulation sim(eroding_scene());
  const auto& L = sim.model().layout();
  const auto c = testing::compare_with_fd(sim, testing::perturbed_state(sim, 3));
  std::printf("erosion: row-scaled error %.2e, entry error %.2e\n", c.max_rel_err,
              c.max_entry_err);
  EXPECT_LT(c.max_rel_err, 1e-7) << "worst d(" << L.describe(c.worst_row) << ")/d("
                                 << L.describe(c.worst_col) << ")";
  EXPECT_LT(c.max_entry_err, 1e-4);
  EXPECT_EQ(c.outside_pattern, 0);
}

// Mass in the bins below 1e-8 g of every cell, summed [g cm^-2].
double small_bin_mass(const Simulation& sim, const std::vector<double>& y) {
  const auto* d = sim.distribution();
  const auto& L = sim.model().layout();
  double sum = 0.0;
  for (int i = 0; i < sim.grid().n_cells(); ++i)
    for (int k = 0; k < d->n_bins() && d->mass_grid().m[k] < 1e-8; ++k)
      sum += y[L.index(i, d->bin_slot(k))];
  return sum;
}

TEST(SizeDistributionErosion, RunKeepsTheBudgetAndErodesBelowVfrag) {
  Simulation eroding(eroding_scene());
  Simulation dustpy(eroding_scene({"erosion.model=\"none\""}));
  const auto ye = evolved_state(eroding, 3000.0), yd = evolved_state(dustpy, 3000.0);
  const double small_e = small_bin_mass(eroding, ye),
               small_d = small_bin_mass(dustpy, yd);
  std::printf(
      "3000 yr: budget error %.1e; mass below 1e-8 g: %.3e (erosion at 0.3 m/s) "
      "vs %.3e (DustPy's cratering at 1 m/s)\n",
      eroding.budget_error(ye), small_e, small_d);
  EXPECT_LT(eroding.budget_error(ye), 1e-10);
  EXPECT_GT(small_e, 1.1 * small_d);
}

}  // namespace
}  // namespace panoptic
