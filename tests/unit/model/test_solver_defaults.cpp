// The solver keys whose default 0 the model kind resolves: solver.newton_coef is 0.03
// for the single-size model and 0.05 for a size distribution, compact or porous
// (keys_run.cpp; tests/bench/results/porous_newton.md), and a value given in the scene
// is kept.
#include <gtest/gtest.h>

#include <string>
#include <vector>

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
  EXPECT_EQ(newton_coef("tests/distribution_small.toml", {"porosity.enabled=true"}),
            0.05);
  EXPECT_EQ(newton_coef("tests/distribution_small.toml", {"solver.newton_coef=0.03"}),
            0.03);
  EXPECT_EQ(newton_coef("fiducial.toml", {"solver.newton_coef=0.1"}), 0.1);
}

}  // namespace
}  // namespace panoptic
