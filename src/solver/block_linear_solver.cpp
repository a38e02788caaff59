#include "src/solver/block_linear_solver.hpp"

#include <sunmatrix/sunmatrix_sparse.h>

#include <span>
#include <stdexcept>

namespace panoptic {
namespace {

BlockBandedLU& lu_of(SUNLinearSolver s) {
  return *static_cast<BlockBandedLU*>(s->content);
}

extern "C" SUNLinearSolver_Type block_gettype(SUNLinearSolver) {
  return SUNLINEARSOLVER_DIRECT;
}
extern "C" SUNLinearSolver_ID block_getid(SUNLinearSolver) {
  return SUNLINEARSOLVER_CUSTOM;
}
extern "C" int block_setup(SUNLinearSolver s, SUNMatrix a) {
  return block_linear_solver_setup(s, a);
}
extern "C" int block_solve(SUNLinearSolver s, SUNMatrix a, N_Vector x, N_Vector b,
                           sunrealtype tol) {
  return block_linear_solver_solve(s, a, x, b, tol);
}
extern "C" int block_free(SUNLinearSolver s) {
  if (s == nullptr) return SUNLS_SUCCESS;
  s->content = nullptr;  // the BlockBandedLU belongs to the integrator
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

}  // namespace

int block_linear_solver_setup(SUNLinearSolver s, SUNMatrix a) {
  const std::span<const double> values(SUNSparseMatrix_Data(a),
                                       static_cast<std::size_t>(SUNSparseMatrix_NNZ(a)));
  return lu_of(s).factorize(values) ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
}

int block_linear_solver_solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b,
                              sunrealtype) {
  if (x != b) N_VScale(1.0, b, x);
  const std::span<double> v(N_VGetArrayPointer(x),
                            static_cast<std::size_t>(N_VGetLength(x)));
  return lu_of(s).solve(v) ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
}

SUNLinearSolver make_block_linear_solver(BlockBandedLU& lu, SUNContext ctx) {
  SUNLinearSolver s = SUNLinSolNewEmpty(ctx);
  if (s == nullptr) throw std::runtime_error("SUNLinSolNewEmpty failed");
  s->ops->gettype = block_gettype;
  s->ops->getid = block_getid;
  s->ops->setup = block_setup;
  s->ops->solve = block_solve;
  s->ops->free = block_free;
  s->content = &lu;
  return s;
}

}  // namespace panoptic
