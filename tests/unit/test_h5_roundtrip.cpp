// HDF5 round trip: what RunOutput writes (root attributes, static datasets, time-stacked
// snapshot fields, series, solver statistics) reads back bit for bit, with its units and
// description attributes, and an existing file is refused unless overwrite is asked for.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "src/cvode_integrator.hpp"
#include "src/error.hpp"
#include "src/h5.hpp"
#include "src/run_output.hpp"

using namespace panoptic;
namespace fs = std::filesystem;

namespace {

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "panoptic_h5_roundtrip";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  fs::remove(p);
  return p;
}

}  // namespace

TEST(H5RoundTrip, EverythingWrittenReadsBackExactly) {
  const fs::path path = temp_file("run.h5");
  const std::vector<double> r_c{1.0, 2.0, 3.5};
  // values that stress the binary round trip: extremes, NaN, negative zero
  const std::vector<double> a{1e-300, -0.0, 6.02214076e23};
  const std::vector<double> b{std::nextafter(1.0, 2.0), 1.0 / 3.0,
                              std::numeric_limits<double>::quiet_NaN()};
  {
    RunOutput out(path, false, {"scene_x", "[grid]\nn_cells = 3\n", "abc123", "9.9"});
    out.write_static("grid", "r_c", r_c, "au", "cell centres");
    out.add_field("sigma_d", 3, "g cm^-2", "dust");
    out.add_field("m_dust", 0, "g", "dust mass");
    out.write_snapshot(0.0, {{"sigma_d", a}, {"m_dust", {42.0}}});
    out.write_snapshot(1e6, {{"sigma_d", b}, {"m_dust", {-1.5}}});
    out.add_series("timeseries", "flux", 2, "M_earth Myr^-1", "flux");
    out.append_series("timeseries", "flux", std::vector<double>{1.0, 2.0});
    SolverStats s;
    s.nst = 123;
    s.nje = 7;
    out.write_solver(s, 2.5, "completed");
  }
  h5::quiet_errors();
  h5::Handle f = h5::open_file(path.string(), false);
  EXPECT_EQ(h5::get_attr_string(f.get(), "scene"), "scene_x");
  EXPECT_EQ(h5::get_attr_string(f.get(), "config_toml"), "[grid]\nn_cells = 3\n");
  EXPECT_EQ(h5::get_attr_string(f.get(), "git_sha"), "abc123");
  EXPECT_EQ(h5::get_attr_string(f.get(), "version"), "9.9");

  h5::Handle grid = h5::open_group(f.get(), "grid");
  EXPECT_EQ(h5::read_doubles(grid.get(), "r_c"), r_c);

  h5::Handle snaps = h5::open_group(f.get(), "snapshots");
  EXPECT_EQ(h5::read_doubles(snaps.get(), "time"), (std::vector<double>{0.0, 1e6}));
  EXPECT_EQ(h5::stack_rows(snaps.get(), "sigma_d"), 2u);
  const auto sd = h5::read_doubles(snaps.get(), "sigma_d");
  ASSERT_EQ(sd.size(), 6u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(std::memcmp(&sd[k], &a[k], sizeof(double)), 0) << k;  // bits, -0.0 too
    if (std::isnan(b[k]))
      EXPECT_TRUE(std::isnan(sd[3 + k]));
    else
      EXPECT_EQ(sd[3 + k], b[k]);
  }
  EXPECT_EQ(h5::read_doubles(snaps.get(), "m_dust"), (std::vector<double>{42.0, -1.5}));
  {
    h5::Handle ds(H5Dopen2(snaps.get(), "sigma_d", H5P_DEFAULT), H5Dclose);
    EXPECT_EQ(h5::get_attr_string(ds.get(), "units"), "g cm^-2");
    EXPECT_EQ(h5::get_attr_string(ds.get(), "description"), "dust");
  }
  h5::Handle ts = h5::open_group(f.get(), "timeseries");
  EXPECT_EQ(h5::read_doubles(ts.get(), "flux"), (std::vector<double>{1.0, 2.0}));
  h5::Handle solver = h5::open_group(f.get(), "solver");
  EXPECT_EQ(h5::get_attr_long(solver.get(), "nst"), 123);
  EXPECT_EQ(h5::get_attr_long(solver.get(), "nje"), 7);
  EXPECT_EQ(h5::get_attr_double(solver.get(), "wall_s"), 2.5);
  EXPECT_EQ(h5::get_attr_string(solver.get(), "status"), "completed");
}

TEST(H5RoundTrip, ExistingOutputIsRefusedWithoutOverwrite) {
  const fs::path path = temp_file("exists.h5");
  { RunOutput out(path, false, {"s", "", "", ""}); }
  EXPECT_THROW(RunOutput(path, false, {"s", "", "", ""}), IoError);
  EXPECT_NO_THROW(RunOutput(path, true, {"s", "", "", ""}));
}

TEST(H5RoundTrip, StaticDatasetIsReplacedNotDuplicated) {
  const fs::path path = temp_file("replace.h5");
  {
    RunOutput out(path, false, {"s", "", "", ""});
    out.write_static("summary", "m", std::vector<double>{1.0}, "M_earth", "first");
    out.write_static("summary", "m", std::vector<double>{2.0}, "M_earth", "second");
  }
  h5::Handle f = h5::open_file(path.string(), false);
  h5::Handle g = h5::open_group(f.get(), "summary");
  EXPECT_EQ(h5::read_doubles(g.get(), "m"), (std::vector<double>{2.0}));
}
