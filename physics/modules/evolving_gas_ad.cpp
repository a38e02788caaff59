#include "physics/modules/evolving_gas_ad.hpp"

#include "physics/modules/planetesimals_cell_rates.hpp"
#include "physics/modules/porous_growth.hpp"

namespace panoptic::physics {

ParticleRates<AD> particle_rates_ad_gas(const AD& sigma_d, const AD& m, const AD& phi,
                                        const AD& St, const LocalGasT<AD>& gas,
                                        const Species& sp, const GrowthOptions& o) {
  return particle_rates(sigma_d, m, phi, St, gas, sp, o);
}

AD stokes_number_ad_gas(const AD& m, const AD& phi, double rho0, const LocalGasT<AD>& gas,
                        DragLaw law) {
  return stokes_number(m, phi, rho0, gas, law);
}

}  // namespace panoptic::physics

namespace panoptic {

void Planetesimals::cell_rates_ad_gas(int cell, const AD* yc, AD& coag, AD& si) const {
  cell_rates_with(cell, yc, gas_.at_ad(cell, yc), coag, si);
}

}  // namespace panoptic
