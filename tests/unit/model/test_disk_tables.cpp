// The radial-structure keys of a scene (disk.model = "table", disk.alpha_profile,
// disk.sigma_norm, disk.sigma_bump): the files read relative to the scene, and every bad
// input refused by name: key, value, what is wrong, the fix.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "src/core/units.hpp"
#include "src/model/scene_to_physics.hpp"
#include "src/model/scene_validation.hpp"
#include "tests/unit/support/config_error.hpp"

using namespace panoptic;

namespace {

class DiskTables : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("panoptic_disk_tables_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir_ / "tables");
    write("tables/disk.csv",
          "r_au,sigma_g_gcm2,T_K\n0.5,4808.32,395.98\n1,1700,280\n500,0.152,12.52\n");
    write("tables/alpha.csv", "r_au,alpha\n0.5,1e-3\n10,1e-4\n500,1e-3\n");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  // the scene `text` in the test directory, loaded and validated
  Config scene(const std::string& text) {
    write("scene.toml", text);
    Config cfg = load_scene(dir_ / "scene.toml");
    validate_scene(cfg);
    return cfg;
  }
  // the message of the error of scene `text`, which must name every one of `parts`
  void expect_error(const std::string& text, const std::vector<std::string>& parts) {
    const std::string msg = config_error_message([&] { scene(text); }, text);
    for (const auto& p : parts)
      EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  }
  std::filesystem::path dir_;
};

const std::string kTable =
    "[disk]\nmodel = \"table\"\ntable_file = \"tables/disk.csv\"\n";

}  // namespace

TEST_F(DiskTables, ReadsTheFilesRelativeToTheScene) {
  const Config cfg =
      scene(kTable + "alpha_profile = \"table\"\nalpha_file = \"tables/alpha.csv\"\n");
  const auto disk = make_disk(disk_params_from_config(cfg));
  EXPECT_EQ(disk->name(), "table");
  EXPECT_NEAR(disk->sigma_g(units::kAu), 1700.0, 1e-9);
  EXPECT_NEAR(disk->temperature(units::kAu), 280.0, 1e-9);
  EXPECT_NEAR(disk->alpha(10.0 * units::kAu), 1e-4, 1e-16);
}

TEST_F(DiskTables, ASetPathIsRelativeToTheCurrentDirectory) {
  // a path on the command line reads as the shell sees it, not from the scene's folder
  const auto from_here = std::filesystem::relative(dir_ / "tables/disk.csv");
  write("scene.toml", "[disk]\nmodel = \"table\"\n");
  const std::vector<std::string> set{"disk.table_file=\"" + from_here.string() + "\""};
  const Config cfg = load_scene(dir_ / "scene.toml", set);
  validate_scene(cfg);
  EXPECT_NEAR(make_disk(disk_params_from_config(cfg))->sigma_g(units::kAu), 1700.0, 1e-9);
  // and "tables/disk.csv", which the scene file reads from its own folder
  // (ReadsTheFilesRelativeToTheScene), is not found from the current directory
  ASSERT_FALSE(std::filesystem::exists("tables/disk.csv"));
  const std::vector<std::string> from_scene{"disk.table_file=\"tables/disk.csv\""};
  const std::string msg = config_error_message(
      [&] { validate_scene(load_scene(dir_ / "scene.toml", from_scene)); }, "--set");
  EXPECT_NE(msg.find("cannot open tables/disk.csv"), std::string::npos) << msg;
}

TEST_F(DiskTables, RefusesATemperatureRisingAcrossTheSnowLine) {
  // T falls to T_sub = 170 K inside 2 au and rises above it again at 50 au: two snow
  // lines
  write("warm.csv",
        "r_au,sigma_g_gcm2,T_K\n0.5,100,400\n2,100,150\n50,100,200\n"
        "500,100,100\n");
  expect_error("[disk]\nmodel = \"table\"\ntable_file = \"warm.csv\"\n",
               {"disk.table_file", "row 3 (r = 50 au) has T = 200 K", "above disk.T_sub",
                "snowline.enabled = false"});
  // with the snow line off the same table is a disk
  scene(
      "[disk]\nmodel = \"table\"\ntable_file = \"warm.csv\"\n"
      "[snowline]\nenabled = false\n");
}

