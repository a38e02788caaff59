// Planetesimal formation per mass bin in the size-distribution mode (spec §15.4, §7;
// physics/modules/bin_planetesimals.*): the dust of one bin converts at the single-size
// rate (direct coagulation: the law of a growing particle; d16: the single-size module
// of the same St, through its trigger's switch), bins below St_pl do not convert, a run
// whose last bin cannot reach St_pl says so, psi_k loses the fraction sigma_k loses, the
// budget closes in a run that converts, and the Jacobian, compact and porous, against
// finite differences.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/modules/bin_planetesimals.hpp"
#include "physics/modules/size_distribution.hpp"
#include "physics/particle.hpp"
#include "physics/planetesimal_criteria.hpp"
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

Config small_scene(std::vector<std::string> sets) { return load_scene(kSmall, sets); }

const BinPlanetesimals& bin_module(const Simulation& sim) {
  const auto* pl = dynamic_cast<const BinPlanetesimals*>(sim.planetesimals());
  EXPECT_NE(pl, nullptr);
  return *pl;
}

// y with all the dust of every cell in bin k (sigma_d of the initial state), compact.
std::vector<double> all_in_bin(const Simulation& sim, int k, double scale = 1.0) {
  auto y = sim.initial_state();
  const auto& L = sim.model().layout();
  const auto* d = sim.distribution();
  for (int i = 0; i < sim.grid().n_cells(); ++i) {
    const double sigma = d->sigma_d(i, y) * scale;
    for (int j = 0; j < d->cell_vars(); ++j) y[L.index(i, d->bin_slot(0) + j)] = 0.0;
    y[L.index(i, d->bin_slot(k))] = sigma;
    if (d->porous()) y[L.index(i, d->psi_slot(k))] = sigma;
  }
  return y;
}

TEST(BinPlanetesimals, AcceptedWithTheDistributionButZcritIsRefused) {
  EXPECT_NO_THROW(validate_scene(
      small_scene({"planetesimals.coagulation=true", "planetesimals.si=\"d16\""})));
  EXPECT_NO_THROW(validate_scene(small_scene({"planetesimals.si=\"s18\""})));
  const std::string msg = config_error_message(
      [] { validate_scene(small_scene({"planetesimals.si=\"zcrit\""})); }, "zcrit");
  EXPECT_NE(msg.find("planetesimals.si"), std::string::npos) << msg;
  EXPECT_NE(msg.find("model.kind = \"distribution\""), std::string::npos) << msg;
  // the same variables and fields as the single-size model's
  Simulation sim(
      small_scene({"planetesimals.coagulation=true", "planetesimals.si=\"d16\""}));
  const auto& L = sim.model().layout();
  EXPECT_TRUE(L.find_cell_var("sigma_pl_coag"));
  EXPECT_TRUE(L.find_cell_var("sigma_pl_si"));
  std::vector<std::string> names;
  for (const auto& f : bin_module(sim).output_fields()) names.push_back(f.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"sigma_pl", "sigma_pl_coag", "sigma_pl_si"}));
  // a channel that is off owns no variable
  Simulation coag_only(small_scene({"planetesimals.coagulation=true"}));
  EXPECT_FALSE(coag_only.model().layout().find_cell_var("sigma_pl_si"));
}

// A mass grid whose last bin stays below St_pl converts nothing by direct coagulation:
// the run says so (distribution_small ends at 100 g). The threshold is the last bin's
// largest compact St over the cells: St_pl just above it warns, just below it does not.
TEST(BinPlanetesimals, TheRunWarnsWhenNoBinCanReachStPl) {
  const std::string warning = "WARNING: no bin can reach planetesimals.St_pl";
  const Simulation sim(small_scene({"planetesimals.coagulation=true"}));
  EXPECT_NE(sim.summary().find(warning), std::string::npos) << sim.summary();
  EXPECT_NE(sim.summary().find("model.m_max_g = 100"), std::string::npos);
  const auto* d = sim.distribution();
  double st_top = 0.0;
  for (int i = 0; i < sim.grid().n_cells(); ++i)
    st_top = std::max(st_top, d->bin_stokes(i, d->n_bins() - 1, 1.0));
  ASSERT_GT(st_top, 0.0);
  ASSERT_LT(st_top, 10.0);
  const auto with_st_pl = [&](double st_pl) {
    return Simulation(small_scene({"planetesimals.coagulation=true",
                                   "planetesimals.St_pl=" + std::to_string(st_pl)}))
        .summary();
  };
  EXPECT_NE(with_st_pl(1.01 * st_top).find(warning), std::string::npos);
  EXPECT_EQ(with_st_pl(0.99 * st_top).find(warning), std::string::npos);
  // only direct coagulation has the threshold: SI alone does not warn
  EXPECT_EQ(Simulation(small_scene({"planetesimals.si=\"d16\""})).summary().find(warning),
            std::string::npos);
}

