#pragma once
//! The ODE system CVODE integrates: the sum of the scene's physics modules on one state
//! layout (style guide "DiskModel : OdeSystem"). Owns the sparsity pattern, built once.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "src/physics_module.hpp"
#include "src/sparsity.hpp"
#include "src/state_layout.hpp"

namespace panoptic {

class DiskModel {
 public:
  DiskModel(std::shared_ptr<const StateLayout> layout,
            std::vector<std::unique_ptr<PhysicsModule>> modules);

  const StateLayout& layout() const { return *layout_; }
  const SparsityPattern& pattern() const { return pattern_; }
  const std::vector<std::unique_ptr<PhysicsModule>>& modules() const { return modules_; }

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

 private:
  std::shared_ptr<const StateLayout> layout_;
  std::vector<std::unique_ptr<PhysicsModule>> modules_;
  SparsityPattern pattern_;
  std::string last_error_;
};

}  // namespace panoptic
