//! Tests of physics/contact_mechanics.{hpp,cpp} (spec §0, §1.7, §12). Reference numbers:
//! the spec's (§0 E_roll, §12 m0) and an independent python3 evaluation of the JKR/Hertz
//! formulas (separate script; the zero and the minimum of F_JKR found there by bisection
//! and by scanning, not from the closed forms).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "physics/contact_mechanics.hpp"
#include "src/core/units.hpp"

namespace panoptic::physics {
namespace {

double rel_err(double value, double ref) { return std::abs(value / ref - 1.0); }

//! Independent values of a material's contact mechanics, with the relative tolerances
//! of E* and mu_T (a_eq and F_c: 1e-6).
struct ExpectedContact {
  double e_star, e_star_tolerance, a_eq, f_pulloff, tabor, tabor_tolerance;
};

//! `c` against `want`; the material is at the JKR-DMT transition (neither JKR nor DMT).
void expect_transition_material(const ContactProperties& c, const ExpectedContact& want) {
  EXPECT_LT(rel_err(c.e_star, want.e_star), want.e_star_tolerance);
  EXPECT_LT(rel_err(c.a_eq, want.a_eq), 1e-6);
  EXPECT_LT(rel_err(c.f_pulloff, want.f_pulloff), 1e-6);
  EXPECT_LT(rel_err(c.tabor, want.tabor), want.tabor_tolerance);
  EXPECT_FALSE(c.jkr_valid);
  EXPECT_FALSE(c.dmt_regime);
}

TEST(ContactMechanics, DefaultMaterials) {
  const MonomerMaterial ice = ice_material();
  EXPECT_DOUBLE_EQ(ice.a0, 1e-5);
  EXPECT_DOUBLE_EQ(ice.rho0, 1.4);
  EXPECT_DOUBLE_EQ(ice.gamma_surf, 100.0);
  EXPECT_DOUBLE_EQ(ice.youngs_modulus, 7e10);  // 7 GPa in dyn cm^-2
  EXPECT_DOUBLE_EQ(ice.poisson, 0.25);
  EXPECT_DOUBLE_EQ(ice.xi_crit, 8e-8);
  EXPECT_DOUBLE_EQ(ice.z0, 4e-8);
  EXPECT_DOUBLE_EQ(ice.rolling_radius_factor, 1.0);
  const MonomerMaterial sil = silicate_material();
  EXPECT_DOUBLE_EQ(sil.rho0, 3.0);
  EXPECT_DOUBLE_EQ(sil.gamma_surf, 25.0);
  EXPECT_DOUBLE_EQ(sil.youngs_modulus, 5.4e11);
  EXPECT_DOUBLE_EQ(sil.poisson, 0.17);
}

TEST(ContactMechanics, RollingEnergyMatchesSpec) {
  // spec §0 / §1.7 / §10.1: 4.74e-9 erg (ice), 1.18e-9 erg (silicate), 3 digits.
  // Hand: 6 pi^2 * 100 * 1e-5 * 8e-8 = 59.2176 * 8e-11 = 4.73741e-9 erg.
  const ContactProperties ice = contact_properties(ice_material());
  const ContactProperties sil = contact_properties(silicate_material());
  EXPECT_LT(rel_err(ice.e_roll, 4.74e-9), 0.002);
  EXPECT_LT(rel_err(sil.e_roll, 1.18e-9), 0.005);
  EXPECT_LT(rel_err(ice.e_roll, 4.737410112522892e-09), 1e-12);
  EXPECT_LT(rel_err(sil.e_roll, 1.184352528130723e-09), 1e-12);
  // the other convention, R_r = a0/2 (reduced radius), spec §1.7: 2.37e-9 erg
  MonomerMaterial half = ice_material();
  half.rolling_radius_factor = 0.5;
  EXPECT_LT(rel_err(contact_properties(half).e_roll, 2.37e-9), 0.002);
}

TEST(ContactMechanics, MonomerMass) {
  // spec §12: 5.86e-15 g for ice; silicate (4 pi/3) 1e-15 * 3.0 = 1.25664e-14 g
  EXPECT_LT(rel_err(contact_properties(ice_material()).m0, 5.86e-15), 0.001);
  EXPECT_LT(rel_err(contact_properties(silicate_material()).m0, 1.2566370614e-14), 1e-9);
}

TEST(ContactMechanics, IcePropertiesAgainstIndependentValues) {
  // The JKR and Tabor formulas take the work of adhesion w = 2 gamma (header). python:
  // E* = 7e10 / (2 * 0.9375) = 3.7333e10; w = 200; a_eq = (9 pi w R^2/(2 E*))^(1/3) =
  // 1.2371201e-6 cm, equal to Dominik & Tielens' (9 pi gamma R^2/E*)^(1/3); F_c = 3 pi
  // gamma R = 4.7123890e-3 dyn; mu_T = (R w^2/(E*^2 z0^3))^(1/3) = 1.308837 (z0 = 0.4
  // nm), 2.617674 (0.2 nm).
  const ContactProperties c = contact_properties(ice_material());
  EXPECT_DOUBLE_EQ(c.reduced_radius, 5e-6);
  EXPECT_DOUBLE_EQ(c.work_adhesion, 200.0);
  // 0.1-micron ice monomers are NOT in the JKR regime (mu_T < 5) for any z0 in 0.2-0.4 nm
  expect_transition_material(
      c, {3.733333333333e10, 1e-12, 1.2371201e-6, 4.7123890e-3, 1.308837, 1e-6});
  MonomerMaterial ice02 = ice_material();
  ice02.z0 = 2e-8;
  EXPECT_LT(rel_err(contact_properties(ice02).tabor, 2.617674), 1e-6);
  EXPECT_FALSE(contact_properties(ice02).jkr_valid);
}

TEST(ContactMechanics, SilicatePropertiesAgainstIndependentValues) {
  // python: E* = 2.780352e11; w = 50; a_eq = 3.9907776e-7 cm; F_c = 1.1780972e-3 dyn;
  // mu_T = 0.136200 (z0 = 0.4 nm), 0.272400 (z0 = 0.2 nm): the JKR-DMT transition for
  // both (with gamma in place of w, as spec §0 writes it, 0.0858 would have been DMT)
  const ContactProperties c = contact_properties(silicate_material());
  expect_transition_material(
      c, {2.780352e11, 1e-6, 3.9907776e-7, 1.1780972e-3, 0.136200, 1e-5});
}

TEST(ContactMechanics, HertzAndJkrAgainstIndependentValues) {
  // ice, a = a_eq / 2, w = 200 (python): delta_H = 7.6523311e-8 cm, F_H = 2.3561945e-3
  // dyn, delta_JKR = -6.7770428e-8 cm, F_JKR = -4.3081299e-3 dyn
  const ContactProperties c = contact_properties(ice_material());
  const double a = 0.5 * c.a_eq, r = c.reduced_radius, w = 200.0;
  EXPECT_LT(rel_err(hertz_approach(a, r), 7.6523311e-8), 1e-6);
  EXPECT_LT(rel_err(hertz_force(a, r, c.e_star), 2.3561945e-3), 1e-6);
  EXPECT_LT(rel_err(jkr_approach(a, r, c.e_star, w), -6.7770428e-8), 1e-6);
  EXPECT_LT(rel_err(jkr_force(a, r, c.e_star, w), -4.3081299e-3), 1e-6);
}

TEST(ContactMechanics, JkrEquilibriumAndPullOff) {
  for (const MonomerMaterial& mat : {ice_material(), silicate_material()}) {
    const ContactProperties c = contact_properties(mat);
    const double r = c.reduced_radius, es = c.e_star, g = c.work_adhesion;
    // zero load at a_eq
    EXPECT_LT(std::abs(jkr_force(c.a_eq, r, es, g)), 1e-10 * c.f_pulloff);
    // minimum of F_JKR(a) is -F_c, at a_eq / 4^(1/3) (python scan: a/a_eq = 0.62996)
    double f_min = 0.0, a_min = 0.0;
    for (int i = 1; i <= 100000; ++i) {
      const double a = c.a_eq * i / 100000.0;
      const double f = jkr_force(a, r, es, g);
      if (f < f_min) {
        f_min = f;
        a_min = a;
      }
    }
    EXPECT_LT(rel_err(-f_min, c.f_pulloff), 1e-8);
    EXPECT_NEAR(a_min / c.a_eq, 0.62996, 2e-5);
    // JKR -> Hertz for a >> a_eq (adhesion negligible)
    const double big = 100.0 * c.a_eq;
    EXPECT_LT(rel_err(jkr_force(big, r, es, g), hertz_force(big, r, es)), 1e-2);
  }
}

TEST(ContactMechanics, CombinedModulusAndReducedRadius) {
  // ice on silicate, by hand: 1/E* = 0.9375/7e10 + 0.9711/5.4e11 = 1.33929e-11
  // + 1.79833e-12
  EXPECT_LT(rel_err(combined_modulus(7e10, 0.25, 5.4e11, 0.17), 1.0 / 1.5191190e-11),
            1e-6);
  EXPECT_DOUBLE_EQ(reduced_radius(1.0, 3.0), 0.75);
}

TEST(ContactMechanics, SummaryLine) {
  const std::string ice = contact_summary("ice", ice_material());
  EXPECT_EQ(ice.rfind("ice: ", 0), 0u) << ice;
  EXPECT_NE(ice.find("E_roll = 4.74e-09 erg"), std::string::npos) << ice;
  EXPECT_NE(ice.find("mu_T = 1.31"), std::string::npos) << ice;
  EXPECT_NE(ice.find("WARNING"), std::string::npos) << ice;
  const std::string sil = contact_summary("silicate", silicate_material());
  EXPECT_NE(sil.find("WARNING: JKR-DMT transition"), std::string::npos) << sil;
  MonomerMaterial weak = silicate_material();  // gamma = 10: mu_T = 0.1362 * 0.4^(2/3)
  weak.gamma_surf = 10.0;                      // = 0.0739 (python), DMT
  EXPECT_NE(contact_summary("weak", weak).find("WARNING: DMT regime"), std::string::npos);
  MonomerMaterial stiff = ice_material();  // a soft, sticky material in the JKR regime
  stiff.youngs_modulus = 1e8;
  EXPECT_EQ(contact_summary("soft", stiff).find("WARNING"), std::string::npos);
  EXPECT_NE(contact_summary("soft", stiff).find("JKR valid"), std::string::npos);
}

}  // namespace
}  // namespace panoptic::physics
