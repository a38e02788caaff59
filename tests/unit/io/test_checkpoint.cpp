// Checkpoints (src/io/checkpoint.hpp): the checksum, the atomic write that keeps the
// previous checkpoint, the detection of truncated, flipped and incomplete files with the
// fallback to the previous checkpoint, the compatibility check of a restarted scene, and
// the property restarts rest on: CVODE reinitialised at t equals a new CVODE built at t,
// bit for bit.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/checkpoint.hpp"
#include "src/run/checkpoint_schedule.hpp"
#include "src/run/max_wall.hpp"
#include "src/run/restart.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "src/solver/disk_model.hpp"
#include "src/solver/state_layout.hpp"
#include "tests/unit/support/config_error.hpp"
#include "tests/unit/support/robertson.hpp"

using namespace panoptic;
namespace fs = std::filesystem;

namespace {

std::span<const std::byte> bytes_of(const char* s) {
  return {reinterpret_cast<const std::byte*>(s), std::strlen(s)};
}

Checkpoint sample(double scale = 1.0) {
  Checkpoint c;
  c.t = 1234.5 * units::kYr;
  for (int i = 0; i < 41; ++i) c.y.push_back(scale * (1.0 + i) * 1e-3);
  c.layout_signature = "n_cells=40;cell:sigma_d,;global:m_out_dust,";
  c.n_cells = 40;
  c.snapshot_index = 7;
  c.config_toml = "[grid]\nn_cells = 40\n";
  c.stats.nst = 123;
  c.stats.nfe = 456;
  c.stats.nreinit = 7;
  c.stats.h_last = 3.5e7;
  c.wall_s = 12.5;
  c.output_file = "/tmp/x.h5";
  c.run_id = "0123456789abcdef";
  c.git_sha = "abc";
  c.version = "0.1.0";
  c.row_digests["snapshots/sigma_d"] = {0x0123456789abcdefULL, 0xfedcba9876543210ULL,
                                        static_cast<std::uint64_t>(scale * 1e6)};
  c.row_digests["snapshots/time"] = {1, 2, 3};
  c.row_digests["timeseries/m_through"] = {};
  return c;
}

void expect_same(const Checkpoint& a, const Checkpoint& b) {
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.layout_signature, b.layout_signature);
  EXPECT_EQ(a.n_cells, b.n_cells);
  EXPECT_EQ(a.snapshot_index, b.snapshot_index);
  EXPECT_EQ(a.config_toml, b.config_toml);
  EXPECT_EQ(a.stats.nst, b.stats.nst);
  EXPECT_EQ(a.stats.nfe, b.stats.nfe);
  EXPECT_EQ(a.stats.nreinit, b.stats.nreinit);
  EXPECT_EQ(a.stats.h_last, b.stats.h_last);
  EXPECT_EQ(a.wall_s, b.wall_s);
  EXPECT_EQ(a.output_file, b.output_file);
  EXPECT_EQ(a.run_id, b.run_id);
  EXPECT_EQ(a.row_digests, b.row_digests);
}

//! A fresh directory under the build's temporary space, removed at the end.
class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() /
            ("panoptic_test_checkpoint_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no exception)";
}

//! Offset of the first byte of the contiguous dataset /y in the file.
long y_offset(const fs::path& file) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, "y", H5P_DEFAULT);
  const haddr_t off = H5Dget_offset(d);
  H5Dclose(d);
  H5Fclose(f);
  return static_cast<long>(off);
}

void flip_byte(const fs::path& file, long offset) {
  std::fstream s(file, std::ios::in | std::ios::out | std::ios::binary);
  s.seekg(offset);
  char c = 0;
  s.get(c);
  s.seekp(offset);
  s.put(static_cast<char>(c ^ 0x5a));
}

// ---------------------------------------------------------------------------------------
// Checksum

TEST(CheckpointChecksum, Fnv1aMatchesTheReferenceVectors) {
  // Test vectors of the FNV reference (http://www.isthe.com/chongo/tech/comp/fnv/).
  EXPECT_EQ(fnv1a64(bytes_of("")), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a64(bytes_of("a")), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a64(bytes_of("foobar")), 0x85944171f73967e8ULL);
  // Chaining: hashing in two pieces equals hashing at once.
  EXPECT_EQ(fnv1a64(bytes_of("bar"), fnv1a64(bytes_of("foo"))),
            fnv1a64(bytes_of("foobar")));
}

