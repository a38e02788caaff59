// The critical metallicity of the zcrit streaming-instability option (spec §7.2,
// physics/modules/planetesimals.hpp) against numbers worked out by hand from
// log10 Z_crit = 0.10 x^2 + 0.07 x - 2.36, x = log10 St (Lim et al. 2025 eq. 15).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "disk/gas_disk.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/modules/planetesimals.hpp"
#include "physics/planetesimal_criteria.hpp"
#include "physics/stokes_model.hpp"
#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/state_layout.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

using panoptic::physics::zcrit_lim25;

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
// Lithwick 2007), with particles grown to St ~ 0.13-0.22, and Sigma_d set in each cell so
// that rho_d/rho_g runs from 10^-0.15 to 10^+0.15 across the 12 cells: the trigger goes
// from 0.012 to 0.988 through its midpoint, so that a rate without it, or with another
// width or centre, fails. Taken from the code: St (its drag law has its own tests), and
// T(r), Sigma_g(r) and the constants of src/core/units.hpp (tested in test_disk.cpp).
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
  auto st = sim.snapshot_fields(y).at("St");
  const double zeta = 0.1, eps_crit = 1.0, alpha = 1e-3, width_dex = 0.1;  // defaults
  const double k = std::log(19.0) / (width_dex * std::log(10.0));
  const auto h_ratio = [&](int i) {  // h_g / h_d and Omega of cell i
    const double r = sim.grid().r_c(i);
    const double omega = std::sqrt(units::kG * units::kMsun / (r * r * r));
    const double s = st[i];
    return std::pair{std::sqrt(1.0 + s / alpha * (1.0 + 2.0 * s) / (1.0 + s)), omega};
  };
  // rescale each cell's dust (Sigma_d and its log-moments alike: m and phi unchanged)
  // to rho_d/rho_g = 10^(-0.15 + 0.3 i/11)
  for (int i = 0; i < L.n_cells(); ++i) {
    const double sigma_g = sim.disk().sigma_g(sim.grid().r_c(i));
    const double eps_now = y[L.index(i, sd)] / sigma_g * h_ratio(i).first;
    const double target = std::pow(10.0, -0.15 + 0.3 * i / (L.n_cells() - 1.0));
    for (int v = 0; v < L.n_cell_vars(); ++v) y[L.index(i, v)] *= target / eps_now;
  }
  // St again: the codec's floor on Sigma_d moves the decoded m by ~1e-11 relative
  st = sim.snapshot_fields(y).at("St");
  int on = 0, off = 0, between = 0;
  for (int i = 0; i < L.n_cells(); ++i) {
    const double r = sim.grid().r_c(i);
    const auto [h_over_hd, omega] = h_ratio(i);
    const double sigma_g = sim.disk().sigma_g(r), sigma_d = y[L.index(i, sd)];
    const double s = st[i];
    const double eps_mid = sigma_d / sigma_g * h_over_hd;  // the sqrt(2 pi) cancel
    const double trigger = 1.0 / (1.0 + std::pow(eps_crit / eps_mid, k));
    const double expected = zeta * sigma_d * s * omega * trigger;
    const double si = sim.planetesimals()->rates(i, y).second;
    EXPECT_NEAR(si / expected, 1.0, 1e-9)
        << "cell " << i << ", St " << s << ", eps_mid " << eps_mid;
    on += trigger > 0.9;
    off += trigger < 0.1;
    between += trigger > 0.2 && trigger < 0.8;
  }
  EXPECT_TRUE(on > 0 && off > 0 && between >= 3)
      << "the trigger must be seen on (" << on << " cells), off (" << off
      << ") and on its flank (" << between << ")";
}

// The direct-coagulation channel (spec §7.1) and the d16 trigger (spec §7.2; Drazkowska
// et al. 2016) of Planetesimals::cell_rates_with
// (physics/modules/planetesimals_cell_rates.hpp), on one cell at 5 au of the MMSN gas of
// spec §1 (tests/unit/support/mmsn_gas.hpp, written out from the spec formulas), with the
// Stokes number prescribed so that the switches can be put exactly at their midpoints.
// The smooth steps are logistic in ln x (spec §6.4): step(x; x0) = 1/(1 + (x0/x)^k), k =
// ln 19/(w ln 10), w = 0.1 dex: by hand, 1/2 at x = x0, 19/20 = 0.95 at x0 10^w, 1/20 at
// x0 10^-w, and 1/(1 + 19^-10) = 1 - 1.6e-13 at 10 x0 (1 dex = 10 w).
namespace panoptic {
namespace {

struct OneCell {
  physics::LocalGas gas = physics::mmsn_gas(5.0);
  GasColumn column;  // static gas
  std::vector<physics::Species> species;
  ParticleCodec codec;
  StateLayout layout{1};
  std::unique_ptr<CellGas> cell_gas;
  std::unique_ptr<PrescribedStokes> stokes;
  std::unique_ptr<Planetesimals> pl;
  physics::GrowthOptions growth;  // defaults: no erosion or fragmentation

