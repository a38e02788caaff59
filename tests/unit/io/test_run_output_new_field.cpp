// A restart tells a field that an earlier panoptic did not write from one the file lost
// (src/io/run_output.hpp, add_field). A checkpoint holds the digests of every snapshot
// row its run wrote, field by field (RunOutput::row_digests). An output continued without
// a field the run declares gets the field back with NaN in its kept rows, and:
// * the checkpoint has the field's digests: its run wrote it, the file lost it (a dataset
//   torn by a kill while HDF5 flushed): named in lost_rows();
// * the checkpoint has none: its run never wrote it (an earlier panoptic's output,
//   continued by this one): named in new_fields(), not as lost.
#include <H5Lpublic.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "src/io/h5.hpp"
#include "src/io/run_output.hpp"

namespace panoptic {
namespace {

namespace fs = std::filesystem;

//! A run file with fields "a" and "b" and two snapshots, "b" then deleted (as an earlier
//! panoptic without "b" would have left it); returns the run's row digests.
RowDigests two_snapshots_without_b(const fs::path& path) {
  fs::remove(path);
  RowDigests digests;
  {
    RunOutput out(path, false, {"s", "", "", ""});
    out.add_field("a", 2, "", "field a");
    out.add_field("b", 2, "", "field b");
    out.start_appending();
    for (double t : {1.0, 2.0})
      out.write_snapshot(t, {{"a", {t, 2 * t}}, {"b", {3 * t, 4 * t}}});
    digests = out.row_digests();
  }
  h5::quiet_errors();
  h5::Handle f = h5::open_file(path.string(), true);
  h5::Handle g = h5::open_group(f.get(), "snapshots");
  EXPECT_GE(H5Ldelete(g.get(), "b", H5P_DEFAULT), 0);
  return digests;
}

//! Continues the file with the digests `digests`, declares "a" and "b" and returns
//! {lost_rows(), new_fields()}; checks that b's kept rows are NaN.
std::pair<std::string, std::string> continue_with(const fs::path& path,
                                                  const RowDigests& digests) {
  RunOutput out(path, ContinueRun{2, digests});
  out.add_field("a", 2, "", "field a");
  out.add_field("b", 2, "", "field b");
  out.start_appending();
  h5::Handle g = h5::open_group(out.file(), "snapshots");
  const std::vector<double> b = h5::read_rows(g.get(), "b", 0, 2);
  EXPECT_EQ(b.size(), 4u);
  for (double v : b) EXPECT_TRUE(std::isnan(v));
  return {out.lost_rows(), out.new_fields()};
}

TEST(RunOutputRestart, AFieldTheCheckpointsRunWroteIsLost) {
  const fs::path dir = fs::temp_directory_path() / "panoptic_new_field";
  fs::create_directories(dir);
  const fs::path path = dir / "lost.h5";
  const RowDigests digests = two_snapshots_without_b(path);
  ASSERT_TRUE(digests.contains("snapshots/b"));
  const auto [lost, added] = continue_with(path, digests);
  EXPECT_NE(lost.find("/snapshots/b rows 0-1"), std::string::npos) << lost;
  EXPECT_EQ(added, "");
}

TEST(RunOutputRestart, AFieldTheCheckpointsRunDidNotWriteIsNew) {
  const fs::path dir = fs::temp_directory_path() / "panoptic_new_field";
  fs::create_directories(dir);
  const fs::path path = dir / "new.h5";
  RowDigests digests = two_snapshots_without_b(path);
  digests.erase("snapshots/b");  // the checkpoint of a run without "b"
  const auto [lost, added] = continue_with(path, digests);
  EXPECT_EQ(lost, "");
  EXPECT_EQ(added, "/snapshots/b rows 0-1");
}

}  // namespace
}  // namespace panoptic
