// Radial structure of the gas disk: tables (disk/radial_table.hpp) against the closed
// forms of the power-law disk (spec §1.2 A, §1.3, §1.7), the alpha profile
// (disk/alpha_profile.hpp) where alpha is used (nu, spec §1.5), the Gaussian Sigma_g
// bump, and the power law normalised by its mass.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "disk/disk_local_gas.hpp"
#include "disk/gas_disk.hpp"
#include "disk/radial_table.hpp"
#include "disk/viscous_gas.hpp"
#include "src/core/units.hpp"
#include "src/solver/grid.hpp"

using namespace panoptic;
using units::kAu;

namespace {

const Star kSun{units::kMsun, units::kLsun};

// The MMSN (1700 r^-1.5, 280 r^-1/2 K) tabulated at `rows` radii from 0.5 to 500 au.
std::vector<std::shared_ptr<const RadialTable>> mmsn_tables(int rows) {
  std::vector<double> r, sigma, t;
  for (int i = 0; i < rows; ++i) {
    const double r_au = 0.5 * std::pow(1000.0, double(i) / (rows - 1));
    r.push_back(r_au * kAu);
    sigma.push_back(1700.0 * std::pow(r_au, -1.5));
    t.push_back(280.0 * std::pow(r_au, -0.5));
  }
  return {std::make_shared<const RadialTable>(r, sigma, "sigma_g"),
          std::make_shared<const RadialTable>(r, t, "T")};
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

}  // namespace

TEST(RadialTable, PowerLawTableReproducesThePowerLaw) {
  // log-log interpolation is exact for a power law: the table disk equals the power-law
  // disk to round-off at any radius, in Sigma_g, T, c_s, nu, the annulus mass and the
  // snow line (spec §1.7: 2.71 au)
  const auto t = mmsn_tables(7);
  const ThermalParams th;
  const TableDisk table(kSun, th, t[0], t[1]);
  const PowerLawDisk law(kSun, th, 1700.0, 1.5);
  double worst = 0.0;
  for (double r_au : {0.5, 0.7, 1.0, 2.71, 9.99, 33.3, 123.0, 500.0}) {
    const double r = r_au * kAu;
    for (auto [a, b] : {std::pair{table.sigma_g(r), law.sigma_g(r)},
                        {table.temperature(r), law.temperature(r)},
                        {table.c_s(r), law.c_s(r)},
                        {table.nu(r), law.nu(r)}})
      worst = std::max(worst, std::abs(a / b - 1.0));
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_NEAR(table.mass_between(0.7 * kAu, 300.0 * kAu) /
                  law.mass_between(0.7 * kAu, 300.0 * kAu),
              1.0, 1e-13);
  EXPECT_NEAR(table.r_snow() / law.r_snow(), 1.0, 1e-13);
  EXPECT_EQ(table.name(), "table");
}

TEST(RadialTable, RefusesBadTables) {
  const std::vector<double> r{1.0, 2.0, 3.0};
  auto make = [](std::vector<double> rr, std::vector<double> v) {
    return [rr, v] { RadialTable t(rr, v, "alpha"); };
  };
  EXPECT_NE(error_of(make({1.0, 3.0, 2.0}, {1, 1, 1})).find("strictly increasing"),
            std::string::npos);
  EXPECT_NE(error_of(make({1.0, 2.0, 2.0}, {1, 1, 1})).find("row 3"), std::string::npos);
  EXPECT_NE(error_of(make(r, {1.0, 0.0, 1.0})).find("alpha must be a finite number > 0"),
            std::string::npos);
  EXPECT_NE(error_of(make(r, {1.0, -1.0, 1.0})).find("row 2"), std::string::npos);
  EXPECT_NE(error_of(make({0.0, 2.0}, {1, 1})).find("radius"), std::string::npos);
  EXPECT_NE(error_of(make({1.0}, {1.0})).find("at least two rows"), std::string::npos);
  const RadialTable t(r, {1.0, 2.0, 4.0}, "alpha");
  EXPECT_THROW(t(0.5), std::out_of_range);
  EXPECT_THROW(t(3.1), std::out_of_range);
  EXPECT_DOUBLE_EQ(t(3.0), 4.0);
  EXPECT_NEAR(t(std::sqrt(2.0)), std::sqrt(2.0), 1e-15);  // power law between rows
}

TEST(RadialTable, ReadsColumnsByNameAndRefusesBadFiles) {
  const auto dir = std::filesystem::temp_directory_path() / "panoptic_radial_table_test";
  std::filesystem::create_directories(dir);
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  const std::vector<std::string> names{"r_au", "sigma_g_gcm2", "T_K"};
  // any column order, comments and blank lines skipped
  const auto cols = read_csv_columns(
      write("ok.csv", "# a disk\nT_K, r_au ,sigma_g_gcm2\n\n280,1,1700\n88.5,10,53.8\n"),
      names);
  ASSERT_EQ(cols.size(), 3u);
  EXPECT_EQ(cols[0], (std::vector<double>{1.0, 10.0}));
  EXPECT_EQ(cols[1], (std::vector<double>{1700.0, 53.8}));
  EXPECT_EQ(cols[2], (std::vector<double>{280.0, 88.5}));
  auto err = [&](const std::string& text) {
    const auto p = write("bad.csv", text);
    return error_of([&] { read_csv_columns(p, names); });
  };
  EXPECT_NE(err("r_au,sigma_g_gcm2\n1,2\n").find("no column \"T_K\""), std::string::npos);
  EXPECT_NE(err("r_au,sigma_g,T_K\n1,2,3\n").find("unknown column \"sigma_g\""),
            std::string::npos);
  EXPECT_NE(err("r_au,sigma_g_gcm2,T_K\n1,2,3\n2,x,3\n").find("bad.csv:3:"),
            std::string::npos);
  EXPECT_NE(err("r_au,sigma_g_gcm2,T_K\n1,2,3\n2,x,3\n").find("not a finite number"),
            std::string::npos);
  EXPECT_NE(err("r_au,sigma_g_gcm2,T_K\n1,2\n").find("2 fields where the header has 3"),
            std::string::npos);
  EXPECT_NE(err("").find("no header line"), std::string::npos);
  EXPECT_NE(
      error_of([&] { read_csv_columns(dir / "missing.csv", names); }).find("cannot open"),
      std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(AlphaProfile, ConstantIsExactlyTheKeyAndGaussianHasItsShape) {
  ThermalParams th;
  th.alpha = 3e-4;
  PowerLawDisk disk(kSun, th, 1700.0, 1.5);
  for (double r_au : {1.0, 10.0, 100.0}) {
    EXPECT_EQ(disk.alpha(r_au * kAu), 3e-4);
    EXPECT_EQ(disk.nu(r_au * kAu), 3e-4 * disk.c_s(r_au * kAu) * disk.h_g(r_au * kAu));
  }
  AlphaProfile dip;
  dip.kind = AlphaProfile::Kind::kGaussian;
  dip.amplitude = -0.9;
  dip.r0 = 10.0 * kAu;
  dip.width = 2.0 * kAu;
  disk.set_alpha_profile(dip);
  EXPECT_NEAR(disk.alpha(10.0 * kAu), 3e-5, 1e-18);  // alpha_0 (1 + A)
  EXPECT_NEAR(disk.alpha(12.0 * kAu), 3e-4 * (1.0 - 0.9 * std::exp(-0.5)), 1e-18);
  EXPECT_NEAR(disk.alpha(50.0 * kAu), 3e-4, 1e-16);
  // nu follows alpha(r) (spec §1.5): the viscosity of an evolving gas and D_g
  const double r = 11.0 * kAu;
  EXPECT_DOUBLE_EQ(disk.nu(r), disk.alpha(r) * disk.c_s(r) * disk.h_g(r));
}

TEST(BumpedDisk, SigmaAndMassOfTheBump) {
  DiskParams p;
  p.star = kSun;
  p.profile.bump_amplitude = 2.0;
  p.profile.bump_r0 = 10.0 * kAu;
  p.profile.bump_width = 1.0 * kAu;
  const auto disk = make_disk(p);
  const PowerLawDisk smooth(kSun, {}, 1700.0, 1.5);
  EXPECT_NEAR(disk->sigma_g(10.0 * kAu) / smooth.sigma_g(10.0 * kAu), 3.0, 1e-14);
  EXPECT_NEAR(disk->sigma_g(30.0 * kAu) / smooth.sigma_g(30.0 * kAu), 1.0, 1e-14);
  EXPECT_EQ(disk->temperature(7.0 * kAu), smooth.temperature(7.0 * kAu));
  // mass against a fine midpoint sum over 5-15 au
  const double r1 = 5.0 * kAu, r2 = 15.0 * kAu;
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = r1 + (i + 0.5) * (r2 - r1) / n;
    sum += disk->sigma_g(r) * 2.0 * units::kPi * r * (r2 - r1) / n;
  }
  EXPECT_NEAR(disk->mass_between(r1, r2) / sum, 1.0, 1e-9);
}

TEST(PowerLawDisk, NormalisedByItsMassBetweenTwoRadii) {
  // disk.sigma_norm = "mass": m between r1 and r2, whatever p (p = 2: the log case)
  for (double p : {0.5, 1.0, 1.5, 2.0, 2.5}) {
    const double m = 0.02 * units::kMsun, r1 = 1.0 * kAu, r2 = 300.0 * kAu;
    const double s1 = PowerLawDisk::sigma_1au_for_mass(m, p, r1, r2);
    EXPECT_NEAR(PowerLawDisk(kSun, {}, s1, p).mass_between(r1, r2) / m, 1.0, 1e-14) << p;
  }
  // the MMSN has 0.0147 M_sun between 1 and 300 au: 2 pi 1700 au^2 (2 sqrt(r)) |_1^300
  const double mmsn =
      2.0 * units::kPi * 1700.0 * kAu * kAu * 2.0 * (std::sqrt(300.0) - 1.0);
  EXPECT_NEAR(PowerLawDisk::sigma_1au_for_mass(mmsn, 1.5, kAu, 300.0 * kAu), 1700.0,
              1e-9);
}

TEST(AlphaProfile, ReachesTheLocalGasAndTheViscosity) {
  // the gas a cell sees (relative velocities V_g^2 ∝ alpha, the dust scale height, spec
  // §2-§3) and the viscous stencil (nu = alpha c_s H, §1.2) take alpha(r), not alpha_0
  DiskParams p;
  p.star = kSun;
  p.alpha.kind = AlphaProfile::Kind::kGaussian;
  p.alpha.amplitude = -0.9;
  p.alpha.r0 = 10.0 * kAu;
  p.alpha.width = 1.0 * kAu;
  const auto disk = make_disk(p);
  const Grid grid(5.0 * kAu, 20.0 * kAu, 64);
  std::vector<double> sigma(grid.n_cells());
  for (int i = 0; i < grid.n_cells(); ++i) sigma[i] = disk->sigma_g(grid.r_c(i));
  const auto gas = local_gas_centres(*disk, grid, sigma);
  const ViscousStencil visc = make_viscous_stencil(*disk, grid, false);
  double lowest = 1.0;
  for (int i = 0; i < grid.n_cells(); ++i) {
    const double r = grid.r_c(i);
    EXPECT_EQ(gas[i].alpha, disk->alpha(r));
    EXPECT_EQ(visc.g_coef[i],
              disk->alpha(r) * disk->c_s(r) * disk->h_g(r) * std::sqrt(r));
    lowest = std::min(lowest, gas[i].alpha);
  }
  EXPECT_LT(lowest, 1.5e-4);  // the dip is on the grid: alpha_0 would fail the checks
}
