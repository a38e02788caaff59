// The critical metallicity of the zcrit streaming-instability option (spec §7.2,
// physics/planetesimals.hpp) against numbers worked out by hand from
// log10 Z_crit = 0.10 x^2 + 0.07 x - 2.36, x = log10 St (Lim et al. 2025 eq. 15).
#include <gtest/gtest.h>

#include <cmath>

#include "physics/planetesimals.hpp"

using panoptic::zcrit_lim25;

TEST(Planetesimals, ZcritAtHandWorkedStokesNumbers) {
  EXPECT_NEAR(zcrit_lim25(0.01), 7.9433e-3, 1e-7);  // x = -2: -2.10
  EXPECT_NEAR(zcrit_lim25(0.1), 4.6774e-3, 1e-7);   // x = -1: -2.33
  EXPECT_NEAR(zcrit_lim25(1.0), 4.3652e-3, 1e-7);   // x = 0: -2.36
  EXPECT_NEAR(zcrit_lim25(0.3), 4.2731e-3, 1e-7);   // x = -0.52288: -2.36929
}

TEST(Planetesimals, ZcritMinimumIsLiYoudinsOptimum) {
  // the parabola's vertex, x = -0.07/0.2 = -0.35 (St = 0.447): 10^-2.37225 = 0.42438%,
  // Li & Youdin 2021's "as low as 0.4% for the optimum particle sizes"
  const double st_opt = std::pow(10.0, -0.35);
  EXPECT_NEAR(zcrit_lim25(st_opt), 4.2438e-3, 1e-7);
  for (double f : {0.9, 1.1}) EXPECT_GT(zcrit_lim25(st_opt * f), zcrit_lim25(st_opt));
}
