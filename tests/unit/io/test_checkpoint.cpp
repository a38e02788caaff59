// Checkpoints (src/io/checkpoint.hpp): the checksum, the atomic write that keeps the
// previous checkpoint, the detection of truncated, flipped and incomplete files, and the
// property restarts rest on: CVODE reinitialised at t equals a new CVODE built at t, bit
// for bit. The restart policy that reads them (src/run/restart.hpp): tests/unit/run/
// test_restart.cpp.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/checkpoint.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "tests/unit/support/checkpoint_sample.hpp"
#include "tests/unit/support/robertson.hpp"

using namespace panoptic;
using namespace panoptic::test_support;
namespace fs = std::filesystem;

namespace {

std::span<const std::byte> bytes_of(const char* s) {
  return {reinterpret_cast<const std::byte*>(s), std::strlen(s)};
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