// All the dust of a cell in one bin: direct coagulation converts it at the single-size
// law of a growing particle of the bin's St (spec §7.1), to the bit, on the flanks and in
// the middle of the St_pl switch (St_pl set to the bin's St times 0.8, 1 and 1.25).
TEST(BinPlanetesimals, OneBinDirectCoagulationIsTheSingleSizeRate) {
  const int k = 40, cell = 4;
  Simulation probe(small_scene({"planetesimals.coagulation=true"}));
  const double st = probe.distribution()->bin_stokes(cell, k, 1.0);
  for (double f : {0.8, 1.0, 1.25}) {
    char set[64];
    std::snprintf(set, sizeof set, "planetesimals.St_pl=%.17g", st * f);
    Simulation sim(small_scene({"planetesimals.coagulation=true", set}));
    const auto y = all_in_bin(sim, k);
    const auto* d = sim.distribution();
    const PlanetesimalOptions o;  // tau_pl_omega, width_dex of the scene (defaults)
    const physics::LocalGas& g = d->bin_gas(cell);
    const double sigma = d->sigma_d(cell, y);
    const double dlnm_dt = 1.0 / (100.0 * units::kYr);  // a growing particle
    const double single = physics::coagulation_conversion(
        sigma, st, dlnm_dt, g.omega_k, o.tau_pl_omega, st * f, o.width_dex);
    const auto [coag, si] = sim.planetesimals()->rates(cell, y);
    std::printf("St_pl = %.2f St_k: distribution %.17g, single size %.17g g cm^-2 s^-1\n",
                f, coag, single);
    EXPECT_GT(single, 0.0);
    EXPECT_EQ(coag, single);
    EXPECT_EQ(si, 0.0);
  }
}

// All the dust of a cell in one bin of St >= 32 St_si_min (where the St switch is 1 to
// round-off): d16 of the distribution is the single-size module's d16 for a prescribed
// St equal to the bin's, to the bit, below, at and above its trigger (Sigma_d scaled so
// that the midplane rho_d/rho_g is 0.8, 1 and 1.25 of eps_crit). The positive part's
// floor of the empty bins is put below round-off (solver.atol_sigma).
TEST(BinPlanetesimals, OneBinD16IsTheSingleSizeRate) {
  const std::vector<std::string> common{"gas.evolve=false", "planetesimals.si=\"d16\"",
                                        "solver.atol_sigma=1e-30"};
  Simulation dist(small_scene(common));
  const auto* d = dist.distribution();
  // the top bin in the outermost cell: the largest St of the scene
  const int k = d->n_bins() - 1, cell = dist.grid().n_cells() - 1;
  const double st = d->bin_stokes(cell, k, 1.0);
  ASSERT_GT(st, 32.0 * 0.01);
  std::vector<std::string> single_sets = common;
  char st_set[64];
  std::snprintf(st_set, sizeof st_set, "transport.St=%.17g", st);
  for (std::string s : {"model.kind=\"single_size\"", "growth.enabled=false",
                        "transport.St_slope=0.0", "porosity.enabled=false"})
    single_sets.push_back(s);
  single_sets.push_back(st_set);
  Simulation single(small_scene(single_sets));
  const physics::LocalGas& g = d->bin_gas(cell);
  // Sigma_d that puts the midplane dust-to-gas ratio at eps_crit = 1
  const double sigma_crit =
      g.rho_g * std::sqrt(2.0 * units::kPi) * physics::dust_scale_height(st, g);
  for (double f : {0.8, 1.0, 1.25}) {
    auto yd = all_in_bin(dist, k);
    const double scale = f * sigma_crit / d->sigma_d(cell, yd);
    yd = all_in_bin(dist, k, scale);
    auto ys = single.initial_state();
    ys[single.model().layout().index(cell, single.transport().sigma_slot())] =
        d->sigma_d(cell, yd);
    const double rate_d = dist.planetesimals()->rates(cell, yd).second;
    const double rate_s = single.planetesimals()->rates(cell, ys).second;
    std::printf("eps_mid = %.2f eps_crit: distribution %.17g, single size %.17g\n", f,
                rate_d, rate_s);
    EXPECT_GT(rate_s, 0.0);
    EXPECT_EQ(rate_d, rate_s);
  }
}

