#pragma once
//! The whole-grid terms of a module whose terms are local to a cell or to a face:
//! add_rhs() and add_jacobian() are its range form on every cell. Derived provides, as
//! plain members,
//!   add_rhs_cells(t, y, ydot, lo, hi): add_rhs() on the rows of cells [lo, hi) and of
//!     the globals fed through the faces lo..hi; rows of the neighbouring cells may be
//!     written too;
//!   add_jacobian_cells(t, y, jac, lo, hi): add_jacobian() on the same rows.
//! A run uses the range form on [0, n); block-local time stepping evaluates it on a block
//! (tests/bench/cell_range_model.hpp), so the benchmark and the run share one kernel.
#include <span>

#include "src/solver/physics_module.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

template <class Derived>
class CellRangeForm : public PhysicsModule {
 public:
  void add_rhs(double t, std::span<const double> y, std::span<double> ydot) const final {
    derived().add_rhs_cells(t, y, ydot, 0, layout_.n_cells());
  }
  void add_jacobian(double t, std::span<const double> y,
                    JacobianValues& jac) const final {
    derived().add_jacobian_cells(t, y, jac, 0, layout_.n_cells());
  }

 protected:
  explicit CellRangeForm(const StateLayout& layout) : layout_(layout) {}

  //! The model's state layout, where the module finds its variables and the cells.
  const StateLayout& layout_;

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }
};

}  // namespace panoptic
