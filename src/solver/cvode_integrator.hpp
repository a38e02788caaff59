#pragma once
//! CVODE (BDF, variable order) with a sparse Jacobian in CSC form, its Newton systems
//! solved by KLU, by the block-banded solver (block_banded_lu.hpp) of a layout of
//! cells, or by GMRES with a per-cell block preconditioner
//! (cell_block_preconditioner.hpp). RAII over SUNContext, N_Vector, SUNSparseMatrix,
//! SUNLinearSolver and the CVODE memory; non-copyable. The Jacobian pattern comes from
//! the DiskModel and is copied into the matrix at every call (CVODE zeroes the index
//! arrays with the values).
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "src/solver/conservative_gmres.hpp"
#include "src/solver/disk_model.hpp"
#include "src/solver/integrator.hpp"
#include "src/solver/solver_stats.hpp"

namespace panoptic {

class CellBlockPreconditioner;

//! Wall time spent in each part of the integration, for benchmarks (see
//! CvodeIntegrator::set_profile): the model's right-hand side and Jacobian, and KLU's
//! set-up (factorisation) and solve, timed around each call (those of the block solver
//! with solver.linear = "block").
struct CallbackTimes {
  double rhs_s = 0.0, jac_s = 0.0, lsetup_s = 0.0, lsolve_s = 0.0;
  long n_rhs = 0, n_jac = 0, n_lsetup = 0, n_lsolve = 0;
};

//! What the CVODE callbacks receive as user data.
struct CvodeCallbackData {
  DiskModel* model = nullptr;
  void* newton_iterate = nullptr;  //!< N_Vector: y of the last nonlinear-solver RHS call
  CallbackTimes* times = nullptr;  //!< accumulate callback wall times (benchmarks)
  //! The last Jacobian's values (the pattern's CSC order), kept for the Newton matrix
  //! I - gamma J of the steps that reuse it, and where each column's diagonal sits.
  std::vector<double> jacobian;
  std::vector<std::size_t> diagonal;
  //! GMRES (solver.linear = "gmres"): the pattern for the products J v, the
  //! preconditioner, and the Jacobian evaluations since CVODE's creation (CVODE counts
  //! only those of its matrix-based interface).
  const SparsityPattern* pattern = nullptr;
  CellBlockPreconditioner* preconditioner = nullptr;
  long n_jacobian = 0;
  //! GMRES: the budget's weights c (IntegratorOptions::invariant; empty: GMRES's
  //! solutions are not corrected), the Krylov directions and the residual
  //! (conservative_gmres.hpp).
  std::span<const double> invariant;
  GmresDirections gmres;
  std::vector<double> residual;
};

//! The counters of the Krylov iteration (solver.linear = "gmres"; zero otherwise) since
//! the integrator's construction: not in SolverStats, so not carried by checkpoints.
struct KrylovStats {
  long nli = 0;   //!< linear (GMRES) iterations
  long nps = 0;   //!< preconditioner solves
  long nlcf = 0;  //!< linear convergence failures
};

class BlockBandedLU;

//! CVODE's weighted RMS norm sqrt(sum_i (x_i w_i)^2 / n), summed in four independent
//! partial sums (the integrator installs it as the state vector's norm).
double weighted_rms_norm(std::span<const double> x, std::span<const double> w);

class CvodeIntegrator final : public Integrator {
 public:
  CvodeIntegrator(DiskModel& model, double t0, std::span<const double> y0,
                  IntegratorOptions options);
  ~CvodeIntegrator();
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  //! Integrates to exactly t_out (CVODE stop time). `on_step(t, nst)` is called after
  //! every internal step. Throws SolverError with the flag name, the time, CVODE's
  //! message, the model's message and the components with the largest weighted local
  //! error, each with the physical state of its cell (DiskModel::describe).
  void advance_to(double t_out,
                  const std::function<void(double, long)>& on_step = {}) override;
  //! Restarts the integrator (order 1, fresh history) from (t, y), exactly as a new
  //! integrator built at (t, y): this is what makes a run restarted from a checkpoint
  //! bit-for-bit identical to one that reinitialises at the same time.
  void reinit(double t, std::span<const double> y) override;
  //! Adds the statistics of the part of the run before a restart, so that stats() and
  //! the step budget solver.max_steps cover the whole run.
  void carry_stats(const SolverStats& before) override;