// The porous scene of the two tests below, with both channels (St_pl 1e-4, d16 at
// eps_crit 1e-3).
Config porous_converting_scene() {
  return small_scene({"porosity.enabled=true", "planetesimals.coagulation=true",
                      "planetesimals.St_pl=1e-4", "planetesimals.si=\"d16\"",
                      "planetesimals.eps_crit=1e-3"});
}

// y with the filling factors of a spread distribution: u_k = 1 .. 100 over the bins.
void spread_porosity(const Simulation& sim, std::vector<double>& y) {
  const auto* d = sim.distribution();
  const auto& L = sim.model().layout();
  for (int i = 0; i < sim.grid().n_cells(); ++i)
    for (int k = 0; k < d->n_bins(); ++k)
      y[L.index(i, d->psi_slot(k))] =
          (1.0 + 99.0 * k / d->n_bins()) * y[L.index(i, d->bin_slot(k))];
}

// A spread distribution: bins with St_k far below St_pl (the switch 0 to round-off) do
// not convert, bins far above convert at sigma_k / tau_pl; d16 takes no dust from bins
// far below St_si_min; and psi_k loses the fraction sigma_k loses (spec §6.2).
TEST(BinPlanetesimals, OnlyBinsAboveTheThresholdsConvertAndPhiIsKept) {
  Simulation sim(porous_converting_scene());
  const auto* d = sim.distribution();
  const auto& L = sim.model().layout();
  auto y = testing::perturbed_state(sim, 3);
  spread_porosity(sim, y);
  const PlanetesimalOptions o;
  BinPlanetesimals::CellRates r;
  int below = 0, above = 0, si_below = 0;
  double worst_fraction = 0.0;
  for (int i = 0; i < sim.grid().n_cells(); ++i) {
    bin_module(sim).cell_rates(i, y, r);
    const double tau_pl = o.tau_pl_omega / d->bin_gas(i).omega_k;
    for (int k = 0; k < d->n_bins(); ++k) {
      const double st = d->bin_stokes(i, k, d->phi(i, k, y));
      const double sigma = y[L.index(i, d->bin_slot(k))];
      const double psi = y[L.index(i, d->psi_slot(k))];
      if (st < 1e-4 / 64.0) {
        ++below;
        EXPECT_EQ(r.coag[k], 0.0) << "cell " << i << " bin " << k << " St " << st;
      }
      if (st > 1e-4 * 64.0) {
        ++above;
        EXPECT_DOUBLE_EQ(r.coag[k], sigma / tau_pl);
      }
      if (st < 0.01 / 64.0) {
        ++si_below;
        EXPECT_EQ(r.si[k], 0.0) << "cell " << i << " bin " << k << " St " << st;
      }
      const double loss = r.coag[k] + r.si[k], loss_psi = r.coag_psi[k] + r.si_psi[k];
      if (loss > 0.0)
        worst_fraction = std::max(worst_fraction,
                                  std::abs(loss_psi / psi - loss / sigma) * sigma / loss);
    }
  }
  std::printf(
      "%d bins below St_pl, %d above, %d below St_si_min; |psi fraction - sigma "
      "fraction| / sigma fraction <= %.1e\n",
      below, above, si_below, worst_fraction);
  EXPECT_GT(below, 50);
  EXPECT_GT(above, 10);
  EXPECT_GT(si_below, 50);
  EXPECT_LT(worst_fraction, 1e-14);
}