TEST(CheckpointChecksum, ChangesWithAnyBitOfTheState) {
  const Checkpoint c = sample();
  const std::uint64_t h = checkpoint_checksum(c);
  EXPECT_EQ(checkpoint_checksum(sample()), h) << "deterministic";
  for (std::size_t i : {std::size_t{0}, std::size_t{20}, std::size_t{40}}) {
    for (int bit : {0, 31, 63}) {
      Checkpoint d = c;
      std::uint64_t u;
      std::memcpy(&u, &d.y[i], sizeof u);
      u ^= std::uint64_t{1} << bit;
      std::memcpy(&d.y[i], &u, sizeof u);
      EXPECT_NE(checkpoint_checksum(d), h) << "y[" << i << "] bit " << bit;
    }
  }
  Checkpoint d = c;
  d.t = std::nextafter(c.t, 0.0);
  EXPECT_NE(checkpoint_checksum(d), h) << "t";
  d = c;
  d.snapshot_index += 1;
  EXPECT_NE(checkpoint_checksum(d), h) << "snapshot_index";
  d = c;
  d.config_toml[3] = 'X';
  EXPECT_NE(checkpoint_checksum(d), h) << "config_toml";
  d = c;
  d.row_digests["snapshots/time"][1] ^= 1;
  EXPECT_NE(checkpoint_checksum(d), h) << "a row digest";
  d = c;
  d.row_digests["snapshots/time"].push_back(4);
  EXPECT_NE(checkpoint_checksum(d), h) << "one more row digest";
  // A checkpoint written before the digests were kept has none: its checksum is the
  // one computed then, over the other fields only.
  d = c;
  d.row_digests.clear();
  Checkpoint e = d;
  e.row_digests["timeseries/m_through"] = {};
  EXPECT_NE(checkpoint_checksum(e), checkpoint_checksum(d)) << "an empty digest list";
}

// ---------------------------------------------------------------------------------------
// Writing and reading

TEST(CheckpointFile, PathsSitNextToTheOutput) {
  EXPECT_EQ(checkpoint_path("out/run.h5"), fs::path("out/run.chk.h5"));
  EXPECT_EQ(previous_checkpoint_path("out/run.chk.h5"), fs::path("out/run.chk.prev.h5"));
  EXPECT_EQ(previous_checkpoint_path("out/run.chk.prev.h5"),
            fs::path("out/run.chk.prev.h5"));
}

TEST(CheckpointFile, AtomicWriteKeepsThePreviousAndLeavesNoTemporary) {
  TempDir dir;
  const fs::path chk = dir.path() / "run.chk.h5";
  const Checkpoint first = sample(1.0), second = sample(2.0);
  write_checkpoint(chk, first);
  EXPECT_TRUE(fs::exists(chk));
  EXPECT_FALSE(fs::exists(previous_checkpoint_path(chk))) << "nothing to keep yet";
  write_checkpoint(chk, second);
  expect_same(read_checkpoint(chk), second);
  expect_same(read_checkpoint(previous_checkpoint_path(chk)), first);
  const Checkpoint third = sample(3.0);
  write_checkpoint(chk, third);
  expect_same(read_checkpoint(chk), third);
  expect_same(read_checkpoint(previous_checkpoint_path(chk)), second);
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos)
        << "left behind: " << entry.path();
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()),
            2);
}

TEST(CheckpointFile, ADamagedCheckpointIsNotPromotedToPrevious) {
  TempDir dir;
  const fs::path chk = dir.path() / "run.chk.h5";
  write_checkpoint(chk, sample(1.0));
  write_checkpoint(chk, sample(2.0));
  fs::resize_file(chk, fs::file_size(chk) / 2);
  write_checkpoint(chk, sample(3.0));
  expect_same(read_checkpoint(chk), sample(3.0));
  expect_same(read_checkpoint(previous_checkpoint_path(chk)), sample(1.0));
}

