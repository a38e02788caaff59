#include "src/solver/implicit_euler_integrator.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "src/core/error.hpp"
#include "src/core/units.hpp"

namespace panoptic {
namespace {

// The Newton matrix's solver for the model's layout, or SolverError with the reason the
// pattern does not fit it (returned as a prvalue: built in place, never moved).
BlockBandedLU block_solver_for(const DiskModel& model) {
  const StateLayout& layout = model.layout();
  try {
    return BlockBandedLU(model.pattern(), layout.n_cells(), layout.n_cell_vars());
  } catch (const BlockStructureRefused& e) {
    throw SolverError(
        "solver.method = \"implicit_euler\" needs the block solver, which "
        "cannot solve this scene's linear systems: " +
        e.reason + "; use solver.method = \"bdf\"");
  }
}

}  // namespace

ImplicitEulerIntegrator::ImplicitEulerIntegrator(DiskModel& model, double t0,
                                                 std::span<const double> y0,
                                                 IntegratorOptions options)
    : model_(model),
      opt_(std::move(options)),
      t_(t0),
      y_(y0.begin(), y0.end()),
      lu_(block_solver_for(model)) {
  const auto n = static_cast<std::size_t>(model.layout().size());
  if (y_.size() != n || (!opt_.step_floor.empty() && opt_.step_floor.size() != n))
    throw std::invalid_argument(
        "ImplicitEulerIntegrator: state or step floors of the wrong length");
  f_.resize(n);
  delta_.resize(n);
  const SparsityPattern& pattern = model.pattern();
  jacobian_.resize(static_cast<std::size_t>(pattern.nnz()));
  matrix_.resize(jacobian_.size());
  diagonal_ = pattern.diagonal_positions();
}

double ImplicitEulerIntegrator::step_size(std::span<const double> y,
                                          std::span<const double> f,
                                          std::span<const double> floor, double cfl,
                                          long* limiting) {
  // DustPy's rule (dustpy/std/dust.py `dt`, gas.f90 `timestep`, sim.py `dt`): the time
  // in which the fastest-shrinking component above its floor would empty at its rate
  double shortest = std::numeric_limits<double>::infinity();
  long arg = -1;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double level = floor.empty() ? 0.0 : floor[i];
    if (f[i] < 0.0 && y[i] > level && y[i] / -f[i] < shortest) {
      shortest = y[i] / -f[i];
      arg = static_cast<long>(i);
    }
  }
  if (limiting) *limiting = arg;
  return cfl * shortest;
}

void ImplicitEulerIntegrator::advance_to(
    double t_out, const std::function<void(double, long)>& on_step) {
  while (t_ < t_out) {
    if (stats_.nst >= opt_.max_steps)
      fail("the step budget solver.max_steps = " + std::to_string(opt_.max_steps) +
           " is used up; raise it or raise solver.cfl");
    // f and J at the step's start: once per step, whatever its retries
    ++stats_.nfe;
    if (model_.rhs_nothrow(t_, y_, f_) != 0)
      fail("the right-hand side is not finite at the step's start");
    ++stats_.nje;
    if (model_.jacobian_nothrow(t_, y_, jacobian_) != 0)
      fail("the Jacobian is not finite at the step's start");
    double dt = step_size(y_, f_, opt_.step_floor, opt_.cfl, &limiting_);
    if (opt_.max_dt > 0.0 && opt_.max_dt < dt) {
      dt = opt_.max_dt;
      limiting_ = -1;
    }
    step(dt, t_out);
    if (on_step) on_step(t_, stats_.nst);
  }
  t_ = t_out;
}

void ImplicitEulerIntegrator::step(double dt, double t_out) {
  bool to_output = dt >= t_out - t_;
  if (to_output) {
    dt = t_out - t_;
    limiting_ = -1;
  }
  for (int halvings = 0;; ++halvings) {
    if (halvings > kMaxHalvings || dt <= 4.0 * DBL_EPSILON * std::abs(t_))
      fail(
          "the Newton matrix I - dt J stayed singular, or its solution not finite, "
          "after " +
          std::to_string(halvings) + " halvings of the step (dt = " + std::to_string(dt) +
          " s)");
    // M = I - dt J on J's pattern (BlockBandedLU's input), then M Delta = dt f
    newton_matrix(jacobian_, diagonal_, dt, matrix_);
    ++stats_.nsetups;
    bool solved = lu_.factorize(matrix_);
    if (solved) {
      for (std::size_t i = 0; i < f_.size(); ++i) delta_[i] = dt * f_[i];
      ++stats_.nni;
      solved = lu_.solve(delta_);
    }
    if (solved) break;
    ++stats_.nncf;
    dt *= 0.5;
    to_output = false;
  }
  for (std::size_t i = 0; i < y_.size(); ++i) y_[i] += delta_[i];
  t_ = to_output ? t_out : std::min(t_ + dt, t_out);
  ++stats_.nst;
  stats_.h_last = dt;
}

void ImplicitEulerIntegrator::reinit(double t, std::span<const double> y) {
  std::copy(y.begin(), y.end(), y_.begin());
  t_ = t;
  limiting_ = -1;
  ++stats_.nreinit;
}

void ImplicitEulerIntegrator::carry_stats(const SolverStats& before) {
  for (const SolverCounter& c : kSolverCounters) stats_.*c.value += before.*c.value;
  if (stats_.h_last == 0.0) stats_.h_last = before.h_last;
}

void ImplicitEulerIntegrator::fail(const std::string& what) const {
  std::ostringstream msg;
  msg << "implicit Euler failed at t = " << t_ << " s (" << t_ / units::kYr
      << " yr): " << what;
  if (!model_.last_error().empty()) msg << "\n  model says: " << model_.last_error();
  if (limiting_ >= 0)
    msg << "\n  the last step was set by " << model_.describe(limiting_, y_) << ", value "
        << y_[static_cast<std::size_t>(limiting_)] << " "
        << model_.layout().info_of(limiting_).units;
  throw SolverError(msg.str());
}

}  // namespace panoptic
