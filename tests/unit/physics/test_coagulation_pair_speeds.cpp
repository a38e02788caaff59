//! The distribution mode's pair speeds from per-bin terms (physics/coagulation/
//! pair_speed_evaluator.hpp) against spec §3's dv_total (physics/relative_velocity.hpp)
//! pair by pair: St 1e-8 .. 1e2 with masses 1e-12 .. 1e12 g, in the three regimes of
//! Ormel & Cuzzi (2007), and the bins of a mass grid whose St come from the Epstein and
//! the Stokes drag laws.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/coagulation/collision_kernel.hpp"
#include "physics/coagulation/mass_grid.hpp"
#include "physics/coagulation/pair_speed_evaluator.hpp"
#include "physics/relative_velocity.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

namespace panoptic::physics::coagulation {
namespace {

//! n log-spaced values from lo to hi.
std::vector<double> log_range(double lo, double hi, int n) {
  std::vector<double> v(n);
  for (int k = 0; k < n; ++k) v[k] = lo * std::pow(hi / lo, k / (n - 1.0));
  return v;
}

//! Largest |dv / dv_total - 1| over all pairs (St_a, St_b) x (m_i, m_j); counts the
//! pairs by the OC07 regime of their larger St (tight below St_eta/2, heavy above 2).
double worst_pair(const LocalGas& gas, const TurbulenceModel& turbulence,
                  const std::vector<double>& st, const std::vector<double>& m,
                  int regimes[3]) {
  PairSpeedEvaluator eval;
  eval.set_gas(gas, m, turbulence);
  const double st_eta = 1.0 / std::sqrt(gas.reynolds());
  double worst = 0.0;
  for (double st_a : st)
    for (double st_b : st) {
      const BinSpeedTerms ta = eval.bin_terms(st_a), tb = eval.bin_terms(st_b);
      const double hi = std::max(st_a, st_b);
      ++regimes[hi < 0.5 * st_eta ? 0 : hi > 2.0 ? 2 : 1];
      for (int i = 0; i < static_cast<int>(m.size()); ++i)
        for (int j = 0; j < static_cast<int>(m.size()); ++j) {
          const double ref = dv_total(st_a, st_b, m[i], m[j], gas, turbulence);
          worst = std::max(worst, std::abs(eval.dv(ta, tb, i, j) / ref - 1.0));
        }
    }
  return worst;
}

TEST(CoagulationPairSpeeds, EqualDvTotalOverStokesNumbersAndMasses) {
  const std::vector<double> st = log_range(1e-8, 1e2, 41), m = log_range(1e-12, 1e12, 25);
  TurbulenceModel dustpy;
  dustpy.vg2_factor = 1.5;
  for (const double r_au : {1.0, 5.0, 30.0})
    for (const TurbulenceModel& turbulence : {TurbulenceModel{}, dustpy}) {
      LocalGas gas = mmsn_gas(r_au);
      gas.v_r_gas = -10.0;  // a moving gas: v_r of the drift has both terms
      int regimes[3] = {0, 0, 0};
      const double worst = worst_pair(gas, turbulence, st, m, regimes);
      std::printf("%g au, V_g^2 factor %g: worst relative difference %.3g\n", r_au,
                  turbulence.vg2_factor, worst);
      EXPECT_LE(worst, 1e-13) << r_au << " au";
      // every OC07 regime (spec §3.5) holds pairs: St_eta = 1.3e-4 .. 1.1e-3 here
      for (int r = 0; r < 3; ++r) EXPECT_GT(regimes[r], 100) << r_au << " au " << r;
    }
}

TEST(CoagulationPairSpeeds, EqualDvTotalOnBinsOfEpsteinAndStokesDrag) {
  // bins 1e-12 .. 1e12 g, compact and fluffy (phi 1e-3), at 1 au, where the large
  // bins are in the Stokes regime (a > 9 lambda / 4), and their St by the drag law
  const LocalGas gas = mmsn_gas(1.0);
  const MassGrid grid(1e-12, 1e12, 3.5);
  const int n = grid.size();
  for (const DragLaw law : {DragLaw::kEpstein, DragLaw::kStokesRe})
    for (const double phi_all : {1.0, 1e-3}) {
      const std::vector<double> phi(n, phi_all);
      const BinProperties bins = bin_properties(grid, phi, 1.67, gas, law);
      PairSpeedEvaluator eval;
      eval.set_gas(gas, grid.m, {});
      double worst = 0.0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const double ref = dv_total(bins.St[i], bins.St[j], grid.m[i], grid.m[j], gas);
          const double v =
              eval.dv(eval.bin_terms(bins.St[i]), eval.bin_terms(bins.St[j]), i, j);
          worst = std::max(worst, std::abs(v / ref - 1.0));
        }
      EXPECT_LE(worst, 1e-13);
      // the bins span OC07's regimes below St = 1 (St > 1 is in the test above) and,
      // compact, reach the Stokes regime (x = 4 a / (9 lambda) > 1)
      EXPECT_LT(bins.St[0], 1e-6);
      EXPECT_GT(bins.St[n - 1], 0.05);
      if (phi_all == 1.0) {
        EXPECT_GT(knudsen_ratio(bins.a[n - 1], gas), 10.0);
      }
    }
}

TEST(CoagulationPairSpeeds, BrownianTermFollowsTheGasTemperature) {
  // the per-pair Brownian table is rebuilt when the temperature changes
  const std::vector<double> m = log_range(1e-12, 1e-6, 4);
  PairSpeedEvaluator eval;
  LocalGas gas = mmsn_gas(5.0);
  eval.set_gas(gas, m, {});
  gas.temperature *= 4.0;
  eval.set_gas(gas, m, {});
  const BinSpeedTerms t = eval.bin_terms(1e-6);
  const double ref = dv_total(1e-6, 1e-6, m[0], m[1], gas);
  EXPECT_LE(std::abs(eval.dv(t, t, 0, 1) / ref - 1.0), 1e-13);
}

}  // namespace
}  // namespace panoptic::physics::coagulation
