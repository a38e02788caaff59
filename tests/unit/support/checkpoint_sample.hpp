#pragma once
//! Test helpers of the checkpoint file (tests/unit/io/test_checkpoint.cpp) and of the
//! restart policy that reads it (tests/unit/run/test_restart.cpp): a sample checkpoint,
//! a field-by-field comparison, a temporary directory per test, the message of an Error,
//! and the damage done to a file on disk.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/checkpoint.hpp"
#include "tests/unit/support/expect_fields.hpp"

namespace panoptic::test_support {

inline Checkpoint sample(double scale = 1.0) {
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

inline void expect_same(const Checkpoint& a, const Checkpoint& b) {
  expect_fields_equal(a, b, &Checkpoint::t, &Checkpoint::y, &Checkpoint::layout_signature,
                      &Checkpoint::n_cells, &Checkpoint::snapshot_index,
                      &Checkpoint::config_toml);
  expect_fields_equal(a.stats, b.stats, &SolverStats::nst, &SolverStats::nfe,
                      &SolverStats::nreinit, &SolverStats::h_last);
  expect_fields_equal(a, b, &Checkpoint::wall_s, &Checkpoint::output_file,
                      &Checkpoint::run_id, &Checkpoint::row_digests);
}

//! A fresh directory under the build's temporary space, removed at the end.
class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("panoptic_test_checkpoint_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no exception)";
}

//! Offset of the first byte of the contiguous dataset /y in the file.
inline long y_offset(const std::filesystem::path& file) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, "y", H5P_DEFAULT);
  const haddr_t off = H5Dget_offset(d);
  H5Dclose(d);
  H5Fclose(f);
  return static_cast<long>(off);
}

inline void flip_byte(const std::filesystem::path& file, long offset) {
  std::fstream s(file, std::ios::in | std::ios::out | std::ios::binary);
  s.seekg(offset);
  char c = 0;
  s.get(c);
  s.seekp(offset);
  s.put(static_cast<char>(c ^ 0x5a));
}

}  // namespace panoptic::test_support
