#pragma once
//! Test helper: the MMSN midplane gas written out from the spec formulas (§1.2-1.6),
//! independently of make_local_gas(), for the unit tests of the local laws (particle,
//! relative velocities, growth rates): Sigma = 1700 r^-1.5, T = 280 r^-0.5, mu = 2.34,
//! sigma_mol = 2e-15, dlnP/dlnr = -3.25, alpha = 1e-3, M_* = 1 M_sun.
#include <cmath>

#include "disk/local_gas.hpp"
#include "src/core/units.hpp"

namespace panoptic::physics {

inline LocalGas mmsn_gas(double r_au) {
  const double r = r_au * units::kAu;
  const double mu = 2.34;
  LocalGas g;
  g.sigma_g = 1700.0 * std::pow(r_au, -1.5);
  g.temperature = 280.0 / std::sqrt(r_au);
  g.c_s = std::sqrt(units::kBoltzmann * g.temperature / (mu * units::kMassH));
  g.v_th = std::sqrt(8.0 / units::kPi) * g.c_s;
  g.omega_k = std::sqrt(units::kG * units::kMsun / (r * r * r));
  g.v_k = g.omega_k * r;
  g.h_g = g.c_s / g.omega_k;
  g.rho_g = g.sigma_g / (std::sqrt(2.0 * units::kPi) * g.h_g);
  g.mfp = mu * units::kMassH / (2e-15 * g.rho_g);
  g.nu_mol = 0.5 * g.v_th * g.mfp;
  g.eta = -0.5 * (g.h_g / r) * (g.h_g / r) * (-3.25);
  g.alpha = 1e-3;
  return g;
}

//! |value / ref - 1|.
inline double rel_err(double value, double ref) { return std::abs(value / ref - 1.0); }

}  // namespace panoptic::physics
