#pragma once
//! Test helper: a scene's state after some growth, for tests that need cells that are
//! growing, compacting and converting (at 300 yr on the fiducial scene) rather than the
//! monomers of the initial state.
#include <vector>

#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/solver/cvode_integrator.hpp"

namespace panoptic {

//! The state of `sim` integrated from its initial state to t_yr with the scene's solver
//! options.
inline std::vector<double> evolved_state(Simulation& sim, double t_yr) {
  CvodeIntegrator cvode(sim.model(), 0.0, sim.initial_state(), sim.integrator_options());
  cvode.advance_to(t_yr * units::kYr);
  return {cvode.state().begin(), cvode.state().end()};
}

}  // namespace panoptic
