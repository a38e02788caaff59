//! Tests of fragmentation and bouncing in the growth rates (physics/fragmentation.hpp;
//! spec §5.3): the fragmentation factor and its limits, its interplay with the erosion
//! halt and balance, the species the scene names, the bouncing switch. Set-up and
//! reference numbers: growth_fixture.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "tests/unit/physics/growth_fixture.hpp"

using namespace growth_fixture;

// ------------------------------------------------------- fragmentation, bouncing, §5.3

TEST(GrowthFragmentation, ErosionHaltStopsGrowthButNotFragmentation) {
  // E1 + fragmentation: where dv_ls >> v_eros (S = 0) growth stops, but collisions above
  // v_frag still fragment: the factor is the fragmentation loss, not 0 (S frag, the
  // spec's literal composition, froze the particle). Below v_frag: 0 (halted) up to the
  // smooth positive part's band. Without erosion the factor is frag itself.
  const LocalGas gas = mmsn_gas(5.0);
  const double m = 1e10, phi = 1e-5, st = 1.0;  // dv_ls ~ 68 m/s: S = 0 at 40 m/s
  GrowthOptions none = plain_options(), halt = plain_options(), frag = plain_options();
  halt.erosion = ErosionModel::kHalt;
  halt.fragmentation = true;
  frag.fragmentation = true;
  Species sp = ice_species();
  const double coag = particle_rates(kSigmaD, m, phi, st, gas, sp, none).dm_dt;
  for (double v_frag : {1e3, 2e3}) {  // 10 and 20 m/s, both below dv: loss
    sp.v_frag = v_frag;
    const auto r = particle_rates(kSigmaD, m, phi, st, gas, sp, halt);
    const double f = particle_rates(kSigmaD, m, phi, st, gas, sp, frag).dm_dt / coag;
    ASSERT_LT(f, -0.1) << v_frag;
    ASSERT_GT(r.dv_ls, 1.5 * halt.v_eros);  // S = 0 to round-off
    EXPECT_NEAR(r.dm_dt / coag, f, 1e-6) << v_frag;
  }
  sp.v_frag = 1e5;  // 1 km/s: no fragmentation, growth only, halted
  const auto r = particle_rates(kSigmaD, m, phi, st, gas, sp, halt);
  EXPECT_LT(std::abs(r.dm_dt / coag), 1e-6);
}

TEST(GrowthFragmentation, WithErosionBalanceFragmentsOnlyTheSimilarSizeTerm) {
  // E2 + fragmentation: dm/dt = (1 - f_s) F_frag R_coag + f_s (projectile term). With
  // net erosion (f_s = 0.95) and fragmentation (v_frag = 10 m/s < dv) both terms are
  // losses; multiplying the whole E2 factor by F_frag (as before this test) turned the
  // two negatives into growth (+9.75 g/s against -481 and -11.6 g/s alone, measured at
  // Sigma_d = 1.5 g cm^-2; 1.35 % more at this test's kSigmaD).
  const LocalGas gas = mmsn_gas(5.0);
  Species sp = ice_species();
  sp.v_frag = 1e3;
  const double m = 1e10, phi = 1e-5, st = 1.0;
  GrowthOptions none = plain_options(), e2 = plain_options();
  e2.erosion = ErosionModel::kBalance;
  e2.f_s = 0.95;
  GrowthOptions frag = plain_options(), both = e2;
  frag.fragmentation = true;
  both.fragmentation = true;
  const double coag = particle_rates(kSigmaD, m, phi, st, gas, sp, none).dm_dt;
  const double r_frag = particle_rates(kSigmaD, m, phi, st, gas, sp, frag).dm_dt / coag;
  const double r_e2 = particle_rates(kSigmaD, m, phi, st, gas, sp, e2).dm_dt / coag;
  const double r_both = particle_rates(kSigmaD, m, phi, st, gas, sp, both).dm_dt / coag;
  ASSERT_LT(r_frag, 0.0);
  ASSERT_LT(r_e2, 0.0);
  // the projectile share of E2: r_e2 = (1 - f_s) + f_s X
  const double x = (r_e2 - (1.0 - e2.f_s)) / e2.f_s;
  EXPECT_LT(r_both, 0.0);
  EXPECT_NEAR(r_both, (1.0 - e2.f_s) * r_frag + e2.f_s * x, 1e-12);
  // and the filling factor sees no growth: the smooth positive part (band 1e-3) of a
  // loss r R_coag is ~1e-6/(4|r|) R_coag, here 2e-6 of |d ln m/dt| (|slope| <= 0.58);
  // it was |slope| |d ln m/dt| when the loss was taken for growth)
  both.porosity = true;
  const auto rb = particle_rates(kSigmaD, m, phi, st, gas, sp, both);
  EXPECT_LT(rb.dlnm_dt, 0.0);
  EXPECT_LT(std::abs(rb.dlnphi_dt), 1e-5 * std::abs(rb.dlnm_dt)) << r_both;
}

