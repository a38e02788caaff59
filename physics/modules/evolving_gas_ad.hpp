#pragma once
//! The particle laws differentiated by an evolving Sigma_g (LocalGasT<AD>, from
//! CellGas::at_ad), for the Jacobians of scenes with gas.evolve. Compiled in a
//! translation unit of their own: instantiated next to the static-gas (LocalGas)
//! versions, they stop GCC inlining Eigen's AD kernels there, which slows the Jacobian
//! of every scene (bench_kernels measures it).
#include "physics/growth_rates.hpp"
#include "src/core/autodiff.hpp"

namespace panoptic::physics {

//! particle_rates() (spec §4-§5) on a gas whose density-dependent fields carry
//! derivatives.
ParticleRates<AD> particle_rates_ad_gas(const AD& sigma_d, const AD& m, const AD& phi,
                                        const AD& St, const LocalGasT<AD>& gas,
                                        const Species& sp, const GrowthOptions& o);
//! stokes_number() (spec §2) likewise.
AD stokes_number_ad_gas(const AD& m, const AD& phi, double rho0, const LocalGasT<AD>& gas,
                        DragLaw law);

}  // namespace panoptic::physics
