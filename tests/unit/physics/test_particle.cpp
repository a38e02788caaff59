//! Tests of physics/particle.hpp, physics/drag.hpp, physics/smooth_switches.hpp and
//! disk/local_gas.hpp (spec §1.3-1.6, §2, §12).
//! Reference numbers are the spec's (§12) and independent evaluations of the spec
//! formulas made with a separate python3 script (bisection on the fixed-point equation,
//! no Newton iteration, no C++), quoted to 10+ digits where used with tight tolerances.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "disk/local_gas.hpp"
#include "physics/drag.hpp"
#include "physics/particle.hpp"
#include "src/core/units.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

namespace panoptic::physics {
namespace {

using AD = Eigen::AutoDiffScalar<Eigen::Vector2d>;
constexpr double kRho0Ice = 1.4;  // spec §12 [g cm^-3]

//! St of the smooth law as a plain function of (m, phi), for finite differences.
double st_of(double m, double phi, const LocalGas& gas) {
  return stokes_number(m, phi, kRho0Ice, gas);
}

class ParticleMmsn5au : public ::testing::Test {
 protected:
  LocalGas gas = mmsn_gas(5.0);
};

// ------------------------------------------------------------------------------- gas,
// §12 --

TEST_F(ParticleMmsn5au, GasMatchesSpecTable) {
  // spec §12 row "5 AU" (3 significant digits -> 0.5-1% tolerances)
  EXPECT_LT(rel_err(gas.sigma_g, 152.0), 0.005);
  EXPECT_LT(rel_err(gas.temperature, 125.0), 0.005);
  EXPECT_LT(rel_err(gas.c_s, 665e2), 0.005);
  EXPECT_LT(rel_err(gas.h_g / (5.0 * units::kAu), 0.0499), 0.005);
  EXPECT_LT(rel_err(gas.rho_g, 1.63e-11), 0.005);
  EXPECT_LT(rel_err(gas.mfp, 120.0), 0.01);
  EXPECT_LT(rel_err(gas.eta, 4.04e-3), 0.005);
  EXPECT_LT(rel_err(gas.headwind(), 53.9e2), 0.005);                  // eta v_K, §1.4
  EXPECT_LT(rel_err(9.0 * gas.mfp / 4.0, 271.0), 0.005);              // Epstein/Stokes
  EXPECT_LT(rel_err(gas.reynolds(), 3.9e7), 0.02);                    // Re, 2 digits
  EXPECT_LT(rel_err(1.0 / std::sqrt(gas.reynolds()), 1.6e-4), 0.03);  // St_eta, 2 digits
  EXPECT_LT(rel_err(gas.alpha * gas.c_s * gas.h_g, 2.5e14), 0.02);    // D_g, 2 digits
  // orbital period 11.2 yr
  EXPECT_LT(rel_err(2.0 * units::kPi / gas.omega_k / units::kYr, 11.2), 0.005);
}

TEST(LocalGas, MakeLocalGasReproducesSpecTable) {
  // spec §12 table: r [AU], Sigma_g, T, c_s [m/s], H/r, rho_g, lambda, eta, P_orb [yr];
  // 3 significant digits (0.5%), 2 for eta at 30 AU (1%). The same rows were reproduced
  // independently in python (e.g. 2.7 AU: 383.18, 170.4 K, 775.1 m/s, 0.04276, 8.851e-11,
  // 22.12 cm, 2.971e-3, 4.436 yr).
  struct Row {
    double r_au, sigma, temp, cs, h_r, rho, mfp, eta, p_orb, eta_tol;
  };
  const std::vector<Row> rows = {
      {1.0, 1700.0, 280.0, 994.0, 0.0334, 1.36e-9, 1.44, 1.81e-3, 1.0, 0.005},
      {2.7, 383.0, 170.0, 775.0, 0.0428, 8.85e-11, 22.1, 2.97e-3, 4.4, 0.005},
      {5.0, 152.0, 125.0, 665.0, 0.0499, 1.63e-11, 120.0, 4.04e-3, 11.2, 0.005},
      {10.0, 53.8, 88.5, 559.0, 0.0593, 2.42e-12, 810.0, 5.72e-3, 31.6, 0.005},
      {30.0, 10.3, 51.1, 425.0, 0.0781, 1.18e-13, 1.66e4, 9.9e-3, 164.0, 0.01},
      {100.0, 1.70, 28.0, 314.0, 0.1055, 4.30e-15, 4.56e5, 1.81e-2, 1000.0, 0.005},
  };
  for (const Row& w : rows) {
    const double r = w.r_au * units::kAu;
    const LocalGas g =
        make_local_gas(1700.0 * std::pow(w.r_au, -1.5), 280.0 / std::sqrt(w.r_au), r,
                       units::kMsun, 1e-3, -3.25);
    EXPECT_LT(rel_err(g.sigma_g, w.sigma), 0.005) << w.r_au;
    EXPECT_LT(rel_err(g.temperature, w.temp), 0.005) << w.r_au;
    EXPECT_LT(rel_err(g.c_s, 100.0 * w.cs), 0.005) << w.r_au;
    EXPECT_LT(rel_err(g.h_g / r, w.h_r), 0.005) << w.r_au;
    EXPECT_LT(rel_err(g.rho_g, w.rho), 0.005) << w.r_au;
    EXPECT_LT(rel_err(g.mfp, w.mfp), 0.005) << w.r_au;
    EXPECT_LT(rel_err(g.eta, w.eta), w.eta_tol) << w.r_au;
    // P_orb quoted to 2-4 digits: 4.4 and 1.0 are 2 digits (1.2%, 5%)
    EXPECT_LT(rel_err(2.0 * units::kPi / g.omega_k / units::kYr, w.p_orb), 0.012)
        << w.r_au;
    EXPECT_LT(rel_err(g.headwind(), 53.9e2), 0.002)
        << w.r_au;  // 53.9 m/s at all r (§1.4)
  }
}

TEST_F(ParticleMmsn5au, MakeLocalGasAgreesWithSpecFormulas) {
  const LocalGas g = make_local_gas(1700.0 * std::pow(5.0, -1.5), 280.0 / std::sqrt(5.0),
                                    5.0 * units::kAu, units::kMsun, 1e-3, -3.25);
  EXPECT_LT(rel_err(g.rho_g, gas.rho_g), 1e-12);
  EXPECT_LT(rel_err(g.c_s, gas.c_s), 1e-12);
  EXPECT_LT(rel_err(g.v_th, gas.v_th), 1e-12);
  EXPECT_LT(rel_err(g.omega_k, gas.omega_k), 1e-12);
  EXPECT_LT(rel_err(g.v_k, gas.v_k), 1e-12);
  EXPECT_LT(rel_err(g.h_g, gas.h_g), 1e-12);
  EXPECT_LT(rel_err(g.mfp, gas.mfp), 1e-12);
  EXPECT_LT(rel_err(g.nu_mol, gas.nu_mol), 1e-12);
  EXPECT_LT(rel_err(g.eta, gas.eta), 1e-12);
  EXPECT_EQ(g.alpha, 1e-3);
  EXPECT_EQ(g.v_r_gas, 0.0);
}

// ----------------------------------------------------------------------- structure, §2
// --

TEST(Particle, MonomerMassIce) {
  // spec §12: 5.86e-15 g; hand: 4.18879 * 1e-15 * 1.4 = 5.86431e-15
  const double m0 = monomer_mass(1e-5, kRho0Ice);
  EXPECT_LT(rel_err(m0, 5.86e-15), 0.001);
  EXPECT_LT(rel_err(m0, 5.864306286700947e-15), 1e-12);
}

TEST(Particle, RadiusAndMonomerCount) {
  const double m0 = monomer_mass(1e-5, kRho0Ice);
  EXPECT_LT(rel_err(radius(m0, 1.0, kRho0Ice), 1e-5), 1e-12);  // a(m0, 1) = a0
  // a = a0 (m / (m0 phi))^(1/3): N = 1e9 monomers at phi = 1e-3 -> a = a0 * 1e4
  EXPECT_LT(rel_err(radius(1e9 * m0, 1e-3, kRho0Ice), 0.1), 1e-12);
  EXPECT_LT(rel_err(monomer_count(1e9 * m0, m0), 1e9), 1e-12);
  EXPECT_DOUBLE_EQ(internal_density(1e-3, kRho0Ice), 1.4e-3);
}

TEST_F(ParticleMmsn5au, SpecExampleParticles) {
  struct Case {
    double m, phi;
    double a_spec, st_spec, a_tol, st_tol;  // spec §12 and tolerances from its digits
    double st_indep;                        // python bisection of the smooth law
  };
  const std::vector<Case> cases = {
      {1.0, 1e-3, 5.5, 8.0e-5, 0.01, 0.01, 8.020136923798523e-05},
      // St: the spec's 0.21 is the hard piecewise law (python: 0.20581); the p = 8
      // soft-max of spec §2 is 0.75% lower (0.20428) because Re_p = 2.2 is near the Re_p
      // = 1 corner.
      {1e8, 5e-4, 3200.0, 0.21, 0.02, 0.03, 0.20427797089107294},
      {1e10, 1e-3, 12000.0, 2.2, 0.01, 0.01, 2.1894345047934904},
  };
  for (const Case& c : cases) {
    const double a = radius(c.m, c.phi, kRho0Ice);
    const double st = st_of(c.m, c.phi, gas);
    EXPECT_LT(rel_err(a, c.a_spec), c.a_tol) << "m = " << c.m;
    EXPECT_LT(rel_err(st, c.st_spec), c.st_tol) << "m = " << c.m;
    EXPECT_LT(rel_err(st, c.st_indep), 1e-9) << "m = " << c.m;
  }
  // h_d/H = 0.064 for (1e8 g, 5e-4) (spec §12); python with the smooth St: 0.0645593
  const double st = st_of(1e8, 5e-4, gas);
  EXPECT_LT(rel_err(dust_scale_height(st, gas) / gas.h_g, 0.064), 0.01);
  EXPECT_LT(rel_err(dust_scale_height(st, gas) / gas.h_g, 0.06455927048366601), 1e-9);
}

TEST_F(ParticleMmsn5au, MonomerStokesNumber) {
  // spec §12: 1.45e-7; hand: pi * 1.4 * 1e-5 / (2 * 152.05) = 1.44629e-7
  const double m0 = monomer_mass(1e-5, kRho0Ice);
  const double st = st_of(m0, 1.0, gas);
  EXPECT_LT(rel_err(st, 1.45e-7), 0.005);
  EXPECT_LT(rel_err(st, 1.4462853858025006e-07), 1e-9);
}

TEST_F(ParticleMmsn5au, EpsteinEqualsMidplaneSurfaceDensityForm) {
  // spec §2: t_s Omega = pi rho_int a / (2 Sigma_g) at the midplane
  const double a = 3.0, rho_int = 0.01;
  const double st = stokes_epstein(a, rho_int, gas);
  EXPECT_LT(rel_err(st, units::kPi * rho_int * a / (2.0 * gas.sigma_g)), 1e-12);
}

// ------------------------------------------------------------------ drag-law regimes, §2
// --

TEST(DragLaw, SmoothFactorLimits) {
  // soft-max error: (1 + r^8)^(1/8) - 1 < 1% for r < 0.73
  EXPECT_NEAR(drag_regime_factor(1e-2, 0.0), 1.0, 1e-12);       // Epstein
  EXPECT_NEAR(drag_regime_factor(1e2, 0.0) / 1e2, 1.0, 1e-12);  // Stokes, Re_p = 0
  // Re_p = 100: the C_D = 0.44 branch is 0.29x the Re^-0.4 one -> 6.4e-6 relative
  // (python)
  EXPECT_NEAR(drag_regime_factor(1e4, 1e2) / (1e4 / std::pow(1e2, 0.4)), 1.0, 1e-5);
  EXPECT_NEAR(drag_regime_factor(1e6, 1e5) / (1e6 / (0.44 / 24.0 * 1e5)), 1.0, 1e-6);
  // worst case of p = 8: exactly at a boundary, 2^(1/8) above the hard law
  EXPECT_NEAR(drag_regime_factor(1.0, 0.0), std::pow(2.0, 0.125), 1e-12);
}

TEST_F(ParticleMmsn5au, DeepEpsteinMatchesEpstein) {
  // (1 g, 1e-3): x = 0.020; Epstein to 1%
  const double a = radius(1.0, 1e-3, kRho0Ice);
  const double st_ep = stokes_epstein(a, 1e-3 * kRho0Ice, gas);
  EXPECT_LT(rel_err(st_of(1.0, 1e-3, gas), st_ep), 0.01);
  // the Epstein law itself against its midplane form pi rho_int a / (2 Sigma_g) (spec
  // §2), written out here (comparing stokes_number with stokes_epstein ran one code path)
  const double st_midplane = units::kPi * 1e-3 * kRho0Ice * a / (2.0 * gas.sigma_g);
  EXPECT_LT(
      rel_err(stokes_number(1.0, 1e-3, kRho0Ice, gas, DragLaw::kEpstein), st_midplane),
      1e-12);
}

TEST(DragLaw, DeepStokesMatchesStokesLaw) {
  // 1 AU, m = 200 g, phi = 1e-4: x = 21.5, Re_p = 2.6e-3 (python). Stokes law
  // t_s = 2 rho_int a^2 / (9 nu_mol rho_g) (spec §2), written out here.
  const LocalGas gas = mmsn_gas(1.0);
  const double m = 200.0, phi = 1e-4;
  const double a = radius(m, phi, kRho0Ice);
  const double st_stokes =
      2.0 * phi * kRho0Ice * a * a / (9.0 * gas.nu_mol * gas.rho_g) * gas.omega_k;
  EXPECT_GT(4.0 * a / (9.0 * gas.mfp), 20.0);
  EXPECT_LT(rel_err(st_of(m, phi, gas), st_stokes), 0.01);
  EXPECT_LT(rel_err(st_of(m, phi, gas), 0.00019481003612107102), 1e-9);  // python
}

TEST(DragLaw, AgreesWithIndependentSolutionInEveryRegime) {
  // python bisection on ln St = ln(St_Ep g(x, Re_p(St))); columns r [AU], m [g], phi, St.
  struct Case {
    double r_au, m, phi, st;
  };
  const std::vector<Case> cases = {
      {1.0, 200.0, 1e-4, 0.00019481003612107102},  // Stokes, Re_p = 2.6e-3
      {1.0, 1e7, 1e-2, 0.31380311939543853},       // Re_p^-0.4 branch, Re_p = 30
      {1.0, 1e12, 0.1, 270.2257457491375},         // C_D = 0.44, Re_p = 1127
      {0.3, 1e9, 1e-3, 0.4023011031152867},        // C_D = 0.44 at St < 1 (Picard fails)
      {5.0, 1e8, 5e-4, 0.20427797089107294},       // near the Re_p = 1 corner
      {30.0, 1e6, 1e-3, 0.11787145878336643},      // Epstein
      {5.0, 1e15, 1e-2, 3092.919173781433},        // Re_p = 434, St >> 1
  };
  for (const Case& c : cases) {
    const LocalGas gas = mmsn_gas(c.r_au);
    EXPECT_LT(rel_err(st_of(c.m, c.phi, gas), c.st), 1e-9)
        << c.r_au << " AU, m = " << c.m;
  }
}

TEST(DragLaw, NewtonIterationSolvesTheFixedPointEverywhere) {
  // Self-consistency over 0.3-100 AU, 1e-15 < m < 1e23 g, 1e-6 < phi < 1:
  // St = St_Ep g(x, Re_p(dv_pg(St))) to round-off.
  for (double r_au : {0.3, 1.0, 5.0, 30.0, 100.0}) {
    const LocalGas gas = mmsn_gas(r_au);
    for (int lm = -15; lm <= 23; ++lm) {
      for (int lp = -6; lp <= 0; ++lp) {
        const double m = std::pow(10.0, lm), phi = std::pow(10.0, lp);
        const double st = st_of(m, phi, gas);
        const double a = radius(m, phi, kRho0Ice);
        const double st_ep = stokes_epstein(a, phi * kRho0Ice, gas);
        const double re_p = particle_reynolds(a, gas_drift_speed(st, gas), gas);
        const double rhs = st_ep * drag_regime_factor(knudsen_ratio(a, gas), re_p);
        ASSERT_LT(std::abs(std::log(st / rhs)), 1e-12)
            << r_au << " AU, m = " << m << ", phi = " << phi;
      }
    }
  }
}

TEST(DragLaw, ContinuousAcrossEveryRegimeBoundary) {
  // Boundaries of g(x, Re_p): x = f_Re (Epstein/Stokes), Re_p = 1 and Re_p = 784
  // (24 Re^-0.6 = 0.44). A tiny step across each must give a tiny change.
  const double h = 1e-9;
  for (double re : {0.0, 1.0, 784.0}) {
    const double xb = reynolds_correction(re);  // x at the Epstein/Stokes corner
    for (double x : {xb, 1e3}) {
      const double lo = drag_regime_factor(x * (1 - h), re * (1 - h));
      const double hi = drag_regime_factor(x * (1 + h), re * (1 + h));
      EXPECT_LT(std::abs(hi / lo - 1.0), 10 * h) << "x = " << x << ", Re = " << re;
    }
  }
  // And along St(m) at 1 AU, phi = 1e-2, across the masses where x = 1, Re_p = 1, Re_p =
  // 784: scan ln m finely and check that no step changes ln St by more than 2x the smooth
  // slope.
  const LocalGas gas = mmsn_gas(1.0);
  const double dlnm = 1e-4;
  double prev = std::log(st_of(1e-2, 1e-2, gas));
  for (double lnm = std::log(1e-2) + dlnm; lnm < std::log(1e14); lnm += dlnm) {
    const double cur = std::log(st_of(std::exp(lnm), 1e-2, gas));
    ASSERT_LT(std::abs(cur - prev), 1.0 * dlnm) << "m = " << std::exp(lnm);  // slope <= 1
    prev = cur;
  }
}

TEST(DragLaw, ShortcutsReturnTheFixedPointToRoundOff) {
  // stokes_number returns St_Ep for x < 0.01, and the Re_p = 0 law without a Newton step
  // where Re_p < kReNegligible there; elsewhere the Newton solve stops at |G| < 1e-8.
  // Scan m across both edges (x = 0.01 and Re_p = 1e-5 fall between 1e-9 and 1e9 g at
  // these radii and filling factors) and hold St to the fixed point St = St_Ep g(x,
  // Re_p(St)) of the p-norm law written with soft_max (drag_regime_factor) to the
  // round-off of a solve in u = ln St: 8 ulp (1 + |u|). The shortcuts drop terms below
  // half an ulp; with the Epstein edge at x < 0.1 (ln g up to 1.25e-9), the Re_p edge at
  // 1e-2 (ln f_Re up to 5e-8) or the Newton stop at |G| < 1e-6, this fails.
  int epstein = 0, re_zero = 0, newton = 0;
  for (double r_au : {1.0, 5.0, 30.0}) {
    const LocalGas gas = mmsn_gas(r_au);
    for (double phi : {1e-4, 1e-2, 1.0}) {
      for (int i = 0; i <= 3600; ++i) {
        const double m = std::pow(10.0, -9.0 + 18.0 * i / 3600.0);
        const double st = st_of(m, phi, gas);
        const double a = radius(m, phi, kRho0Ice);
        const double st_ep = stokes_epstein(a, phi * kRho0Ice, gas);
        const double x = knudsen_ratio(a, gas);
        const double re_p = particle_reynolds(a, gas_drift_speed(st, gas), gas);
        const double rhs = st_ep * drag_regime_factor(x, re_p);
        ASSERT_LT(std::abs(st / rhs - 1.0),
                  8.0 * 2.2e-16 * (1.0 + std::abs(std::log(st))))
            << r_au << " AU, m = " << m << ", phi = " << phi << ", x = " << x
            << ", Re_p = " << re_p;
        // the code's test: Re_p at the Re_p = 0 law, bounded with dv_pg <= 2 eta v_K St
        const double st0 = st_ep * soft_max(1.0, x);
        const double re_bound = particle_reynolds(a, 2.0 * gas.headwind() * st0, gas);
        (x < 1e-2 ? epstein : re_bound < kReNegligible ? re_zero : newton) += 1;
      }
    }
  }
  EXPECT_GT(epstein, 1000);  // the scan covers all three paths
  EXPECT_GT(re_zero, 1000);
  EXPECT_GT(newton, 1000);
}

// ---------------------------------------------------------------- AutoDiff vs finite
// diff --

TEST(DragLaw, AutoDiffMatchesCentralFiniteDifferences) {
  struct Case {
    double r_au, m, phi;
  };
  const std::vector<Case> cases = {
      {5.0, 1.0, 1e-3},   {5.0, 1e8, 5e-4},  {5.0, 1e10, 1e-3},
      {1.0, 200.0, 1e-4}, {1.0, 1e7, 1e-2},  {1.0, 1e12, 0.1},
      {0.3, 1e9, 1e-3},   {5.0, 1e15, 1e-2}, {5.0, 1.2e5, 1e-3},  // near x = 1 at 5 AU
  };
  for (const Case& c : cases) {
    const LocalGas gas = mmsn_gas(c.r_au);
    const AD m(c.m, 2, 0), phi(c.phi, 2, 1);
    const AD st = stokes_number(m, phi, kRho0Ice, gas);
    EXPECT_LT(rel_err(st.value(), st_of(c.m, c.phi, gas)), 1e-14);
    const double hm = 1e-6 * c.m, hp = 1e-6 * c.phi;
    const double fd_m =
        (st_of(c.m + hm, c.phi, gas) - st_of(c.m - hm, c.phi, gas)) / (2 * hm);
    const double fd_p =
        (st_of(c.m, c.phi + hp, gas) - st_of(c.m, c.phi - hp, gas)) / (2 * hp);
    EXPECT_LT(rel_err(st.derivatives()(0), fd_m), 1e-6) << c.r_au << " AU, m = " << c.m;
    EXPECT_LT(rel_err(st.derivatives()(1), fd_p), 1e-6) << c.r_au << " AU, m = " << c.m;
  }
}

// ---------------------------------------------------------------- vertical structure, §2
// --

TEST_F(ParticleMmsn5au, DustScaleHeight) {
  // YL07 at St = 0.21: H [1 + 210 * 1.42 / 1.21]^-1/2 = H / sqrt(247.446) = 0.0635715 H
  EXPECT_LT(rel_err(dust_scale_height(0.21, gas) / gas.h_g, 0.063571), 1e-5);
  // St << 1: Dubrulle-type H sqrt(alpha / (alpha + St)), relative difference O(St)
  const double st = 1e-5;
  EXPECT_LT(rel_err(dust_scale_height(st, gas), gas.h_g * std::sqrt(1e-3 / (1e-3 + st))),
            1e-4);
  // St = 0: h_d = H
  EXPECT_DOUBLE_EQ(dust_scale_height(0.0, gas), gas.h_g);
}

TEST_F(ParticleMmsn5au, MidplaneDustDensity) {
  // Sigma_d = 0.01 Sigma_g with h_d = H gives rho_d = 0.01 rho_g exactly.
  const double sigma_d = 0.01 * gas.sigma_g;
  EXPECT_LT(rel_err(midplane_dust_density(sigma_d, gas.h_g), 0.01 * gas.rho_g), 1e-12);
  EXPECT_LT(rel_err(midplane_dust_to_gas(sigma_d, gas.h_g, gas), 0.01), 1e-12);
}

TEST_F(ParticleMmsn5au, ParticleGasSpeed) {
  // dv_pg(St = 1) = eta v_K sqrt(5)/2; St >> 1 -> eta v_K; St << 1 -> 2 St eta v_K
  EXPECT_LT(rel_err(gas_drift_speed(1.0, gas), gas.headwind() * std::sqrt(5.0) / 2.0),
            1e-14);
  EXPECT_LT(rel_err(gas_drift_speed(1e6, gas), gas.headwind()), 1e-11);
  EXPECT_LT(rel_err(gas_drift_speed(1e-6, gas), 2e-6 * gas.headwind()), 1e-11);
  // the analytic log-slope used by the Newton iteration, against a central difference
  for (double st : {1e-3, 0.5, 1.7, 30.0}) {
    const double h = 1e-6;
    const double fd = (std::log(gas_drift_speed(st * (1 + h), gas)) -
                       std::log(gas_drift_speed(st * (1 - h), gas))) /
                      (std::log1p(h) - std::log1p(-h));
    EXPECT_NEAR(gas_drift_speed_log_slope(st), fd, 1e-8);
  }
}

// ----------------------------------------------------------------------- smooth switches
// --

TEST(SmoothSwitches, SoftMaxSoftMinLogistic) {
  EXPECT_NEAR(soft_max(1.0, 1.0), std::pow(2.0, 0.125), 1e-15);
  EXPECT_DOUBLE_EQ(soft_max(3.0, 0.5), soft_max(0.5, 3.0));
  EXPECT_DOUBLE_EQ(soft_max(1e200, 1e100), 1e200);  // no overflow
  EXPECT_NEAR(soft_min(1.0, 1.0), std::pow(2.0, -0.125), 1e-15);
  EXPECT_LT(rel_err(soft_min(2.0, 1e3), 2.0), 1e-15);
  EXPECT_DOUBLE_EQ(logistic_step(0.0, 3.0), 0.5);
  EXPECT_EQ(logistic_step(-1e3, 1.0), 0.0);
  EXPECT_EQ(logistic_step(1e3, 1.0), 1.0);
  EXPECT_NEAR(log_step(std::pow(10.0, 0.1), 1.0, 0.1), 0.95, 1e-12);
  EXPECT_NEAR(log_step(std::pow(10.0, -0.1), 1.0, 0.1), 0.05, 1e-12);
  // derivatives stay finite in the far tails and at the soft-max pivot
  const AD z(-1e3, 2, 0);
  EXPECT_TRUE(std::isfinite(logistic_step(z, 1.0).derivatives()(0)));
  const AD a(2.0, 2, 0), b(2.0, 2, 1);
  const AD s = soft_max(a, b);
  EXPECT_NEAR(s.derivatives()(0), 0.5 * std::pow(2.0, 0.125), 1e-14);  // d/da at a = b
  EXPECT_NEAR(s.derivatives()(1), 0.5 * std::pow(2.0, 0.125), 1e-14);
}

TEST(SmoothSwitches, LogSpaceSoftMaxAndSoftMinEqualTheLinearOnes) {
  // ln_soft_max(ln a, ln b) = ln (a^p + b^p)^(1/p), ln_soft_min = -ln (a^-p +
  // b^-p)^(1/p), against long double, across the saturation edge p |ln a - ln b| = 40 and
  // both orders; AutoDiff derivative d/d ln a = a^p / (a^p + b^p) (soft_min: a^-p /
  // (...)).
  const double p = kSoftMaxPower;
  int saturated = 0;
  for (double lb : {-7.3, 0.0, 4.1}) {
    for (int i = -3000; i <= 3000; ++i) {
      const double la = lb + 8.0 * i / 3000.0;  // |ln a - ln b| up to 8: p |d| up to 64
      const long double ea = std::exp(static_cast<long double>(p) * la);
      const long double eb = std::exp(static_cast<long double>(p) * lb);
      const long double ref_max = std::log(ea + eb) / p;
      const long double ref_min = -std::log(1.0L / ea + 1.0L / eb) / p;
      const double bound = 4.0 * 2.2e-16 * (1.0 + std::abs(la) + std::abs(lb));
      const AD a(la, 2, 0), b(lb, 2, 1);
      const AD mx = ln_soft_max(a, b), mn = ln_soft_min(a, b);
      ASSERT_LE(std::abs(mx.value() - static_cast<double>(ref_max)), bound)
          << la << " " << lb;
      ASSERT_LE(std::abs(mn.value() - static_cast<double>(ref_min)), bound)
          << la << " " << lb;
      const double wa = static_cast<double>(ea / (ea + eb));
      const double wa_min = static_cast<double>((1.0L / ea) / (1.0L / ea + 1.0L / eb));
      ASSERT_LE(std::abs(mx.derivatives()(0) - wa), 1e-15);
      ASSERT_LE(std::abs(mx.derivatives()(1) - (1.0 - wa)), 1e-15);
      ASSERT_LE(std::abs(mn.derivatives()(0) - wa_min), 1e-15);
      if (p * std::abs(la - lb) > 40.0) ++saturated;
    }
  }
  EXPECT_GT(saturated, 3000);
}

TEST(SmoothSwitches, Log1pSeriesAndTanhStepAreExactToRoundOff) {
  // log1p_nonneg: y - y^2/2 below 1e-8, ln y + 1/y above 1e8, log1p between; against long
  // double over 1e-20 .. 1e20, value within 1 ulp and AutoDiff derivative 1 / (1 + y).
  for (int i = 0; i <= 4000; ++i) {
    const double y = std::pow(10.0, -20.0 + 40.0 * i / 4000.0);
    const long double ref = std::log1p(static_cast<long double>(y));
    const AD ya(y, 2, 0);
    const AD v = log1p_nonneg(ya);
    ASSERT_LE(std::abs(v.value() - static_cast<double>(ref)),
              2.3e-16 * static_cast<double>(ref))
        << y;
    ASSERT_LE(std::abs(v.derivatives()(0) * (1.0 + y) - 1.0), 1e-15) << y;
    EXPECT_EQ(log1p_nonneg(y), v.value());
  }
  // tanh_step: the same bits as (1 + tanh z) / 2 everywhere, the saturated edges included
  for (int i = -30000; i <= 30000; ++i) {
    const double z = 25.0 * i / 30000.0;
    ASSERT_EQ(tanh_step(z), 0.5 * (1.0 + std::tanh(z))) << z;
  }
  // cbrt_of: value and derivative x^(-2/3) / 3
  for (double x : {1e-30, 0.3, 8.0, 1e40}) {
    const AD c = cbrt_of(AD(x, 2, 0));
    EXPECT_EQ(c.value(), std::cbrt(x));
    const long double ref = std::pow(static_cast<long double>(x), -2.0L / 3.0L) / 3.0L;
    EXPECT_LT(rel_err(c.derivatives()(0), static_cast<double>(ref)), 1e-15);
  }
}

// The saturated log_step returns 0 or 1 without evaluating the logistic; it must agree
// with the logistic 1 / (1 + (x0/x)^k) to round-off everywhere: the shortcut may only
// fire where the logistic is within 8.5e-17 of 0 or 1 (kLogisticSaturation). Scanned
// across both saturation edges (to twice their distance from x0) for three widths, 8001
// points each, double and AD.
TEST(SmoothSwitches, SaturatedLogStepEqualsTheLogistic) {
  for (double w : {0.01, 0.1, 0.3}) {
    const double k = std::log(19.0) / (w * std::log(10.0));
    const double x0 = 3.7;
    const double edge_dex = kLogisticSaturation / k / std::log(10.0);
    int shortcut_hits = 0;
    for (int i = -4000; i <= 4000; ++i) {
      const double x = x0 * std::pow(10.0, 2.0 * edge_dex * i / 4000.0);
      const long double exact =
          1.0L / (1.0L + std::pow(static_cast<long double>(x0 / x), k));
      const double v = log_step(x, x0, w);
      // saturated (0 or 1): within 1.12e-16 (the shortcut's 8.5e-17, or the rounding of
      // 1 / (1 + e) to 1 for e < 2^-53); elsewhere to the round-off of x0/x (condition
      // number k) and of z = ln(x/x0) (amplified by |k z| < 37 in exp(k z))
      const bool saturated = v == 0.0 || v == 1.0;
      const double bound = saturated ? 1.12e-16
                                     : 4.0 * (k + kLogisticSaturation) * 2.2e-16 *
                                           static_cast<double>(exact);
      ASSERT_LE(std::abs(v - static_cast<double>(exact)), bound)
          << "w " << w << " x " << x;
      if (saturated) ++shortcut_hits;
      const AD xa(x, 1, 0);
      const AD va = log_step(xa, x0, w);
      EXPECT_EQ(va.value(), v);
      // d/dx of the logistic: k s (1 - s) / x; zero where saturated to round-off
      const double dexact = k * static_cast<double>(exact * (1.0L - exact)) / x;
      ASSERT_LE(std::abs(va.derivatives()(0) - dexact), 1e-15 * k / x + 1e-12 * dexact);
    }
    EXPECT_GT(shortcut_hits, 3000);  // the scan reaches well into the saturated tails
  }
  // no NaN hidden behind the shortcut
  EXPECT_TRUE(std::isnan(log_step(std::nan(""), 1.0, 0.1)));
  EXPECT_EQ(log_step(0.0, 1.0, 0.1), 0.0);
}

// Where the pressure rises outward (eta < 0: inside a pressure maximum, or a surface
// density rising with r) the particle drifts outward as fast as it drifts inward where
// eta > 0: every local law depends on |eta|. With the signed eta the drag solve and the
// gas-compaction floor took logs of a negative speed (NaN: every scene with disk.p <=
// -1.9 failed at t = 0).
TEST(DragLaw, OutwardPressureGradientActsThroughItsMagnitude) {
  LocalGas in = mmsn_gas(1.0), out = in;
  out.eta = -in.eta;
  for (double m : {1e-12, 1e-3, 1e3, 1e9, 1e15})
    for (double phi : {1.0, 1e-3}) {
      const double st_in = stokes_number(m, phi, 1.0, in),
                   st_out = stokes_number(m, phi, 1.0, out);
      ASSERT_TRUE(std::isfinite(st_out)) << m;
      EXPECT_EQ(st_out, st_in) << "m = " << m << ", phi = " << phi;
      EXPECT_EQ(gas_drift_speed(st_in, out), gas_drift_speed(st_in, in));
      EXPECT_GT(gas_drift_speed(st_in, out), 0.0);
    }
}

}  // namespace
}  // namespace panoptic::physics
