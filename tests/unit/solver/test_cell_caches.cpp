// The per-cell caches of the right-hand side are keyed by the cell's state values: the
// growth model's St cache (which also holds the decoded m and phi that the growth rates
// reuse, physics/modules/porous_growth.cpp) and the memo of the rates. A right-hand side
// at y evaluated after one at another state must equal, bit for bit, the right-hand side
// at y of a model that has never seen another state.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/disk_model.hpp"
#include "tests/unit/support/evolved_state.hpp"

namespace panoptic {
namespace {

TEST(CellCaches, RhsAfterAnotherStateEqualsAFreshModels) {
  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> sets{"grid.n_cells=40"};
  const Config cfg = load_scene(file, sets);
  Simulation evolving(cfg);
  const std::vector<double> y =
      evolved_state(evolving, 300.0);  // growing, converting cells
  // a new model: the caches of `evolving` hold the states CVODE visited
  Simulation never_used(cfg);
  std::vector<double> f_fresh(y.size());
  never_used.model().rhs(0.0, y, f_fresh);

  // another state: every cell's particle changes (Q_m and Q_phi scaled), Sigma_d too
  const auto& L = evolving.model().layout();
  std::vector<double> y2 = y;
  for (long i = 0; i < L.size(); ++i)
    if (L.cell_of(i) >= 0) y2[i] *= 1.01;
  Simulation used(cfg);
  std::vector<double> f(y.size()), f2(y.size());
  used.model().rhs(0.0, y2, f2);  // the caches first hold the other state
  used.model().rhs(0.0, y, f);
  long differing = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    EXPECT_EQ(f[k], f_fresh[k]) << L.describe(static_cast<long>(k));
    differing += f2[k] != f[k];
  }
  // the other state did change the right-hand side (the test would be empty otherwise)
  EXPECT_GT(differing, L.n_cells());
}

}  // namespace
}  // namespace panoptic
