//! Tests of erosion in the growth rates (physics/erosion.hpp; spec §5.2): the E1 halt
//! (a tanh switch of dv_LS/v_eros) and the E2 balance of gain and loss. Set-up and
//! reference numbers: growth_fixture.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/unit/physics/growth_fixture.hpp"

using namespace growth_fixture;

// ---------------------------------------------------------------------- erosion, §5.2

TEST(GrowthErosionHalt, FactorIsTanhSwitchOfDvLsOverVEros) {
  // E1 (spec §5.2): dm/dt(halt) / dm/dt(none) = S(x), S = 1/2 [1 - tanh((x - 1)/w)],
  // x = dv_ls / v_eros, dv_ls the speed against monomers (St_s = kStMono, m_s = m0; from
  // the C++ dv_small_projectile). v_eros = 40 m/s; python puts dv_ls = v_eros at St* =
  // 0.33688427671 (spec §5.2: "40 m/s -> St = 0.32-0.36"). St is passed directly
  // around St*, for the target (1e10 g, phi = 1e-5) whose own St is 0.328.
  constexpr double kStStar = 0.3368842767113562;
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  const double m = 1e10, phi = 1e-5;
  for (double w : {0.01, 0.05}) {  // GrowthOptions default, and spec §5.2's value
    GrowthOptions none = plain_options(), halt = plain_options();
    halt.erosion = ErosionModel::kHalt;
    halt.v_eros = 4e3;
    halt.w_eros = w;
    for (double f : {0.8, 0.9, 0.97, 0.99, 0.995, 1.0, 1.005, 1.01, 1.03, 1.1, 1.5}) {
      const double st = kStStar * f;
      const auto rn = particle_rates(kSigmaD, m, phi, st, gas, sp, none);
      const auto rh = particle_rates(kSigmaD, m, phi, st, gas, sp, halt);
      const double dv_ls = dv_small_projectile(st, m, kStMono, kM0, gas);
      EXPECT_LT(rel_err(rh.dv_ls, dv_ls), 1e-12) << "St = " << st;
      const double s = erosion_switch(dv_ls / 4e3, w);
      EXPECT_NEAR(rh.dm_dt / rn.dm_dt, s, 1e-12) << "St = " << st << ", w = " << w;
    }
    // the stall point: S = 1/2 at St*, ~1 ten per cent below it, ~0 ten per cent above
    // (w = 0.01: d ln dv_ls / d ln St = 0.71 there, so x - 1 = +-0.07 = 7 w)
    auto ratio = [&](double st) {
      return particle_rates(kSigmaD, m, phi, st, gas, sp, halt).dm_dt /
             particle_rates(kSigmaD, m, phi, st, gas, sp, none).dm_dt;
    };
    EXPECT_NEAR(ratio(kStStar), 0.5, 1e-9) << "w = " << w;
    if (w == 0.01) {
      EXPECT_GT(ratio(0.9 * kStStar), 1.0 - 1e-5);
      EXPECT_LT(ratio(1.1 * kStStar), 1e-5);
    }
  }
}

TEST(GrowthErosionBalance, MatchesSpecFormula) {
  // E2 (spec §5.2): dm/dt = (1 - f_s) 2 sqrt(pi) a^2 dv Sigma_d/h_d
  //                       + f_s 2 sqrt(pi) a^2 dv_ls Sigma_d/h_bar [1 - (1+eps)(1 - S)],
  // h_bar = sqrt(h_d^2 + h_s^2)/sqrt(2), h_s = h_d(St_monomer). python: K_d = 2 sqrt(pi)
  // a^2 Sigma_d / h_d, K_s = 2 sqrt(pi) a^2 Sigma_d / h_bar for (1e10 g, phi = 1e-5);
  // dv, dv_ls from the C++; S from the formula; v_eros = 40 m/s, w = 0.01.
  struct Case {
    double st, k_d, k_s;
  };
  const std::vector<Case> cases = {
      {0.1, 0.04661469552358535, 0.006255034508931037},
      {0.3368842767113562, 0.09134873094712836, 0.006275963867994706},  // x = 1
      {1.0, 0.17212243008823552, 0.0062812905531666775},
      {100.0, 1.9819174241863486, 0.006283367087154696},
  };
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  const double m = 1e10, phi = 1e-5;
  for (double f_s : {0.1, 0.5, 0.95}) {
    for (double eps_eros : {1.0, 3.0}) {
      GrowthOptions o = plain_options();
      o.erosion = ErosionModel::kBalance;
      o.v_eros = 4e3;
      o.f_s = f_s;
      o.eps_eros = eps_eros;
      for (const Case& c : cases) {
        const double dv = dv_pair(c.st, m, gas);
        const double dv_ls = dv_small_projectile(c.st, m, kStMono, kM0, gas);
        const double s = erosion_switch(dv_ls / 4e3, 0.01);
        const double expected =
            (1.0 - f_s) * c.k_d * dv +
            f_s * c.k_s * dv_ls * (1.0 - (1.0 + eps_eros) * (1.0 - s));
        const double got = particle_rates(kSigmaD, m, phi, c.st, gas, sp, o).dm_dt;
        EXPECT_NEAR(got, expected,
                    1e-12 * (1.0 - f_s) * c.k_d * dv + 1e-12 * c.k_s * dv_ls)
            << "St = " << c.st << ", f_s = " << f_s << ", eps_eros = " << eps_eros;
      }
    }
  }
}

