#pragma once
//! Local (one cell, midplane) gas state seen by the dust: the inputs of the particle and
//! relative-velocity laws (physics/particle.hpp, physics/drag.hpp,
//! physics/relative_velocity.hpp). Models: spec §1.3 (sound speed, scale height, midplane
//! density), §1.4 (pressure-gradient parameter eta), §1.5 (alpha turbulence), §1.6 (mean
//! free path, molecular viscosity). Sources: standard thin-disk relations;
//! Weidenschilling (1977) for eta; Shakura & Sunyaev (1973) for alpha. All quantities
//! cgs.
#include <cmath>

#include "disk/gas_defaults.hpp"
#include "disk/pressure_gradient.hpp"
#include "src/core/units.hpp"

namespace panoptic::physics {

//! Gas quantities of one cell at the midplane, all cgs. Filled once per cell by the
//! engine (directly, or with make_local_gas()). The quantities that follow the gas
//! surface density where the gas evolves (Sigma_g, rho_g, lambda, nu_mol) have the type
//! G: double in the right-hand side and with static gas, AD in the Jacobian of a cell
//! whose Sigma_g is a state variable (CellGas::at_ad), so that the particle laws are
//! differentiated by Sigma_g too; the rest is fixed per cell.
template <class G>
struct LocalGasT {
  G sigma_g = G(0.0);        //!< gas surface density [g cm^-2]
  G rho_g = G(0.0);          //!< midplane gas density [g cm^-3]
  double temperature = 0.0;  //!< gas temperature [K] (Brownian motion)
  double c_s = 0.0;          //!< isothermal sound speed [cm s^-1]
  double v_th = 0.0;         //!< mean thermal speed sqrt(8/pi) c_s [cm s^-1]
  double omega_k = 0.0;      //!< Keplerian angular frequency [s^-1]
  double v_k = 0.0;          //!< Keplerian speed [cm s^-1]
  double h_g = 0.0;          //!< gas pressure scale height c_s/omega_k [cm]
  G mfp = G(0.0);            //!< molecular mean free path lambda [cm]
  G nu_mol = G(0.0);         //!< molecular kinematic viscosity [cm^2 s^-1]
  double alpha = 0.0;        //!< Shakura-Sunyaev turbulence parameter [-]
  double eta = 0.0;          //!< pressure-gradient parameter (headwind = eta v_k) [-]
  double v_r_gas = 0.0;      //!< radial gas velocity (0 for a static disk) [cm s^-1]

  //! Turbulent Reynolds number alpha c_s H / nu_mol (spec §1.5) [-].
  G reynolds() const { return alpha * c_s * h_g / nu_mol; }
  //! Headwind speed eta v_K (spec §1.4) [cm s^-1].
  double headwind() const { return eta * v_k; }
};

//! The gas of the right-hand side, of static gas, and of output.
using LocalGas = LocalGasT<double>;

//! `g` with a gas surface density `ratio` times its own (spec §1.3, §1.6: rho_g ∝
//! Sigma_g; lambda and nu_mol ∝ 1/Sigma_g); the temperature, the pressure gradient (eta)
//! and the rest are kept. G = AD carries the derivatives of the ratio (a Jacobian by an
//! evolving Sigma_g).
template <class G>
LocalGasT<G> with_density_ratio(const LocalGas& g, const G& ratio) {
  LocalGasT<G> out;
  out.sigma_g = g.sigma_g * ratio;
  out.rho_g = g.rho_g * ratio;
  out.temperature = g.temperature;
  out.c_s = g.c_s;
  out.v_th = g.v_th;
  out.omega_k = g.omega_k;
  out.v_k = g.v_k;
  out.h_g = g.h_g;
  out.mfp = g.mfp / ratio;
  out.nu_mol = g.nu_mol / ratio;
  out.alpha = g.alpha;
  out.eta = g.eta;
  out.v_r_gas = g.v_r_gas;
  return out;
}

//! Builds a LocalGas from the basic quantities of one cell.
//! sigma_g [g cm^-2], temperature [K], r [cm], m_star [g], alpha [-], dlnp_dlnr: midplane
//! d ln P / d ln r at r [-] (-3.25 for the MMSN; computed numerically by the engine for
//! general profiles), mu [-], sigma_mol [cm^2].
inline LocalGas make_local_gas(double sigma_g, double temperature, double r,
                               double m_star, double alpha, double dlnp_dlnr,
                               double mu = gas_defaults::kMu,
                               double sigma_mol = gas_defaults::kSigmaMol) {
  using units::kBoltzmann, units::kG, units::kMassH, units::kPi;
  LocalGas g;
  g.sigma_g = sigma_g;
  g.temperature = temperature;
  g.alpha = alpha;
  g.c_s = std::sqrt(kBoltzmann * temperature / (mu * kMassH));  // spec §1.3
  g.v_th = std::sqrt(8.0 / kPi) * g.c_s;                        // spec §1.3
  g.omega_k = std::sqrt(kG * m_star / (r * r * r));             // spec §1.3
  g.v_k = g.omega_k * r;                                        // spec §1.3
  g.h_g = g.c_s / g.omega_k;                                    // spec §1.3
  g.rho_g = sigma_g / (std::sqrt(2.0 * kPi) * g.h_g);  // spec §1.3, isothermal Gaussian
  g.mfp = mu * kMassH / (sigma_mol * g.rho_g);         // spec §1.6
  g.nu_mol = 0.5 * g.v_th * g.mfp;                     // spec §1.6
  const double h_over_r = g.h_g / r;
  g.eta = pressure_gradient_eta(h_over_r * h_over_r, dlnp_dlnr);  // spec §1.4
  return g;
}

}  // namespace panoptic::physics
