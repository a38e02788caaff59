// The critical metallicity of the zcrit streaming-instability option (spec §7.2,
// physics/planetesimals.hpp) against numbers worked out by hand from
// log10 Z_crit = 0.10 x^2 + 0.07 x - 2.36, x = log10 St (Lim et al. 2025 eq. 15).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "disk/gas_disk.hpp"
#include "physics/planetesimals.hpp"
#include "src/config.hpp"
#include "src/simulation.hpp"
#include "src/units.hpp"

using panoptic::zcrit_lim25;

TEST(Planetesimals, ZcritAtHandWorkedStokesNumbers) {
  EXPECT_NEAR(zcrit_lim25(0.01), 7.9433e-3, 1e-7);  // x = -2: -2.10
  EXPECT_NEAR(zcrit_lim25(0.1), 4.6774e-3, 1e-7);   // x = -1: -2.33
  EXPECT_NEAR(zcrit_lim25(1.0), 4.3652e-3, 1e-7);   // x = 0: -2.36
  EXPECT_NEAR(zcrit_lim25(0.3), 4.2731e-3, 1e-7);   // x = -0.52288: -2.36929
}

TEST(Planetesimals, ZcritMinimumIsLiYoudinsOptimum) {
  // the parabola's vertex, x = -0.07/0.2 = -0.35 (St = 0.447): 10^-2.37225 = 0.42438%,
  // Li & Youdin 2021's "as low as 0.4% for the optimum particle sizes"
  const double st_opt = std::pow(10.0, -0.35);
  EXPECT_NEAR(zcrit_lim25(st_opt), 4.2438e-3, 1e-7);
  for (double f : {0.9, 1.1}) EXPECT_GT(zcrit_lim25(st_opt * f), zcrit_lim25(st_opt));
}

// The s18 channel (spec §7.2; Schoonenberg, Ormel & Krijt 2018): Sdot = zeta Sigma_d St
// Omega where the midplane rho_d/rho_g >= eps_crit, switched by a logistic in ln(rho_d/
// rho_g) of half-width width_dex. Checked on the grid against the formula written out
// here from spec §1.3 (Omega, c_s, H, rho_g of the MMSN) and §2 (h_d of Youdin &
// Lithwick 2007), with particles grown to St ~ 0.1 and Sigma_d = 0.5 Sigma_g, where the
// trigger is nearly saturated; only St is taken from the code (its drag law has its own
// tests).
TEST(Planetesimals, S18RateIsZetaSigmaStOmegaTimesTheTrigger) {
  using namespace panoptic;
  const std::vector<std::string> sets{"grid.n_cells=12",
                                      "grid.r_in_au=4.0",
                                      "grid.r_out_au=6.0",
                                      "snowline.enabled=false",
                                      "dust.dust_to_gas=0.5",
                                      "planetesimals.si=\"s18\"",
                                      "planetesimals.coagulation=false"};
  Simulation sim(
      load_scene(std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml", sets));
  const auto& L = sim.model().layout();
  auto y = sim.initial_state();
  const int sd = *L.find_cell_var("sigma_d"), qm = *L.find_cell_var("q_m");
  for (int i = 0; i < L.n_cells(); ++i)  // m = 1e4 g, compact enough: St ~ 0.01-1
    y[L.index(i, qm)] = y[L.index(i, sd)] * std::log(1e4 / 5.9e-15);
  const auto st = sim.snapshot_fields(y).at("St");
  const double zeta = 0.1, eps_crit = 1.0, alpha = 1e-3, width_dex = 0.1;  // defaults
  int checked = 0;
  for (int i = 0; i < L.n_cells(); ++i) {
    const double r = sim.grid().r_c(i);
    const double omega = std::sqrt(units::kG * units::kMsun / (r * r * r));
    const double c_s =
        std::sqrt(units::kBoltzmann * sim.disk().temperature(r) / (2.34 * units::kMassH));
    const double h_g = c_s / omega;
    const double sigma_g = sim.disk().sigma_g(r), sigma_d = y[L.index(i, sd)];
    const double s = st[i];
    const double h_d = h_g / std::sqrt(1.0 + s / alpha * (1.0 + 2.0 * s) / (1.0 + s));
    const double eps_mid = (sigma_d / h_d) / (sigma_g / h_g);  // the sqrt(2 pi) cancel
    const double k = std::log(19.0) / (width_dex * std::log(10.0));
    const double trigger = 1.0 / (1.0 + std::pow(eps_crit / eps_mid, k));
    const double expected = zeta * sigma_d * s * omega * trigger;
    const double si = sim.planetesimals()->rates(i, y).second;
    EXPECT_NEAR(si / expected, 1.0, 1e-9)
        << "cell " << i << ", St " << s << ", eps_mid " << eps_mid;
    if (trigger > 0.5) ++checked;
  }
  EXPECT_GT(checked, 0) << "no cell where the channel is on: the check saw nothing";
}