  OneCell(double st, PlanetesimalOptions opt) {
    const auto c = physics::contact_properties(physics::ice_material());
    physics::Species sp;
    sp.a0 = physics::ice_material().a0;
    sp.rho0 = physics::ice_material().rho0;
    sp.m0 = c.m0;
    sp.e_roll = c.e_roll;
    species.push_back(sp);
    column.static_sigma = {gas.sigma_g};
    cell_gas = std::make_unique<CellGas>(std::vector<physics::LocalGas>{gas}, column);
    stokes = std::make_unique<PrescribedStokes>(std::vector<double>{st});
    codec.sigma_slot = layout.add_cell_var({"sigma_d", "g cm^-2", "dust", 1.0, false});
    codec.qm_slot = layout.add_cell_var({"q_m", "g cm^-2", "Q_m", 1.0, false});
    codec.qphi_slot = layout.add_cell_var({"q_phi", "g cm^-2", "Q_phi", 1.0, false});
    codec.m_ref = sp.m0;
    codec.x_lo = {0.0};
    pl = std::make_unique<Planetesimals>(layout, codec, *cell_gas, *stokes, species,
                                         growth, opt, 1.0);
    layout.freeze();
  }
  // {coagulation, SI} rates for Sigma_d and particles of mass m, filling factor phi
  std::pair<double, double> rates(double sigma_d, double m, double phi) const {
    std::vector<double> y(layout.size(), 0.0);
    y[layout.index(0, codec.sigma_slot)] = sigma_d;
    y[layout.index(0, codec.qm_slot)] = sigma_d * std::log(m / codec.m_ref);
    y[layout.index(0, codec.qphi_slot)] = sigma_d * std::log(1.0 / phi);
    return pl->rates(0, y);
  }
};

}  // namespace

// spec §7.1: Sdot = Sigma_d/tau_pl W(St/St_pl) [dm/dt > 0], tau_pl = 10/Omega_K,
// St_pl = 10. Particles of m = 1e12 g, phi = 1e-2, Sigma_d = 1.5 g cm^-2, still growing
// (checked: 1e9 dlnm/dt/Omega > 20, where the code's growth switch tanh is 1 to
// round-off). Expected Sigma_d Omega/10 x (1/2, 0.95, 0.05, 1), Omega from spec §1.3.
// Measured relative error <= 7e-16 (against 1 in saturation instead of 1/(1 + 19^-10):
// 1.6e-13, so the test sees the logistic's tail); tolerance 1e-12.
TEST(Planetesimals, DirectCoagulationAtItsSwitchMidpointAndInSaturation) {
  PlanetesimalOptions opt;
  opt.coagulation = true;
  opt.si = StreamingInstability::kNone;
  const double sigma_d = 1.5, m = 1e12, phi = 1e-2;
  const double omega = physics::mmsn_gas(5.0).omega_k;
  const double saturated = 1.0 / (1.0 + std::pow(19.0, -10.0));  // 1 dex past x0
  struct Case {
    double st, step;
  };
  const Case cases[] = {{10.0, 0.5},
                        {10.0 * std::pow(10.0, 0.1), 0.95},
                        {10.0 * std::pow(10.0, -0.1), 0.05},
                        {100.0, saturated}};
  for (const Case& c : cases) {
    SCOPED_TRACE("St = " + std::to_string(c.st));
    OneCell cell(c.st, opt);
    const auto rates = physics::particle_rates(sigma_d, m, phi, c.st, cell.gas,
                                               cell.species[0], cell.growth);
    ASSERT_GT(1e9 / omega * rates.dlnm_dt, 20.0);  // growing: the tanh switch is 1
    const auto [coag, si] = cell.rates(sigma_d, m, phi);
    EXPECT_NEAR(coag / (sigma_d * omega / 10.0 * c.step), 1.0, 1e-12);
    EXPECT_EQ(si, 0.0);
  }
}

// spec §7.2, d16: Sdot = zeta Sigma_d Omega, zeta = 0.01, where the midplane
// rho_d/rho_g >= 1 counting particles with St >= 0.01, both thresholds smooth steps:
// Sdot = zeta Sigma_d Omega step(eps_mid; 1) step(St; 0.01). eps_mid = Sigma_d H/(Sigma_g
// h_d) (spec §1.3, §2: the sqrt(2 pi) cancel), h_d of Youdin & Lithwick 2007 (spec §2)
// written out here; Sigma_d is chosen to put eps_mid at 1, 10^0.1, 10^-0.1 or 10.
// Expected factors by hand: 1/4 (both at the midpoint), 0.95^2 = 0.9025, 1/2 (St at its
// midpoint, eps saturated), 0.05 (eps 0.1 dex low, St saturated), 1 (both saturated),
// each saturated step being 1/(1 + 19^-10). Measured relative error <= 2.2e-16 (3.3e-13
// if the saturated steps are taken as 1); tolerance 1e-12.
TEST(Planetesimals, D16TriggerAtItsSwitchMidpointsAndInSaturation) {
  PlanetesimalOptions opt;
  opt.coagulation = false;
  opt.si = StreamingInstability::kD16;  // zeta 0.01, St_si_min 0.01, eps_crit 1
  const physics::LocalGas g = physics::mmsn_gas(5.0);
  struct Case {
    double st, eps_mid, factor;
  };
  const double up = std::pow(10.0, 0.1);
  const double saturated = 1.0 / (1.0 + std::pow(19.0, -10.0));  // 1 dex past x0
  const Case cases[] = {{0.01, 1.0, 0.25},
                        {0.01 * up, up, 0.9025},
                        {0.01, 10.0, 0.5 * saturated},
                        {0.1, 1.0 / up, 0.05 * saturated},
                        {0.1, 10.0, saturated * saturated}};
  for (const Case& c : cases) {
    SCOPED_TRACE("St = " + std::to_string(c.st) +
                 ", eps_mid = " + std::to_string(c.eps_mid));
    OneCell cell(c.st, opt);
    const double h_d =
        g.h_g / std::sqrt(1.0 + c.st / g.alpha * (1.0 + 2.0 * c.st) / (1.0 + c.st));
    const double sigma_d = c.eps_mid * g.sigma_g * h_d / g.h_g;
    const auto [coag, si] = cell.rates(sigma_d, 1.0, 1e-3);
    EXPECT_NEAR(si / (0.01 * sigma_d * g.omega_k * c.factor), 1.0, 1e-12);
    EXPECT_EQ(coag, 0.0);
  }
}

// spec §7.2, zcrit: Sdot = zeta Sigma_d Omega where Z = Sigma_d/Sigma_g >= Z_crit(St),
// for St >= St_si_min = 0.01, both thresholds smooth steps as above: Sdot = zeta Sigma_d
// Omega step(Z/Z_crit; 1) step(St; 0.01). At St = 0.1: log10 Z_crit = 0.10 - 0.07 - 2.36
// = -2.33 (Lim et al. 2025 eq. 15, as in ZcritAtHandWorkedStokesNumbers), so Z_crit =
// 10^-2.33 = 4.677e-3, and the St step is 1 dex past its midpoint (1/(1 + 19^-10)).
// Sigma_d is put at Z = Z_crit x (1, 10^0.1, 10^-0.1): expected factors by hand 1/2,
// 0.95, 0.05 times the saturated St step. Tolerance 1e-12 as for d16.
TEST(Planetesimals, ZcritTriggerAtItsSwitchMidpointAndFlanks) {
  PlanetesimalOptions opt;
  opt.coagulation = false;
  opt.si = StreamingInstability::kZcrit;
  opt.zeta = 0.01;  // zeta_zcrit default
  const physics::LocalGas g = physics::mmsn_gas(5.0);
  const double st = 0.1, z_crit = std::pow(10.0, -2.33);
  const double up = std::pow(10.0, 0.1);
  const double saturated = 1.0 / (1.0 + std::pow(19.0, -10.0));
  struct Case {
    double z_over_zcrit, factor;
  };
  for (const Case c : {Case{1.0, 0.5}, Case{up, 0.95}, Case{1.0 / up, 0.05}}) {
    SCOPED_TRACE("Z/Z_crit = " + std::to_string(c.z_over_zcrit));
    OneCell cell(st, opt);
    const double sigma_d = c.z_over_zcrit * z_crit * g.sigma_g;
    const auto [coag, si] = cell.rates(sigma_d, 1.0, 1e-3);
    EXPECT_NEAR(si / (0.01 * sigma_d * g.omega_k * c.factor * saturated), 1.0, 1e-12);
    EXPECT_EQ(coag, 0.0);
  }
}

}  // namespace panoptic