// The bins' St that the rates read are those of the state asked (spec §15.1; one law,
// SizeDistribution::bin_stokes_numbers, computed once per state): after a right-hand side
// at another state y1, the rates at y2 equal those after a right-hand side at y2, every
// St equals the law at y2's phi_k, and after a refresh() of the gas (evolving) the St of
// the same state follow the new gas.
TEST(BinPlanetesimals, RatesReadTheStOfTheStateAsked) {
  Simulation sim(porous_converting_scene());
  const auto* d = sim.distribution();
  const auto& L = sim.model().layout();
  const int n = sim.grid().n_cells(), nb = d->n_bins();
  const auto y1 = testing::perturbed_state(sim, 3);
  auto y2 = y1;
  spread_porosity(sim, y2);
  // the St of every bin at y2 by the law, and whether any differs from y1's
  const auto law_st = [&](const std::vector<double>& y, int i, int k) {
    return d->bin_stokes(i, k, d->phi(i, k, y));
  };
  std::vector<double> ydot(y1.size());
  sim.model().rhs(0.0, y1, ydot);
  std::vector<BinPlanetesimals::CellRates> after_y1(n);
  for (int i = 0; i < n; ++i) bin_module(sim).cell_rates(i, y2, after_y1[i]);
  const std::vector<double> st_y2 = [&] {
    const auto st = d->bin_stokes_numbers(y2);
    return std::vector<double>(st.begin(), st.end());
  }();
  sim.model().rhs(0.0, y2, ydot);
  int moved = 0;
  for (int i = 0; i < n; ++i) {
    BinPlanetesimals::CellRates after_y2;
    bin_module(sim).cell_rates(i, y2, after_y2);
    EXPECT_EQ(after_y1[i].coag, after_y2.coag) << "cell " << i;
    EXPECT_EQ(after_y1[i].si, after_y2.si) << "cell " << i;
    for (int k = 0; k < nb; ++k) {
      const std::size_t ik = static_cast<std::size_t>(i) * nb + k;
      EXPECT_EQ(st_y2[ik], law_st(y2, i, k)) << "cell " << i << " bin " << k;
      moved += law_st(y1, i, k) != st_y2[ik];
    }
  }
  EXPECT_GT(moved, n * nb / 2);
  // a refresh() with twice the gas (evolving): the same state's St follow it
  auto y3 = y2;
  const int sigma_g = L.find_cell_var("sigma_g").value();
  for (int i = 0; i < n; ++i) y3[L.index(i, sigma_g)] *= 2.0;
  d->refresh(y3);
  const auto st_new_gas = d->bin_stokes_numbers(y2);
  int changed = 0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < nb; ++k) {
      const std::size_t ik = static_cast<std::size_t>(i) * nb + k;
      EXPECT_EQ(st_new_gas[ik], law_st(y2, i, k)) << "cell " << i << " bin " << k;
      changed += st_new_gas[ik] != st_y2[ik];
    }
  EXPECT_GT(changed, n * nb / 2);
}

// A run that converts by both channels (St_pl, St_si_min and eps_crit lowered so that
// the small scene's grains, St ~1e-6 .. 1e-4 within 1 000 yr, form planetesimals): the
// budget terms' rates cancel and the budget closes to 1e-10, with the planetesimal terms
// of the single-size model.
TEST(BinPlanetesimals, BudgetClosesInARunThatConverts) {
  for (const char* porous : {"porosity.enabled=false", "porosity.enabled=true"}) {
    Simulation sim(
        small_scene({porous, "planetesimals.coagulation=true", "planetesimals.St_pl=1e-5",
                     "planetesimals.si=\"d16\"", "planetesimals.St_si_min=1e-5",
                     "planetesimals.eps_crit=5e-3"}));
    const std::vector<double> y = evolved_state(sim, 1000.0);
    std::vector<double> ydot(y.size());
    sim.model().rhs(1000.0 * units::kYr, y, ydot);
    const auto rates = sim.budget_masses(ydot);  // linear terms
    const auto masses = sim.budget_masses(y);
    double sum = 0.0, scale = 0.0, m_coag = 0.0, m_si = 0.0, m0 = 0.0;
    for (std::size_t k = 0; k < rates.size(); ++k) {
      sum += rates[k];
      scale += std::abs(rates[k]);
      m0 += masses[k];
      const std::string& name = sim.budget_terms()[k].name;
      if (name == "m_pl_coag") m_coag = masses[k];
      if (name == "m_pl_si") m_si = masses[k];
    }
    std::printf(
        "%s: budget error %.1e after 1000 yr, rates cancel to %.1e; m_pl_coag "
        "%.3f, m_pl_si %.3f of the dust\n",
        porous, sim.budget_error(y), std::abs(sum) / scale, m_coag / m0, m_si / m0);
    EXPECT_GT(m_coag, 1e-3 * m0) << porous;
    EXPECT_GT(m_si, 1e-3 * m0) << porous;
    EXPECT_LT(std::abs(sum), 1e-12 * scale) << porous;
    EXPECT_LT(sim.budget_error(y), 1e-10) << porous;
  }
}

