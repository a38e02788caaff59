// The solver keys whose default 0 the model kind resolves: solver.newton_coef is 0.03
// for the single-size model, 0.05 for a compact size distribution and 0.1 for a porous
// one (keys_run.cpp; tests/bench/results/porous_newton.md); solver.atol_sigma is 1e-10
// for a porous distribution and 1e-8 otherwise (scene_to_physics.cpp;
// tests/bench/results/porous_cost.md). A value given in the scene is kept.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "physics/modules/size_distribution.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"

namespace panoptic {
namespace {

double newton_coef(const std::string& scene, const std::vector<std::string>& sets) {
  const std::string dir = std::string(PANOPTIC_SOURCE_DIR) + "/params/";
  return Simulation(load_scene(dir + scene, sets)).integrator_options().newton_coef;
}

TEST(SolverDefaults, NewtonCoefficientByModelKind) {
  EXPECT_EQ(load_scene(std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml", {})
                .real("solver.newton_coef"),
            0.0);
  EXPECT_EQ(newton_coef("fiducial.toml", {}), 0.03);
  EXPECT_EQ(newton_coef("tests/distribution_small.toml", {}), 0.05);
  EXPECT_EQ(newton_coef("tests/distribution_small.toml", {"porosity.enabled=true"}), 0.1);
  EXPECT_EQ(newton_coef("tests/distribution_small.toml", {"solver.newton_coef=0.03"}),
            0.03);
  EXPECT_EQ(newton_coef("fiducial.toml", {"solver.newton_coef=0.1"}), 0.1);
}

// CVODE's absolute tolerance of the first dust variable of cell 0 (sigma_d, or bin 0 of
// a distribution) in units of its scale.
double atol_sigma(const std::string& scene, const std::vector<std::string>& sets) {
  const std::string dir = std::string(PANOPTIC_SOURCE_DIR) + "/params/";
  Simulation sim(load_scene(dir + scene, sets));
  const auto& L = sim.model().layout();
  const auto* d = sim.distribution();
  const int slot = d != nullptr ? d->bin_slot(0) : *L.find_cell_var("sigma_d");
  return sim.integrator_options().atol[L.index(0, slot)] / L.cell_var(slot).abs_scale;
}

TEST(SolverDefaults, AbsoluteToleranceByModel) {
  EXPECT_EQ(load_scene(std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml", {})
                .real("solver.atol_sigma"),
            0.0);
  const std::string small = "tests/distribution_small.toml";
  EXPECT_NEAR(atol_sigma("fiducial.toml", {}), 1e-8, 1e-20);
  EXPECT_NEAR(atol_sigma(small, {}), 1e-8, 1e-20);
  EXPECT_NEAR(atol_sigma(small, {"porosity.enabled=true"}), 1e-10, 1e-22);
  EXPECT_NEAR(atol_sigma(small, {"porosity.enabled=true", "solver.atol_sigma=1e-8"}),
              1e-8, 1e-20);
  EXPECT_NEAR(atol_sigma("fiducial.toml", {"solver.atol_sigma=1e-9"}), 1e-9, 1e-21);
}

}  // namespace
}  // namespace panoptic
