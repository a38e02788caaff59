#pragma once
//! DustPy's time step as a baseline integrator (solver.method = "implicit_euler"; issue
//! 35, item 5): a linearly implicit Euler step on the model's assembled Jacobian with
//! DustPy's step-size rule and no error control.
//!
//! What DustPy does (v1.0.8, stammler/dustpy at aa42101, the version of the anchors in
//! shared/anchors/):
//! - Step size (dustpy/std/sim.py `dt`): cfl times the smaller of the gas's and the
//!   dust's time step, cfl = 0.1 (dustpy/simulation.py, `t.cfl`). The dust's
//!   (dustpy/std/dust.py `dt`): the least Sigma/|S_tot| over the bins that shrink
//!   (S_tot < 0) and lie above the floor SigmaFloor = 0.1 m_k / A_i (a tenth of a
//!   particle per annulus: dust.py `SigmaFloor` times the 0.1 of simulation.py), the two
//!   boundary cells left out; the gas's (dustpy/std/gas.f90 `timestep`): the same on
//!   Sigma_g above its floor 1e-100. simframe's integrator cuts the step at the next
//!   snapshot (simframe IntVar.maxstepsize). No step is rejected.
//! - Step (dust.py `impl_1_direct`): (I - dt J) Sigma_{n+1} = Sigma_n (+ dt S_ext), by
//!   scipy's SuperLU, with J (dust.py `jacobian`) the sum of the transport's exact
//!   Jacobian (dust.f90 `jacobian_hydrodynamic_generator`) and a coagulation matrix
//!   (`jacobian_coagulation_generator`) built so that J_coag Sigma = S_coag (the
//!   partner's number density factored out of each pair), not the derivative of the
//!   quadratic S_coag. Since J Sigma_n = S(Sigma_n), the step is
//!   (I - dt J) Delta = dt S(Sigma_n): a linearly implicit Euler step with that matrix.
//!   Kernel, velocities and fragmentation probabilities are those of the step's start.
//!   The gas takes its own implicit step after the dust's (gas.py `impl_1_direct`).
//! - After the step (dust.py `finalize_implicit`, `enforce_floor_value`): every bin
//!   below SigmaFloor is set to 0.1 SigmaFloor, mass that is not booked.
//!
//! What panoptic does here, the same or not:
//! - The same step-size rule, on the components the options name (step_floor: the
//!   Simulation names every sigma_k with DustPy's floor and Sigma_g with 1e-100, in every
//!   cell, panoptic's cells being all interior), cut at the output time and at
//!   solver.max_dt_yr. The porosity moments psi_k (DustPy has none), the booked masses
//!   and Sigma_pl ride along outside the rule.
//! - (I - dt J(y_n)) Delta = dt f(y_n), y_{n+1} = y_n + Delta with J the model's own
//!   Jacobian (the derivative: exact for compact bins and the transport; the porous
//!   coefficients' derivatives by ln u by forward differences), gas and dust in one
//!   system (no splitting). First order, as DustPy's; for y' = A y exactly implicit
//!   Euler. The Newton matrix is factorised by BlockBandedLU.
//! - No floor after the step: sigma_k is not constrained in panoptic's BDF runs either
//!   (physics/modules/size_distribution.cpp). A conservative model (w . f(y) = 0 for all
//!   y, w the budget's weights: cell areas and the booked masses) has w . J = 0, so
//!   w . Delta = w . (dt f + dt J Delta) = 0: the budget closes to round-off, where
//!   DustPy's floor adds mass.
//! - A step whose Newton matrix has a singular pivot block or whose solution is not
//!   finite is retried with half the step (counted as a convergence failure, nncf);
//!   DustPy retries nothing.
//! Counters (SolverStats): a step takes one right-hand side, one Jacobian, one
//! factorisation and one solve per attempt (nfe, nje, nsetups, nni); netf stays 0.
#include <string>
#include <vector>

#include "src/solver/block_banded_lu.hpp"
#include "src/solver/disk_model.hpp"
#include "src/solver/integrator.hpp"

namespace panoptic {

class ImplicitEulerIntegrator final : public Integrator {
 public:
  //! Throws SolverError when BlockBandedLU cannot solve the model's pattern (a cell row
  //! that reads a global variable), std::invalid_argument for options of the wrong size.
  ImplicitEulerIntegrator(DiskModel& model, double t0, std::span<const double> y0,
                          IntegratorOptions options);

  //! Steps to exactly t_out; `on_step(t, nst)` after every step. Throws SolverError
  //! (time, reason, the model's message, the component that set the last step).
  void advance_to(double t_out,
                  const std::function<void(double, long)>& on_step = {}) override;
  //! Sets (t, y): the scheme keeps no history, so this is a new integrator there.
  void reinit(double t, std::span<const double> y) override;
  void carry_stats(const SolverStats& before) override;
  double time() const override { return t_; }
  std::span<const double> state() const override { return y_; }
  SolverStats stats() const override { return stats_; }

  //! The step of the rule: cfl min y_i/|f_i| over the components with f_i < 0 and
  //! y_i > floor_i (an empty `floor`: every component, floor 0); +inf when none
  //! shrinks. `limiting` (if not null) receives the component of the minimum, or -1.
  static double step_size(std::span<const double> y, std::span<const double> f,
                          std::span<const double> floor, double cfl,
                          long* limiting = nullptr);
  //! The component that set the last step by the rule (-1: none, or the output time
  //! or solver.max_dt_yr set it).
  long limiting_component() const { return limiting_; }

 private:
  //! One step from (t_, y_) of at most dt (halved on a singular matrix or a
  //! non-finite solution) to a time that does not pass t_out.
  void step(double dt, double t_out);
  [[noreturn]] void fail(const std::string& what) const;

  DiskModel& model_;
  IntegratorOptions opt_;
  double t_ = 0.0;
  std::vector<double> y_, f_, jacobian_, matrix_, delta_;
  std::vector<std::size_t> diagonal_;  //!< where each column's diagonal sits in J
  BlockBandedLU lu_;
  SolverStats stats_;
  long limiting_ = -1;
  //! Halvings of a step before the run fails.
  static constexpr int kMaxHalvings = 30;
};

}  // namespace panoptic