TEST_F(DiskTables, RefusesBadTables) {
  expect_error("[disk]\nmodel = \"table\"\n",
               {"disk.table_file", "names no file", "r_au,sigma_g_gcm2,T_K"});
  expect_error("[disk]\nmodel = \"table\"\ntable_file = \"nope.csv\"\n",
               {"disk.table_file = \"nope.csv\"", "cannot open", "nope.csv"});
  write("unsorted.csv", "r_au,sigma_g_gcm2,T_K\n0.5,1,1\n600,1,1\n300,1,1\n");
  expect_error("[disk]\nmodel = \"table\"\ntable_file = \"unsorted.csv\"\n",
               {"disk.table_file", "row 3", "strictly increasing", "sort the rows"});
  write("zero.csv", "r_au,sigma_g_gcm2,T_K\n0.5,1,1\n600,0,1\n");
  expect_error("[disk]\nmodel = \"table\"\ntable_file = \"zero.csv\"\n",
               {"disk.table_file", "row 2", "sigma_g_gcm2 must be a finite number > 0"});
  write("units.csv", "r_au,sigma_g,T_K\n0.5,1,1\n600,1,1\n");
  expect_error("[disk]\nmodel = \"table\"\ntable_file = \"units.csv\"\n",
               {"unknown column \"sigma_g\"", "r_au,sigma_g_gcm2,T_K"});
  write("short.csv", "r_au,sigma_g_gcm2,T_K\n2,1,1\n100,1,1\n");
  expect_error("[disk]\nmodel = \"table\"\ntable_file = \"short.csv\"\n",
               {"disk.table_file", "covers r = 2 to 100 au", "grid.r_in_au = 1",
                "extend the table or narrow the grid"});
}

TEST_F(DiskTables, RefusesBadAlphaProfiles) {
  expect_error("[disk]\nalpha_profile = \"table\"\n",
               {"disk.alpha_file", "names no file"});
  write("big.csv", "r_au,alpha\n0.5,1e-3\n30,2\n600,1e-3\n");
  expect_error("[disk]\nalpha_profile = \"table\"\nalpha_file = \"big.csv\"\n",
               {"disk.alpha_file", "row 2 (r = 30 au) has alpha = 2", "fix the row"});
  expect_error(
      "[disk]\nalpha = 1e-3\nalpha_profile = \"gaussian\"\nalpha_bump_amplitude = "
      "-0.999999999\n",
      {"disk.alpha_bump_amplitude", "outside [1e-08, 1]",
       "make the bump or dip shallower"});
  expect_error("[disk]\nalpha_profile = \"gaussian\"\nalpha_bump_amplitude = -1\n",
               {"disk.alpha_bump_amplitude = -1", "> -1"});
  expect_error("[disk]\nsigma_bump = \"gaussian\"\nsigma_bump_width_au = 0\n",
               {"disk.sigma_bump_width_au = 0", "> 0"});
}

TEST_F(DiskTables, PowerLawByItsMass) {
  const Config cfg = scene("[disk]\nsigma_norm = \"mass\"\nm_gas_msun = 0.02\n");
  const auto disk = make_disk(disk_params_from_config(cfg));
  const double r_in = cfg.real("grid.r_in_au") * units::kAu;
  const double r_out = cfg.real("grid.r_out_au") * units::kAu;
  EXPECT_NEAR(disk->mass_between(r_in, r_out) / (0.02 * units::kMsun), 1.0, 1e-14);
  // the other normalisation's key is not read: a warning names the switch
  write("scene.toml", "[disk]\nsigma_norm = \"mass\"\nsigma_1au = 100\n");
  const auto w = unused_key_warnings(load_scene(dir_ / "scene.toml"));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("disk.sigma_1au = 100"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("disk.sigma_norm = \"mass\""), std::string::npos) << w[0];
}
