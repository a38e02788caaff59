// solver.method = "implicit_euler" in a scene: refused for the single-size model with
// the key, value, constraint and fix; the keys that only one integrator reads warned
// about under the other; DustPy's step floors (0.1 m_k / A_i for every bin, 1e-100 for
// Sigma_g, the rest out of the rule); and the small distribution scene stepped by it
// with its mass budget closed to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "physics/modules/size_distribution.hpp"
#include "src/core/units.hpp"
#include "src/model/scene_validation.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/implicit_euler_integrator.hpp"
#include "tests/unit/support/config_error.hpp"

namespace panoptic {
namespace {

const std::string kEuler = "solver.method=\"implicit_euler\"";

Config scene(const std::string& file, std::vector<std::string> sets) {
  return load_scene(std::string(PANOPTIC_SOURCE_DIR) + "/params/" + file, sets);
}

bool any_mentions(const std::vector<std::string>& lines, const std::string& what) {
  for (const std::string& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

TEST(ImplicitEulerScene, RefusedForTheSingleSizeModel) {
  const std::string msg = config_error_message(
      [] { validate_scene(scene("fiducial.toml", {kEuler})); }, "single size");
  for (const char* part :
       {"solver.method", "\"implicit_euler\"", "needs model.kind = \"distribution\"",
        "\"single_size\"", "set solver.method = \"bdf\""})
    EXPECT_NE(msg.find(part), std::string::npos) << msg;
  EXPECT_NO_THROW(validate_scene(scene("tests/distribution_small.toml", {kEuler})));
}

TEST(ImplicitEulerScene, WarnsOfTheKeysTheOtherIntegratorReads) {
  const auto bdf =
      unused_key_warnings(scene("tests/distribution_small.toml", {"solver.cfl=0.2"}));
  EXPECT_TRUE(any_mentions(bdf, "solver.cfl")) << "cfl with bdf";
  const auto euler =
      unused_key_warnings(scene("tests/distribution_small.toml",
                                {kEuler, "solver.cfl=0.2", "solver.linear=\"gmres\""}));
  EXPECT_FALSE(any_mentions(euler, "solver.cfl"));
  EXPECT_TRUE(any_mentions(euler, "solver.linear")) << "linear with implicit_euler";
  const std::string msg = config_error_message(
      [] {
        scene("tests/distribution_small.toml", {kEuler, "solver.cfl=0"});
      },
      "cfl 0");
  EXPECT_NE(msg.find("solver.cfl"), std::string::npos) << msg;
}

TEST(ImplicitEulerScene, DustPysStepFloors) {
  Simulation sim(scene("tests/distribution_small.toml", {kEuler, "solver.cfl=0.05"}));
  const IntegratorOptions opt = sim.integrator_options();
  EXPECT_EQ(opt.method, IntegrationMethod::implicit_euler);
  EXPECT_EQ(opt.cfl, 0.05);
  const StateLayout& L = sim.model().layout();
  ASSERT_EQ(opt.step_floor.size(), static_cast<std::size_t>(L.size()));
  const SizeDistribution& d = *sim.distribution();
  const auto sigma_g = L.find_cell_var("sigma_g");
  ASSERT_TRUE(sigma_g.has_value());
  long in_rule = 0;
  for (int c = 0; c < L.n_cells(); ++c) {
    for (int k = 0; k < d.n_bins(); ++k)
      EXPECT_DOUBLE_EQ(opt.step_floor[L.index(c, d.bin_slot(k))],
                       0.1 * d.mass_grid().m[k] / sim.grid().area(c));
    EXPECT_EQ(opt.step_floor[L.index(c, *sigma_g)], 1e-100);
  }
  for (const double f : opt.step_floor) in_rule += std::isfinite(f) ? 1 : 0;
  EXPECT_EQ(in_rule, static_cast<long>(L.n_cells()) * (d.n_bins() + 1));
}

TEST(ImplicitEulerScene, SmallDistributionClosesItsBudget) {
  Simulation sim(scene("tests/distribution_small.toml", {kEuler}));
  const std::vector<double> y0 = sim.initial_state();
  ImplicitEulerIntegrator euler(sim.model(), 0.0, y0, sim.integrator_options());
  euler.advance_to(100.0 * units::kYr);
  EXPECT_GT(euler.stats().nst, 10);
  // measured 2e-16
  EXPECT_LT(sim.budget_error(euler.state()), 1e-13);
  EXPECT_LT(sim.dust_mass_on_grid(euler.state()), sim.initial_dust_mass());
}

}  // namespace
}  // namespace panoptic
