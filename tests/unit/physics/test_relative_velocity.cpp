//! Tests of physics/relative_velocity.hpp (spec §3, §12). Reference numbers: the spec's
//! own (§3, §12) and an independent python3 evaluation of the same formulas (separate
//! script, written from the spec, not from this code), quoted to 10+ digits where used
//! tightly. Gas: MMSN at 5 AU, alpha = 1e-3, from the spec formulas (§1.3-1.6).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "disk/local_gas.hpp"
#include "physics/drag.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"
#include "src/core/units.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

namespace panoptic::physics {
namespace {

using AD = Eigen::AutoDiffScalar<Eigen::Vector2d>;

constexpr double kStSmall = 1e-4;  // small-projectile St (spec §3 default option)
constexpr double kMSmall = 1e-12;  // its mass [g]: Brownian term negligible (< 1 cm/s)
constexpr double kMTarget = 1.0;   // target mass for Brownian term [g]; negligible too

double dv_ls(double st, const LocalGas& gas) {
  return dv_small_projectile(st, kMTarget, kStSmall, kMSmall, gas);
}
double dv_pr(double st, const LocalGas& gas) { return dv_pair(st, kMTarget, gas); }

class RelVelMmsn5au : public ::testing::Test {
 protected:
  LocalGas gas = mmsn_gas(5.0);
};

// ------------------------------------------------------------------------------ OC07
// beta --

TEST(Oc07, BetaValues) {
  // spec §3.5 / §12: 1.969, 2.292, 2.969 (4 digits); exact: 128/65, 2.2921855921...,
  // 193/65
  EXPECT_NEAR(beta_oc07(1.0), 1.969, 5e-4);
  EXPECT_NEAR(beta_oc07(0.5), 2.292, 5e-4);
  EXPECT_NEAR(beta_oc07(1e-12), 2.969, 5e-4);
  EXPECT_NEAR(beta_oc07(1.0), 128.0 / 65.0, 1e-14);  // 3.2 - 2 + 1/2.6 + 1/2.6 by hand
  EXPECT_NEAR(beta_oc07(0.5), 2.292185592185592, 1e-14);
  EXPECT_NEAR(beta_oc07(0.0), 193.0 / 65.0, 1e-14);  // 3.2 - 1 + 2/2.6
}

// ------------------------------------------------------------------ components, §3.1-3.5
// --

TEST_F(RelVelMmsn5au, ComponentsAgainstIndependentValues) {
  // St1 = 0.7, St2 = 0.35, m1 = 1 g, m2 = 1/8 g; python values [cm^2 s^-2]
  const RelativeVelocity2<double> c = relative_velocity2(0.7, 0.35, 1.0, 0.125, gas);
  EXPECT_LT(rel_err(c.brownian, 3.9623695521826606e-13), 1e-9);
  EXPECT_LT(rel_err(c.radial, 2895967.2754337443), 1e-9);
  EXPECT_LT(rel_err(c.azimuthal, 1400291.180722645), 1e-9);
  EXPECT_LT(rel_err(c.vertical, 2526.5037967337134), 1e-9);
  EXPECT_LT(rel_err(c.turbulent, 7071417.075666841), 1e-9);
  EXPECT_LT(rel_err(c.total(), 3371.973018222412 * 3371.973018222412), 1e-9);
}

TEST_F(RelVelMmsn5au, BrownianTwoMonomers) {
  // sqrt(16 k_B T / (pi m0)) = 3.87492 cm/s for two ice monomers (python)
  const double m0 = monomer_mass(1e-5, 1.4);
  EXPECT_LT(rel_err(dv_brownian(m0, m0, gas), 3.8749215063837723), 1e-9);
}

TEST_F(RelVelMmsn5au, PairPartnerHasTheMassOfEpsCubed) {
  // spec §3 pair convention: the partner of (St, m) is (eps St, eps^3 m), eps = 0.5, so
  // the Brownian term of dv_pair is 8 k_B T (m + m/8) / (pi m m/8) = 72 k_B T/(pi m).
  // Two compact ice monomers (m = m0 = 5.864306286700947e-15 g, Epstein St = pi rho0 a0
  // / (2 Sigma_g) = 1.4462853858025024e-07), where Brownian motion dominates: python,
  // from the spec formulas of §1.3-1.6, §2, §3.1-3.5 with T = 280/sqrt(5) K:
  //   dv_B^2 = 67.56757506285966 cm^2 s^-2; radial + azimuthal + vertical + turbulent
  //   (tight regime, St_eta = 1.6048e-4) = 1.674e-4 cm^2 s^-2 (2.5e-6 of dv_B^2);
  //   dv = sqrt(67.56757506285966 + 1.6740307650879707e-4) = 8.21996000391341 cm/s.
  // A partner of mass eps m (m/2) would give sqrt(24 k_B T/(pi m)) = 4.7458 cm/s.
  const double m0 = 5.864306286700947e-15;
  const double st = 1.4462853858025024e-07;
  EXPECT_LT(rel_err(dv_pair(st, m0, gas), 8.21996000391341), 1e-9);
}

TEST_F(RelVelMmsn5au, DriftComponentsLimits) {
  const double vw = gas.headwind();  // eta v_K = 53.9 m/s (spec §1.4)
  EXPECT_LT(rel_err(vw, 53.9e2), 0.001);
  EXPECT_LT(rel_err(v_radial_drift(1.0, gas), -vw), 1e-14);  // peak -eta v_K at St = 1
  EXPECT_LT(rel_err(v_azimuthal_offset(1e-8, gas), -vw), 1e-14);  // gas-coupled
  EXPECT_LT(rel_err(dv_radial(1.0, 1e-8, gas), vw), 1e-6);
  EXPECT_LT(rel_err(dv_azimuthal(1e8, 1e-8, gas), vw), 1e-6);  // headwind on a boulder
  EXPECT_DOUBLE_EQ(dv2_radial(0.3, 0.3, gas), 0.0);
  // spec §12: t_drift(St = 1) = r / |v_r| = 440 yr at 5 AU (python: 440.09 yr)
  const double t_drift = 5.0 * units::kAu / std::abs(v_radial_drift(1.0, gas));
  EXPECT_LT(rel_err(t_drift / units::kYr, 440.0), 0.005);
  // settling speed h_d Omega St/(1+St); St = 1: h_d = H / sqrt(1 + 1000 * 1.5) (YL07)
  EXPECT_LT(
      rel_err(v_settling(1.0, gas), gas.h_g / std::sqrt(1501.0) * gas.omega_k * 0.5),
      1e-12);
}

// spec §3.2 (and §6.1): v_r = (-2 St eta v_K + v_g)/(1 + St^2) with the gas moving,
// v_r,gas = -500 cm/s. eta v_K = 5385.4804222618910 cm/s at 5 au (mpmath, 30 digits, from
// the spec §1.3-1.4 formulas, dlnP/dlnr = -3.25); v_r(St = 0.5) = (-5385.48 - 500)/1.25 =
// -4708.3843378095128, v_r(St = 2) = (-4 x 5385.48 - 500)/5 = -4408.3843378095128 cm/s.
// St and 1/St drift alike (St/(1 + St^2) = 0.4 for both), so their radial relative speed
// is the gas term alone, by hand: 500 (1/1.25 - 1/5) = 300 cm/s, 9e4 cm^2 s^-2 (0 without
// gas motion). Measured relative errors 2.2e-16 (v_r), 0 for dv2 (it is the square of
// the difference of two 4.5e3 cm/s speeds: up to ~1e-12 could be lost); tolerances 1e-13,
// 1e-10.
TEST_F(RelVelMmsn5au, RadialDriftWithMovingGas) {
  LocalGas moving = gas;
  moving.v_r_gas = -500.0;
  EXPECT_LT(rel_err(v_radial_drift(0.5, moving), -4708.3843378095128), 1e-13);
  EXPECT_LT(rel_err(v_radial_drift(2.0, moving), -4408.3843378095128), 1e-13);
  EXPECT_LT(rel_err(dv2_radial(0.5, 2.0, moving), 9e4), 1e-10);
  EXPECT_NEAR(dv2_radial(0.5, 2.0, gas), 0.0, 1e-6);
  // a particle tied to the gas moves with it
  EXPECT_LT(rel_err(v_radial_drift(1e-9, moving), -500.0), 1e-7);
}

TEST_F(RelVelMmsn5au, TurbulentRegimes) {
  // python: pure OC07 eqs. 27-29 (the blend weights are < 1e-12 off the boundaries here)
  EXPECT_LT(rel_err(dv2_turbulent(1e-6, 5e-7, gas), 0.006828090772562611),
            1e-9);  // tight
  EXPECT_LT(rel_err(dv2_turbulent(0.01, 0.005, gas), 101200.01067429288),
            1e-9);                                                               // inter.
  EXPECT_LT(rel_err(dv2_turbulent(100.0, 50.0, gas), 130281.5203392193), 1e-9);  // heavy
  // spec §3.5: dv_t ~ sqrt(2.3 alpha St) c_s for eps = 0.5 (2 digits)
  EXPECT_LT(rel_err(dv_turbulent(0.01, 0.005, gas), std::sqrt(2.3e-5) * gas.c_s), 0.01);
  // symmetric in its arguments
  EXPECT_DOUBLE_EQ(dv2_turbulent(0.02, 0.3, gas), dv2_turbulent(0.3, 0.02, gas));
  EXPECT_DOUBLE_EQ(dv_total(0.02, 0.3, 1.0, 2.0, gas),
                   dv_total(0.3, 0.02, 2.0, 1.0, gas));
}

// -------------------------------------------------------------------- spec §3 numbers --

TEST_F(RelVelMmsn5au, SmallProjectileSpeedsMatchSpec) {
  // spec §3: dv_ls ~ 17 (St=0.1), 37 (0.3), 52 (0.5), 67 (1.5) m/s; 2 digits -> 3%.
  // python: 16.650, 36.792, 51.953, 67.462 m/s.
  struct Case {
    double st, spec, indep;
  };
  const std::vector<Case> cases = {{0.1, 1700.0, 1664.9734659108492},
                                   {0.3, 3700.0, 3679.1965858695326},
                                   {0.5, 5200.0, 5195.272277566171},
                                   {1.5, 6700.0, 6746.15732808902}};
  for (const Case& c : cases) {
    EXPECT_LT(rel_err(dv_ls(c.st, gas), c.spec), 0.03) << "St = " << c.st;
    EXPECT_LT(rel_err(dv_ls(c.st, gas), c.indep), 1e-9) << "St = " << c.st;
  }
}

TEST_F(RelVelMmsn5au, SmallProjectileAtStOne) {
  // spec §3 quotes 66 m/s at St = 1: that is the *unblended* law, where St1 >= 1 selects
  // the heavy OC07 branch (python: 66.022 m/s). St = 1 is the centre of the spec's own
  // +-0.1 dex blend, where dv_t^2 is the mean of the intermediate (2.969 V_g^2) and heavy
  // (1.5 V_g^2) values: python gives 68.434 m/s, 3.7% above the quoted 66. We test the
  // blended value and that it lies between the heavy branch (66.0 m/s) and 70.58 m/s (the
  // unblended law reaches 7056.7 cm/s at St = 0.990; the intermediate branch's St -> 1
  // limit is 7076.4).
  const double v = dv_ls(1.0, gas);
  EXPECT_LT(rel_err(v, 6843.419116118557), 1e-9);
  EXPECT_GT(v, 6602.0);
  EXPECT_LT(v, 7058.0);
}

TEST_F(RelVelMmsn5au, SmallProjectilePlateau) {
  // spec §3: ~58-60 m/s for St >> 1; limit sqrt((eta v_K)^2 + V_g^2) = 57.808 m/s
  // (python, heavy branch 1/(1+St1) -> 0). python: 58.795 (St=10), 57.868 (100), 57.809
  // (1e4).
  EXPECT_LT(rel_err(dv_ls(10.0, gas), 5879.492998723494), 1e-9);
  EXPECT_LT(rel_err(dv_ls(100.0, gas), 5786.809029897509), 1e-9);
  EXPECT_LT(rel_err(dv_ls(1e4, gas), 5780.8711814839435), 1e-9);
  const double limit = std::sqrt(gas.headwind() * gas.headwind() +
                                 gas.alpha * gas.c_s * gas.c_s / (1.0 + kStSmall));
  EXPECT_LT(rel_err(dv_ls(1e8, gas), limit), 1e-6);
  for (double st : {10.0, 100.0, 1e4, 1e8}) {  // "58-60", 2 digits: [57.5, 60.5] m/s
    EXPECT_GT(dv_ls(st, gas), 5750.0) << "St = " << st;
    EXPECT_LT(dv_ls(st, gas), 6050.0) << "St = " << st;
  }
}

TEST_F(RelVelMmsn5au, PairSpeedPeak) {
  // spec §3: "dv(St, St/2) peaks ~34 m/s near St ~ 0.7". Independent python evaluation:
  // dv(0.7) = 33.720 m/s, but the maximum of the (blended) law is 35.218 m/s at St =
  // 0.870; the unblended law rises to 37.26 m/s at St -> 1- and drops to 29.87 m/s at St
  // = 1. The spec's statement is the St = 0.7 sample of a coarse grid (0.1, 0.3, 0.5,
  // 0.7, 1, ...); 35.2 m/s is 3.5% above "34", outside a 2-digit tolerance, so we test
  // the true peak.
  EXPECT_LT(rel_err(dv_pr(0.7, gas), 3400.0), 0.03);
  EXPECT_LT(rel_err(dv_pr(0.7, gas), 3371.973018222412), 1e-9);
  // locate the maximum by golden-section search in ln St on [0.3, 2]
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double lo = std::log(0.3), hi = std::log(2.0);
  for (int i = 0; i < 200; ++i) {
    const double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
    if (dv_pr(std::exp(c), gas) > dv_pr(std::exp(d), gas)) {
      hi = d;
    } else {
      lo = c;
    }
  }
  const double st_peak = std::exp(0.5 * (lo + hi));
  EXPECT_LT(rel_err(st_peak, 0.8700482079836537), 1e-4);
  EXPECT_LT(rel_err(dv_pr(st_peak, gas), 3521.805423093797), 1e-9);
}

// ----------------------------------------------------------------- continuity of blends
// --

TEST_F(RelVelMmsn5au, ContinuousAcrossRegimeBoundaries) {
  // OC07 boundaries St1 = St_eta and St1 = 1; a relative step h must change dv by O(h).
  const double st_eta = 1.0 / std::sqrt(gas.reynolds());
  const double h = 1e-9;
  for (double st_b : {st_eta, 1.0}) {
    const double lo = st_b * (1 - h), hi = st_b * (1 + h);
    EXPECT_LT(std::abs(dv_pr(hi, gas) / dv_pr(lo, gas) - 1.0), 100 * h) << st_b;
    EXPECT_LT(std::abs(dv_ls(hi, gas) / dv_ls(lo, gas) - 1.0), 100 * h) << st_b;
    const double t_lo = dv2_turbulent(lo, 0.5 * lo, gas);
    const double t_hi = dv2_turbulent(hi, 0.5 * hi, gas);
    EXPECT_LT(std::abs(t_hi / t_lo - 1.0), 100 * h) << st_b;
  }
  // Target crossing its projectile's St (the soft ordering of dv2_turbulent): no jump.
  for (double st_b : {kStSmall, 0.3}) {
    const double lo = dv_small_projectile(st_b * (1 - h), kMTarget, st_b, kMSmall, gas);
    const double hi = dv_small_projectile(st_b * (1 + h), kMTarget, st_b, kMSmall, gas);
    EXPECT_LT(std::abs(hi / lo - 1.0), 100 * h) << st_b;
  }
  // The blends are steep but bounded: scan ln St on [1e-6, 1e3] with step 1e-4 and bound
  // |d ln dv / d ln St| between neighbours. Measured maxima: 4.5 (pair, at the St_eta
  // blend) and 7.4 (dv_ls, near St = St_s = 1e-4, where dv_ls = 1.7 cm/s; its smooth
  // minimum, 1.60 cm/s, is at St = 9.73e-5). The
  // unblended law jumps by up to ln 4.5 in one step there, i.e. a "slope" of ~1e4.
  const double dl = 1e-4;
  double prev_pr = std::log(dv_pr(1e-6, gas)), prev_ls = std::log(dv_ls(1e-6, gas));
  for (double l = std::log(1e-6) + dl; l < std::log(1e3); l += dl) {
    const double pr = std::log(dv_pr(std::exp(l), gas));
    const double ls = std::log(dv_ls(std::exp(l), gas));
    ASSERT_LT(std::abs(pr - prev_pr), 6 * dl) << "St = " << std::exp(l);
    ASSERT_LT(std::abs(ls - prev_ls), 10 * dl) << "St = " << std::exp(l);
    prev_pr = pr;
    prev_ls = ls;
  }
}

// ---------------------------------------------------------------- AutoDiff vs finite
// diff --

TEST_F(RelVelMmsn5au, AutoDiffMatchesCentralFiniteDifferences) {
  const double st_eta = 1.0 / std::sqrt(gas.reynolds());
  for (double st : {1e-7, 1e-5, kStSmall, st_eta, 3e-3, 0.1, 0.7, 0.99, 1.0, 1.2, 30.0}) {
    const double m = 3.0;
    const AD st_ad(st, 2, 0), m_ad(m, 2, 1);
    const AD pr = dv_pair(st_ad, m_ad, gas);
    const AD ls = dv_small_projectile(st_ad, m_ad, kStSmall, kMSmall, gas);
    const double h = 1e-6;
    auto fd = [&](auto f, double x, double dx) {
      return (f(x + dx) - f(x - dx)) / (2 * dx);
    };
    const double fd_pr_st = fd([&](double s) { return dv_pair(s, m, gas); }, st, h * st);
    const double fd_pr_m = fd([&](double mm) { return dv_pair(st, mm, gas); }, m, h * m);
    const double fd_ls_st =
        fd([&](double s) { return dv_small_projectile(s, m, kStSmall, kMSmall, gas); },
           st, h * st);
    EXPECT_LT(rel_err(pr.value(), dv_pair(st, m, gas)), 1e-14);
    EXPECT_LT(rel_err(pr.derivatives()(0), fd_pr_st), 1e-6) << "St = " << st;
    EXPECT_LT(rel_err(ls.derivatives()(0), fd_ls_st), 1e-6) << "St = " << st;
    // d/dm only through the Brownian term: compare absolutely, scaled by dv/m
    EXPECT_NEAR(pr.derivatives()(1), fd_pr_m, 1e-6 * pr.value() / m) << "St = " << st;
  }
}

TEST(RelativeVelocity, AutoDiffThroughDragLawMatchesFiniteDifferences) {
  // End to end, as the engine will use it: dv(St(m, phi), m) with St from the Newton drag
  // law.
  for (double r_au : {1.0, 5.0}) {
    const LocalGas gas = mmsn_gas(r_au);
    for (double m : {1e-10, 1.0, 1e6, 1e9, 1e12}) {
      const double phi = 1e-3;
      auto f = [&](double mm, double pp) {
        const double st = stokes_number(mm, pp, 1.4, gas);
        return dv_pair(st, mm, gas);
      };
      const AD m_ad(m, 2, 0), phi_ad(phi, 2, 1);
      const AD st = stokes_number(m_ad, phi_ad, 1.4, gas);
      const AD dv = dv_pair(st, m_ad, gas);
      const double hm = 1e-6 * m, hp = 1e-6 * phi;
      const double fd_m = (f(m + hm, phi) - f(m - hm, phi)) / (2 * hm);
      const double fd_p = (f(m, phi + hp) - f(m, phi - hp)) / (2 * hp);
      EXPECT_LT(rel_err(dv.derivatives()(0), fd_m), 1e-5) << r_au << " AU, m = " << m;
      EXPECT_LT(rel_err(dv.derivatives()(1), fd_p), 1e-5) << r_au << " AU, m = " << m;
    }
  }
}

TEST(RelativeVelocity, DynamicSizeAutoDiffGivesTheSameDerivatives) {
  // The engine's AD type has a dynamic derivative vector (max 16), where constants such
  // as T(1.0) carry an empty one; the laws must give the same derivatives as with
  // Vector2d.
  using DynAD = Eigen::AutoDiffScalar<Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 16, 1>>;
  const LocalGas gas = mmsn_gas(5.0);
  for (double m : {1e-10, 1.0, 1e8, 1e12}) {
    const DynAD m_d(m, 3, 0), phi_d(1e-3, 3, 2);
    const DynAD st_d = stokes_number(m_d, phi_d, 1.4, gas);
    const DynAD dv_d =
        dv_pair(st_d, m_d, gas) + dv_small_projectile(st_d, m_d, kStSmall, kMSmall, gas);
    const AD m_2(m, 2, 0), phi_2(1e-3, 2, 1);
    const AD st_2 = stokes_number(m_2, phi_2, 1.4, gas);
    const AD dv_2 =
        dv_pair(st_2, m_2, gas) + dv_small_projectile(st_2, m_2, kStSmall, kMSmall, gas);
    ASSERT_EQ(dv_d.derivatives().size(), 3);
    EXPECT_EQ(dv_d.value(), dv_2.value());
    EXPECT_LT(rel_err(dv_d.derivatives()(0), dv_2.derivatives()(0)), 1e-13) << m;
    EXPECT_EQ(dv_d.derivatives()(1), 0.0);
    EXPECT_LT(rel_err(dv_d.derivatives()(2), dv_2.derivatives()(1)), 1e-13) << m;
  }
}

}  // namespace
}  // namespace panoptic::physics
