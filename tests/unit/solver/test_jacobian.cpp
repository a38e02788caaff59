// The assembled Jacobian equals a central finite-difference Jacobian of the RHS, and no
// finite-difference non-zero lies outside the declared sparsity pattern: per module
// (transport alone, diffusion alone, drift alone, viscous gas) and for the whole system.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/disk_model.hpp"
#include "tests/bench/cell_range_model.hpp"
#include "tests/unit/support/evolved_state.hpp"
#include "tests/unit/support/jacobian_check.hpp"

using namespace panoptic;
using namespace panoptic::testing;

namespace {

// Measured (2026-11-24; every check prints its two errors): at most 6.3e-7 for
// transport and gas (van Leer drift), 7e-6 for growth, erosion and planetesimals, 6.8e-5
// where the bouncing switch is sharp (porous bouncing, d q_m / d q_phi: the central
// difference's truncation error)
constexpr double kEntryTolerance = 5e-4;

void print_errors(const std::string& label, unsigned seed, double row, double entry) {
  std::printf("%s, seed %u: row-scaled error %.2e, entry error %.2e\n", label.c_str(),
              seed, row, entry);
}

Config scene(const std::vector<std::string>& overrides) {
  const std::string text = R"(
[grid]
n_cells = 24
r_in_au = 1.0
r_out_au = 100.0
[transport]
St = 0.05
St_slope = 0.3
)";
  return load_scene_text(text, "jacobian_test.toml", overrides);
}

//! The checks of one comparison with finite differences (its errors printed first): the
//! row-scaled error below `row_tolerance`, every entry's below kEntryTolerance, no
//! finite-difference non-zero outside the pattern; failures name `label` and `seed`.
void expect_matches_fd(const JacobianCheck& c, const StateLayout& L,
                       const std::string& label, unsigned seed, double row_tolerance) {
  print_errors(label, seed, c.max_rel_err, c.max_entry_err);
  EXPECT_LT(c.max_rel_err, row_tolerance)
      << label << ", seed " << seed << ": worst d(" << L.describe(c.worst_row) << ")/d("
      << L.describe(c.worst_col) << "): analytic " << c.worst_analytic << ", FD "
      << c.worst_fd;
  EXPECT_LT(c.max_entry_err, kEntryTolerance)
      << label << ", seed " << seed << ": d(" << L.describe(c.entry_row) << ")/d("
      << L.describe(c.entry_col) << ")";
  EXPECT_EQ(c.outside_pattern, 0) << label << ", seed " << seed;
}

void expect_exact(const std::vector<std::string>& overrides, const char* label) {
  Simulation sim(scene(overrides));
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto c = compare_with_fd(sim, perturbed_state(sim, seed));
    expect_matches_fd(c, sim.model().layout(), label, seed, 1e-7);
    EXPECT_GT(c.nnz_fd, 0) << label;
  }
}

}  // namespace

namespace {

//! One check of the table-driven cases below, registered as the test Jacobian.<name>:
//! the scene's --set overrides and the label its errors are printed with.
struct JacobianCase {
  const char* name;
  std::vector<std::string> overrides;
  const char* label;
};

class JacobianCaseTest : public ::testing::Test {
 public:
  explicit JacobianCaseTest(std::function<void()> body) : body_(std::move(body)) {}
  void TestBody() override { body_(); }

