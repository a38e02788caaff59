#include "src/solver/disk_model.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>

namespace panoptic {
namespace {

SparsityPattern build_pattern(
    const StateLayout& layout,
    const std::vector<std::unique_ptr<PhysicsModule>>& modules) {
  PatternBuilder builder(layout.size());
  for (const auto& m : modules) m->declare_pattern(builder);
  return SparsityPattern(std::move(builder));
}

//! Index of the first non-finite entry, or -1.
long first_non_finite(std::span<const double> v) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) return static_cast<long>(i);
  return -1;
}

//! What a CVODE callback returns for `evaluate` (DiskModel::rhs_nothrow): 0 when it
//! returns "", 1 (recoverable) when it returns the message of a non-finite result, -1
//! (unrecoverable) when it throws; the message goes to `last_error`, an exception's
//! prefixed with `what`.
template <class Evaluate>
int callback_status(const char* what, std::string& last_error,
                    Evaluate&& evaluate) noexcept {
  try {
    std::string non_finite = evaluate();
    if (non_finite.empty()) return 0;
    last_error = std::move(non_finite);
    return 1;
  } catch (const std::exception& e) {
    last_error = std::string(what) + ": " + e.what();
  } catch (...) {
    last_error = std::string(what) + ": unknown exception";
  }
  return -1;
}

}  // namespace

DiskModel::DiskModel(std::shared_ptr<const StateLayout> layout,
                     std::vector<std::unique_ptr<PhysicsModule>> modules)
    : layout_(std::move(layout)),
      modules_(std::move(modules)),
      pattern_(build_pattern(*layout_, modules_)) {}

void DiskModel::rhs(double t, std::span<const double> y, std::span<double> ydot) const {
  std::fill(ydot.begin(), ydot.end(), 0.0);
  for (const auto& m : modules_)
    if (!active_ || active_(m->name())) m->add_rhs(t, y, ydot);
}

void DiskModel::jacobian(double t, std::span<const double> y,
                         std::span<double> values) const {
  std::fill(values.begin(), values.end(), 0.0);
  JacobianValues jac(pattern_, values);
  for (const auto& m : modules_) {
    if (active_ && !active_(m->name())) continue;
    try {
      m->add_jacobian(t, y, jac);
    } catch (const PatternMiss& e) {
      throw std::logic_error("module " + std::string(m->name()) +
                             " wrote the Jacobian entry d(" + layout_->describe(e.row) +
                             ")/d(" + layout_->describe(e.col) +
                             "), which its declare_pattern did not declare: add it there "
                             "(physics/README.md, Adding a physical process)");
    }
  }
}

std::string DiskModel::describe(long index, std::span<const double> y) const noexcept {
  try {
    std::string s = layout_->describe(index);
    if (describer_) {
      const std::string state = describer_(index, y);
      if (!state.empty()) s += " (" + state + ")";
    }
    return s;
  } catch (...) {
    return "component " + std::to_string(index);
  }
}

int DiskModel::rhs_nothrow(double t, std::span<const double> y,
                           std::span<double> ydot) noexcept {
  return callback_status("right-hand side", last_error_, [&]() -> std::string {
    rhs(t, y, ydot);
    if (const long i = first_non_finite(ydot); i >= 0)
      return "non-finite right-hand side for " + describe(i, y);
    return "";
  });
}

int DiskModel::jacobian_nothrow(double t, std::span<const double> y,
                                std::span<double> values) noexcept {
  return callback_status("Jacobian", last_error_, [&]() -> std::string {
    jacobian(t, y, values);
    const long k = first_non_finite(values);
    if (k < 0) return "";
    // the row of value k: the column is the one whose range holds k
    const auto cols = pattern_.col_ptr();
    const long col =
        static_cast<long>(std::upper_bound(cols.begin(), cols.end(), k) - cols.begin()) -
        1;
    return "non-finite Jacobian entry d(" +
           describe(static_cast<long>(pattern_.row_index()[k]), y) + ")/d(" +
           layout_->describe(col) + ")";
  });
}

}  // namespace panoptic
