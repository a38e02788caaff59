#pragma once
//! Shared set-up of the growth-rate tests (tests/unit/physics/test_growth_*.cpp, which
//! test physics/growth_rates.hpp, particle_rates(), and the processes it combines;
//! spec §2-§5, §12): the gas is the MMSN at 5 AU, alpha = 1e-3, ice monomers.
//!
//! Reference numbers come from a separate python3 script written from the spec (not from
//! this code): gas (§1.3-1.6), St by bisection of the smooth drag law (§2), a, h_d (§2),
//! dv (§3, used only to cross-check), phi_gas, phi_grav (§4.3). They are quoted to 16
//! digits. The collision speeds dv_pair / dv_small_projectile are taken from the C++
//! (tested in test_relative_velocity.cpp); St is an argument of particle_rates(), so most
//! tests pass the python St directly.
#include <cmath>

#include "disk/local_gas.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/drag.hpp"
#include "physics/growth_rates.hpp"
#include "physics/particle.hpp"
#include "physics/relative_velocity.hpp"
#include "src/core/autodiff.hpp"
#include "src/core/units.hpp"
#include "tests/unit/support/mmsn_gas.hpp"

namespace growth_fixture {

using panoptic::AD;
using panoptic::physics::contact_properties;
using panoptic::physics::ContactProperties;
using panoptic::physics::DragLaw;
using panoptic::physics::dv_pair;
using panoptic::physics::dv_small_projectile;
using panoptic::physics::ErosionModel;
using panoptic::physics::GrowthOptions;
using panoptic::physics::ice_material;
using panoptic::physics::LocalGas;
using panoptic::physics::mmsn_gas;
using panoptic::physics::particle_rates;
using panoptic::physics::ParticleRates;
using panoptic::physics::rel_err;
using panoptic::physics::silicate_material;
using panoptic::physics::Species;
using panoptic::physics::stokes_number;
namespace units = panoptic::units;

inline constexpr double kRho0 = 1.4;  // ice monomers (spec §0, §12) [g cm^-3]

// python (spec §0, §2, §12): m0 = 4 pi/3 a0^3 rho0, E_roll = 6 pi^2 gamma a0 xi_crit,
// monomer St (Epstein, pi rho0 a0 / (2 Sigma_g)), Omega_K and Sigma_g at 5 AU.
inline constexpr double kM0 = 5.864306286700947e-15;        // [g]
inline constexpr double kERoll = 4.737410112522892e-09;     // [erg] (spec: 4.74e-9)
inline constexpr double kStMono = 1.4462853858025006e-07;   // (spec §12: 1.45e-7)
inline constexpr double kOmega = 1.780976118388187e-08;     // [s^-1]
inline constexpr double kSigmaG = 152.0526224699857;        // [g cm^-2]
inline constexpr double kSigmaD = 0.01 * kSigmaG;           // Z = 0.01 (spec §1.7)
inline constexpr double kThreshold = 2.131834550635301e-9;  // 3 b E_roll, b = 0.15 [erg]

//! Icy monomers as the engine builds them: m0 and E_roll from contact_properties().
inline Species ice_species() {
  const ContactProperties c = contact_properties(ice_material());
  Species sp;
  sp.a0 = ice_material().a0;
  sp.rho0 = ice_material().rho0;
  sp.m0 = c.m0;
  sp.e_roll = c.e_roll;
  return sp;
}

//! Growth model with every optional process off (the defaults: no erosion,
//! fragmentation or bouncing) and, unless asked for, no compaction floors.
inline GrowthOptions plain_options(bool compaction = false) {
  GrowthOptions o;
  o.gas_compaction = compaction;
  o.self_gravity = compaction;
  return o;
}

//! E1 factor of spec §5.2, S(x) = 1/2 [1 - tanh((x - 1)/w)].
inline double erosion_switch(double x, double w) {
  return 0.5 * (1.0 - std::tanh((x - 1.0) / w));
}

//! Fragmentation factor of spec §5.3, 1 - 2 dv^2 / (dv^2 + v_frag^2).
inline double fragmentation_factor(double dv, double v_frag) {
  return 1.0 - 2.0 * dv * dv / (dv * dv + v_frag * v_frag);
}

//! Rates with St from the drag law (kStokesRe unless `o` says otherwise).
inline ParticleRates<double> rates_at(double sigma, double m, double phi,
                                      const LocalGas& gas, const Species& sp,
                                      const GrowthOptions& o) {
  const double st = stokes_number(m, phi, kRho0, gas, o.drag);
  return particle_rates(sigma, m, phi, st, gas, sp, o);
}

}  // namespace growth_fixture
