#pragma once
//! GMRES's solve of CVODE's Newton systems A x = b, A = I - gamma J, for solver.linear =
//! "gmres": SPGMR's iteration (SUNDIALS' sunlinsol_spgmr.c, right-preconditioned by the
//! cells' blocks, cell_block_preconditioner.hpp), keeping what the budget's correction
//! needs (preconditioned_gmres), and each solution corrected to keep the budget's
//! invariant (conservative_spgmr_solve).
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_nvector.h>

#include <vector>

namespace panoptic {

//! What preconditioned_gmres keeps besides SPGMR's own workspace: the preconditioned
//! directions z_l = P^-1 s2^-1 V_l and their products A z_l, one pair per iteration.
struct GmresDirections {
  std::vector<std::vector<double>> z, az;
};

//! SPGMR's solve (right preconditioning, zero initial guess, no restart, modified
//! Gram-Schmidt: how CVODE creates and calls it) on the SPGMR solver `s` as CVODE set
//! it up (its products A v, preconditioner, scaling vectors s1 = s2 = CVODE's error
//! weights and Krylov dimension), with SUNDIALS' own Gram-Schmidt and QR steps. It keeps
//! each direction z_l and its product A z_l (`d`), so that x = sum_l y_l z_l and the
//! residual r = b - sum_l y_l A z_l come without SPGMR's last preconditioner solve (its
//! P^-1 of V y) or the product A x that the correction would otherwise need. Returns
//! SPGMR's flag (SUNLS_SUCCESS, SUNLS_RES_REDUCED, SUNLS_CONV_FAIL or a failed solve or
//! product) and sets its counters (iterations, residual norm, last flag) as SPGMR does;
//! on success or reduced residual, x and r.
int preconditioned_gmres(SUNLinearSolver s, N_Vector x, N_Vector b, double tol,
                         GmresDirections& d, std::vector<double>& r);

//! The solve of CVODE's SPGMR for the integrator (CvodeIntegrator, cvode_integrator.hpp,
//! whose callback data it reads through CVODE's memory, SPGMR's preconditioner data):
//! preconditioned_gmres, each solution then corrected to keep the budget
//! (CvodeCallbackData::invariant; none where it is empty).
extern "C" int conservative_spgmr_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x,
                                        N_Vector b, double tol);

}  // namespace panoptic
