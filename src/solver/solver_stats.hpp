#pragma once
//! The counters of a CVODE integration, as a plain struct: written to the output's
//! /solver group and carried in checkpoints, so that the I/O layer needs no integrator
//! (CvodeIntegrator::stats fills it).

namespace panoptic {

struct SolverStats {
  long nst = 0;      //!< steps
  long nfe = 0;      //!< RHS evaluations (excluding those for difference quotients: none)
  long nje = 0;      //!< Jacobian evaluations
  long nsetups = 0;  //!< linear-solver set-ups (KLU factorisations)
  long netf = 0;     //!< error-test failures
  long nni = 0;      //!< nonlinear (Newton) iterations
  long nncf = 0;     //!< nonlinear convergence failures
  long nreinit = 0;  //!< re-initialisations
  double h_last = 0.0;  //!< last step size [s]
};

}  // namespace panoptic
