// Sublimation at the snow line (spec §1.7, §6.3, §11 #18): dust drifting inward through
// the snow-line face loses the ice fraction f_ice of its mass. Each particle keeps its
// filling factor and its mass drops to (1 - f_ice) m, so the log-moment it carries,
// Q_m = Sigma ln(m/m_ref), arrives as keep Sigma (ln(m/m_ref) + ln keep) with
// keep = 1 - f_ice. Checked on the right-hand side of the whole model: two models that
// differ only in f_ice, at the same state, differ only in the cell just inside the snow
// line and in the sublimated mass, by amounts whose ratios follow from the rule above
// alone (the flow through the face cancels out of them).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "disk/gas_disk.hpp"
#include "physics/modules/dust_transport.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/disk_model.hpp"
#include "src/solver/grid.hpp"

namespace panoptic {
namespace {

Config snow_scene(double f_ice) {
  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  // r_in = 2 au: the largest initial Sigma_d (which sets the codec's and the tolerances'
  // scales) then lies just outside the snow line for both f_ice below, so the two models
  // differ in the sublimation alone
  const std::vector<std::string> sets{"grid.n_cells=40", "grid.r_in_au=2.0",
                                      "transport.diffusion=false",
                                      "snowline.f_ice=" + std::to_string(f_ice)};
  return load_scene(file, sets);
}

TEST(SnowLineTransport, InflowLosesTheIceFractionOfItsMassAndOfEachParticle) {
  const double f_ice = 0.5, f_ref = 0.4;
  Simulation sim(snow_scene(f_ice)), ref(snow_scene(f_ref));
  const auto& L = sim.model().layout();
  ASSERT_EQ(L.size(), ref.model().layout().size());
  const auto sd = L.find_cell_var("sigma_d"), qm = L.find_cell_var("q_m");
  ASSERT_TRUE(sd && qm);
  const int sub = sim.transport().sublimated_slot();  // the booked m_sublimated
  ASSERT_GE(sub, 0);

  // Grown particles everywhere: ln(m/m_ref) = ln_m in every cell (m = 1e-10 g: the dust
  // drifts inward through the snow-line face).
  std::vector<double> y = sim.initial_state();
  const double ln_m = std::log(1e-10 / 5.86e-15);
  for (int i = 0; i < L.n_cells(); ++i) y[L.index(i, *qm)] = y[L.index(i, *sd)] * ln_m;

  std::vector<double> f(y.size()), g(y.size());
  sim.model().rhs(0.0, y, f);
  ref.model().rhs(0.0, y, g);

  // the cell just inside the snow line
  const double r_snow = sim.disk().r_snow();
  int inner = -1;
  for (int i = 0; i + 1 <= L.n_cells(); ++i)
    if (sim.grid().r_f(i) < r_snow && r_snow <= sim.grid().r_f(i + 1)) inner = i;
  ASSERT_GT(inner, 0);
  // The snow face is the face nearest r_snow: one of the two faces of `inner`.
  int differing = -1, n_differing = 0;
  for (int i = 0; i < L.n_cells(); ++i)
    if (f[L.index(i, *sd)] != g[L.index(i, *sd)]) {
      differing = i;
      ++n_differing;
    }
  ASSERT_EQ(n_differing, 1);
  EXPECT_TRUE(differing == inner || differing == inner - 1) << differing << " " << inner;

  const double keep = 1.0 - f_ice, keep_ref = 1.0 - f_ref;
  // Delta dSigma/dt = (keep - keep_ref) F, Delta dQ/dt = [keep (ln_m + ln keep) -
  // keep_ref (ln_m + ln keep_ref)] F, with F the inward flow per area (< 0 here).
  const double d_sigma = f[L.index(differing, *sd)] - g[L.index(differing, *sd)];
  const double d_q = f[L.index(differing, *qm)] - g[L.index(differing, *qm)];
  const double flow = d_sigma / (keep - keep_ref);
  EXPECT_GT(flow, 0.0);  // dust arrives: the inner cell gains less with more ice lost
  const double expect_q =
      (keep * (ln_m + std::log(keep)) - keep_ref * (ln_m + std::log(keep_ref))) * flow;
  EXPECT_NEAR(d_q / expect_q, 1.0, 1e-9) << d_q << " vs " << expect_q;
  // the particle arriving is keep m: without the ln keep terms (0.5 ln 0.5 - 0.6 ln 0.6
  // = -0.040 against (0.5 - 0.6) ln_m = -0.975) the difference would be 4 % smaller
  const double without_log = (keep - keep_ref) * ln_m * flow;
  EXPECT_GT(std::abs(d_q / without_log - 1.0), 0.03);
  // every other cell and every Q_m elsewhere unchanged
  for (int i = 0; i < L.n_cells(); ++i)
    if (i != differing) {
      EXPECT_EQ(f[L.index(i, *qm)], g[L.index(i, *qm)]) << i;
    }
  // the sublimated mass grows at f_ice of the flow: in grams (the variable is in units of
  // each model's initial dust mass, which depends on f_ice) its rate over that of the
  // reference is f_ice / f_ref (the flow itself is the same)
  const double s = f[L.global_index(sub)] * sim.transport().mass_unit(),
               s_ref = g[L.global_index(sub)] * ref.transport().mass_unit();
  EXPECT_NE(sim.transport().mass_unit(), ref.transport().mass_unit());
  EXPECT_GT(s, 0.0);
  EXPECT_NEAR(s / s_ref, f_ice / f_ref, 1e-6 * f_ice / f_ref);
}

}  // namespace
}  // namespace panoptic
