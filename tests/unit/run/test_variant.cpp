// The label of a variant (src/run/README.md, Variants) and the `overrides` attribute:
// the items written out when they make a plain file name, their digest otherwise.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "src/run/variant.hpp"

namespace panoptic {
namespace {

using Items = std::vector<std::string>;

TEST(Variant, LabelWritesThePresetAndTheItems) {
  EXPECT_EQ(variant_label("fiducial", "", Items{}), "fiducial");
  EXPECT_EQ(variant_label("fiducial", "fast", Items{}), "fiducial+fast");
  EXPECT_EQ(variant_label("fiducial", "", Items{"disk.sigma_1au=5100"}),
            "fiducial+disk.sigma_1au=5100");
  // blanks around key and value, the quotes of a plain string
  EXPECT_EQ(
      variant_label("f", "accurate", Items{" disk.model = \"lbp\" ", "grid.n_cells=64"}),
      "f+accurate+disk.model=lbp+grid.n_cells=64");
}

TEST(Variant, LabelTakesTheDigestOfItemsThatMakeNoPlainName) {
  // FNV-1a 64 of "pebbles.radii_au=[5.0, 50.0]\n", its upper 32 bits (computed with
  // the reference algorithm in tests/regression/cli/test_variants.py)
  const std::string list = variant_label("f", "", Items{"pebbles.radii_au=[5.0, 50.0]"});
  EXPECT_EQ(list.rfind("f+set-", 0), 0u) << list;
  EXPECT_EQ(list.size(), std::string("f+set-").size() + 8);
  for (const char* unsafe : {"output.file=a/b.h5", "meta.description=\"two words\"",
                             "meta.description=\"\"", "disk.alpha", "=1"})
    EXPECT_NE(variant_label("f", "", Items{unsafe}).find("+set-"), std::string::npos)
        << unsafe;
  // long: a hundred characters at most
  Items many;
  for (int k = 0; k < 10; ++k) many.push_back("solver.rtol=1e-" + std::to_string(k));
  const std::string long_label = variant_label("fiducial", "", many);
  EXPECT_EQ(long_label.rfind("fiducial+set-", 0), 0u) << long_label;
  // one digest per set of items, in order
  EXPECT_NE(variant_label("f", "", Items{"a.b=[1]", "c.d=[2]"}),
            variant_label("f", "", Items{"c.d=[2]", "a.b=[1]"}));
  EXPECT_EQ(variant_label("f", "", Items{"a.b=[1]"}),
            variant_label("f", "", Items{"a.b=[1]"}));
}

TEST(Variant, OverridesAreAJsonListOfTheItems) {
  EXPECT_EQ(overrides_json(Items{}), "[]");
  EXPECT_EQ(overrides_json(Items{"disk.alpha=1e-4", "dust.init=\"gaussian_ring\""}),
            "[\"disk.alpha=1e-4\", \"dust.init=\\\"gaussian_ring\\\"\"]");
  EXPECT_EQ(overrides_json(Items{"meta.description=a\\b\tc"}),
            "[\"meta.description=a\\\\b\\u0009c\"]");
}

}  // namespace
}  // namespace panoptic
