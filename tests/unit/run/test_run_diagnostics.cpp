// The run summary and the /timeseries rows of src/run/diagnostics.cpp (spec §8), on a
// state set by hand, against numbers worked out from the scene alone: the fiducial scene
// on 30 log-spaced cells from 2 to 300 au (grid.stretch = 0), so
//   r_f(i) = 2 au 150^(i/30),  r_c(i) = 2 au 150^((i + 1/2)/30)  (geometric means),
// MMSN gas Sigma_g = 1700 (r/au)^-1.5 g cm^-2 and Sigma_d0 = Z Sigma_g, Z = 0.01 outside
// the snow line and (1 - f_ice) 0.01 = 0.005 inside it (r_snow = (280/170)^2 au = 2.713
// au, between r_c(1) = 2.569 and r_c(2) = 3.036 au). The largest initial Sigma_d is then
// that of cell 2, 17 x 3.0365^-1.5 = 3.2129 g cm^-2, not that of cell 0 (8.5
// x 2.1742^-1.5 = 2.6514): the formed threshold is 1e-6 of it (src/io/README.md,
// "Output"), 3.2129e-6 g cm^-2. Sigma_pl is set by hand in a few cells (direct
// coagulation in cells 10-14, the streaming instability in 20-21, values just below the
// threshold in others), the monitors' cumulative masses to chosen fractions of the
// initial dust mass, and the dust to 0.9 of its initial profile; RunDiagnostics::on_step
// sees that state at two times and finish() writes /summary.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "src/io/h5.hpp"
#include "src/io/run_output.hpp"
#include "src/model/simulation.hpp"
#include "src/run/diagnostics.hpp"
#include "src/scene/config.hpp"

