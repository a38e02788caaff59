//! Tests of the collision speed the growth rates use (physics/relative_velocity.hpp;
//! spec §3.5): the V_g^2 normalisation of the turbulent term and its scene key. Set-up
//! and reference numbers: growth_fixture.hpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "tests/unit/physics/growth_fixture.hpp"

using namespace growth_fixture;

// ---------------------------------------------- the V_g^2 normalisation of §3.5

TEST(GrowthTurbulence, Vg2FactorScalesOnlyTheTurbulentTermAndIsReadFromTheScene) {
  // spec §3.5: V_g^2 = alpha c_s^2 (OC07), alt. 1.5 alpha c_s^2 (growth.vg2_factor). Only
  // the turbulent term scales: dv^2(1.5) - dv^2(1) = 0.5 dv_t^2(St, eps St).
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  const double m = 1e8, phi = 5e-4, st = 0.20427797089107294;
  GrowthOptions one = plain_options(), alt = plain_options();
  alt.turbulence.vg2_factor = 1.5;
  const auto r1 = particle_rates(kSigmaD, m, phi, st, gas, sp, one);
  const auto r15 = particle_rates(kSigmaD, m, phi, st, gas, sp, alt);
  const double dvt2 = panoptic::physics::dv2_turbulent(st, 0.5 * st, gas);
  EXPECT_LT(rel_err(r15.dv * r15.dv - r1.dv * r1.dv, 0.5 * dvt2), 1e-9);
  EXPECT_GT(dvt2, 0.5 * r1.dv * r1.dv);  // turbulence dominates here: the test has teeth
  // dm/dt is proportional to dv (spec §4.1)
  EXPECT_LT(rel_err(r15.dm_dt / r1.dm_dt, r15.dv / r1.dv), 1e-12);

  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> none, set{"growth.vg2_factor=1.5"};
  EXPECT_EQ(panoptic::growth_options_from_config(panoptic::load_scene(file, none))
                .turbulence.vg2_factor,
            1.0);
  EXPECT_EQ(panoptic::growth_options_from_config(panoptic::load_scene(file, set))
                .turbulence.vg2_factor,
            1.5);
}
