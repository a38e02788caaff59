// read_number_text(): the one reading of "does this text say a number, and is it in
// range" behind the loader's "write the number without quotes" / "beyond the range of a
// double" and the TOML guard's hint for a token toml++ could not read.
#include <gtest/gtest.h>

#include "src/scene/number_text.hpp"

namespace panoptic {
namespace {

TEST(NumberText, ReadsWholeNumbersOnly) {
  const NumberText n = read_number_text("42");
  EXPECT_TRUE(n.real);
  EXPECT_TRUE(n.integer);
  EXPECT_FALSE(n.beyond_double);
  EXPECT_FALSE(n.beyond_int64);
  const NumberText x = read_number_text("1.5e3");
  EXPECT_TRUE(x.real);
  EXPECT_FALSE(x.integer);
  for (const char* text : {"", "abc", "1.5 au", "1e3x", " "}) {
    const NumberText t = read_number_text(text);
    EXPECT_FALSE(t.real) << text;
    EXPECT_FALSE(t.integer) << text;
    EXPECT_FALSE(t.beyond_double) << text;
    EXPECT_FALSE(t.beyond_int64) << text;
  }
}

TEST(NumberText, OutOfRange) {
  EXPECT_TRUE(read_number_text("1e999").beyond_double);
  EXPECT_TRUE(read_number_text("-1e999").beyond_double);
  EXPECT_TRUE(read_number_text("1e-999").beyond_double);  // underflow: ERANGE too
  EXPECT_FALSE(read_number_text("1e308").beyond_double);
  const NumberText big = read_number_text("99999999999999999999");
  EXPECT_TRUE(big.integer);
  EXPECT_TRUE(big.beyond_int64);
  EXPECT_TRUE(big.real);
  EXPECT_FALSE(big.beyond_double);
  EXPECT_FALSE(read_number_text("9223372036854775807").beyond_int64);
  EXPECT_FALSE(read_number_text("1e999x").beyond_double);  // not a number at all
}

}  // namespace
}  // namespace panoptic