 private:
  std::function<void()> body_;
};

//! Registers Jacobian.<name> for every case, each running check(overrides, label): a
//! table of cases instead of a TEST that repeats the call for each.
template <class Check>
bool register_jacobian_cases(const std::vector<JacobianCase>& cases, Check check) {
  for (const JacobianCase& c : cases)
    ::testing::RegisterTest(
        "Jacobian", c.name, nullptr, nullptr, __FILE__, __LINE__,
        [c, check]() -> ::testing::Test* {
          return new JacobianCaseTest([c, check] { check(c.overrides, c.label); });
        });
  return true;
}

// The transport and the gas.
const bool kTransportCases = register_jacobian_cases(
    {
        {"TransportDriftAndDiffusion", {}, "drift + diffusion"},
        {"DiffusionAlone", {"transport.drift=false"}, "diffusion alone"},
        {"DriftAlone", {"transport.diffusion=false"}, "drift alone"},
        // The limited (van Leer) advection widens the stencil to the far upwind cell:
        // its entries come from the limiter's analytic derivative, checked here against
        // FD on states perturbed by +-30 % per cell, so both branches of the limiter
        // (ab > 0 and ab <= 0) occur.
        {"DriftVanLeer",
         {"transport.diffusion=false", "transport.advection=\"van_leer\""},
         "drift alone, van Leer"},
        {"DriftAndDiffusionVanLeerEvolvingGas",
         {"transport.advection=\"van_leer\"", "gas.evolve=true"},
         "drift + diffusion + viscous gas, van Leer"},
        // transport.face_stokes = "upwind": each cell's dust at its own St's speed
        {"DriftUpwindStokes",
         {"transport.face_stokes=\"upwind\""},
         "drift + diffusion, upwind St"},
        {"DriftUpwindStokesEvolvingGas",
         {"transport.face_stokes=\"upwind\"", "gas.evolve=true"},
         "drift + diffusion + viscous gas, upwind St"},
        {"ViscousGasAlone",
         {"gas.evolve=true", "transport.drift=false", "transport.diffusion=false"},
         "viscous gas alone"},
        {"ViscousGasAndDustTogether", {"gas.evolve=true"}, "viscous gas + dust"},
        {"LbpDiskWithEvolvingGas",
         {"gas.evolve=true", "disk.model=\"lbp\"", "disk.r_c_au=20.0"},
         "lbp + viscous gas"},
    },
    expect_exact);

}  // namespace

namespace {

//! A state with grown particles: m from 1e-10 g to 1e12 g and phi from 1 to 1e-4 across
//! the grid (inside and outside the snow line), so every regime of the rates is visited.
std::vector<double> grown_state(const Simulation& sim, unsigned seed) {
  auto y = perturbed_state(sim, seed);
  const auto& L = sim.model().layout();
  const int n = L.n_cells();
  const auto sd = L.find_cell_var("sigma_d"), qm = L.find_cell_var("q_m"),
             qp = L.find_cell_var("q_phi");
  for (int i = 0; i < n; ++i) {
    const double f = double(i) / (n - 1);
    const double sigma = y[L.index(i, *sd)];
    y[L.index(i, *qm)] = sigma * (std::log(1e-10 / 6e-15) + f * std::log(1e22));
    if (qp) y[L.index(i, *qp)] = sigma * f * std::log(1e4);
  }
  return y;
}

//! refresh: the particle laws' eta and gas velocity first set from the state's gas
//! (Simulation::refresh_local_gas, as at a snapshot of a run on evolving gas).
void expect_exact_growth(const std::vector<std::string>& overrides, const char* label,
                         bool refresh = false) {
  std::vector<std::string> sets{"growth.enabled=true", "grid.r_in_au=1.0"};
  sets.insert(sets.end(), overrides.begin(), overrides.end());
  Simulation sim(scene(sets));
  for (unsigned seed : {1u, 2u}) {
    const std::vector<double> y = grown_state(sim, seed);
    if (refresh) sim.refresh_local_gas(y);
    const auto c = compare_with_fd(sim, y);
    expect_matches_fd(c, sim.model().layout(), label, seed,
                      1e-7);  // measured at most 1.4e-8
  }
}

}  // namespace