namespace panoptic {
namespace {

namespace fs = std::filesystem;

// spec §1.1 (the values of src/core/units.hpp, written here again)
constexpr double kAuCm = 1.496e13, kYrS = 3.156e7, kMearthG = 5.972e27;
constexpr double kPiHere = 3.14159265358979323846;
constexpr int kN = 30;

double face_au(int i) { return 2.0 * std::pow(150.0, double(i) / kN); }
double centre_au(int i) { return 2.0 * std::pow(150.0, (i + 0.5) / kN); }
// annulus area pi (r_f(i+1)^2 - r_f(i)^2) [cm^2]
double area_cm2(int i) {
  const double a = face_au(i) * kAuCm, b = face_au(i + 1) * kAuCm;
  return kPiHere * (b * b - a * a);
}
// initial Sigma_d [g cm^-2]: Z Sigma_g, Z halved inside the snow line (2.713 au)
double sigma_d0(int i) {
  const double r = centre_au(i);
  return (r < 2.7128 ? 0.005 : 0.01) * 1700.0 * std::pow(r, -1.5);
}

double summary_scalar(hid_t g, const std::string& name) {
  const auto v = h5::read_doubles(g, name);
  EXPECT_EQ(v.size(), 1u) << name;
  return v.empty() ? std::nan("") : v[0];
}

std::string units_of(hid_t g, const std::string& name) {
  h5::Handle ds(H5Dopen2(g, name.c_str(), H5P_DEFAULT), H5Dclose);
  return h5::get_attr_string(ds.get(), "units");
}

TEST(RunDiagnostics, SummaryOfAStateSetByHand) {
  const std::string scene = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> sets{"grid.n_cells=30",         "grid.r_in_au=2.0",
                                      "grid.stretch=0.0",        "output.t_end_yr=1000.0",
                                      "output.t_first_yr=100.0", "output.n_snapshots=2"};
  const Simulation sim(load_scene(scene, sets));
  const auto& L = sim.model().layout();
  const int sd = *L.find_cell_var("sigma_d");
  const int coag = *L.find_cell_var("sigma_pl_coag"),
            si = *L.find_cell_var("sigma_pl_si");
  ASSERT_EQ(L.n_cells(), kN);
  for (int i = 0; i <= kN; ++i)
    ASSERT_NEAR(sim.grid().r_f(i) / kAuCm / face_au(i), 1.0, 1e-13) << "face " << i;
  const std::vector<double> y0 = sim.initial_state();
  for (int i = 0; i < kN; ++i)  // the set-up: the initial profile as worked out above
    ASSERT_NEAR(y0[L.index(i, sd)] / sigma_d0(i), 1.0, 1e-12) << "cell " << i;

  double m0 = 0.0;  // initial dust mass [g]
  for (int i = 0; i < kN; ++i) m0 += sigma_d0(i) * area_cm2(i);
  const double thr = 1e-6 * sigma_d0(2);  // 3.2129e-6 g cm^-2 (the largest: cell 2)

  // Sigma_pl by channel: above the threshold in coag 10-14 and si 20-21; at or below it
  // in coag 9 (0.9 thr), 15 (exactly thr: not above) and si 25 (0.5 thr)
  std::vector<double> pl_coag(kN, 0.0), pl_si(kN, 0.0);
  for (int i = 10; i <= 14; ++i) pl_coag[i] = 3.0 * thr;
  pl_coag[9] = 0.9 * thr;
  pl_coag[15] = thr;
  pl_si[20] = pl_si[21] = 5.0 * thr;
  pl_si[25] = 0.5 * thr;
  double m_coag = 0.0, m_si = 0.0;
  for (int i = 0; i < kN; ++i) {
    m_coag += pl_coag[i] * area_cm2(i);
    m_si += pl_si[i] * area_cm2(i);
  }

  // the monitors: cumulative masses 0.02 m0 through r_in, 0.01 m0 through the snow line
  // (their variables are in units of the initial dust mass)
  int snow = -1, inner = -1;
  const auto& mons = sim.pebble_monitors();
  for (std::size_t k = 0; k < mons.size(); ++k) {
    if (mons[k].name == "snow line") snow = int(k);
    if (mons[k].name == "r_in") inner = int(k);
  }
  ASSERT_GE(snow, 0);
  ASSERT_GE(inner, 0);

  // y1: coag formed only; y2: both channels, the dust at 0.9 of its initial profile
  std::vector<double> y1 = y0;
  for (int i = 0; i < kN; ++i) y1[L.index(i, coag)] = pl_coag[i];
  std::vector<double> y2 = y1;
  for (int i = 0; i < kN; ++i) {
    y2[L.index(i, si)] = pl_si[i];
    y2[L.index(i, sd)] = 0.9 * y0[L.index(i, sd)];
  }
  y2[L.global_index(mons[inner].global_slot)] = 0.02;
  y2[L.global_index(mons[snow].global_slot)] = 0.01;

  const fs::path dir = fs::temp_directory_path() / "panoptic_run_diagnostics";
  fs::create_directories(dir);
  const fs::path path = dir / "summary.h5";
  fs::remove(path);
  // samples: 10 linear ones up to the first snapshot at 100 yr, 10 log-spaced to 1000 yr
  const double t1 = 5.0 * kYrS;     // before the first sample time (10 yr): no row taken
  const double t2 = 70.0 * kYrS;    // after 7 of them: one row, at t2
  const double t3 = 1000.0 * kYrS;  // t_end
  {
    RunOutput out(path, false, {"fiducial", "", "", ""});
    RunDiagnostics diag(sim, out, 0.0);
    out.start_appending();
    diag.on_step(t1, y1);
    diag.on_step(t2, y2);
    diag.finish(t3, y2);
  }

  h5::quiet_errors();
  h5::Handle f = h5::open_file(path.string(), false);
  h5::Handle s = h5::open_group(f.get(), "summary");

  // the threshold: 1e-6 of the largest initial Sigma_d (cell 2, not cell 0)
  EXPECT_NEAR(summary_scalar(s.get(), "formed_threshold") / thr, 1.0, 1e-12);
  // masses [M_earth]: sum of Sigma_pl x annulus area, over every cell
  EXPECT_NEAR(summary_scalar(s.get(), "m_pl_coag") / (m_coag / kMearthG), 1.0, 1e-12);
  EXPECT_NEAR(summary_scalar(s.get(), "m_pl_si") / (m_si / kMearthG), 1.0, 1e-12);
  // the zones [au]: centres of the first and last cells above the threshold
  //   coag: r_c(10) = 11.5521, r_c(14) = 22.5324 au; si: r_c(20) = 61.3798, r_c(21) =
  //   72.5374 au
  EXPECT_NEAR(summary_scalar(s.get(), "r_min_pl_coag"), centre_au(10), 1e-12 * 11.55);
  EXPECT_NEAR(summary_scalar(s.get(), "r_max_pl_coag"), centre_au(14), 1e-12 * 22.53);
  EXPECT_NEAR(summary_scalar(s.get(), "r_min_pl_si"), centre_au(20), 1e-12 * 61.38);
  EXPECT_NEAR(summary_scalar(s.get(), "r_max_pl_si"), centre_au(21), 1e-12 * 72.54);
  // first formation [yr]: coag cells at t1 = 5 yr (a step that took no sample), the si
  // cells at t2 = 70 yr, every other cell never (NaN)
  const auto t_first = h5::read_doubles(s.get(), "t_first_pl");
  ASSERT_EQ(t_first.size(), std::size_t(kN));
  for (int i = 0; i < kN; ++i) {
    if (i >= 10 && i <= 14) {
      EXPECT_NEAR(t_first[i], 5.0, 1e-12) << "cell " << i;
    } else if (i == 20 || i == 21) {
      EXPECT_NEAR(t_first[i], 70.0, 1e-12) << "cell " << i;
    } else {
      EXPECT_TRUE(std::isnan(t_first[i])) << "cell " << i << ": " << t_first[i];
    }
  }
  // pebble masses [M_earth] through r_in and through the snow line
  EXPECT_NEAR(summary_scalar(s.get(), "m_peb_r_in") / (0.02 * m0 / kMearthG), 1.0, 1e-12);
  EXPECT_NEAR(summary_scalar(s.get(), "m_peb_snowline") / (0.01 * m0 / kMearthG), 1.0,
              1e-12);
  // the dust left, and the budget: dust 0.9 m0 + planetesimals + 0.02 m0 through r_in
  // (nothing sublimated) = 0.92 m0 + m_pl, so |sum - m0| / m0 = 0.08 - m_pl/m0
  const double m_dust = 0.9 * m0;
  EXPECT_NEAR(summary_scalar(s.get(), "m_dust_final") / (m_dust / kMearthG), 1.0, 1e-12);
  const double err = 0.08 - (m_coag + m_si) / m0;
  EXPECT_NEAR(summary_scalar(s.get(), "budget_error") / err, 1.0, 1e-10);
  EXPECT_EQ(units_of(s.get(), "m_pl_coag"), "M_earth");
  EXPECT_EQ(units_of(s.get(), "r_min_pl_si"), "au");
  EXPECT_EQ(units_of(s.get(), "t_first_pl"), "yr");
  EXPECT_EQ(units_of(s.get(), "m_peb_snowline"), "M_earth");

  // /timeseries: one row at t2 (70 yr) and one at t_end (1000 yr), both of state y2
  h5::Handle ts = h5::open_group(f.get(), "timeseries");
  const auto time = h5::read_doubles(ts.get(), "time");
  ASSERT_EQ(time.size(), 2u);
  EXPECT_NEAR(time[0], 70.0, 1e-12);
  EXPECT_NEAR(time[1], 1000.0, 1e-12);
  // the pebble flux in M_earth Myr^-1: 1 M_earth/Myr = 1.892e14 g/s (spec §8; 5.972e27
  // g / 3.156e13 s = 1.89227e14, hence the 5e-4 tolerance on the spec's rounded value)
  const auto flux_gs = sim.pebble_flux(y2);  // g s^-1, inward positive
  const std::size_t nm = mons.size();
  const auto flux = h5::read_rows(ts.get(), "pebble_flux", 0, 2);
  ASSERT_EQ(flux.size(), 2 * nm);
  EXPECT_EQ(units_of(ts.get(), "pebble_flux"), "M_earth Myr^-1");
  ASSERT_GT(std::abs(flux_gs[inner]), 0.0);
  for (std::size_t k = 0; k < nm; ++k) {
    if (flux_gs[k] != 0.0) {
      EXPECT_NEAR(flux[nm + k] * 1.892e14 / flux_gs[k], 1.0, 5e-4) << mons[k].name;
    }
  }
  // cumulative masses through the monitors [M_earth]
  const auto m_through = h5::read_rows(ts.get(), "m_through", 0, 2);
  EXPECT_EQ(units_of(ts.get(), "m_through"), "M_earth");
  EXPECT_NEAR(m_through[nm + inner] / (0.02 * m0 / kMearthG), 1.0, 1e-12);
  EXPECT_NEAR(m_through[nm + snow] / (0.01 * m0 / kMearthG), 1.0, 1e-12);
  // the budget columns [M_earth]: m_dust, m_pl_coag, m_pl_si, m_out_inner,
  // m_sublimated, then |sum - initial| = (0.08 m0 - m_pl) (positive: dust is missing)
  EXPECT_EQ(h5::get_attr_string(ts.get(), "mass_budget_columns"),
            "m_dust;m_pl_coag;m_pl_si;m_out_inner;m_sublimated;error");
  const auto budget = h5::read_rows(ts.get(), "mass_budget", 0, 2);
  ASSERT_EQ(budget.size(), 12u);
  const double want[6] = {m_dust,    m_coag, m_si,
                          0.02 * m0, 0.0,    0.08 * m0 - (m_coag + m_si)};
  for (int c = 0; c < 6; ++c)
    EXPECT_NEAR(budget[6 + c] * kMearthG, want[c], 1e-10 * m0) << "column " << c;
}

// /grid as Simulation::prepare_output writes it (src/io/README.md, "Output",
// postprocess/reader.py:
// "/grid/r_c, r_f cell centres (N,) and faces (N+1,) [au]; /grid/area (N,) [cm^2]"):
// values and units attributes against the grid worked out above.
TEST(RunDiagnostics, GridIsWrittenInAu) {
  const std::string scene = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> sets{"grid.n_cells=30", "grid.r_in_au=2.0",
                                      "grid.stretch=0.0"};
  const Simulation sim(load_scene(scene, sets));
  const fs::path dir = fs::temp_directory_path() / "panoptic_run_diagnostics";
  fs::create_directories(dir);
  const fs::path path = dir / "grid.h5";
  fs::remove(path);
  {
    RunOutput out(path, false, {"fiducial", "", "", ""});
    out.start_appending();
    sim.prepare_output(out);
  }
  h5::quiet_errors();
  h5::Handle f = h5::open_file(path.string(), false);
  h5::Handle g = h5::open_group(f.get(), "grid");
  EXPECT_EQ(units_of(g.get(), "r_c"), "au");
  EXPECT_EQ(units_of(g.get(), "r_f"), "au");
  EXPECT_EQ(units_of(g.get(), "area"), "cm^2");
  const auto r_c = h5::read_doubles(g.get(), "r_c"),
             r_f = h5::read_doubles(g.get(), "r_f"),
             area = h5::read_doubles(g.get(), "area");
  ASSERT_EQ(r_c.size(), std::size_t(kN));
  ASSERT_EQ(r_f.size(), std::size_t(kN + 1));
  ASSERT_EQ(area.size(), std::size_t(kN));
  for (int i = 0; i <= kN; ++i) EXPECT_NEAR(r_f[i] / face_au(i), 1.0, 1e-13) << i;
  for (int i = 0; i < kN; ++i) {
    EXPECT_NEAR(r_c[i] / centre_au(i), 1.0, 1e-13) << i;
    EXPECT_NEAR(area[i] / area_cm2(i), 1.0, 1e-12) << i;
  }
}

}  // namespace
}  // namespace panoptic
