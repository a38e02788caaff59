// The scan's summary and records are written atomically (src/scan/scan_summary.hpp,
// src/scan/scan_exec.hpp): a write that fails (disk full, quota) leaves the old file
// whole and no temporary file behind. The failure is made with RLIMIT_FSIZE: writing past
// the limit fails with EFBIG, as a full disk fails with ENOSPC.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "src/core/error.hpp"
#include "src/io/durable_file.hpp"
#include "src/scan/scan_exec.hpp"
#include "src/scan/scan_manifest.hpp"
#include "src/scan/scan_summary.hpp"

namespace panoptic {
namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

//! Files can grow to `bytes` at most while it lives (SIGXFSZ ignored: write fails).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    getrlimit(RLIMIT_FSIZE, &old_);
    rlimit r = old_;
    r.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &r);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit old_{};
  void (*old_handler_)(int) = nullptr;
};

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() /
                     ("panoptic_unit_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d / "runs");
  return d;
}

std::vector<std::string> files_in(const fs::path& d) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(d))
    if (e.is_regular_file()) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ScanSummary, FailedWriteLeavesTheOldFileAndNoTemporary) {
  const fs::path d = fresh_dir("atomic");
  write_atomically(d / "record", std::string(100, 'a'));
  {
    FileSizeLimit limit(1000);
    EXPECT_THROW(write_atomically(d / "record", std::string(5000, 'b')), IoError);
  }
  EXPECT_EQ(slurp(d / "record"), std::string(100, 'a'));
  EXPECT_EQ(files_in(d), std::vector<std::string>{"record"});
  fs::remove_all(d);
}

TEST(ScanSummary, TemporaryNameIsNotAnotherProcessesFile) {
  // Processes of one scan on two nodes of a shared file system may have the same PID:
  // a temporary named after the PID alone (".tmpPID", as before) would be written by both
  // and renamed away under the other. The file at that name stands for the other's.
  const fs::path d = fresh_dir("unique");
  const fs::path others = d / ("record.tmp" + std::to_string(::getpid()));
  { std::ofstream(others) << "another process's record"; }
  write_atomically(d / "record", "this process's record");
  EXPECT_EQ(slurp(d / "record"), "this process's record");
  ASSERT_TRUE(fs::exists(others));
  EXPECT_EQ(slurp(others), "another process's record");
  EXPECT_EQ(files_in(d).size(), 2u);  // no temporary of its own left
  // readable like any file the user writes (mkstemp creates 0600)
  EXPECT_EQ(fs::status(d / "record").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                fs::perms::others_read);
  fs::remove_all(d);
}

TEST(ScanSummary, FailedSummaryLeavesTheOldSummaryAndNoTemporary) {
  const fs::path d = fresh_dir("summary");
  const Manifest m = expand_scan_text(
      "[scan]\nscene = \"fiducial.toml\"\nset = [\"output.t_end_yr=100.0\"]\n"
      "[[axis]]\nkey = \"star.mass_msun\"\nvalues = [0.5, 1.0, 2.0]\n",
      "test.toml", fs::path(PANOPTIC_SOURCE_DIR) / "params");
  const std::vector<ResolvedRun> resolved = validate_manifest(m);
  const ScanCounts c = write_scan_summary(d, m, resolved);
  EXPECT_EQ(c.other, 3);  // no run has run
  const std::string h5 = slurp(d / "summary.h5"), csv = slurp(d / "summary.csv");
  ASSERT_GT(h5.size(), 2000u);
  {
    FileSizeLimit limit(2000);
    EXPECT_THROW(write_scan_summary(d, m, resolved), IoError);
  }
  EXPECT_EQ(slurp(d / "summary.h5"), h5);
  EXPECT_EQ(slurp(d / "summary.csv"), csv);
  EXPECT_EQ(files_in(d), (std::vector<std::string>{"summary.csv", "summary.h5"}));
  fs::remove_all(d);
}

}  // namespace
}  // namespace panoptic