namespace {

// The growth model, its outcomes and the planetesimal channels.
const bool kGrowthCases = register_jacobian_cases(
    {
        {"GrowthCompactParticles", {}, "growth, phi = 1"},
        {"GrowthPorous", {"porosity.enabled=true"}, "porous growth"},
        {"GrowthPorousErosionHalt",
         {"porosity.enabled=true", "erosion.model=\"halt\""},
         "erosion halt"},
        {"GrowthPorousErosionBalance",
         {"porosity.enabled=true", "erosion.model=\"balance\""},
         "erosion balance"},
        {"GrowthFragmentationBouncing",
         {"fragmentation.enabled=true", "bouncing.enabled=true"},
         "fragmentation + bouncing"},
        // With porosity off and bouncing on (above) every particle has phi = 1 and
        // bounces, so the growth terms nearly vanish; the cases below have the porous
        // state of grown_state (phi from 1 to 1e-4 across the grid), so fragmentation
        // (v_frag of 10 m/s, crossed by the grown cells), its combination with erosion
        // E2 and the bouncing switch at phi_bounce are each exercised.
        {"GrowthPorousFragmentation",
         {"porosity.enabled=true", "fragmentation.enabled=true",
          "fragmentation.v_frag_ice_m_s=10.0", "fragmentation.v_frag_sil_m_s=10.0"},
         "porous fragmentation"},
        {"GrowthPorousErosionBalanceFragmentation",
         {"porosity.enabled=true", "erosion.model=\"balance\"", "erosion.f_s=0.95",
          "fragmentation.enabled=true", "fragmentation.v_frag_ice_m_s=10.0",
          "fragmentation.v_frag_sil_m_s=10.0"},
         "erosion balance + fragmentation"},
        // halt stops growth but not the fragmentation loss: S (frag)_+ + (frag -
        // (frag)_+)
        {"GrowthPorousErosionHaltFragmentation",
         {"porosity.enabled=true", "erosion.model=\"halt\"", "erosion.v_eros_m_s=20.0",
          "fragmentation.enabled=true", "fragmentation.v_frag_ice_m_s=10.0",
          "fragmentation.v_frag_sil_m_s=10.0"},
         "erosion halt + fragmentation"},
        {"GrowthPorousBouncing",
         {"porosity.enabled=true", "bouncing.enabled=true"},
         "porous bouncing"},
        {"GrowthEpsteinDrag",
         {"porosity.enabled=true", "growth.drag_law=\"epstein\""},
         "Epstein drag"},
        {"PlanetesimalsDirectCoagulation",
         {"porosity.enabled=true", "planetesimals.coagulation=true"},
         "planetesimals, direct coagulation"},
        {"PlanetesimalsStreamingInstabilityD16",
         {"porosity.enabled=true", "planetesimals.si=\"d16\"", "dust.dust_to_gas=0.5"},
         "planetesimals, SI d16"},
        {"PlanetesimalsStreamingInstabilityS18",
         {"planetesimals.si=\"s18\"", "planetesimals.coagulation=true",
          "dust.dust_to_gas=0.5"},
         "planetesimals, SI s18 + coagulation"},
        // Z = 0.006 sits inside the smooth threshold Z_crit(St) = 0.4-0.8% over the St
        // range
        {"PlanetesimalsStreamingInstabilityZcrit",
         {"porosity.enabled=true", "planetesimals.si=\"zcrit\"",
          "dust.dust_to_gas=0.006"},
         "planetesimals, SI zcrit"},
    },
    [](const std::vector<std::string>& overrides, const char* label) {
      expect_exact_growth(overrides, label);
    });

}  // namespace

// Growth on evolving gas: the particle laws depend on Sigma_g through rho_g, the mean
// free path and nu_mol (St, the relative speeds, the small projectiles' St, the SI
// triggers), so the growth, Stokes and planetesimal blocks have d/dSigma_g entries
// (CellGas::at_ad). Read at its value instead, the gas left them out: errors 0.36
// (porous) and 0.55 (compact) relative in those entries.
TEST(Jacobian, GrowthOnEvolvingGas) {
  expect_exact_growth({"gas.evolve=true"}, "growth, phi = 1, evolving gas");
  expect_exact_growth({"gas.evolve=true", "porosity.enabled=true"},
                      "porous growth, evolving gas");
}

