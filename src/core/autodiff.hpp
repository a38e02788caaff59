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
inline constexpr int kMaxLocalDerivs = 12;

//! Fixed-size derivative vectors: a constant made from a double (AD(x)) then carries
//! zeros of the full size. (With dynamic sizes an AD constant has an empty derivative
//! vector, and Eigen's AutoDiff does not reconcile sizes inside expression templates:
//! mixing the two reads past the end in release builds.)
using ADVector = Eigen::Matrix<double, kMaxLocalDerivs, 1>;
using AD = Eigen::AutoDiffScalar<ADVector>;

//! The derivatives of one cell's costly local laws (the Stokes number, the growth
//! rates) by that cell's own state: Sigma_d, Q_m, Q_phi and Sigma_g, at most four
//! directions. Differentiated once per cell state with these, a third of the arithmetic
//! of AD's twelve entries, and chained onto any caller's AD seeds by ad_chain(); each
//! derivative entry is computed by the same operations either way, so the same bits.
inline constexpr int kCellDerivs = 4;
using ADCell = Eigen::AutoDiffScalar<Eigen::Matrix<double, kCellDerivs, 1>>;

//! An AD variable (AD or ADCell) with value `v`, seeded as local input `k`.
template <class A = AD>
A ad_seed(double v, int k) {
  A a(v);
  a.derivatives()[k] = 1.0;
  return a;
}

//! An AD value from a value v and its gradient grad[i] = dv/d y[slots[i]] with respect to
//! entries of a local state, chained onto the derivatives the entries of `y` carry: lets
//! a costly local law be differentiated once per cell and reused under any seeding.
template <class A>
A ad_chain(double v, const double* grad, const int* slots, int n, const A* y) {
  A out(v);
  for (int i = 0; i < n; ++i)
    if (grad[i] != 0.0) out.derivatives() += grad[i] * y[slots[i]].derivatives();
  return out;
}

inline double value_of(double x) { return x; }
inline double value_of(const AD& x) { return x.value(); }
//! Any other AutoDiff type (the unit tests use narrower derivative vectors).
template <class D>
double value_of(const Eigen::AutoDiffScalar<D>& x) {
  return x.value();
}

}  // namespace panoptic
