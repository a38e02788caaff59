// src/io/README.md's copy of `panoptic reference --outputs` (the Output table) is the
// command's output: the table is generated from the declarations, and this copy cannot
// drift from them.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "src/run/output_reference.hpp"

using namespace panoptic;

TEST(OutputReference, ReadmeCopyIsUpToDate) {
  const std::string path = std::string(PANOPTIC_SOURCE_DIR) + "/src/io/README.md";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  std::stringstream text;
  text << in.rdbuf();
  const std::string readme = text.str();
  const std::string begin = "<!-- panoptic reference --outputs: begin -->\n";
  const std::string end = "<!-- panoptic reference --outputs: end -->";
  const auto a = readme.find(begin), b = readme.find(end);
  ASSERT_NE(a, std::string::npos) << path << " has no line " << begin;
  ASSERT_NE(b, std::string::npos) << path << " has no line " << end;
  ASSERT_LT(a, b);
  EXPECT_TRUE(readme.substr(a + begin.size(), b - a - begin.size()) ==
              output_reference_markdown())
      << path << ": the table between the markers differs from `build/panoptic reference "
      << "--outputs`; paste the command's output there and commit it";
}
