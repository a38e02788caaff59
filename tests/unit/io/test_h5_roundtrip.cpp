// HDF5 round trip: what RunOutput writes (root attributes, static datasets, time-stacked
// snapshot fields, series, solver statistics) reads back bit for bit, with its units and
// description attributes, and an existing file is refused unless overwrite is asked for.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/io/h5.hpp"
#include "src/io/run_output.hpp"
#include "src/solver/cvode_integrator.hpp"

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
    out.start_appending();
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
  {
    RunOutput out(path, false, {"s", "", "", ""});
    out.start_appending();
  }
  EXPECT_THROW(RunOutput(path, false, {"s", "", "", ""}), IoError);
  EXPECT_NO_THROW(RunOutput(path, true, {"s", "", "", ""}));
}

// A new output is set up beside its path and moved there by start_appending, in SWMR
// mode: an output dropped before (a set-up that failed, a run killed in it) leaves
// nothing at the path and no stub, and the file that --overwrite replaces is the one at
// the path until then.
TEST(H5RoundTrip, NewOutputAppearsAtItsPathOnlyOnceStarted) {
  const fs::path path = temp_file("staged.h5");
  const fs::path staging = path.string() + ".setup.tmp";
  {
    RunOutput out(path, false, {"first", "", "", ""});
    EXPECT_FALSE(fs::exists(path));
    EXPECT_TRUE(fs::exists(staging));
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(staging));
  {
    RunOutput out(path, false, {"first", "", "", ""});
    out.start_appending();
    EXPECT_TRUE(fs::exists(path));
    EXPECT_FALSE(fs::exists(staging));
    unsigned intent = 0;
    ASSERT_GE(H5Fget_intent(out.file(), &intent), 0);
    EXPECT_NE(intent & H5F_ACC_SWMR_WRITE, 0u);
    EXPECT_TRUE(out.in_swmr_mode());
    out.write_snapshot(0.0, {});
    // the closing attributes: the file leaves SWMR mode first (HDF5 1.10 fails to
    // flush attributes created in it: "slist not empty")
    out.write_solver(SolverStats{}, 1.0, "completed");
    EXPECT_FALSE(out.in_swmr_mode());
    ASSERT_GE(H5Fget_intent(out.file(), &intent), 0);
    EXPECT_EQ(intent & H5F_ACC_SWMR_WRITE, 0u);
  }
  h5::quiet_errors();
  {
    RunOutput out(path, true, {"second", "", "", ""});
    h5::Handle f = h5::open_file(path.string(), false);  // still the first run's file
    EXPECT_EQ(h5::get_attr_string(f.get(), "scene"), "first");
  }
  h5::Handle f = h5::open_file(path.string(), false);  // a dropped set-up left it so
  EXPECT_EQ(h5::get_attr_string(f.get(), "scene"), "first");
}

TEST(H5RoundTrip, StaticDatasetIsReplacedNotDuplicated) {
  const fs::path path = temp_file("replace.h5");
  {
    RunOutput out(path, false, {"s", "", "", ""});
    out.start_appending();
    out.write_static("summary", "m", std::vector<double>{1.0}, "M_earth", "first");
    out.write_static("summary", "m", std::vector<double>{2.0}, "M_earth", "second");
  }
  h5::Handle f = h5::open_file(path.string(), false);
  h5::Handle g = h5::open_group(f.get(), "summary");
  EXPECT_EQ(h5::read_doubles(g.get(), "m"), (std::vector<double>{2.0}));
}

TEST(H5RoundTrip, RootAttributesBeyond64KiBAreWrittenAndReplaced) {
  // config_toml holds the resolved scene, which can exceed the 64 KiB that compact
  // attribute storage allows (6 000 output times: "creating attribute config_toml
  // failed" and a stub file); a restart replaces it, and a failed replacement must not
  // leave the file without one. The copy a restart continues keeps it too.
  const fs::path path = temp_file("big_attr.h5"), copy = temp_file("big_attr_copy.h5");
  const std::string big(200000, 'x'), bigger(300000, 'y');
  {
    RunOutput out(path, false, {"s", big, "", ""});
    out.start_appending();
    EXPECT_EQ(out.root_attr("config_toml"), big);
    out.set_root_attr("config_toml", bigger);
    EXPECT_EQ(out.root_attr("config_toml"), bigger);
    out.set_root_attr("config_toml", "short");
    EXPECT_EQ(out.root_attr("config_toml"), "short");
    out.set_root_attr("config_toml", bigger);
  }
  h5::copy_file(path.string(), copy.string());
  for (const fs::path& p : {path, copy}) {
    h5::Handle f = h5::open_file(p.string(), false);
    EXPECT_EQ(h5::get_attr_string(f.get(), "config_toml"), bigger) << p;
    EXPECT_FALSE(H5Aexists(f.get(), "config_toml.__new") > 0) << p;
  }
}