TEST(CheckpointFile, TruncatedFlippedOrIncompleteFilesAreRefusedByName) {
  TempDir dir;
  const fs::path chk = dir.path() / "run.chk.h5";
  write_checkpoint(chk, sample());

  const fs::path cut = dir.path() / "cut.chk.h5";
  fs::copy_file(chk, cut);
  fs::resize_file(cut, fs::file_size(cut) * 2 / 3);
  std::string m = message_of([&] { read_checkpoint(cut); });
  EXPECT_NE(m.find(cut.string()), std::string::npos) << m;
  EXPECT_NE(m.find("truncated"), std::string::npos) << m;

  const fs::path flipped = dir.path() / "flipped.chk.h5";
  fs::copy_file(chk, flipped);
  flip_byte(flipped, y_offset(flipped) + 8 * 17 + 3);
  m = message_of([&] { read_checkpoint(flipped); });
  EXPECT_NE(m.find(flipped.string()), std::string::npos) << m;
  EXPECT_NE(m.find("checksum mismatch"), std::string::npos) << m;

  const fs::path incomplete = dir.path() / "incomplete.chk.h5";
  fs::copy_file(chk, incomplete);
  {
    const hid_t f = H5Fopen(incomplete.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    H5Adelete(f, "complete");
    H5Fclose(f);
  }
  m = message_of([&] { read_checkpoint(incomplete); });
  EXPECT_NE(m.find("incomplete"), std::string::npos) << m;

  m = message_of([&] { read_checkpoint(dir.path() / "missing.chk.h5"); });
  EXPECT_NE(m.find("not found"), std::string::npos) << m;

  const fs::path text = dir.path() / "text.chk.h5";
  std::ofstream(text) << "not an HDF5 file\n";
  EXPECT_THROW(read_checkpoint(text), IoError);
}

TEST(CheckpointFile, TheWrongFileIsBadInputNamingTheCheckpointToGive) {
  // the run's output, the scene or a directory given to --restart were "truncated or
  // damaged" checkpoints (exit 4), with the advice to start the run again
  TempDir dir;
  const fs::path out = dir.path() / "run.h5";
  {
    const hid_t f = H5Fcreate(out.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Gclose(H5Gcreate2(f, "snapshots", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    H5Fclose(f);
  }
  const auto config_error_of = [](const fs::path& p) {
    return config_error_message([&] { load_restart_point(p); }, p.string());
  };
  std::string m = config_error_of(out);
  EXPECT_NE(m.find("the output of a run, not its checkpoint; restart from " +
                   checkpoint_path(out).string() + " (not there"),
            std::string::npos)
      << m;
  write_checkpoint(checkpoint_path(out), sample());
  m = config_error_of(out);
  EXPECT_NE(m.find("restart from " + checkpoint_path(out).string()), std::string::npos)
      << m;
  EXPECT_EQ(m.find("not there"), std::string::npos) << m;
  EXPECT_EQ(m.find("without --restart"), std::string::npos) << m;

  const fs::path scene = dir.path() / "scene.toml";
  std::ofstream(scene) << "[grid]\nn_cells = 100\n";
  m = config_error_of(scene);
  EXPECT_NE(m.find(scene.string() + ": not an HDF5 file"), std::string::npos) << m;
  EXPECT_NE(m.find("<output>.chk.h5"), std::string::npos) << m;
  m = config_error_of(dir.path());
  EXPECT_NE(m.find("is a directory"), std::string::npos) << m;

  // a checkpoint's own name keeps "damaged" (exit 4) and the fallback to .prev
  const fs::path text = dir.path() / "text.chk.h5";
  std::ofstream(text) << "not an HDF5 file\n";
  EXPECT_THROW(load_restart_point(text), IoError);
  const fs::path cut = dir.path() / "cut.h5";  // truncated: the signature is still there
  fs::copy_file(checkpoint_path(out), cut);
  fs::resize_file(cut, 100);
  EXPECT_THROW(load_restart_point(cut), IoError);
}

TEST(CheckpointFile, RestartFallsBackToThePreviousCheckpointAndSaysWhy) {
  TempDir dir;
  const fs::path chk = dir.path() / "run.chk.h5";
  write_checkpoint(chk, sample(1.0));
  write_checkpoint(chk, sample(2.0));
  RestartPoint good = load_restart_point(chk);
  EXPECT_EQ(good.path, chk);
  EXPECT_TRUE(good.fallback_note.empty());

  flip_byte(chk, y_offset(chk) + 5);
  RestartPoint r = load_restart_point(chk);
  EXPECT_EQ(r.path, previous_checkpoint_path(chk));
  expect_same(r.chk, sample(1.0));
  EXPECT_NE(r.fallback_note.find(chk.string()), std::string::npos) << r.fallback_note;
  EXPECT_NE(r.fallback_note.find("checksum"), std::string::npos) << r.fallback_note;

  fs::resize_file(previous_checkpoint_path(chk), 100);
  const std::string m = message_of([&] { load_restart_point(chk); });
  EXPECT_NE(m.find(chk.string()), std::string::npos) << m;
  EXPECT_NE(m.find(previous_checkpoint_path(chk).string()), std::string::npos) << m;
  EXPECT_NE(m.find("without --restart"), std::string::npos) << m;
}

// ---------------------------------------------------------------------------------------
// Compatibility of a restarted scene

struct Scene {
  Config cfg;
  StateLayout layout;
};

Scene scene(std::vector<std::string> overrides, bool gas = false) {
  const std::string text = "[grid]\nn_cells = 40\n[output]\nt_end_yr = 1e5\n";
  Scene s{load_scene_text(text, "scene.toml", overrides), StateLayout(40)};
  s.layout.add_cell_var({"sigma_d", "g cm^-2", "", 1.0, true});
  if (gas) s.layout.add_cell_var({"sigma_g", "g cm^-2", "", 1.0, true});
  s.layout.add_global_var({"m_out_dust", "", "", 1.0, true});
  s.layout.freeze();
  return s;
}

Checkpoint checkpoint_of(const Scene& s) {
  Checkpoint c;
  c.t = 1e3 * units::kYr;
  c.y.assign(static_cast<std::size_t>(s.layout.size()), 1.0);
  c.layout_signature = s.layout.signature();
  c.n_cells = s.layout.n_cells();
  c.config_toml = s.cfg.resolved_toml();
  return c;
}

TEST(CheckpointCompatibility, TheSameSceneIsCompatible) {
  const Scene s = scene({});
  EXPECT_TRUE(check_compatible(checkpoint_of(s), "run.chk.h5", s.cfg, s.layout).empty());
}

TEST(CheckpointCompatibility, OutputTimesSolverAndCheckpointKeysMayChange) {
  const Checkpoint c = checkpoint_of(scene({}));
  const Scene s =
      scene({"output.t_end_yr=1e6", "output.n_snapshots=10", "solver.rtol=1e-8",
             "checkpoint.every_snapshots=3", "meta.description=\"x\""});
  const auto changed = check_compatible(c, "run.chk.h5", s.cfg, s.layout);
  // each with the new value and the checkpoint's (the run's notice and its record)
  EXPECT_EQ(changed, (std::vector<std::string>{"meta.description = \"x\" (was \"\")",
                                               "solver.rtol = 1e-08 (was 1e-06)",
                                               "checkpoint.every_snapshots = 3 (was 0)",
                                               "output.t_end_yr = 1e+06 (was 1e+05)",
                                               "output.n_snapshots = 10 (was 41)"}));
}

TEST(CheckpointCompatibility, GridDiskAndProcessKeysAreRefusedByName) {
  const Checkpoint c = checkpoint_of(scene({}));
  for (const std::string key :
       {"grid.n_cells=50", "grid.r_out_au=200.0", "disk.alpha=1e-4", "transport.St=0.1",
        "transport.drift=false", "dust.dust_to_gas=0.02", "star.mass_msun=0.5"}) {
    const Scene s = scene({key});
    const std::string name = key.substr(0, key.find('='));
    try {
      check_compatible(c, "run.chk.h5", s.cfg, s.layout);
      ADD_FAILURE() << key << " was accepted";
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(name + " = "), std::string::npos) << m;
      EXPECT_NE(m.find("run.chk.h5"), std::string::npos) << m;
      EXPECT_NE(m.find("--set " + name + "="), std::string::npos) << "the fix: " << m;
      EXPECT_EQ(ConfigError(m).exit_code(), 2);
      // the message names every key a restart may change (meta.* was left out), by its
      // name, its table's "table.*" or, in a list of one table, its leaf
      for (const KeySpec& spec : scene_keys()) {
        if (!may_change_on_restart(spec.key)) continue;
        const std::string table = spec.key.substr(0, spec.key.find('.'));
        const std::string leaf = spec.key.substr(table.size() + 1);
        EXPECT_TRUE(m.find(spec.key) != std::string::npos ||
                    m.find(table + ".*") != std::string::npos ||
                    m.find(" " + leaf + ",") != std::string::npos ||
                    m.find(" " + leaf + ")") != std::string::npos)
            << spec.key << " may change but the message does not say so: " << m;
      }
    }
  }
}

TEST(CheckpointCompatibility, ADifferentLayoutIsRefused) {
  const Checkpoint c = checkpoint_of(scene({}));
  const Scene s = scene({}, /*gas=*/true);
  const std::string m =
      message_of([&] { check_compatible(c, "run.chk.h5", s.cfg, s.layout); });
  EXPECT_NE(m.find("state layout differs"), std::string::npos) << m;
  EXPECT_NE(m.find("sigma_g"), std::string::npos) << m;
}

TEST(CheckpointCompatibility, UnknownKeysMayNotChange) {
  EXPECT_TRUE(may_change_on_restart("output.t_end_yr"));
  EXPECT_TRUE(may_change_on_restart("checkpoint.every_wall_s"));
  EXPECT_TRUE(may_change_on_restart("solver.reinit_at_snapshots"));
  EXPECT_FALSE(may_change_on_restart("grid.n_cells"));
  EXPECT_FALSE(may_change_on_restart("solver.some_future_key"));
  EXPECT_FALSE(may_change_on_restart("output.some_future_field"));
}

TEST(CheckpointRestart, SnapshotTimesContinueAfterTheCheckpoint) {
  const std::vector<double> t = {0.0, 1.0, 2.0, 3.0, 4.0};
  EXPECT_EQ(times_after_restart(t, 2.0), (std::vector<double>{2.0, 3.0, 4.0}));
  EXPECT_EQ(times_after_restart(t, 2.5), (std::vector<double>{2.5, 3.0, 4.0}));
  const std::string m = message_of([&] { times_after_restart(t, 4.0); });
  EXPECT_NE(m.find("output.t_end_yr"), std::string::npos) << m;
}

TEST(CheckpointRestart, DurationsForMaxWall) {
  EXPECT_DOUBLE_EQ(parse_duration("90m"), 5400.0);
  EXPECT_DOUBLE_EQ(parse_duration("2h"), 7200.0);
  EXPECT_DOUBLE_EQ(parse_duration("3600s"), 3600.0);
  EXPECT_DOUBLE_EQ(parse_duration("1h30m"), 5400.0);
  EXPECT_DOUBLE_EQ(parse_duration("1.5h"), 5400.0);
  EXPECT_DOUBLE_EQ(parse_duration("1d2h"), 93600.0);
  EXPECT_DOUBLE_EQ(parse_duration("45"), 45.0);
  EXPECT_DOUBLE_EQ(parse_duration("1d2h3m4s"), 93784.0);
  for (const char* bad : {"", "h", "abc", "1h30", "-5m", "0", "0s", "90 m", "2x",
                          "90m30m", "30m1h", "1h1h"})
    EXPECT_THROW(parse_duration(bad), ConfigError) << "'" << bad << "'";
}

TEST(CheckpointRestart, ScheduleBySnapshotsAndWallClock) {
  const CheckpointSchedule by_snapshots(0.0, 3, 0.0);
  EXPECT_FALSE(by_snapshots.due(1, 1e9));
  EXPECT_TRUE(by_snapshots.due(3, 0.0));
  EXPECT_TRUE(by_snapshots.due(6, 0.0));
  CheckpointSchedule by_wall(100.0, 0, 0.0);
  EXPECT_FALSE(by_wall.due(1, 99.0));
  EXPECT_TRUE(by_wall.due(2, 100.0));
  by_wall.taken(100.0);
  EXPECT_FALSE(by_wall.due(3, 150.0));
  EXPECT_TRUE(by_wall.due(4, 201.0));
  const CheckpointSchedule off(0.0, 0, 0.0);
  EXPECT_FALSE(off.due(10, 1e9));
}

// ---------------------------------------------------------------------------------------
// What restarts rest on: CVodeReInit at t is a new CVODE at t, bit for bit.

IntegratorOptions robertson_options() {
  IntegratorOptions o;
  o.rtol = 1e-6;
  o.atol = {1e-10, 1e-14, 1e-8};
  return o;
}

TEST(CheckpointRestart, ReinitEqualsAFreshIntegratorBitForBit) {
  const std::vector<double> y0 = {1.0, 0.0, 0.0};
  const std::vector<double> times = {0.0, 0.4, 4.0, 40.0, 400.0, 4e3, 4e4};
  auto model = robertson_model();
  // The uninterrupted run, reinitialised at every output time.
  CvodeIntegrator straight(*model, 0.0, y0, robertson_options());
  std::vector<std::vector<double>> states;
  for (std::size_t k = 1; k < times.size(); ++k) {
    straight.advance_to(times[k]);
    std::vector<double> y(straight.state().begin(), straight.state().end());
    straight.reinit(times[k], y);
    states.push_back(y);
  }
  // Restarts from each output time with a new integrator.
  for (std::size_t r = 1; r + 1 < times.size(); ++r) {
    auto model2 = robertson_model();
    CvodeIntegrator restarted(*model2, times[r], states[r - 1], robertson_options());
    for (std::size_t k = r + 1; k < times.size(); ++k) {
      restarted.advance_to(times[k]);
      const std::vector<double> y(restarted.state().begin(), restarted.state().end());
      restarted.reinit(times[k], y);
      EXPECT_EQ(y, states[k - 1])
          << "restart at t = " << times[r] << ", t = " << times[k];
    }
  }
  // The statistics survive the reinitialisations.
  const SolverStats s = straight.stats();
  EXPECT_EQ(s.nreinit, static_cast<long>(times.size() - 1));
  EXPECT_GT(s.nst, 100);
  EXPECT_GT(s.nje, 0);
}

}  // namespace
