//! Adhesive elastic contact of two monomers (spec §0); see contact_mechanics.hpp.
#include "physics/contact_mechanics.hpp"

#include <cmath>
#include <cstdio>

#include "src/core/units.hpp"

namespace panoptic::physics {
namespace {

constexpr double kGPa = 1e10;        // 1 GPa = 1e9 Pa = 1e10 dyn cm^-2
constexpr double kMicron = 1e-4;     // [cm]
constexpr double kNanometre = 1e-7;  // [cm]
constexpr double kAngstrom = 1e-8;   // [cm]

// z0 = 0.4 nm for both species: the upper end of the 0.2-0.4 nm range of spec §0.
// z0 is the equilibrium separation of the two surfaces, of the order of the
// intermolecular spacing (ice Ih: O-O 0.28 nm, bilayer spacing 0.37 nm; silicates: O-O
// 0.26-0.3 nm). Since mu_T ~ z0^-1, the largest value gives the smallest Tabor parameter,
// so the JKR-validity check errs on the side of warning. No disk-scale result depends on
// z0 (E_roll does not).
constexpr double kZ0Default = 0.4 * kNanometre;

}  // namespace

MonomerMaterial ice_material() {
  MonomerMaterial m;
  m.a0 = 0.1 * kMicron;
  m.rho0 = 1.4;          // Okuzumi et al. (2012); 1.0 for pure ice (spec §0)
  m.gamma_surf = 100.0;  // spec §0, §1.7
  m.youngs_modulus = 7.0 * kGPa;
  m.poisson = 0.25;
  m.xi_crit = 8.0 * kAngstrom;
  m.z0 = kZ0Default;
  m.rolling_radius_factor = 1.0;  // R_r = a0 (spec §0, §11 #3)
  return m;
}

MonomerMaterial silicate_material() {
  MonomerMaterial m;
  m.a0 = 0.1 * kMicron;
  m.rho0 = 3.0;
  m.gamma_surf = 25.0;
  m.youngs_modulus = 54.0 * kGPa;
  m.poisson = 0.17;
  m.xi_crit = 8.0 * kAngstrom;
  m.z0 = kZ0Default;
  m.rolling_radius_factor = 1.0;
  return m;
}

double work_of_adhesion(double gamma_surf) {
  return 2.0 * gamma_surf;  // Dupre, two like surfaces; see the header
}

double reduced_radius(double r1, double r2) { return r1 * r2 / (r1 + r2); }  // spec §0

double combined_modulus(double e1, double nu1, double e2, double nu2) {
  // spec §0; Johnson (1985), ch. 4
  return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
}

double hertz_approach(double a, double r) { return a * a / r; }  // spec §0; Hertz (1882)

double hertz_force(double a, double r, double e_star) {
  return 4.0 * e_star * a * a * a / (3.0 * r);  // spec §0; Hertz; Johnson (1985) ch. 4
}

// The JKR and Tabor formulas take the work of adhesion w = 2 gamma (header; spec §0
// writes gamma for w).
double jkr_approach(double a, double r, double e_star, double w) {
  // spec §0; Johnson, Kendall & Roberts (1971)
  return a * a / r - std::sqrt(2.0 * units::kPi * w * a / e_star);
}

double jkr_force(double a, double r, double e_star, double w) {
  // spec §0; Johnson, Kendall & Roberts (1971)
  return hertz_force(a, r, e_star) - std::sqrt(8.0 * units::kPi * w * e_star * a * a * a);
}

double jkr_equilibrium_radius(double r, double e_star, double w) {
  // spec §0: jkr_force(a_eq) = 0; = (9 pi gamma R^2 / E*)^(1/3) of Dominik & Tielens
  // (1997)
  return std::cbrt(9.0 * units::kPi * w * r * r / (2.0 * e_star));
}

double jkr_pulloff_force(double r, double w) {
  // spec §0; JKR (1971), minimum of jkr_force; = 3 pi gamma R (Dominik & Tielens 1997)
  return 1.5 * units::kPi * w * r;
}

double tabor_parameter(double r, double e_star, double w, double z0) {
  // spec §0; Tabor (1977), with the work of adhesion as in Johnson & Greenwood (1997)
  return std::cbrt(r * w * w / (e_star * e_star * z0 * z0 * z0));
}

double rolling_energy(double gamma_surf, double rolling_radius, double xi_crit) {
  // spec §0, §1.7; Dominik & Tielens (1997)
  return 6.0 * units::kPi * units::kPi * gamma_surf * rolling_radius * xi_crit;
}

ContactProperties contact_properties(const MonomerMaterial& mat) {
  ContactProperties c;
  c.reduced_radius = reduced_radius(mat.a0, mat.a0);
  c.e_star =
      combined_modulus(mat.youngs_modulus, mat.poisson, mat.youngs_modulus, mat.poisson);
  c.work_adhesion = work_of_adhesion(mat.gamma_surf);
  c.a_eq = jkr_equilibrium_radius(c.reduced_radius, c.e_star, c.work_adhesion);
  c.f_pulloff = jkr_pulloff_force(c.reduced_radius, c.work_adhesion);
  c.tabor = tabor_parameter(c.reduced_radius, c.e_star, c.work_adhesion, mat.z0);
  c.e_roll =
      rolling_energy(mat.gamma_surf, mat.rolling_radius_factor * mat.a0, mat.xi_crit);
  c.m0 = (4.0 * units::kPi / 3.0) * mat.a0 * mat.a0 * mat.a0 * mat.rho0;  // spec §2
  c.jkr_valid = c.tabor > 5.0;                                            // spec §0
  c.dmt_regime = c.tabor < 0.1;                                           // spec §0
  return c;
}

std::string contact_summary(std::string_view species, const MonomerMaterial& mat) {
  const ContactProperties c = contact_properties(mat);
  const char* verdict = c.jkr_valid ? "JKR valid (mu_T > 5)"
                        : c.dmt_regime
                            ? "WARNING: DMT regime (mu_T < 0.1), JKR not valid"
                            : "WARNING: JKR-DMT transition (0.1 <= mu_T <= 5), "
                              "JKR outside its validity";
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%.*s: a0 = %.3g um, rho0 = %.3g g/cm^3, m0 = %.3g g, E* = %.3g GPa, "
                "gamma = %.3g erg/cm^2 (w = 2 gamma), a_eq = %.3g nm, F_c = %.3g dyn, "
                "E_roll = %.3g erg "
                "(R_r = %.3g a0), mu_T = %.3g (z0 = %.2f nm) -> %s",
                static_cast<int>(species.size()), species.data(), mat.a0 / kMicron,
                mat.rho0, c.m0, c.e_star / kGPa, mat.gamma_surf, c.a_eq / kNanometre,
                c.f_pulloff, c.e_roll, mat.rolling_radius_factor, c.tabor,
                mat.z0 / kNanometre, verdict);
  return std::string(buf);
}

}  // namespace panoptic::physics
