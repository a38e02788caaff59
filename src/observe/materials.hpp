#pragma once
//! The optical solids of `panoptic observe`: silicate inside the snow line, outside it
//! water ice, silicate or their mix (observe.outer_species, mixed by observe.mix_rule),
//! with their optical constants and densities, from the scene's [observe] keys.
#include <complex>
#include <string>
#include <vector>

#include "physics/optical_constants.hpp"

namespace panoptic {

class Config;

struct OpticalMaterials {
  physics::OpticalTable ice, sil;
  std::string outer, rule;              //!< observe.outer_species, observe.mix_rule
  double f_sil_volume = 0.0;            //!< silicate volume fraction of the mix
  double rho_ice = 0.0, rho_sil = 0.0;  //!< densities of the optical solids [g cm^-3]
  //! Density of the solid whose optical constants the outer particles get [g cm^-3].
  double outer_density() const;
  //! Refractive index of the outer solid at lambda [mm] (Im m >= 0).
  std::complex<double> outer_index(double lambda_mm) const;
};

//! The materials of the scene `cfg` (the run's, with --set observe.* overrides).
OpticalMaterials optical_materials(const Config& cfg);

//! Throws ConfigError for a wavelength outside the optical-constant tables the
//! particles use (the ice table only when the outer species holds ice).
void check_wavelengths_covered(const OpticalMaterials& mat,
                               const std::vector<double>& lambda_mm);

}  // namespace panoptic
