#include "src/observe/materials.hpp"

#include "src/core/error.hpp"
#include "src/model/scene_to_physics.hpp"
#include "src/scene/config.hpp"

namespace panoptic {

double OpticalMaterials::outer_density() const {
  if (outer == "ice") return rho_ice;
  if (outer == "sil") return rho_sil;
  return (1.0 - f_sil_volume) * rho_ice + f_sil_volume * rho_sil;
}

std::complex<double> OpticalMaterials::outer_index(double lambda_mm) const {
  using cplx = std::complex<double>;
  if (outer == "ice") return ice.at(lambda_mm);
  if (outer == "sil") return sil.at(lambda_mm);
  const cplx e_ice = ice.at(lambda_mm) * ice.at(lambda_mm);
  const cplx e_sil = sil.at(lambda_mm) * sil.at(lambda_mm);
  const cplx e = rule == "bruggeman"
                     ? physics::bruggeman(e_ice, e_sil, f_sil_volume)
                     : physics::maxwell_garnett(e_ice, e_sil, f_sil_volume);
  cplx m = std::sqrt(e);
  return m.imag() < 0.0 ? -m : m;
}

OpticalMaterials optical_materials(const Config& cfg) {
  const double f_ice = cfg.real("snowline.f_ice");
  const double rho_ice = cfg.real("observe.water_ice_rho");
  const double rho_sil = cfg.real("material.sil_rho0");
  return OpticalMaterials{
      optical_table_from_config(cfg, "ice"),
      optical_table_from_config(cfg, "sil"),
      cfg.str("observe.outer_species"),
      cfg.str("observe.mix_rule"),
      (1.0 - f_ice) / rho_sil / (f_ice / rho_ice + (1.0 - f_ice) / rho_sil),
      rho_ice,
      rho_sil};
}

void check_wavelengths_covered(const OpticalMaterials& mat,
                               const std::vector<double>& lambda_mm) {
  for (const double l : lambda_mm) {
    const bool outer_ice = mat.outer != "sil";
    if (!mat.sil.covers(l) || (outer_ice && !mat.ice.covers(l)))
      throw ConfigError(
          "--lambda-mm " + num(l) + ": outside the optical-constant tables (" +
          "silicate " + num(mat.sil.lambda_min_mm()) + " - " +
          num(mat.sil.lambda_max_mm()) + " mm, ice " + num(mat.ice.lambda_min_mm()) +
          " - " + num(mat.ice.lambda_max_mm()) +
          " mm); extend observe.*_lambda_mm/_n/_k with --set");
  }
}

}  // namespace panoptic
