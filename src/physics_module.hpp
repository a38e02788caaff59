#pragma once
//! A physical process as seen by the integrator (Cantera getJacobianElements; DustPy's
//! J_hyd + J_coag + ...). Modules *add* their terms to ydot and J, never overwrite, so a
//! scene's model is the sum of the modules it turns on and a process that is off costs
//! nothing.
//!
//! NEW_PROCESS: derive from PhysicsModule, register its variables with the StateLayout in
//! its constructor, and build it in Simulation (src/simulation.cpp) when the scene turns
//! it on (README "Adding a physical process").
#include <span>
#include <string_view>

#include "src/sparsity.hpp"

namespace panoptic {

class PhysicsModule {
 public:
  virtual ~PhysicsModule() = default;
  virtual std::string_view name() const = 0;
  //! Declare every (row, col) this module may ever write. Called once, at set-up.
  virtual void declare_pattern(PatternBuilder& pattern) const = 0;
  //! ydot += F(t, y).
  virtual void add_rhs(double t, std::span<const double> y,
                       std::span<double> ydot) const = 0;
  //! J += dF/dy (t, y), exact.
  virtual void add_jacobian(double t, std::span<const double> y,
                            JacobianValues& jac) const = 0;

  //! add_rhs() on the rows of the cells [lo, hi) and of the global variables fed through
  //! the faces lo..hi; rows of other cells may be written too (the default computes them
  //! all). For integrators that step part of the grid on its own (block-local time
  //! stepping, tests/bench/bench_lts.cpp); a module with local or face-by-face terms
  //! overrides it to skip the rest.
  virtual void add_rhs_cells(double t, std::span<const double> y, std::span<double> ydot,
                             int lo, int hi) const {
    (void)lo, (void)hi;
    add_rhs(t, y, ydot);
  }
  //! add_jacobian() on the same rows as add_rhs_cells().
  virtual void add_jacobian_cells(double t, std::span<const double> y,
                                  JacobianValues& jac, int lo, int hi) const {
    (void)lo, (void)hi;
    add_jacobian(t, y, jac);
  }
};

}  // namespace panoptic