TEST(H5RoundTrip, CopyFileKeepsEveryRowAttributeAndLostChunk) {
  // A restart continues h5::copy_file's copy of its output (run_output.cpp, rebuild):
  // every dataset, every attribute (the root's too) must come across bit for bit, and a
  // row whose chunk the original has lost must stay lost (unallocated) in the copy, so
  // that the restart still finds it.
  const fs::path path = temp_file("copy_from.h5"), copy = temp_file("copy_to.h5");
  const std::vector<double> row0{1.5, -0.0, 1e-300}, row2{3.0, 4.0, 5.0};
  {
    RunOutput out(path, false, {"scene_c", "[grid]\nn_cells = 3\n", "sha", "1.0"});
    out.start_appending();
    out.write_static("grid", "r_c", std::vector<double>{1.0, 2.0, 3.0}, "au", "centres");
    out.add_field("sigma_d", 3, "g cm^-2", "dust");
    out.write_snapshot(0.0, {{"sigma_d", row0}});
    out.write_snapshot(1.0, {{"sigma_d", row2}});
    out.set_root_attr("restarts", "a note");
    h5::set_attr(out.file(), "a_double", 2.5);
    h5::set_attr(out.file(), "a_long", 7L);
    // A stack whose middle row was never written: its chunk is not allocated.
    h5::Handle g = h5::open_group(out.file(), "snapshots");
    h5::create_stack(g.get(), "gappy", 3, "-", "rows 0 and 2 only");
    h5::append_row(g.get(), "gappy", row0);
    const hsize_t dims[2] = {3, 3};
    h5::Handle ds(H5Dopen2(g.get(), "gappy", H5P_DEFAULT), H5Dclose);
    ASSERT_GE(H5Dset_extent(ds.get(), dims), 0);
    h5::Handle space(H5Dget_space(ds.get()), H5Sclose);
    const hsize_t start[2] = {2, 0}, count[2] = {1, 3};
    H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
    const hsize_t n[1] = {3};
    h5::Handle mem(H5Screate_simple(1, n, nullptr), H5Sclose);
    ASSERT_GE(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, mem.get(), space.get(), H5P_DEFAULT,
                       row2.data()),
              0);
    out.flush();
  }
  h5::copy_file(path.string(), copy.string());
  h5::Handle a = h5::open_file(path.string(), false),
             b = h5::open_file(copy.string(), false);
  for (const char* name :
       {"run_id", "scene", "config_toml", "git_sha", "version", "restarts"})
    EXPECT_EQ(h5::get_attr_string(b.get(), name), h5::get_attr_string(a.get(), name))
        << name;
  EXPECT_EQ(h5::get_attr_double(b.get(), "a_double"), 2.5);
  EXPECT_EQ(h5::get_attr_long(b.get(), "a_long"), 7);
  h5::Handle ga = h5::open_group(a.get(), "snapshots"),
             gb = h5::open_group(b.get(), "snapshots");
  for (const char* name : {"time", "sigma_d", "gappy"}) {
    const auto x = h5::read_doubles(ga.get(), name), y = h5::read_doubles(gb.get(), name);
    ASSERT_EQ(x.size(), y.size()) << name;
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)), 0) << name;
  }
  EXPECT_EQ(h5::stack_rows(gb.get(), "sigma_d"), 2u);
  {
    h5::Handle ds(H5Dopen2(gb.get(), "sigma_d", H5P_DEFAULT), H5Dclose);
    EXPECT_EQ(h5::get_attr_string(ds.get(), "units"), "g cm^-2");
  }
  using Ranges = std::vector<std::pair<hsize_t, hsize_t>>;
  EXPECT_EQ(h5::unallocated_rows(ga.get(), "gappy", 3), (Ranges{{1, 2}}));
  EXPECT_EQ(h5::unallocated_rows(gb.get(), "gappy", 3), (Ranges{{1, 2}}));
  EXPECT_EQ(h5::read_doubles(h5::open_group(b.get(), "grid").get(), "r_c"),
            (std::vector<double>{1.0, 2.0, 3.0}));
}

