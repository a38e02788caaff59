#pragma once
//! BlockBandedLU as a SUNLinearSolver for CVODE's matrix-based interface (type DIRECT,
//! id CUSTOM): CVODE hands it the Newton matrix I - gamma J that the integrator's
//! linear-system function writes into a SUNSparseMatrix (CSC, the Jacobian pattern's
//! order). Set-up factorises it; a zero or non-finite pivot is a recoverable failure
//! (SUNLS_LUFACT_FAIL: CVODE retries with a fresh Jacobian or a smaller step), as is a
//! solution that is not finite (SUNLS_PACKAGE_FAIL_REC).
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include "src/solver/block_banded_lu.hpp"

namespace panoptic {

//! A SUNLinearSolver over `lu`, which it does not own (it must outlive the solver);
//! freed by SUNLinSolFree.
SUNLinearSolver make_block_linear_solver(BlockBandedLU& lu, SUNContext ctx);
//! Its set-up and solve operations (for the integrator's timed wrappers).
int block_linear_solver_setup(SUNLinearSolver s, SUNMatrix a);
int block_linear_solver_solve(SUNLinearSolver s, SUNMatrix a, N_Vector x, N_Vector b,
                              sunrealtype tol);

}  // namespace panoptic