// The midplane rho_d/rho_g of the bins with St >= St_si_min (spec §15.4), computed here
// from the laws, for placing eps_crit inside the trigger's switch.
double counted_eps_mid(const Simulation& sim, int cell, const std::vector<double>& y,
                       double st_si_min) {
  const auto* d = sim.distribution();
  const physics::LocalGas& g = d->bin_gas(cell);
  double rho = 0.0;
  for (int k = 0; k < d->n_bins(); ++k) {
    const double st = d->bin_stokes(cell, k, d->phi(cell, k, y));
    rho += physics::log_step(st, st_si_min, 0.1) *
           physics::midplane_dust_density(
               y[sim.model().layout().index(cell, d->bin_slot(k))],
               physics::dust_scale_height(st, g));
  }
  return rho / g.rho_g;
}

// The module's Jacobian alone against central differences of its right-hand side, on
// perturbed states (every bin filled), with eps_crit inside the trigger's switch in one
// cell (the dense block of the trigger) and St_pl inside the bins' St range; compact and
// porous (u_k = 1.1 .. 10: St through phi_k; off the kink of bin_porosity at u = 1), d16
// and s18.
TEST(BinPlanetesimals, JacobianMatchesFiniteDifferences) {
  for (const char* porous : {"porosity.enabled=false", "porosity.enabled=true"})
    for (const char* si : {"planetesimals.si=\"d16\"", "planetesimals.si=\"s18\""}) {
      std::vector<std::string> sets{porous,
                                    si,
                                    "planetesimals.coagulation=true",
                                    "planetesimals.St_pl=1e-2",
                                    "planetesimals.St_si_min=1e-3",
                                    "gas.evolve=false"};
      const auto state = [](const Simulation& sim) {
        auto y = testing::perturbed_state(sim, 11);
        const auto* d = sim.distribution();
        const auto& L = sim.model().layout();
        for (int i = 0; d->porous() && i < sim.grid().n_cells(); ++i)
          for (int k = 0; k < d->n_bins(); ++k)
            y[L.index(i, d->psi_slot(k))] =
                (1.1 + 9.0 * k / d->n_bins()) * y[L.index(i, d->bin_slot(k))];
        return y;
      };
      const int cell = 6;
      Simulation probe(small_scene(sets));
      char set[64];
      std::snprintf(set, sizeof set, "planetesimals.eps_crit=%.17g",
                    1.1 * counted_eps_mid(probe, cell, state(probe), 1e-3));
      sets.push_back(set);
      Simulation sim(small_scene(sets));
      sim.model().set_active([](std::string_view m) { return m == "bin_planetesimals"; });
      const auto y = state(sim);
      const auto c = testing::compare_with_fd(sim, y);
      const auto& L = sim.model().layout();
      const int nb = sim.distribution()->n_bins();
      std::printf("%s, %s: row-scaled error %.2e, entry error %.2e, %ld FD non-zeros\n",
                  porous, si, c.max_rel_err, c.max_entry_err, c.nnz_fd);
      EXPECT_LT(c.max_rel_err, 1e-7)
          << porous << si << ": worst d(" << L.describe(c.worst_row) << ")/d("
          << L.describe(c.worst_col) << "): analytic " << c.worst_analytic << ", FD "
          << c.worst_fd;
      // the entry error is the central difference's round-off: 1.1e-4 measured on d
      // sigma_pl_si / d sigma_23 in cell 7 (compact, d16), where steps of 1e-3 and 1e-4
      // (relative) agree with the analytic entry to 8e-8 and 2e-7
      EXPECT_LT(c.max_entry_err, 5e-4)
          << porous << si << ": d(" << L.describe(c.entry_row) << ")/d("
          << L.describe(c.entry_col) << ")";
      EXPECT_EQ(c.outside_pattern, 0);
      // the trigger's entries between bins in the cell at its switch are there
      const auto& pattern = sim.model().pattern();
      std::vector<double> values(pattern.nnz());
      sim.model().jacobian(0.0, y, values);
      const auto* d = sim.distribution();
      int between = 0;
      for (int k = 0; k < nb; ++k)
        for (int j = 0; j < nb; ++j) {
          const long at = pattern.position(L.index(cell, d->bin_slot(k)),
                                           L.index(cell, d->bin_slot(j)));
          between += j != k && at >= 0 && values[at] != 0.0;
        }
      std::printf("  %d entries between bins in cell %d, eps_mid %.3e\n", between, cell,
                  counted_eps_mid(sim, cell, y, 1e-3));
      EXPECT_GT(between, 100) << porous << si;
    }
}

}  // namespace
}  // namespace panoptic
