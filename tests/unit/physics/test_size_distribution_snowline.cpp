// The snow line in the size-distribution mode (spec §1.7, §6.3, §11 #18, §15.4;
// physics/modules/size_distribution.*): silicate monomers inside r_snow, ice outside, on
// one mass grid; the dust of bin k crossing the snow face inward arrives as particles of
// (1 - f_ice) m_k with phi kept, split over the two bins around that mass, and f_ice of
// the flow is booked in m_sublimated. Checked on the right-hand side against the face's
// mass flow (mass, number and volume of the arriving particles), and on runs: the budget
// closes and the sublimated mass is f_ice times the mass that crossed the face inward.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "disk/gas_disk.hpp"
#include "physics/modules/size_distribution.hpp"
#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "tests/unit/support/evolved_state.hpp"

namespace panoptic {
namespace {

const std::string kSmall =
    std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml";

// The small distribution scene (12 cells 1-100 au) with the snow line: r_snow = 1.70 au
// (T = 221 K (r/au)^-1/2, T_sub = 170 K), at face 1 between cells 0 and 1.
Config snow_scene(std::vector<std::string> sets = {}) {
  sets.insert(sets.begin(), "snowline.enabled=true");
  return load_scene(kSmall, sets);
}

int snow_face(const Simulation& sim) {
  const double r_snow = sim.disk().r_snow();
  for (int f = 1; f < sim.grid().n_cells(); ++f)
    if (sim.grid().r_c(f - 1) < r_snow && sim.grid().r_c(f) >= r_snow) return f;
  return -1;
}

TEST(SizeDistributionSnowLine, SpeciesPerCellOnOneGrid) {
  Simulation sim(snow_scene({"model.m_min_g=0.0"}));
  const auto* d = sim.distribution();
  ASSERT_NE(d, nullptr);
  ASSERT_EQ(snow_face(sim), 1);
  ASSERT_GE(d->sublimated_slot(), 0);
  const auto& m = d->mass_grid().m;
  // the grid starts at the lighter (icy) monomers; the silicate ones (rho0 3.0 against
  // 1.67, the same a0) lie 3.5 log10(3.0/1.67) = 0.89 bins up: bin 0 still
  const double m0_ice = 4.0 / 3.0 * units::kPi * 1e-15 * 1.67;
  EXPECT_NEAR(m[0] / m0_ice, 1.0, 1e-6);
  EXPECT_EQ(d->monomer_bin(1), 0);
  EXPECT_EQ(d->monomer_bin(0), 0);
  EXPECT_GT(m[1], 3.0 / 1.67 * m[0]);
  // MRN up to 1 um by each species' own radii: the denser silicates reach more bins
  const auto y = sim.initial_state();
  const auto& L = sim.model().layout();
  auto last_filled = [&](int cell) {
    int last = -1;
    for (int k = 0; k < d->n_bins(); ++k)
      if (y[L.index(cell, d->bin_slot(k))] > 0.0) last = k;
    return last;
  };
  const auto a_sil = d->bin_radii(0), a_ice = d->bin_radii(1);
  EXPECT_LE(a_sil[last_filled(0)], 1e-4);
  EXPECT_GT(a_sil[last_filled(0) + 1], 1e-4);
  EXPECT_LE(a_ice[last_filled(1)], 1e-4);
  EXPECT_GT(a_ice[last_filled(1) + 1], 1e-4);
  // and Z_in = (1 - f_ice) Z_out (spec §1.7)
  const auto sigma_g = [&](int i) { return sim.disk().sigma_g(sim.grid().r_c(i)); };
  EXPECT_NEAR(d->sigma_d(0, y) / sigma_g(0), 0.5 * 0.01, 1e-15);
  EXPECT_NEAR(d->sigma_d(1, y) / sigma_g(1), 0.01, 1e-15);
}

// The silicate cell's bins below its own monomer mass stay empty at the start when the
// grid starts lower (model.m_min_g): the dust starts at the monomers.
TEST(SizeDistributionSnowLine, MonomersStartInTheSpeciesBin) {
  Simulation sim(snow_scene({"model.m_min_g=1e-16", "model.init=\"monomers\""}));
  const auto* d = sim.distribution();
  const auto& m = d->mass_grid().m;
  const auto y = sim.initial_state();
  const auto& L = sim.model().layout();
  for (int cell : {0, 1}) {
    const int k0 = d->monomer_bin(cell);
    const double m0 = 4.0 / 3.0 * units::kPi * 1e-15 * (cell == 0 ? 3.0 : 1.67);
    EXPECT_LE(m[k0], m0 * (1.0 + 1e-9)) << cell;
    EXPECT_GT(m[k0 + 1], m0) << cell;
    EXPECT_EQ(y[L.index(cell, d->bin_slot(k0))], d->sigma_d(cell, y)) << cell;
  }
  EXPECT_GT(d->monomer_bin(0), d->monomer_bin(1));
}

// Only bin k of the first icy cell holds dust (sigma_k, and psi_k = u sigma_k when
// porous); the silicate cell inside is empty, so that all its rates come from what
// crosses the snow face (its own coagulation and its outflow through r_in are zero).
// Then, with M the inward mass flow of the face (mass_flow, summed apart from the
// booking): the silicate cell gains (1 - f_ice) M, in the two bins around (1 - f_ice)
// m_k, as M / m_k particles (Kovetz & Olund's split conserves number), psi with the same
// ratio u (phi kept); m_sublimated grows at f_ice M.
void expect_sublimation_at_the_face(const std::vector<std::string>& sets, double u) {
  Simulation sim(snow_scene(sets));
  const auto* d = sim.distribution();
  const auto& L = sim.model().layout();
  const auto& m = d->mass_grid().m;
  const int nb = d->n_bins(), k = 20;
  const double f_ice = 0.5, keep = 1.0 - f_ice;
  std::vector<double> y = sim.initial_state();
  for (int i = 0; i < sim.grid().n_cells(); ++i)
    for (int q = 0; q < d->cell_vars(); ++q) y[L.index(i, d->bin_slot(0) + q)] = 0.0;
  y[L.index(1, d->bin_slot(k))] = 1e-3;
  if (d->porous()) y[L.index(1, d->psi_slot(k))] = u * 1e-3;

  std::vector<double> ydot(y.size());
  sim.model().rhs(0.0, y, ydot);
  const double inflow = -d->mass_flow(y)[1];  // [g s^-1], inward
  ASSERT_GT(inflow, 0.0);
  const double area = sim.grid().area(0);
  double mass = 0.0, number = 0.0;
  int filled = 0, lo = nb;
  for (int j = 0; j < nb; ++j) {
    const double s = ydot[L.index(0, d->bin_slot(j))] * area;
    if (s == 0.0) continue;
    ++filled;
    lo = std::min(lo, j);
    mass += s;
    number += s / m[j];
    if (d->porous()) {
      EXPECT_NEAR(ydot[L.index(0, d->psi_slot(j))] / ydot[L.index(0, d->bin_slot(j))], u,
                  1e-13 * u)
          << j;
    }
  }
  std::printf("bin %d (m %.3e g) arrives in bins %d, %d (m %.3e, %.3e g) at %.3e g\n", k,
              m[k], lo, lo + 1, m[lo], m[lo + 1], keep * m[k]);
  ASSERT_EQ(filled, 2);
  EXPECT_LE(m[lo], keep * m[k]);
  EXPECT_GT(m[lo + 1], keep * m[k]);
  EXPECT_NEAR(mass / (keep * inflow), 1.0, 1e-13);
  EXPECT_NEAR(number / (inflow / m[k]), 1.0, 1e-13);
  const double sublimated = ydot[L.global_index(d->sublimated_slot())] * d->mass_unit();
  EXPECT_NEAR(sublimated / (f_ice * inflow), 1.0, 1e-13);
}

TEST(SizeDistributionSnowLine, InflowArrivesAsLighterParticlesAndBooksTheIce) {
  expect_sublimation_at_the_face({}, 1.0);
}

TEST(SizeDistributionSnowLine, PorousInflowKeepsItsFillingFactor) {
  expect_sublimation_at_the_face({"porosity.enabled=true", "model.m_max_g=1e-4"}, 7.0);
}

// Outward flow through the snow face (here diffusion against the drift, the silicate
// cell holding more of bin k than the icy one) carries its dust unchanged into bin k of
// the icy cell: no condensation, as the single-size transport.
TEST(SizeDistributionSnowLine, OutflowIsNotChanged) {
  Simulation sim(snow_scene({"gas.evolve=false"}));
  const auto* d = sim.distribution();
  const auto& L = sim.model().layout();
  const int k = 3;  // small grains: diffusion wins over drift
  std::vector<double> y = sim.initial_state();
  for (int i = 0; i < sim.grid().n_cells(); ++i)
    for (int q = 0; q < d->cell_vars(); ++q) y[L.index(i, d->bin_slot(0) + q)] = 0.0;
  y[L.index(0, d->bin_slot(k))] = 1e-3;
  std::vector<double> ydot(y.size());
  sim.model().rhs(0.0, y, ydot);
  const auto flow = d->mass_flow(y);
  ASSERT_GT(flow[1], 0.0);
  EXPECT_NEAR(ydot[L.index(1, d->bin_slot(k))] * sim.grid().area(1) / flow[1], 1.0,
              1e-13);
  EXPECT_EQ(ydot[L.global_index(d->sublimated_slot())], 0.0);
}

// A run whose dust drifts through the snow line: the budget closes to 1e-10, and with
// drift alone (every flow through the face inward) m_sublimated is f_ice times the
// booked mass that crossed the face inward (the pebble monitor at the snow line, spec
// §8).
TEST(SizeDistributionSnowLine, RunBooksTheSublimatedIce) {
  for (const bool diffusion : {true, false}) {
    Simulation sim(
        snow_scene({"output.t_end_yr=1e3", std::string("transport.diffusion=") +
                                               (diffusion ? "true" : "false")}));
    const std::vector<double> y = evolved_state(sim, 1e3);
    const auto* d = sim.distribution();
    const double sub = d->mass_sublimated(y), m0 = d->mass_unit();
    double through = -1.0;
    for (std::size_t q = 0; q < sim.pebble_monitors().size(); ++q)
      if (sim.pebble_monitors()[q].face == snow_face(sim))
        through = sim.pebble_mass(y)[q];
    std::printf(
        "diffusion %d: 1e3 yr, budget error %.1e, m_sublimated %.3e of the dust, through "
        "the snow face %.3e, m_sublimated / (f_ice x through) - 1 = %.1e\n",
        diffusion, sim.budget_error(y), sub / m0, through / m0,
        sub / (0.5 * through) - 1.0);
    EXPECT_LT(sim.budget_error(y), 1e-10);
    EXPECT_GT(sub, 1e-5 * m0);
    if (!diffusion) {
      EXPECT_NEAR(sub / (0.5 * through), 1.0, 1e-10);
    } else {  // some bins diffuse out again through the face
      EXPECT_GT(sub, 0.5 * through);
    }
  }
}

}  // namespace
}  // namespace panoptic
