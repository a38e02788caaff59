// The default gas is stated once (disk/gas_defaults.hpp): the scene schema's defaults of
// the disk keys, a default-constructed ThermalParams and make_local_gas() all read it,
// and the schema's literal of each value reads back as exactly that value.
#include <gtest/gtest.h>

#include "disk/gas_defaults.hpp"
#include "disk/gas_disk.hpp"
#include "disk/local_gas.hpp"
#include "src/scene/config.hpp"

namespace panoptic {
namespace {

TEST(GasDefaults, SchemaThermalParamsAndLocalGasAgree) {
  const ThermalParams th;
  EXPECT_EQ(default_real("disk.T_1au"), gas_defaults::kT1au);
  EXPECT_EQ(default_real("disk.q"), gas_defaults::kQ);
  EXPECT_EQ(default_real("disk.T_floor"), gas_defaults::kTFloor);
  EXPECT_EQ(default_real("disk.mu"), gas_defaults::kMu);
  EXPECT_EQ(default_real("disk.alpha"), gas_defaults::kAlpha);
  EXPECT_EQ(default_real("disk.sigma_mol"), gas_defaults::kSigmaMol);
  EXPECT_EQ(default_real("disk.T_sub"), gas_defaults::kTSub);
  EXPECT_EQ(th.T_1au, default_real("disk.T_1au"));
  EXPECT_EQ(th.q, default_real("disk.q"));
  EXPECT_EQ(th.T_floor, default_real("disk.T_floor"));
  EXPECT_EQ(th.mu, default_real("disk.mu"));
  EXPECT_EQ(th.alpha, default_real("disk.alpha"));
  EXPECT_EQ(th.sigma_mol, default_real("disk.sigma_mol"));
  EXPECT_EQ(th.T_sub, default_real("disk.T_sub"));

  // make_local_gas() with its default mu and sigma_mol equals one given the schema's
  const double sigma_g = 1700.0, T = 280.0, r = units::kAu, m_star = units::kMsun;
  const physics::LocalGas a = physics::make_local_gas(sigma_g, T, r, m_star, 1e-3, -3.25);
  const physics::LocalGas b =
      physics::make_local_gas(sigma_g, T, r, m_star, 1e-3, -3.25, default_real("disk.mu"),
                              default_real("disk.sigma_mol"));
  EXPECT_EQ(a.c_s, b.c_s);
  EXPECT_EQ(a.mfp, b.mfp);
}

// The schema writes the defaults as the reference always listed them.
TEST(GasDefaults, SchemaLiterals) {
  const auto default_of = [](std::string_view key) {
    for (const KeySpec& spec : scene_keys())
      if (spec.key == key) return spec.default_toml;
    return std::string("(no such key)");
  };
  EXPECT_EQ(default_of("disk.T_1au"), "280.0");
  EXPECT_EQ(default_of("disk.q"), "0.5");
  EXPECT_EQ(default_of("disk.T_floor"), "10.0");
  EXPECT_EQ(default_of("disk.mu"), "2.34");
  EXPECT_EQ(default_of("disk.alpha"), "1e-3");
  EXPECT_EQ(default_of("disk.sigma_mol"), "2e-15");
  EXPECT_EQ(default_of("disk.T_sub"), "170.0");
}

}  // namespace
}  // namespace panoptic
