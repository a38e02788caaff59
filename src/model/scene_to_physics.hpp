#pragma once
//! Scene -> physics parameters: the translators from the keys of a scene (src/scene) to
//! the plain parameter structs that the laws (physics/), the gas (disk/) and the grid
//! modules (physics/modules/) take. The only place where those structs meet a Config.
#include <string>

#include "disk/gas_disk.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/growth_options.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/modules/planetesimals.hpp"
#include "physics/optical_constants.hpp"
#include "src/scene/config.hpp"

namespace panoptic {

//! The star, thermal structure and gas profile of the scene (keys star.*, disk.*,
//! spec §1), in cgs.
DiskParams disk_params_from_config(const Config& cfg);
//! The monomer material "ice" or "sil" of the scene (keys material.*, spec §0).
physics::MonomerMaterial material_from_config(const Config& cfg, const std::string& sp);
//! The monomer species "ice" or "sil" of the scene (keys material.*, spec §0).
physics::Species species_from_config(const Config& cfg, const std::string& sp);
//! The optical constants observe.<sp>_lambda_mm, _n, _k of species "ice" or "sil" as a
//! table; a table the scene makes invalid fails naming the key (the one a --set
//! changed, if any).
physics::OpticalTable optical_table_from_config(const Config& cfg, const std::string& sp);
//! The growth-model switches and parameters of the scene (spec §3-§5).
physics::GrowthOptions growth_options_from_config(const Config& cfg);
//! The dust transport's switches (keys transport.*, spec §6.1).
DustTransportOptions transport_options_from_config(const Config& cfg);
//! The planetesimal channels and their parameters (keys planetesimals.*, spec §7).
PlanetesimalOptions planetesimal_options_from_config(const Config& cfg);
//! The absolute tolerance of the surface densities relative to the largest initial
//! Sigma_d (solver.atol_sigma, its 0 resolved by model) [-].
double atol_sigma_from_config(const Config& cfg);

}  // namespace panoptic
