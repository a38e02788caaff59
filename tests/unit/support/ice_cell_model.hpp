#pragma once
//! The icy cell of the coagulation tests and of bench_coagulation: ice monomers of
//! spec §0 (a0, rho0 of physics/contact_mechanics.hpp, E_roll = 4.74e-9 erg) with the
//! given collision outcomes (spec §15.2).
#include "physics/coagulation/cell_coefficients.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/particle.hpp"

namespace panoptic::testing {

//! Ice monomers with the outcomes `outcomes` (default: sticking only).
inline physics::coagulation::CellModel ice_cell_model(
    const physics::coagulation::OutcomeSwitches& outcomes = {}) {
  const physics::MonomerMaterial ice = physics::ice_material();
  physics::coagulation::CellModel model;
  model.species.a0 = ice.a0;
  model.species.rho0 = ice.rho0;
  model.species.m0 = physics::monomer_mass(ice.a0, ice.rho0);
  model.species.e_roll = 4.74e-9;  // spec §0
  model.outcomes = outcomes;
  return model;
}

}  // namespace panoptic::testing