  //! Accumulate the wall time of every callback and of KLU into `times` (null: off).
  //! For benchmarks: the clock reads cost ~50 ns per call.
  void set_profile(CallbackTimes* times);
  //! Current step size [s] and order (of the next step), the size and order of the last
  //! step, and the k components with the largest weighted local error estimate of the
  //! last step (index, |e_i w_i|), largest first: which variables limit the step
  //! (diagnostics, benchmarks). With `all_errors`, also |e_i w_i| of every component
  //! (CVODE's error test: their root mean square over all components <= 1).
  struct StepInfo {
    double h = 0.0, h_last = 0.0;
    int order = 0, order_last = 0;
    std::vector<std::pair<long, double>> largest_errors;
    std::vector<double> weighted_errors;
  };
  StepInfo step_info(int k, bool all_errors = false) const;

  //! The block solver (solver.linear = "block"; null with KLU).
  const BlockBandedLU* block_solver() const { return block_lu_.get(); }
  //! The preconditioner (solver.linear = "gmres"; null otherwise).
  const CellBlockPreconditioner* preconditioner() const { return preconditioner_.get(); }
  KrylovStats krylov_stats() const;

  double time() const override { return t_; }
  std::span<const double> state() const override;
  //! dy/dt at time() from CVODE's interpolating polynomial of the last step (valid after
  //! a step; for dense output between steps, e.g. benchmarks coupling integrators).
  void derivative(std::span<double> out) const;
  //! Totals of the run: CVODE's counters (reset by every reinit) plus those saved at
  //! each reinit and carried over from a checkpoint.
  SolverStats stats() const override;

 private:
  [[noreturn]] void fail(int flag, const std::string& what);
  //! CVODE's own counters since the last (re)initialisation.
  SolverStats cvode_counters() const;
  //! Sets the negative round-off of components constrained to y >= 0 to zero in y_.
  void clip_to_constraints();
  //! Creates the CVODE memory, the matrix and the linear solver at (t0, y_) with the
  //! options.
  void create_cvode(double t0);
  //! create_cvode's part for GMRES: SPGMR, the products J v and the preconditioner.
  void create_krylov_solver();
  //! The step budget, largest step, Newton coefficient and Jacobian ages of the options.
  void set_step_controls();
  void free_cvode();

  DiskModel& model_;
  IntegratorOptions opt_;
  double t_ = 0.0;
  SolverStats before_;      // totals of the segments before the last (re)initialisation
  void* sunctx_ = nullptr;  // SUNContext (opaque pointer type)
  void* y_ = nullptr;       // N_Vector
  void* atol_ = nullptr;    // N_Vector
  void* constr_ = nullptr;  // N_Vector
  void* A_ = nullptr;       // SUNMatrix
  void* LS_ = nullptr;      // SUNLinearSolver
  //! The block solver's factors (solver.linear = "block"), kept across reinit: it holds
  //! no state from one factorisation to the next, only the storage and the pattern's map.
  std::unique_ptr<BlockBandedLU> block_lu_;
  std::unique_ptr<CellBlockPreconditioner> preconditioner_;  // as block_lu_, for GMRES
  KrylovStats krylov_before_;  // of the CVODE instances before the last reinit
  void* cvode_ = nullptr;
  CvodeCallbackData callback_data_;  // newton_iterate: for the report of a failure
  std::string cvode_message_;
  //! Steps in a row that did not advance t (below its round-off); see advance_to.
  static constexpr int kMaxStalledSteps = 100;
  //! GMRES's Krylov dimension (SUNLinSol_SPGMR's maxl; CVODE's default 5).
  static constexpr int kKrylovDimension = 20;
  int stalled_ = 0;
  friend void cvode_error_handler(int, const char*, const char*, char*, void*);
};

}  // namespace panoptic
