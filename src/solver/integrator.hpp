#pragma once
//! The seam between the run loop and the time integrators: what `panoptic run` asks of
//! one (advance to a time, restart from a state, the statistics it writes and
//! checkpoints), the options a scene sets for either, and the factory that picks one by
//! solver.method. CvodeIntegrator (cvode_integrator.hpp, BDF with error control) and
//! ImplicitEulerIntegrator (implicit_euler_integrator.hpp, DustPy's step without error
//! control) implement it.
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "src/solver/solver_stats.hpp"

namespace panoptic {

class DiskModel;

//! The solver of CVODE's Newton systems (solver.linear).
enum class LinearSolverKind {
  klu,    //!< KLU, sparse LU of the whole matrix
  block,  //!< BlockBandedLU: dense LU of the cells' blocks, banded elimination
  gmres   //!< SPGMR, products with the assembled J, right-preconditioned by cell blocks
};

//! The time integrator (solver.method).
enum class IntegrationMethod {
  bdf,            //!< CVODE's BDF, variable order and step, with error control
  implicit_euler  //!< linearly implicit Euler, DustPy's step-size rule, no error control
};

struct IntegratorOptions {
  IntegrationMethod method = IntegrationMethod::bdf;
  double rtol = 1e-6;
  std::vector<double> atol;         //!< per component
  std::vector<double> constraints;  //!< per component: 1 = y >= 0, 0 = none
  long max_steps = 2000000;         //!< total step budget of the run
  double max_dt = 0.0;              //!< largest step [s], 0 = unlimited
  //! CVodeSetNonlinConvCoef (> 0): solver.newton_coef, whose 0 (the key's default)
  //! Simulation::newton_coefficient resolves by the model kind
  double newton_coef = 0.03;
  //! CVodeSetJacEvalFrequency and CVodeSetLSetupFrequency (solver.steps_per_jacobian);
  //! 0: CVODE's own (51 and 20)
  long steps_per_jacobian = 0;
  LinearSolverKind linear = LinearSolverKind::klu;
  //! gmres: the weights c of the booked dust mass (c . y = the sum of the budget terms,
  //! Simulation::budget_weights). A direct solve of the Newton system (I - gamma J) x = b
  //! gives c . x = c . b exactly, since a conservative model has c . J = 0; GMRES's x is
  //! then corrected to the same (cvode_integrator.cpp), so that the budget closes to
  //! round-off with it too. Empty: not corrected.
  std::vector<double> invariant;
  //! implicit_euler: the step is cfl times the shortest time in which a component of
  //! the step rule would empty at its present rate (solver.cfl)
  double cfl = 0.1;
  //! implicit_euler: per component, the value above which a shrinking component enters
  //! the step rule; +inf leaves it out. Empty: every component, floor 0.
  std::vector<double> step_floor;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  //! Integrates to exactly t_out. `on_step(t, nst)` is called after every internal
  //! step with the run's step count. Throws SolverError on a failure.
  virtual void advance_to(double t_out,
                          const std::function<void(double, long)>& on_step = {}) = 0;
  //! Restarts from (t, y) exactly as a new integrator built there: what makes a run
  //! restarted from a checkpoint bit-for-bit identical to one never stopped.
  virtual void reinit(double t, std::span<const double> y) = 0;
  //! Adds the statistics of the part of the run before a restart, so that stats() and
  //! the step budget solver.max_steps cover the whole run.
  virtual void carry_stats(const SolverStats& before) = 0;
  virtual double time() const = 0;
  virtual std::span<const double> state() const = 0;
  //! The run's totals (the checkpointed part included).
  virtual SolverStats stats() const = 0;
};

//! The integrator of options.method on `model` from (t0, y0).
std::unique_ptr<Integrator> make_integrator(DiskModel& model, double t0,
                                            std::span<const double> y0,
                                            IntegratorOptions options);

}  // namespace panoptic