// What a run checkpoints (src/main.cpp): at each snapshot it notes how many rows each
// dataset has (row_counts) and, when it writes the checkpoint later, takes the digests
// of those rows from the output (first_rows) instead of having copied them at the
// snapshot. Equal to the copy because RunOutput only appends digests: rows written after
// the count (snapshots, series, a series declared later) must not change the answer.
TEST(H5RoundTrip, RowDigestsCountedAtASnapshotAreThoseCopiedThen) {
  const fs::path path = temp_file("digests.h5");
  RunOutput out(path, false, {"s", "", "", ""});
  out.start_appending();
  out.add_field("sigma_d", 2, "g cm^-2", "dust");
  out.add_series("timeseries", "flux", 1, "M_earth Myr^-1", "flux");
  out.write_snapshot(0.0, {{"sigma_d", {1.0, 2.0}}});
  out.append_series("timeseries", "flux", std::vector<double>{0.5});
  out.write_snapshot(1.0, {{"sigma_d", {3.0, 4.0}}});
  const RowDigests copied = out.row_digests();
  const RowCounts counted = row_counts(out.row_digests());
  ASSERT_EQ(copied.at("snapshots/sigma_d").size(), 2u);
  ASSERT_EQ(copied.at("timeseries/flux").size(), 1u);
  out.append_series("timeseries", "flux", std::vector<double>{0.7});
  out.add_series("timeseries", "later", 1, "g", "declared after the count");
  out.append_series("timeseries", "later", std::vector<double>{9.0});
  out.write_snapshot(2.0, {{"sigma_d", {5.0, 6.0}}});
  ASSERT_NE(out.row_digests(), copied);
  EXPECT_EQ(first_rows(out.row_digests(), counted), copied);
  // more rows counted than held: a caller's error, refused
  RowCounts too_many = counted;
  too_many["snapshots/sigma_d"] = 9;
  EXPECT_THROW(first_rows(out.row_digests(), too_many), std::logic_error);
}

// A field declared compressed (the distribution's sigma(r, m)) is written with the
// shuffle and deflate filters, takes less room than its values, reads back bit for bit,
// and keeps its filters in the copy a restart continues (h5::copy_file); an ordinary
// field stays unfiltered, so that the single-size outputs keep their layout.
TEST(H5RoundTrip, CompressedFieldIsDeflatedReadsBackExactlyAndCopiesFiltered) {
  const fs::path path = temp_file("deflated.h5"), copy = temp_file("deflated_copy.h5");
  constexpr std::size_t width = 2000;
  std::vector<double> row(width);
  // a smooth profile up to an empty upper half (the bins growth has not reached), -0.0
  for (std::size_t k = 0; k < width / 2; ++k)
    row[k] = 1e-3 * std::exp(-1e-3 * static_cast<double>(k));
  row[1] = -0.0;
  {
    RunOutput out(path, false, {"scene_z", "[grid]\nn_cells = 3\n", "sha", "1.0"});
    out.start_appending();
    out.add_field("sigma", width, "g cm^-2", "per bin", true);
    out.add_field("sigma_d", 3, "g cm^-2", "dust");
    out.write_snapshot(0.0, {{"sigma", row}, {"sigma_d", {1.0, 2.0, 3.0}}});
    out.write_snapshot(1.0, {{"sigma", row}, {"sigma_d", {1.0, 2.0, 3.0}}});
  }
  h5::copy_file(path.string(), copy.string());
  for (const fs::path& p : {path, copy}) {
    h5::Handle f = h5::open_file(p.string(), false);
    h5::Handle g = h5::open_group(f.get(), "snapshots");
    const auto back = h5::read_doubles(g.get(), "sigma");
    ASSERT_EQ(back.size(), 2 * width) << p;
    EXPECT_EQ(std::memcmp(back.data(), row.data(), width * sizeof(double)), 0) << p;
    EXPECT_EQ(std::memcmp(back.data() + width, row.data(), width * sizeof(double)), 0);
    auto filters = [&](const char* name) {
      h5::Handle ds(H5Dopen2(g.get(), name, H5P_DEFAULT), H5Dclose);
      h5::Handle dcpl(H5Dget_create_plist(ds.get()), H5Pclose);
      std::vector<H5Z_filter_t> ids;
      for (int i = 0; i < H5Pget_nfilters(dcpl.get()); ++i) {
        unsigned flags = 0;
        std::size_t n = 0;
        ids.push_back(H5Pget_filter2(dcpl.get(), static_cast<unsigned>(i), &flags, &n,
                                     nullptr, 0, nullptr, nullptr));
      }
      return std::pair{ids, H5Dget_storage_size(ds.get())};
    };
    const auto [sigma_filters, sigma_bytes] = filters("sigma");
    EXPECT_EQ(sigma_filters,
              (std::vector<H5Z_filter_t>{H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE}))
        << p;
    EXPECT_LT(sigma_bytes, 2 * width * sizeof(double) * 3 / 4) << p;
    EXPECT_TRUE(filters("sigma_d").first.empty()) << p;
  }
}
