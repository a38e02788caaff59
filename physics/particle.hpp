#pragma once
//! Properties of the mass-dominating dust particle of a cell (spec §2): monomer mass,
//! internal density, radius from (m, phi), dust scale height and midplane dust density.
//! Its drag (the Stokes number) is in physics/drag.hpp, the smooth switches every
//! regime change uses in physics/smooth_switches.hpp. Sources: Youdin & Lithwick (2007)
//! for h_d; Okuzumi et al. (2012) for their use.
//!
//! Every function in physics/ is a template on the scalar type T, so that it can be
//! evaluated with double and with Eigen::AutoDiffScalar (exact Jacobians). Rules for T
//! code: unqualified sqrt/exp/log/pow after `using std::...` (ADL finds Eigen's
//! overloads), every intermediate is stored in a named T (never `auto`: Eigen's AutoDiff
//! expressions reference temporaries), and no std::max/std::min on T (their derivative
//! jumps): use soft_max/soft_min/logistic. The gas is a LocalGasT<G>
//! (disk/local_gas.hpp): G = double, or AD where the Jacobian differentiates an
//! evolving Sigma_g; quantities derived from its density-dependent fields are G, never
//! double.
#include <cmath>

#include "disk/local_gas.hpp"
#include "physics/smooth_switches.hpp"
#include "src/core/autodiff.hpp"
#include "src/core/units.hpp"

namespace panoptic::physics {

// ---------------------------------------------------------------------------------------------
// Particle structure (spec §2)
// ---------------------------------------------------------------------------------------------

//! Monomer mass m0 = (4 pi / 3) a0^3 rho0 (spec §2) [g]; a0 [cm], rho0 [g cm^-3].
template <class T>
T monomer_mass(const T& a0, const T& rho0) {
  return (4.0 * units::kPi / 3.0) * a0 * a0 * a0 * rho0;
}

//! Internal (aggregate) density rho_int = phi rho0 (spec §2) [g cm^-3].
template <class T>
T internal_density(const T& phi, double rho0) {
  return phi * rho0;
}

//! Aggregate radius a = (3 m / (4 pi rho0 phi))^(1/3) (spec §2) [cm]; m [g], phi [-].
template <class T>
T radius(const T& m, const T& phi, double rho0) {
  const T v = 3.0 * m / (4.0 * units::kPi * rho0 * phi);
  return cbrt_of(v);
}

//! Number of monomers N = m / m0 (spec §2) [-].
template <class T>
T monomer_count(const T& m, double m0) {
  return m / m0;
}

// ---------------------------------------------------------------------------------------------
// Vertical structure (spec §2)
// ---------------------------------------------------------------------------------------------

//! Dust scale height h_d = H [1 + (St/alpha)(1 + 2 St)/(1 + St)]^(-1/2) (spec §2; Youdin
//! & Lithwick 2007 with Sc = 1, as used by Okuzumi et al. 2012) [cm].
template <class T, class G>
T dust_scale_height(const T& St, const LocalGasT<G>& gas) {
  using std::sqrt;
  const T settling = (St / gas.alpha) * (1.0 + 2.0 * St) / (1.0 + St);
  return gas.h_g / sqrt(1.0 + settling);
}

//! Midplane dust density rho_d = Sigma_d / (sqrt(2 pi) h_d) (spec §2) [g cm^-3];
//! sigma_d [g cm^-2], h_d [cm].
template <class T>
T midplane_dust_density(const T& sigma_d, const T& h_d) {
  return sigma_d / (std::sqrt(2.0 * units::kPi) * h_d);
}

//! Midplane dust-to-gas ratio eps_mid = rho_d / rho_g (spec §2) [-].
template <class T, class G>
T midplane_dust_to_gas(const T& sigma_d, const T& h_d, const LocalGasT<G>& gas) {
  return midplane_dust_density(sigma_d, h_d) / gas.rho_g;
}

}  // namespace panoptic::physics
