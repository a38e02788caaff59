//! Tests of the growth rate particle_rates() assembles (physics/growth_rates.hpp; spec
//! §4.1): the coagulation rate against the spec's formula, the growth multiplier and the
//! soft St cap. Set-up and reference numbers: growth_fixture.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/unit/physics/growth_fixture.hpp"

using namespace growth_fixture;

// ------------------------------------------------------------------- growth rate, §4.1

TEST(GrowthRate, CoagulationRateMatchesSpecFormula) {
  // dm/dt = 2 sqrt(pi) a^2 dv Sigma_d / h_d (spec §4.1). Per state python gives St
  // (bisection of the smooth law, §2), a = (3m/(4 pi rho0 phi))^(1/3) and h_d = H [1 +
  // (St/alpha)(1+2St)/(1+St)]^(-1/2) (§2), hence K = 2 sqrt(pi) a^2 Sigma_d / h_d;
  // dv = dv_pair(St, m) from the C++ (python's own dv agrees to < 4e-12).
  struct Case {
    double m, phi, sigma, st, a, h_d, k;
  };
  const std::vector<Case> cases = {
      // Brownian/tight-turbulence compact grain
      {1e-10, 1.0, 0.5, 3.7226177989548756e-06, 0.0002573916486675484, 3723920798776.658,
       3.1532863001418645e-20},
      // spec §12 examples (m = 1 g, phi = 1e-3) and (1e8 g, 5e-4), Sigma_d = 0.01 Sigma_g
      {1.0, 1e-3, kSigmaD, 8.020136923798523e-05, 5.545334968138647, 3589662675536.7915,
       4.617434861409099e-11},
      {1e8, 5e-4, kSigmaD, 0.20427797089107294, 3242.9315622338954, 240860680083.1155,
       0.00023534691278953278},
      // St >> 1 in the Newton drag regime
      {1e12, 1e-3, 3.0, 26.70194547154531, 55453.34968138645, 16291904482.788624,
       2.007288985541329},
  };
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  for (const Case& c : cases) {
    const ParticleRates<double> r =
        particle_rates(c.sigma, c.m, c.phi, c.st, gas, sp, plain_options());
    const double dv = dv_pair(c.st, c.m, gas);
    EXPECT_LT(rel_err(r.a, c.a), 1e-13) << "m = " << c.m;
    EXPECT_LT(rel_err(r.h_d, c.h_d), 1e-12) << "m = " << c.m;
    EXPECT_LT(rel_err(r.dv, dv), 1e-14) << "m = " << c.m;
    EXPECT_LT(rel_err(r.dm_dt, c.k * dv), 1e-12) << "m = " << c.m;
    EXPECT_LT(rel_err(r.dlnm_dt, c.k * dv / c.m), 1e-12) << "m = " << c.m;
  }
}

TEST(GrowthRate, GrowthMultiplierScalesLinearly) {
  // f_grow multiplies dm/dt (spec §4.1): exactly 0.3x and 2.5x, at two states, with and
  // without the optional loss processes (fragmentation, E1 halt) that multiply it.
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  for (double m : {1.0, 1e7}) {
    for (int variant = 0; variant < 2; ++variant) {
      GrowthOptions o = plain_options();
      if (variant == 1) {
        o.fragmentation = true;
        o.erosion = ErosionModel::kHalt;
      }
      const double base = rates_at(kSigmaD, m, 1e-3, gas, sp, o).dm_dt;
      ASSERT_GT(base, 0.0) << m;
      for (double f : {0.3, 2.5}) {
        o.f_grow = f;
        EXPECT_LT(rel_err(rates_at(kSigmaD, m, 1e-3, gas, sp, o).dm_dt, f * base), 1e-14)
            << "m = " << m << ", f_grow = " << f << ", variant " << variant;
      }
    }
  }
}

TEST(GrowthRate, SoftStokesCapSwitchesGrowthOff) {
  // GrowthOptions::st_max: growth is switched off smoothly above St = st_max (1e4). The
  // capped rate, relative to the same state with the cap moved out of reach (1e300), is
  // ~1 a decade below st_max, ~0 a decade above it, and between at st_max.
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  GrowthOptions capped = plain_options(), free = plain_options();
  free.st_max = 1e300;
  auto ratio = [&](double st) {
    return particle_rates(kSigmaD, 1e16, 1e-2, st, gas, sp, capped).dm_dt /
           particle_rates(kSigmaD, 1e16, 1e-2, st, gas, sp, free).dm_dt;
  };
  EXPECT_GT(ratio(1e3), 1.0 - 1e-9);
  EXPECT_LT(ratio(1e5), 1e-9);
  EXPECT_GT(ratio(1e4), 0.25);
  EXPECT_LT(ratio(1e4), 0.75);
}