TEST(GrowthFragmentation, FactorAndLimits) {
  // dm/dt -> dm/dt (1 - 2 dv^2/(dv^2 + v_frag^2)) (spec §5.3): 1 for dv << v_frag, 0 at
  // dv = v_frag, -> -1 for dv >> v_frag. States (python St): (1 g, 1e-3), dv = 5.84
  // cm/s; (1e8 g, 5e-4), dv = 17.8 m/s.
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  struct State {
    double m, phi, st;
  };
  const State slow{1.0, 1e-3, 8.020136923798523e-05};
  const State fast{1e8, 5e-4, 0.20427797089107294};
  GrowthOptions none = plain_options(), frag = plain_options();
  frag.fragmentation = true;
  auto ratio = [&](const State& s, double v_frag) {
    Species spf = sp;
    spf.v_frag = v_frag;
    return particle_rates(kSigmaD, s.m, s.phi, s.st, gas, spf, frag).dm_dt /
           particle_rates(kSigmaD, s.m, s.phi, s.st, gas, spf, none).dm_dt;
  };
  const double dv_slow = dv_pair(slow.st, slow.m, gas);
  const double dv_fast = dv_pair(fast.st, fast.m, gas);
  // dv << v_frag = 60 m/s (ice, the Species default): 1 - 1.9e-6
  EXPECT_NEAR(ratio(slow, 6e3), fragmentation_factor(dv_slow, 6e3), 1e-14);
  EXPECT_NEAR(ratio(slow, 6e3), 1.0, 1e-5);
  // formula across the range: 60 m/s (0.8385), 10 m/s, 5 m/s (silicate), 1 m/s
  for (double v_frag : {6e3, 1e3, 5e2, 1e2})
    EXPECT_NEAR(ratio(fast, v_frag), fragmentation_factor(dv_fast, v_frag), 1e-13)
        << v_frag;
  EXPECT_EQ(ratio(fast, dv_fast), 0.0);       // dv = v_frag: exactly balanced
  EXPECT_LT(ratio(fast, 1e2), -0.99);         // 1 m/s: -0.99369
  EXPECT_NEAR(ratio(fast, 1.0), -1.0, 1e-6);  // 1 cm/s: -1 + 6.3e-7
}

TEST(GrowthFragmentation, OnlyTheSpeciesTheSceneNamesFragment) {
  // fragmentation.species = "silicate" (spec §11 #17: silicates inside the snow line
  // fragment at 5 m/s; §5.3: porous ice does not): the ice species' rates are those
  // without fragmentation, bit for bit, and the silicate's carry the factor.
  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const auto species = [&](const std::vector<std::string>& set) {
    const panoptic::Config cfg = panoptic::load_scene(file, set);
    return std::pair{panoptic::species_from_config(cfg, "ice"),
                     panoptic::species_from_config(cfg, "sil")};
  };
  const std::vector<std::string> on{"fragmentation.enabled=true"};
  std::vector<std::string> sil_only = on, ice_only = on;
  sil_only.push_back("fragmentation.species=\"silicate\"");
  ice_only.push_back("fragmentation.species=\"ice\"");
  EXPECT_TRUE(species(on).first.fragments);
  EXPECT_TRUE(species(on).second.fragments);
  EXPECT_FALSE(species(sil_only).first.fragments);
  EXPECT_TRUE(species(sil_only).second.fragments);
  EXPECT_TRUE(species(ice_only).first.fragments);
  EXPECT_FALSE(species(ice_only).second.fragments);
  EXPECT_EQ(species(sil_only).second.v_frag, 500.0);  // 5 m/s, the scene's default

  // The fast state of FactorAndLimits (dv = 17.8 m/s > 5 m/s) at 5 au.
  const LocalGas gas = mmsn_gas(5.0);
  const double m = 1e8, phi = 5e-4, st = 0.20427797089107294;
  GrowthOptions none = plain_options(), frag = plain_options();
  frag.fragmentation = true;
  const auto [ice, sil] = species(sil_only);
  const auto r_ice = particle_rates(kSigmaD, m, phi, st, gas, ice, frag);
  const auto r_ice_off = particle_rates(kSigmaD, m, phi, st, gas, ice, none);
  EXPECT_EQ(r_ice.dm_dt, r_ice_off.dm_dt);
  EXPECT_EQ(r_ice.dlnphi_dt, r_ice_off.dlnphi_dt);
  const auto r_sil = particle_rates(kSigmaD, m, phi, st, gas, sil, frag);
  const auto r_sil_off = particle_rates(kSigmaD, m, phi, st, gas, sil, none);
  EXPECT_NEAR(r_sil.dm_dt / r_sil_off.dm_dt, fragmentation_factor(r_sil.dv, 500.0),
              1e-13);
  EXPECT_LT(r_sil.dm_dt, 0.0);  // dv > v_frag: loss
}

TEST(GrowthBouncing, OffAboveOnBelowPhiBounce) {
  // Bouncing (spec §5.3): growth stops smoothly for compact aggregates, phi >= phi_bounce
  // = 0.3; unaffected for porous ones. Ratio to the no-bouncing rate at m = 1e3 g.
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  GrowthOptions none = plain_options(), bounce = plain_options();
  bounce.bouncing = true;
  auto ratio = [&](double phi) {
    return rates_at(kSigmaD, 1e3, phi, gas, sp, bounce).dm_dt /
           rates_at(kSigmaD, 1e3, phi, gas, sp, none).dm_dt;
  };
  EXPECT_GT(ratio(0.03), 1.0 - 1e-9);  // a decade below phi_bounce
  EXPECT_GT(ratio(0.1), 1.0 - 1e-6);
  EXPECT_LT(ratio(0.9), 1e-9);  // 0.48 dex above
  EXPECT_LT(ratio(1.0), 1e-9);  // compact
  EXPECT_GT(ratio(0.3), 0.25);  // the switch sits at phi_bounce
  EXPECT_LT(ratio(0.3), 0.75);
}
