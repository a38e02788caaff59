#pragma once
//! The ODE system CVODE integrates: the sum of the scene's physics modules on one state
//! layout (style guide "DiskModel : OdeSystem"). Owns the sparsity pattern, built once.
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "src/solver/physics_module.hpp"
#include "src/solver/sparsity.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

class DiskModel {
 public:
  DiskModel(std::shared_ptr<const StateLayout> layout,
            std::vector<std::unique_ptr<PhysicsModule>> modules);

  const StateLayout& layout() const { return *layout_; }
  const SparsityPattern& pattern() const { return pattern_; }
  const std::vector<std::unique_ptr<PhysicsModule>>& modules() const { return modules_; }

  //! Sum only the modules whose name() passes `active` (null: all, the default) in rhs()
  //! and jacobian(); the pattern stays that of all modules. For operator-splitting
  //! studies (tests/bench/bench_split.cpp), which integrate the processes apart.
  void set_active(std::function<bool(std::string_view)> active) {
    active_ = std::move(active);
  }

  //! ydot = F(t, y). Throws on programming errors.
  void rhs(double t, std::span<const double> y, std::span<double> ydot) const;
  //! values (in pattern order) = dF/dy.
  void jacobian(double t, std::span<const double> y, std::span<double> values) const;

  //! For the CVODE callbacks: 0 = ok, 1 = recoverable (non-finite result: CVODE retries
  //! with a smaller step), -1 = unrecoverable (message kept in last_error()).
  int rhs_nothrow(double t, std::span<const double> y, std::span<double> ydot) noexcept;
  int jacobian_nothrow(double t, std::span<const double> y,
                       std::span<double> values) noexcept;
  const std::string& last_error() const { return last_error_; }

  //! The physical state of the cell of component `index` at state y, for failure
  //! messages ("r = 3.1 au, Sigma_d = ..., m = ..., phi = ..., St = ..."; empty for a
  //! global variable). Set by the Simulation, which knows the grid and the particles.
  using Describer = std::function<std::string(long index, std::span<const double> y)>;
  void set_describer(Describer describer) { describer_ = std::move(describer); }
  //! "q_m in cell 17 (r = 3.1 au, Sigma_d = ...)": the layout's name of component
  //! `index` and, with a describer, the physical state there. Never throws.
  std::string describe(long index, std::span<const double> y) const noexcept;

 private:
  std::shared_ptr<const StateLayout> layout_;
  std::vector<std::unique_ptr<PhysicsModule>> modules_;
  SparsityPattern pattern_;
  std::string last_error_;
  Describer describer_;
  std::function<bool(std::string_view)> active_;
};

}  // namespace panoptic