// ... with eta and v_g set from a perturbed gas (+-30 % per cell): v_g enters the
// collision speeds (spec §3 item 2), eta the drag, speeds and floors, as parameters.
TEST(Jacobian, GrowthOnRefreshedEvolvingGas) {
  expect_exact_growth({"gas.evolve=true", "porosity.enabled=true",
                       "erosion.model=\"balance\"", "planetesimals.coagulation=true"},
                      "porous growth, E2, planetesimals, refreshed gas", true);
}

TEST(Jacobian, ErosionAndPlanetesimalsOnEvolvingGas) {
  expect_exact_growth({"gas.evolve=true", "porosity.enabled=true",
                       "erosion.model=\"balance\"", "planetesimals.coagulation=true",
                       "planetesimals.si=\"d16\"", "dust.dust_to_gas=0.5"},
                      "E2 erosion + planetesimals (coagulation, d16), evolving gas");
  expect_exact_growth(
      {"gas.evolve=true", "planetesimals.si=\"zcrit\"", "dust.dust_to_gas=0.006"},
      "SI zcrit, evolving gas");
}

// The limited advection with passengers (Q_m, Q_phi) through the snow line, where the
// received flows of Q_m mix in the flow of Sigma_d: the far-cell entries of every row.
TEST(Jacobian, GrowthSnowLineVanLeer) {
  expect_exact_growth(
      {"porosity.enabled=true", "snowline.enabled=true",
       "transport.advection=\"van_leer\"", "pebbles.radii_au=[3.0, 10.0]"},
      "growth + snow line + monitors, van Leer");
}

// The Jacobian at a state the fiducial run actually reaches (params/fiducial.toml, 100
// cells, t = 1000 yr: planetesimals forming inside the snow line, compacting aggregates,
// monomers outside; the per-cell St and rate caches warm), where CVODE reports Newton
// convergence failures: it must be as exact there as at the constructed states.
TEST(Jacobian, FiducialStateMidRun) {
  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> sets{"grid.n_cells=100"};
  Simulation sim(load_scene(file, sets));
  const std::vector<double> y = evolved_state(sim, 1e3);
  const auto c = compare_with_fd(sim, y);
  expect_matches_fd(c, sim.model().layout(), "fiducial state at 1000 yr", 0,
                    5e-7);  // measured 6.3e-8
}

// DiskModel::set_active (operator-splitting studies, tests/bench/bench_split.cpp): the
// right-hand side and Jacobian of the whole model are the sums of those of a split of its
// modules, and clearing the filter gives the whole model back.
TEST(DiskModelActive, SplitModulesSumToTheWholeModel) {
  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> sets{"grid.n_cells=60"};
  Simulation sim(load_scene(file, sets));
  const std::vector<double> y = evolved_state(sim, 300.0);  // growing, converting cells
  DiskModel& model = sim.model();
  const auto n = y.size();
  const auto nnz = static_cast<std::size_t>(model.pattern().nnz());
  const auto local = [](std::string_view m) {
    return m == "porous_growth" || m == "planetesimals";
  };
  std::vector<double> f_all(n), f_loc(n), f_tr(n), f_back(n);
  std::vector<double> j_all(nnz), j_loc(nnz), j_tr(nnz);
  model.rhs(0.0, y, f_all);
  model.jacobian(0.0, y, j_all);
  model.set_active(local);
  model.rhs(0.0, y, f_loc);
  model.jacobian(0.0, y, j_loc);
  model.set_active([&](std::string_view m) { return !local(m); });
  model.rhs(0.0, y, f_tr);
  model.jacobian(0.0, y, j_tr);
  model.set_active(nullptr);
  model.rhs(0.0, y, f_back);
  int local_nonzero = 0, transport_nonzero = 0;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_NEAR(f_loc[i] + f_tr[i], f_all[i], 1e-12 * std::abs(f_all[i]) + 1e-300) << i;
    EXPECT_EQ(f_back[i], f_all[i]) << i;
    local_nonzero += f_loc[i] != 0.0;
    transport_nonzero += f_tr[i] != 0.0;
  }
  for (std::size_t k = 0; k < nnz; ++k)
    EXPECT_NEAR(j_loc[k] + j_tr[k], j_all[k], 1e-12 * std::abs(j_all[k]) + 1e-300) << k;
  // both parts act: the split is not trivially "everything in one part"
  EXPECT_GT(local_nonzero, 60);
  EXPECT_GT(transport_nonzero, 60);
}

