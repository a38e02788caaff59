// The restart policy (src/run/restart.hpp): which checkpoint a restart reads (the wrong
// file given to --restart, the fallback to the previous checkpoint), whether a scene may
// continue it (the keys a restart may change, the state layout), the snapshot times after
// it; and the run's --max-wall durations and checkpoint schedule (src/run/max_wall.hpp,
// checkpoint_schedule.hpp).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/checkpoint.hpp"
#include "src/run/checkpoint_schedule.hpp"
#include "src/run/max_wall.hpp"
#include "src/run/restart.hpp"
#include "src/scene/config.hpp"
#include "src/solver/state_layout.hpp"
#include "tests/unit/support/checkpoint_sample.hpp"
#include "tests/unit/support/config_error.hpp"

using namespace panoptic;
using namespace panoptic::test_support;
namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------
// Which checkpoint a restart reads

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

}  // namespace
