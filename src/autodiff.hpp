#pragma once
//! Forward-mode automatic differentiation for exact local Jacobian blocks.
//! A face flux or a cell source is written once as a template on its scalar type; the RHS
//! evaluates it with double, the Jacobian with `AD`, whose derivative vector has one
//! entry per local input (the variables of the cells in the stencil). Fixed maximum size:
//! no heap allocation on the hot path.
#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

namespace panoptic {

//! Largest number of variables per cell times the widest stencil (two cells per face).
inline constexpr int kMaxLocalDerivs = 16;

using ADVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLocalDerivs, 1>;
using AD = Eigen::AutoDiffScalar<ADVector>;

//! An AD variable with value `v`, seeded as input `k` of `n` local inputs.
inline AD ad_seed(double v, int n, int k) { return AD(v, n, k); }
//! An AD constant (zero derivatives) with `n` local inputs.
inline AD ad_const(double v, int n) { return AD(v, ADVector::Zero(n)); }

inline double value_of(double x) { return x; }
inline double value_of(const AD& x) { return x.value(); }

}  // namespace panoptic
