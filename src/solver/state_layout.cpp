#include "src/solver/state_layout.hpp"

#include <stdexcept>

#include "src/core/autodiff.hpp"

namespace panoptic {

namespace {
// A variable out of CVODE's error test has no error weight, so a >= 0 constraint on it
// would be enforced by clipping at any size, losing mass from the budget (VarInfo).
void check_constraint(const VarInfo& info) {
  if (!info.error_test && info.nonnegative)
    throw std::logic_error("StateLayout: " + info.name +
                           " is out of the error test and must not be nonnegative");
}
}  // namespace

int StateLayout::add_cell_var(VarInfo info) {
  if (frozen_) throw std::logic_error("StateLayout: variable added after freeze()");
  check_constraint(info);
  if (!wide_cells_ && 2 * (n_cell_vars() + 1) > kMaxLocalDerivs)
    throw std::logic_error("StateLayout: raise kMaxLocalDerivs in src/core/autodiff.hpp");
  cell_vars_.push_back(std::move(info));
  return n_cell_vars() - 1;
}

int StateLayout::add_global_var(VarInfo info) {
  if (frozen_) throw std::logic_error("StateLayout: variable added after freeze()");
  check_constraint(info);
  global_vars_.push_back(std::move(info));
  return n_global_vars() - 1;
}

std::optional<int> StateLayout::find_cell_var(const std::string& name) const {
  for (int s = 0; s < n_cell_vars(); ++s)
    if (cell_vars_[s].name == name) return s;
  return std::nullopt;
}

int StateLayout::cell_of(long i) const {
  const long n_cell_part = static_cast<long>(n_cells_) * n_cell_vars();
  return i < n_cell_part ? static_cast<int>(i / n_cell_vars()) : -1;
}

const VarInfo& StateLayout::info_of(long i) const {
  const int c = cell_of(i);
  if (c >= 0) return cell_vars_[i % n_cell_vars()];
  return global_vars_[i - static_cast<long>(n_cells_) * n_cell_vars()];
}

std::string StateLayout::describe(long i) const {
  const int c = cell_of(i);
  if (c >= 0) return info_of(i).name + " in cell " + std::to_string(c);
  return info_of(i).name + " (global)";
}

std::string StateLayout::signature() const {
  std::string s = "n_cells=" + std::to_string(n_cells_) + ";cell:";
  for (const auto& v : cell_vars_) s += v.name + ",";
  s += ";global:";
  for (const auto& v : global_vars_) s += v.name + ",";
  return s;
}

}  // namespace panoptic
