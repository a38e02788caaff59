// Which state variables CVODE's error test sees (VarInfo::error_test): the planetesimal
// surface densities, booked quantities that no right-hand side reads back, are left out
// of it, as CVODES does with quadratures. The premise is checked on the right-hand side
// itself: changing such a variable changes no component of the RHS, bit for bit. The
// booked global masses (through r_in, sublimated, pebble monitors) stay in it (their
// error holds the step where Newton converges at the inner edge; dust_transport.cpp).
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/disk_model.hpp"
#include "src/solver/state_layout.hpp"
#include "tests/unit/support/evolved_state.hpp"

namespace panoptic {
namespace {

// The fiducial scene, with static and with evolving (viscous) gas.
void check_booked_out_of_error_test(bool gas_evolves) {
  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> sets{
      "grid.n_cells=40", "solver.atol_sigma=1e-11",
      gas_evolves ? "gas.evolve=true" : "gas.evolve=false"};
  Simulation sim(load_scene(file, sets));
  std::vector<double> y = evolved_state(sim, 300.0);  // growing, compacting, converting
  const auto& L = sim.model().layout();
  const auto opt = sim.integrator_options();

  const std::set<std::string> booked_cell{"sigma_pl_coag", "sigma_pl_si"};
  std::vector<double> f0(y.size()), f1(y.size());
  sim.model().rhs(0.0, y, f0);
  int out_of_test = 0, globals_out = 0;
  for (long i = 0; i < L.size(); ++i) {
    const VarInfo& v = L.info_of(i);
    const bool booked = booked_cell.count(v.name) > 0;
    EXPECT_EQ(v.error_test, !booked) << L.describe(i);
    if (v.error_test) {
      EXPECT_DOUBLE_EQ(opt.atol[i], 1e-11 * v.abs_scale) << L.describe(i);
      continue;
    }
    ++out_of_test;
    // no positivity constraint: CVODE would clip it to zero at any size (no weight)
    EXPECT_FALSE(v.nonnegative) << L.describe(i);
    EXPECT_EQ(opt.constraints[i], 0.0) << L.describe(i);
    if (L.cell_of(i) < 0) ++globals_out;
    EXPECT_GE(opt.atol[i], 1e20 * 1e-11 * v.abs_scale) << L.describe(i);
    // nothing reads it back: the whole RHS is unchanged, bit for bit
    const double saved = y[i];
    y[i] = 3.0 * saved + 1e-3 * v.abs_scale;
    sim.model().rhs(0.0, y, f1);
    y[i] = saved;
    for (long k = 0; k < L.size(); ++k)
      ASSERT_EQ(f1[k], f0[k]) << "d(" << L.describe(k) << ")/dt reads " << L.describe(i);
  }
  // both planetesimal channels in every cell; no global variable
  EXPECT_EQ(out_of_test, 2 * L.n_cells());
  EXPECT_EQ(globals_out, 0);
  EXPECT_GE(L.n_global_vars(), gas_evolves ? 4 : 3);  // r_in, sublimated, monitor (gas)
}

// The layout refuses a variable that is out of the error test and constrained >= 0.
TEST(ErrorWeights, LayoutRefusesAConstrainedVariableOutOfTheErrorTest) {
  StateLayout layout(4);
  EXPECT_THROW(layout.add_cell_var({"booked", "g cm^-2", "", 1.0, true, false}),
               std::logic_error);
  EXPECT_THROW(layout.add_global_var({"booked", "g", "", 1.0, true, false}),
               std::logic_error);
  EXPECT_NO_THROW(layout.add_cell_var({"booked", "g cm^-2", "", 1.0, false, false}));
  EXPECT_NO_THROW(layout.add_cell_var({"sigma", "g cm^-2", "", 1.0, true, true}));
}

TEST(ErrorWeights, PlanetesimalColumnsAreOutOfTheErrorTestAndReadByNoRhs) {
  check_booked_out_of_error_test(false);
  check_booked_out_of_error_test(true);
}

}  // namespace
}  // namespace panoptic
