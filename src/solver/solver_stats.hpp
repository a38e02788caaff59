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

//! One counter of SolverStats by name: the one list of them, in the order the output's
//! /solver attributes and the checkpoints write them (and `panoptic reference --outputs`
//! lists them).
struct SolverCounter {
  const char* name;
  long SolverStats::*value;
  const char* description;
};

inline constexpr SolverCounter kSolverCounters[] = {
    {"nst", &SolverStats::nst, "CVODE steps"},
    {"nfe", &SolverStats::nfe, "right-hand side evaluations"},
    {"nje", &SolverStats::nje, "Jacobian evaluations"},
    {"nsetups", &SolverStats::nsetups, "linear-solver set-ups (KLU factorisations)"},
    {"netf", &SolverStats::netf, "error-test failures"},
    {"nni", &SolverStats::nni, "nonlinear (Newton) iterations"},
    {"nncf", &SolverStats::nncf, "nonlinear convergence failures"},
    {"nreinit", &SolverStats::nreinit, "re-initialisations"},
};

}  // namespace panoptic
