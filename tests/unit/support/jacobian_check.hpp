#pragma once
//! The assembled Jacobian of a Simulation against a dense central finite-difference
//! Jacobian of its right-hand side (tests/unit/solver/test_jacobian.cpp and the modules'
//! own Jacobian tests).
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "src/model/simulation.hpp"
#include "src/solver/disk_model.hpp"

namespace panoptic::testing {

struct JacobianCheck {
  double max_rel_err = 0.0;  //!< max |J - J_fd| / (row scale of J_fd)
  //! max |J_ij - FD_ij| / |FD_ij| over the entries that carry at least kSignificant of
  //! their row's largest |FD_ik y_k|: the row-scaled error above lets an entry far below
  //! its row's largest be wrong by 100 %; this one does not, down to kSignificant (below
  //! it the central difference's round-off, ~1e-10 of the row, is too large a share)
  double max_entry_err = 0.0;
  long entry_row = -1, entry_col = -1;
  long outside_pattern = 0;  //!< FD non-zeros not in the pattern
  long nnz_fd = 0;
  long worst_row = -1, worst_col = -1;  //!< where max_rel_err was found
  double worst_analytic = 0.0, worst_fd = 0.0;
};

//! Perturbs the initial state by up to +-30 % per component (seeded), so that the check
//! does not depend on the smooth initial profile.
inline std::vector<double> perturbed_state(const Simulation& sim, unsigned seed) {
  auto y = sim.initial_state();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.7, 1.3);
  for (auto& v : y) v = (v == 0.0 ? 1e-3 : v) * u(rng);
  return y;
}

inline constexpr double kSignificant = 1e-5;

inline JacobianCheck compare_with_fd(Simulation& sim, const std::vector<double>& y0) {
  const auto& model = sim.model();
  const auto& pattern = model.pattern();
  const long n = static_cast<long>(y0.size());
  std::vector<double> values(pattern.nnz());
  model.jacobian(0.0, y0, values);

  // Dense FD Jacobian, column by column (central differences).
  std::vector<double> fd(n * n), fp(n), fm(n), y = y0;
  for (long j = 0; j < n; ++j) {
    const double h = 1e-6 * std::max(std::abs(y0[j]), 1e-30);
    y[j] = y0[j] + h;
    model.rhs(0.0, y, fp);
    y[j] = y0[j] - h;
    model.rhs(0.0, y, fm);
    y[j] = y0[j];
    for (long i = 0; i < n; ++i) fd[i * n + j] = (fp[i] - fm[i]) / (2.0 * h);
  }
  JacobianCheck out;
  for (long i = 0; i < n; ++i) {
    double row_scale = 0.0;
    for (long j = 0; j < n; ++j)
      row_scale = std::max(row_scale, std::abs(fd[i * n + j] * y0[j]));
    for (long j = 0; j < n; ++j) {
      const double d = fd[i * n + j];
      const long p = pattern.position(i, j);
      const double a = p >= 0 ? values[p] : 0.0;
      // Compare in units of the row's largest |J_ij y_j|: scale-free across variables.
      const double err = std::abs(a - d) * std::abs(y0[j]) / std::max(row_scale, 1e-300);
      if (err > out.max_rel_err) {
        out.max_rel_err = err;
        out.worst_row = i;
        out.worst_col = j;
        out.worst_analytic = a;
        out.worst_fd = d;
      }
      if (std::abs(d * y0[j]) >= kSignificant * row_scale &&
          std::abs(a - d) > out.max_entry_err * std::abs(d)) {
        out.max_entry_err = std::abs(a - d) / std::abs(d);
        out.entry_row = i;
        out.entry_col = j;
      }
      if (std::abs(d * y0[j]) > 1e-12 * row_scale) {
        ++out.nnz_fd;
        if (p < 0) ++out.outside_pattern;
      }
    }
  }
  return out;
}

}  // namespace panoptic::testing