TEST(GrowthErosionBalance, NetErosionWellAboveVEros) {
  // With eps_eros = 1 the projectile term is -f_s R_s for x >> 1 (S -> 0), so dm/dt < 0
  // iff f_s R_s > (1 - f_s) R_coag, R_s/R_coag = (dv_ls h_d)/(dv h_bar). At St = 1
  // (x = 6845/4000 = 1.71, S = 0 in double) python gives R_s/R_coag = 0.0740 (0.114 at
  // St*, < 0.05 for St > 10): net erosion needs f_s > 0.93. Spec inconsistency (see
  // report): with the spec defaults f_s = 0.1, eps_eros = 1 the E2 rate stays >= 0.88 of
  // the coagulation rate at every St at 5 AU: E2 neither erodes nor stalls growth.
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  const double m = 1e10, phi = 1e-5, st = 1.0;
  GrowthOptions none = plain_options(), e2 = plain_options();
  e2.erosion = ErosionModel::kBalance;
  e2.v_eros = 4e3;
  e2.eps_eros = 1.0;
  const double coag = particle_rates(kSigmaD, m, phi, st, gas, sp, none).dm_dt;
  e2.f_s = 0.95;  // reservoir-dominated: net erosion
  const double eroding = particle_rates(kSigmaD, m, phi, st, gas, sp, e2).dm_dt;
  EXPECT_LT(eroding, 0.0);
  // python: 0.05 - 0.95 * 0.07396515995 = -0.02026690
  EXPECT_NEAR(eroding / coag, 0.05 - 0.95 * 0.07396515994630538, 1e-9);
  e2.f_s = 0.1;  // spec default: only the (1 - f_s) dilution and a 0.74% loss remain
  EXPECT_NEAR(particle_rates(kSigmaD, m, phi, st, gas, sp, e2).dm_dt / coag,
              0.9 - 0.1 * 0.07396515994630538, 1e-9);
}

TEST(GrowthErosionBalance, SpecDefaultsHardlyErodeAtAnySt) {
  // tests/README.md's claim (What works) about E2 at the spec defaults, over the whole
  // range of St at 5 au (400 log-spaced St from 1e-6 to 1e4; m and phi enter the ratio to
  // coagulation only through the Brownian term, negligible here): (1) with f_s = 0.1,
  // eps_eros = 1 the E2 rate stays >= 0.88 of the coagulation rate everywhere (measured:
  // 0.889, at St = 0.37); (2) the smallest f_s that gives net erosion at some St: the
  // rate is linear in f_s at fixed St, ratio = 1 - f_s (1 - B(St)), so it turns negative
  // first where the f_s = 0.1 ratio is lowest, at f_s* = 0.1 / (1 - worst) = 0.901 (at St
  // = 1, in the test above, it takes f_s > 0.93); checked on the code's own sign on both
  // sides of f_s*.
  const LocalGas gas = mmsn_gas(5.0);
  const Species sp = ice_species();
  const double m = 1e10, phi = 1e-5;
  GrowthOptions none = plain_options(), e2 = plain_options();
  e2.erosion = ErosionModel::kBalance;
  e2.v_eros = 4e3;
  e2.eps_eros = 1.0;
  auto ratio = [&](double st, double f_s) {
    e2.f_s = f_s;
    return particle_rates(kSigmaD, m, phi, st, gas, sp, e2).dm_dt /
           particle_rates(kSigmaD, m, phi, st, gas, sp, none).dm_dt;
  };
  std::vector<double> sts(400);
  for (int k = 0; k < 400; ++k) sts[k] = std::pow(10.0, -6.0 + 10.0 * k / 399.0);
  double worst = 1.0, st_worst = 0.0;
  for (double st : sts) {
    const double r = ratio(st, 0.1);
    if (r < worst) worst = r, st_worst = st;
  }
  const double f_star = 0.1 / (1.0 - worst);
  std::printf(
      "E2 at 5 au, spec defaults: min rate/coagulation %.4f at St = %.3g; net "
      "erosion from f_s = %.4f\n",
      worst, st_worst, f_star);
  EXPECT_GE(worst, 0.88);
  EXPECT_LT(worst, 0.9);  // the (1 - f_s) dilution plus a loss: E2 is not inert
  EXPECT_NEAR(f_star, 0.90, 0.005);
  EXPECT_LT(ratio(st_worst, 1.001 * f_star), 0.0);
  for (double st : sts) EXPECT_GT(ratio(st, 0.999 * f_star), 0.0) << "St = " << st;
}
