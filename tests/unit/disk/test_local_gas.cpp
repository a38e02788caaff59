// disk/local_gas.hpp: with_density_ratio(), the local gas of a cell whose Sigma_g
// evolves (CellGas::at, at_ad), against the local gas built from scratch at the scaled
// Sigma_g. spec §1.3: rho_g = Sigma_g/(sqrt(2 pi) H) ∝ Sigma_g; §1.6: lambda = mu m_H/
// (sigma_mol rho_g) and nu_mol = v_th lambda/2 ∝ 1/Sigma_g; temperature, c_s, v_th,
// Omega, v_K, H, alpha, eta and v_r,gas do not depend on Sigma_g.
#include <gtest/gtest.h>

#include <cmath>

#include "disk/local_gas.hpp"
#include "src/core/autodiff.hpp"
#include "src/core/units.hpp"
#include "tests/unit/support/expect_fields.hpp"

namespace panoptic::physics {
namespace {

// Measured relative differences <= 2.2e-16 (one rounding of a product or quotient
// against one of the fresh formula); tolerance 1e-14 (brief).
TEST(LocalGas, DensityRatioMatchesTheGasBuiltAtTheScaledSigma) {
  const double r = 5.0 * units::kAu, sigma = 152.05262246998570, t = 125.21980673998822;
  const LocalGas base =
      make_local_gas(sigma, t, r, units::kMsun, 1e-3, -3.25, 2.34, 2e-15);
  for (double ratio : {0.37, 1.0, 2.9, 1e-3}) {
    SCOPED_TRACE("ratio = " + std::to_string(ratio));
    LocalGas b = base;
    b.v_r_gas = -123.0;  // carried over unchanged
    const LocalGas s = with_density_ratio(b, ratio);
    const LocalGas fresh =
        make_local_gas(ratio * sigma, t, r, units::kMsun, 1e-3, -3.25, 2.34, 2e-15);
    const auto rel = [](double a, double want) { return std::abs(a / want - 1.0); };
    EXPECT_LT(rel(s.sigma_g, fresh.sigma_g), 1e-14);
    EXPECT_LT(rel(s.rho_g, fresh.rho_g), 1e-14);
    EXPECT_LT(rel(s.mfp, fresh.mfp), 1e-14);
    EXPECT_LT(rel(s.nu_mol, fresh.nu_mol), 1e-14);
    EXPECT_LT(rel(s.reynolds(), fresh.reynolds()), 1e-14);
    test_support::expect_fields_equal(s, fresh, &LocalGas::temperature, &LocalGas::c_s,
                                      &LocalGas::v_th, &LocalGas::omega_k, &LocalGas::v_k,
                                      &LocalGas::h_g, &LocalGas::alpha, &LocalGas::eta);
    EXPECT_EQ(s.v_r_gas, -123.0);
  }
}

// The AD form carries d/d ratio: d rho_g = rho_g, d lambda = -lambda, d nu_mol = -nu_mol
// at ratio 1 (rho ∝ ratio, lambda ∝ 1/ratio: by hand). Exact to round-off (<= 1e-16).
TEST(LocalGas, DensityRatioDerivatives) {
  const LocalGas base = make_local_gas(152.05, 125.2, 5.0 * units::kAu, units::kMsun,
                                       1e-3, -3.25, 2.34, 2e-15);
  const LocalGasT<AD> s = with_density_ratio(base, ad_seed(1.0, 0));
  EXPECT_NEAR(s.rho_g.derivatives()[0] / base.rho_g, 1.0, 1e-14);
  EXPECT_NEAR(s.sigma_g.derivatives()[0] / base.sigma_g, 1.0, 1e-14);
  EXPECT_NEAR(s.mfp.derivatives()[0] / base.mfp, -1.0, 1e-14);
  EXPECT_NEAR(s.nu_mol.derivatives()[0] / base.nu_mol, -1.0, 1e-14);
}

}  // namespace
}  // namespace panoptic::physics