// CellRangeModel (block-local time stepping, tests/bench/cell_range_model.hpp): on the
// rows of cells [lo, hi), and of each global whose row reads only cells in [lo, hi), the
// same bits as the whole model's rhs() and jacobian(), at a state with growing,
// compacting and converting cells, across the snow line and a pebble-flux monitor.
TEST(DiskModelCells, RangeRowsEqualTheWholeModel) {
  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> sets{"grid.n_cells=60", "pebbles.radii_au=[3.0, 10.0]"};
  Simulation sim(load_scene(file, sets));
  const std::vector<double> y = evolved_state(sim, 300.0);
  const DiskModel& model = sim.model();
  const bench::CellRangeModel cells(model);
  const StateLayout& L = model.layout();
  const int n = L.n_cells();
  const auto cp = model.pattern().col_ptr();
  const auto ri = model.pattern().row_index();
  // per global: the cells its row reads
  std::vector<int> g_lo(L.n_global_vars(), n), g_hi(L.n_global_vars(), -1);
  for (long c = 0; c < L.size(); ++c)
    for (long p = cp[c]; p < cp[c + 1]; ++p)
      if (const long g = ri[p] - L.global_index(0); g >= 0 && L.cell_of(c) >= 0) {
        g_lo[g] = std::min(g_lo[g], L.cell_of(c));
        g_hi[g] = std::max(g_hi[g], L.cell_of(c));
      }
  std::vector<double> f_all(y.size()), j_all(model.pattern().nnz());
  model.rhs(0.0, y, f_all);
  model.jacobian(0.0, y, j_all);
  const auto in_range = [&](long row, int lo, int hi) {
    const int cell = L.cell_of(row);
    if (cell >= 0) return cell >= lo && cell < hi;
    const long g = row - L.global_index(0);
    return g_hi[g] >= 0 && g_lo[g] >= lo && g_hi[g] < hi;
  };
  int globals_checked = 0;
  for (const auto& [lo, hi] : {std::pair{0, 60},
                               {0, 17},
                               {17, 40},
                               {40, 60},
                               {59, 60},
                               {1, 2},
                               {5, 45},
                               {30, 31}}) {
    std::vector<double> f(y.size(), 7.0), j(model.pattern().nnz(), 7.0);  // stale junk
    cells.rhs_cells(0.0, y, f, lo, hi);
    cells.jacobian_cells(0.0, y, j, lo, hi);
    int rows = 0;
    for (long r = 0; r < L.size(); ++r)
      if (in_range(r, lo, hi)) {
        EXPECT_EQ(f[r], f_all[r])
            << L.describe(r) << ", cells [" << lo << ", " << hi << ")";
        ++rows;
        globals_checked += L.cell_of(r) < 0;
      }
    EXPECT_GE(rows, (hi - lo) * L.n_cell_vars());
    for (long c = 0; c < L.size(); ++c) {
      for (long p = cp[c]; p < cp[c + 1]; ++p) {
        if (!in_range(ri[p], lo, hi)) continue;
        EXPECT_EQ(j[p], j_all[p]) << "d(" << L.describe(ri[p]) << ")/d(" << L.describe(c)
                                  << "), cells [" << lo << ", " << hi << ")";
      }
    }
  }
  // the range checks reach the booked globals (r_in's outflow, the snow line's
  // sublimation, the monitors), not only the whole-grid range
  EXPECT_GT(globals_checked, L.n_global_vars());
  std::vector<double> f(y.size());
  EXPECT_THROW(cells.rhs_cells(0.0, y, f, 5, 4), std::invalid_argument);
  EXPECT_THROW(cells.rhs_cells(0.0, y, f, 0, n + 1), std::invalid_argument);
}
