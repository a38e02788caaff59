#pragma once
//! Test helper: CVODE BDF with a dense Jacobian for small systems (one cell of the
//! coagulation engine), outside the DiskModel machinery of src/solver/cvode_integrator:
//! the right-hand side and the analytic Jacobian (row-major, as the engine writes it)
//! as std::functions.
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace panoptic::testing {

struct DenseOde {
  std::function<void(double, std::span<const double>, std::span<double>)> rhs;
  //! Row-major n x n Jacobian.
  std::function<void(double, std::span<const double>, std::span<double>)> jacobian;
};

struct DenseOdeResult {
  long steps = 0;
  long rhs_calls = 0;
  long jacobian_calls = 0;
};

namespace detail {
struct DenseOdeData {
  const DenseOde* ode = nullptr;
  std::vector<double> row_major;
};
inline int dense_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
  auto* d = static_cast<DenseOdeData*>(data);
  const auto n = static_cast<std::size_t>(N_VGetLength_Serial(y));
  d->ode->rhs(t, {N_VGetArrayPointer(y), n}, {N_VGetArrayPointer(ydot), n});
  return 0;
}
inline int dense_jac(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jac, void* data,
                     N_Vector, N_Vector, N_Vector) {
  auto* d = static_cast<DenseOdeData*>(data);
  const auto n = static_cast<std::size_t>(N_VGetLength_Serial(y));
  d->row_major.resize(n * n);
  d->ode->jacobian(t, {N_VGetArrayPointer(y), n}, d->row_major);
  for (std::size_t c = 0; c < n; ++c) {
    sunrealtype* col = SUNDenseMatrix_Column(jac, static_cast<sunindextype>(c));
    for (std::size_t r = 0; r < n; ++r) col[r] = d->row_major[r * n + c];
  }
  return 0;
}
}  // namespace detail

//! Integrates y from t0 to t1 in place (CVODE BDF, dense direct solve, scalar
//! tolerances).
inline DenseOdeResult integrate_dense(const DenseOde& ode, double t0, double t1,
                                      std::vector<double>& y, double rtol, double atol,
                                      long max_steps = 100000) {
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0)
    throw std::runtime_error("SUNContext_Create");
  const auto n = static_cast<sunindextype>(y.size());
  N_Vector v = N_VNew_Serial(n, ctx);
  std::copy(y.begin(), y.end(), N_VGetArrayPointer(v));
  SUNMatrix a = SUNDenseMatrix(n, n, ctx);
  SUNLinearSolver ls = SUNLinSol_Dense(v, a, ctx);
  void* mem = CVodeCreate(CV_BDF, ctx);
  detail::DenseOdeData data{&ode, {}};
  int flag = CVodeInit(mem, detail::dense_rhs, t0, v);
  flag |= CVodeSStolerances(mem, rtol, atol);
  flag |= CVodeSetUserData(mem, &data);
  flag |= CVodeSetLinearSolver(mem, ls, a);
  flag |= CVodeSetJacFn(mem, detail::dense_jac);
  flag |= CVodeSetMaxNumSteps(mem, max_steps);
  flag |= CVodeSetStopTime(mem, t1);
  double t = t0;
  if (flag == 0) flag = CVode(mem, t1, v, &t, CV_NORMAL);
  DenseOdeResult res;
  CVodeGetNumSteps(mem, &res.steps);
  CVodeGetNumRhsEvals(mem, &res.rhs_calls);
  CVodeGetNumJacEvals(mem, &res.jacobian_calls);
  std::copy(N_VGetArrayPointer(v), N_VGetArrayPointer(v) + n, y.begin());
  CVodeFree(&mem);
  SUNLinSolFree(ls);
  SUNMatDestroy(a);
  N_VDestroy(v);
  SUNContext_Free(&ctx);
  if (flag < 0) throw std::runtime_error("CVODE failed: " + std::to_string(flag));
  return res;
}

}  // namespace panoptic::testing
