#include "src/solver/cvode_integrator.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

#include "src/core/error.hpp"
#include "src/solver/block_linear_solver.hpp"
#include "src/solver/cell_block_preconditioner.hpp"
#include "src/solver/conservative_gmres.hpp"
#include "src/solver/serial_vector_ops.hpp"

namespace panoptic {
namespace {

N_Vector nv(void* p) { return static_cast<N_Vector>(p); }

std::span<const double> as_span(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))};
}
std::span<double> as_mut_span(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))};
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// No C++ exception may cross these C callbacks: the model's *_nothrow methods return
// 0 / 1 (recoverable: CVODE retries with a smaller step) / -1 (fatal).
extern "C" int rhs_callback(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
  auto* d = static_cast<CvodeCallbackData*>(data);
  if (d->times == nullptr) return d->model->rhs_nothrow(t, as_span(y), as_mut_span(ydot));
  const auto t0 = Clock::now();
  const int flag = d->model->rhs_nothrow(t, as_span(y), as_mut_span(ydot));
  d->times->rhs_s += seconds_since(t0);
  ++d->times->n_rhs;
  return flag;
}

// The linear solver's set-up and solve timed for CvodeIntegrator::set_profile. A
// SUNLinearSolver has no user data, so the accumulator is a file-level pointer
// (benchmarks are single-threaded).
CallbackTimes* g_ls_times = nullptr;
template <int (*Setup)(SUNLinearSolver, SUNMatrix)>
int timed_lsetup(SUNLinearSolver S, SUNMatrix A) {
  const auto t0 = Clock::now();
  const int flag = Setup(S, A);
  if (g_ls_times) {
    g_ls_times->lsetup_s += seconds_since(t0);
    ++g_ls_times->n_lsetup;
  }
  return flag;
}
template <int (*Solve)(SUNLinearSolver, SUNMatrix, N_Vector, N_Vector, sunrealtype)>
int timed_lsolve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b,
                 sunrealtype tol) {
  const auto t0 = Clock::now();
  const int flag = Solve(S, A, x, b, tol);
  if (g_ls_times) {
    g_ls_times->lsolve_s += seconds_since(t0);
    ++g_ls_times->n_lsolve;
  }
  return flag;
}

// Sets the set-up and solve of `ls` (KLU's, the block solver's or GMRES's, whose solve
// is conservative_spgmr_solve), timed or not.
void set_solver_ops(void* ls, LinearSolverKind kind, bool timed) {
  auto* ops = static_cast<SUNLinearSolver>(ls)->ops;
  if (kind == LinearSolverKind::block) {
    ops->setup =
        timed ? timed_lsetup<block_linear_solver_setup> : block_linear_solver_setup;
    ops->solve =
        timed ? timed_lsolve<block_linear_solver_solve> : block_linear_solver_solve;
  } else if (kind == LinearSolverKind::gmres) {
    ops->setup = timed ? timed_lsetup<SUNLinSolSetup_SPGMR> : SUNLinSolSetup_SPGMR;
    ops->solve =
        timed ? timed_lsolve<conservative_spgmr_solve> : conservative_spgmr_solve;
  } else {
    ops->setup = timed ? timed_lsetup<SUNLinSolSetup_KLU> : SUNLinSolSetup_KLU;
    ops->solve = timed ? timed_lsolve<SUNLinSolSolve_KLU> : SUNLinSolSolve_KLU;
  }
}

// The RHS inside the Newton iteration: the same, keeping the iterate, so that a
// convergence failure can name the components that did not converge.
extern "C" int nls_rhs_callback(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
  N_VScale(1.0, y,
           static_cast<N_Vector>(static_cast<CvodeCallbackData*>(data)->newton_iterate));
  return rhs_callback(t, y, ydot, data);
}

// The Newton matrix A = I - gamma J (CVODE's linear-system function). J is evaluated
// when CVODE asks for a fresh one (jok false) and kept in callback data for the steps
// that reuse it; A's values are then written by newton_matrix (sparsity.hpp) over the
// pattern, whose structure A holds from its creation. CVODE's own version of this
// (cvLsLinSys) zeroes A with its index arrays, copies J to a saved matrix or back, and
// adds the identity by a search for each diagonal: three passes more, 5 % of the
// fiducial run (perf). Same arithmetic (A_ij = c J_ij, A_jj = 1 + c J_jj, c = -gamma),
// so the same bits.
// Evaluates J into d->jacobian unless CVODE lets the last one be reused (jok).
int update_jacobian(CvodeCallbackData* d, sunrealtype t, N_Vector y, sunbooleantype jok,
                    sunbooleantype* jcur) {
  *jcur = jok ? SUNFALSE : SUNTRUE;  // before the evaluation, as cvLsLinSys
  if (jok) return 0;
  ++d->n_jacobian;
  const auto t0 = Clock::now();
  const int flag = d->model->jacobian_nothrow(t, as_span(y), d->jacobian);
  if (d->times) {
    d->times->jac_s += seconds_since(t0);
    ++d->times->n_jac;
  }
  return flag;
}

extern "C" int linsys_callback(sunrealtype t, N_Vector y, N_Vector, SUNMatrix A,
                               sunbooleantype jok, sunbooleantype* jcur,
                               sunrealtype gamma, void* data, N_Vector, N_Vector,
                               N_Vector) {
  auto* d = static_cast<CvodeCallbackData*>(data);
  const std::vector<double>& jac = d->jacobian;
  if (const int flag = update_jacobian(d, t, y, jok, jcur); flag != 0) return flag;
  newton_matrix(jac, d->diagonal, gamma,
                std::span<double>(SUNSparseMatrix_Data(A), jac.size()));
  return 0;
}

// GMRES (solver.linear = "gmres"). CVODE's iterative interface forms the products
// (I - gamma J) v from J v; these come from the Jacobian the modules assemble (the one
// KLU would factorise), evaluated in the preconditioner's set-up when CVODE asks for a
// fresh one (jok false) and reused otherwise, so that GMRES solves the Newton systems
// KLU solves, up to its tolerance, rather than those of difference quotients.
extern "C" int jtimes_callback(N_Vector v, N_Vector jv, sunrealtype, N_Vector, N_Vector,
                               void* data, N_Vector) {
  const auto* d = static_cast<CvodeCallbackData*>(data);
  d->pattern->multiply(d->jacobian, as_span(v), as_mut_span(jv));
  return 0;
}

// P = I - gamma J_cc (cell_block_preconditioner.hpp); a singular block is recoverable.
extern "C" int psetup_callback(sunrealtype t, N_Vector y, N_Vector, sunbooleantype jok,
                               sunbooleantype* jcur, sunrealtype gamma, void* data) {
  auto* d = static_cast<CvodeCallbackData*>(data);
  if (const int flag = update_jacobian(d, t, y, jok, jcur); flag != 0) return flag;
  return d->preconditioner->setup(d->jacobian, gamma) ? 0 : 1;
}

extern "C" int psolve_callback(sunrealtype, N_Vector, N_Vector, N_Vector r, N_Vector z,
                               sunrealtype, sunrealtype, int, void* data) {
  N_VScale(1.0, r, z);
  return static_cast<CvodeCallbackData*>(data)->preconditioner->solve(as_mut_span(z)) ? 0
                                                                                      : 1;
}

// The state vector's weighted RMS norm (used by every Newton iteration and error test):
// N_VWrmsNorm_Serial sums in one dependent chain of additions, which took 7 % of the
// fiducial run (perf); weighted_rms_norm lets four of them overlap.
extern "C" sunrealtype wrms_norm_callback(N_Vector x, N_Vector w) {
  return weighted_rms_norm(as_span(x), as_span(w));
}

std::string flag_name(int flag) {
  char* name = CVodeGetReturnFlagName(flag);
  std::string s = name ? name : "NONE";
  std::free(name);
  if (s == "NONE") s = "CVODE flag " + std::to_string(flag);
  if (flag == CV_CONSTR_FAIL) s = "CV_CONSTR_FAIL";
  if (flag == CV_WARNING) s = "CV_WARNING (t + h = t)";
  return s;
}

void check(int flag, const char* call) {
  if (flag < 0)
    throw SolverError(std::string("CVODE set-up failed in ") + call + ": " +
                      flag_name(flag));
}

}  // namespace

double weighted_rms_norm(std::span<const double> x, std::span<const double> w) {
  const std::size_t n = x.size();
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4)
    for (std::size_t k = 0; k < 4; ++k) {
      const double p = x[i + k] * w[i + k];
      s[k] += p * p;
    }
  for (; i < n; ++i) {
    const double p = x[i] * w[i];
    s[0] += p * p;
  }
  return std::sqrt(((s[0] + s[1]) + (s[2] + s[3])) / static_cast<double>(n));
}

void cvode_error_handler(int, const char*, const char* function, char* msg, void* data) {
  auto* self = static_cast<CvodeIntegrator*>(data);
  self->cvode_message_ = std::string(function ? function : "") + ": " + (msg ? msg : "");
}

CvodeIntegrator::CvodeIntegrator(DiskModel& model, double t0, std::span<const double> y0,
                                 IntegratorOptions options)
    : model_(model), opt_(std::move(options)), t_(t0) {
  const auto n = static_cast<sunindextype>(model.layout().size());
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0)
    throw SolverError("SUNContext_Create failed");
  sunctx_ = ctx;
  y_ = N_VNew_Serial(n, ctx);
  // CVODE clones its work vectors from y_, operations included: the element-wise ones
  // compiled with panoptic (Debian's SUNDIALS is built unoptimised;
  // serial_vector_ops.hpp) and the weighted RMS norm in four partial sums.
  install_serial_vector_ops(nv(y_));
  nv(y_)->ops->nvwrmsnorm = wrms_norm_callback;
  atol_ = N_VNew_Serial(n, ctx);
  callback_data_.model = &model_;
  callback_data_.newton_iterate = N_VNew_Serial(n, ctx);
  install_serial_vector_ops(nv(callback_data_.newton_iterate));  // its copy of y
  callback_data_.times = nullptr;
  N_VConst(0.0, nv(callback_data_.newton_iterate));
  std::copy(y0.begin(), y0.end(), N_VGetArrayPointer(nv(y_)));
  std::copy(opt_.atol.begin(), opt_.atol.end(), N_VGetArrayPointer(nv(atol_)));
  if (!opt_.constraints.empty() &&
      std::any_of(opt_.constraints.begin(), opt_.constraints.end(),
                  [](double c) { return c != 0.0; })) {
    constr_ = N_VNew_Serial(n, ctx);
    std::copy(opt_.constraints.begin(), opt_.constraints.end(),
              N_VGetArrayPointer(nv(constr_)));
  }
  clip_to_constraints();
  create_cvode(t0);
}

void CvodeIntegrator::clip_to_constraints() {
  // CVODE accepts steps whose non-negative components dip below zero by less than its
  // error weights, but a new start rejects any: clip those round-off negatives (only
  // Sigma_g is constrained; Sigma_d is not, as clipping it would create dust). Done
  // at every start, the constructor's too, so that a run restarted from a checkpoint
  // (which stores the state as integrated) starts from the same bits as the run that
  // reinitialised there.
  double* yv = N_VGetArrayPointer(nv(y_));
  for (std::size_t i = 0; i < opt_.constraints.size(); ++i)
    if (opt_.constraints[i] > 0.0 && yv[i] < 0.0) yv[i] = 0.0;
}

void CvodeIntegrator::create_cvode(double t0) {
  SUNContext ctx = static_cast<SUNContext>(sunctx_);
  const auto n = static_cast<sunindextype>(model_.layout().size());
  cvode_ = CVodeCreate(CV_BDF, ctx);
  if (cvode_ == nullptr) throw SolverError("CVodeCreate failed");
  check(CVodeSetErrHandlerFn(cvode_, cvode_error_handler, this), "CVodeSetErrHandlerFn");
  check(CVodeInit(cvode_, rhs_callback, t0, nv(y_)), "CVodeInit");
  check(CVodeSVtolerances(cvode_, opt_.rtol, nv(atol_)), "CVodeSVtolerances");
  check(CVodeSetUserData(cvode_, &callback_data_), "CVodeSetUserData");
  check(CVodeSetNlsRhsFn(cvode_, nls_rhs_callback), "CVodeSetNlsRhsFn");
  if (constr_) check(CVodeSetConstraints(cvode_, nv(constr_)), "CVodeSetConstraints");
  const auto& pattern = model_.pattern();
  callback_data_.jacobian.assign(static_cast<std::size_t>(pattern.nnz()), 0.0);
  callback_data_.n_jacobian = 0;
  if (opt_.linear == LinearSolverKind::gmres) {
    create_krylov_solver();
    return;
  }
  A_ = SUNSparseMatrix(n, n, pattern.nnz(), CSC_MAT, ctx);
  if (opt_.linear == LinearSolverKind::block) {
    if (!block_lu_) {
      const StateLayout& layout = model_.layout();
      try {
        block_lu_ = std::make_unique<BlockBandedLU>(pattern, layout.n_cells(),
                                                    layout.n_cell_vars());
      } catch (const BlockStructureRefused& e) {
        throw SolverError(
            "solver.linear = \"block\" cannot solve this scene's Newton "
            "systems: " +
            e.reason + "; use solver.linear = \"klu\"");
      }
    }
    LS_ = make_block_linear_solver(*block_lu_, ctx);
  } else {
    LS_ = SUNLinSol_KLU(nv(y_), static_cast<SUNMatrix>(A_), ctx);
  }
  if (A_ == nullptr || LS_ == nullptr) throw SolverError("linear solver set-up failed");
  if (callback_data_.times) set_solver_ops(LS_, opt_.linear, true);
  check(CVodeSetLinearSolver(cvode_, static_cast<SUNLinearSolver>(LS_),
                             static_cast<SUNMatrix>(A_)),
        "CVodeSetLinearSolver");
  // A keeps the pattern's structure; linsys_callback writes only its values
  pattern.copy_structure_to(SUNSparseMatrix_IndexPointers(static_cast<SUNMatrix>(A_)),
                            SUNSparseMatrix_IndexValues(static_cast<SUNMatrix>(A_)));
  callback_data_.diagonal = pattern.diagonal_positions();
  check(CVodeSetLinSysFn(cvode_, linsys_callback), "CVodeSetLinSysFn");
  set_step_controls();
}

void CvodeIntegrator::create_krylov_solver() {
  // Right preconditioning: SPGMR's stopping test then bounds the weighted residual of
  // the Newton system itself, ||W (b - (I - gamma J) x)|| < delta, whatever P's quality
  // (left preconditioning would bound that of P^-1 (b - A x), which for a block-Jacobi P
  // that drops the transport between cells is not the Newton system's residual).
  const StateLayout& layout = model_.layout();
  if (!preconditioner_)
    preconditioner_ = std::make_unique<CellBlockPreconditioner>(
        model_.pattern(), layout.n_cells(), layout.n_cell_vars());
  callback_data_.pattern = &model_.pattern();
  callback_data_.preconditioner = preconditioner_.get();
  LS_ = SUNLinSol_SPGMR(nv(y_), SUN_PREC_RIGHT, kKrylovDimension,
                        static_cast<SUNContext>(sunctx_));
  if (LS_ == nullptr) throw SolverError("linear solver set-up failed");
  callback_data_.invariant = opt_.invariant;
  set_solver_ops(LS_, opt_.linear, callback_data_.times != nullptr);
  check(CVodeSetLinearSolver(cvode_, static_cast<SUNLinearSolver>(LS_), nullptr),
        "CVodeSetLinearSolver");
  check(CVodeSetJacTimes(cvode_, nullptr, jtimes_callback), "CVodeSetJacTimes");
  check(CVodeSetPreconditioner(cvode_, psetup_callback, psolve_callback),
        "CVodeSetPreconditioner");
  // conservative_spgmr_solve finds the callback data through SPGMR's preconditioner
  // data, and runs SPGMR's iteration as created here (preconditioned_gmres)
  const auto* spgmr = static_cast<SUNLinearSolverContent_SPGMR>(
      static_cast<SUNLinearSolver>(LS_)->content);
  if (spgmr->PData != cvode_)
    throw SolverError("GMRES's preconditioner data is not CVODE's memory");
  if (spgmr->pretype != SUN_PREC_RIGHT || spgmr->gstype != SUN_MODIFIED_GS ||
      spgmr->max_restarts != 0)
    throw SolverError("GMRES is not SPGMR's right-preconditioned GMRES without restarts");
  set_step_controls();
}

void CvodeIntegrator::set_step_controls() {
  // Our step budget is counted across calls (advance_to); CVODE's per-call limit of 500
  // only ends a call early, it is not an error (see advance_to).
  check(CVodeSetMaxNumSteps(cvode_, 5000), "CVodeSetMaxNumSteps");
  if (opt_.max_dt > 0.0) check(CVodeSetMaxStep(cvode_, opt_.max_dt), "CVodeSetMaxStep");
  check(CVodeSetNonlinConvCoef(cvode_, opt_.newton_coef), "CVodeSetNonlinConvCoef");
  if (opt_.steps_per_jacobian > 0) {
    check(CVodeSetJacEvalFrequency(cvode_, opt_.steps_per_jacobian),
          "CVodeSetJacEvalFrequency");
    check(CVodeSetLSetupFrequency(cvode_, opt_.steps_per_jacobian),
          "CVodeSetLSetupFrequency");
  }
}

void CvodeIntegrator::free_cvode() {
  // Reverse order of creation.
  CVodeFree(&cvode_);
  SUNLinSolFree(static_cast<SUNLinearSolver>(LS_));
  if (A_) SUNMatDestroy(static_cast<SUNMatrix>(A_));
  LS_ = nullptr;
  A_ = nullptr;
}

CvodeIntegrator::~CvodeIntegrator() {
  free_cvode();
  if (constr_) N_VDestroy(nv(constr_));
  N_VDestroy(nv(atol_));
  N_VDestroy(nv(callback_data_.newton_iterate));
  N_VDestroy(nv(y_));
  SUNContext ctx = static_cast<SUNContext>(sunctx_);
  SUNContext_Free(&ctx);
}

std::span<const double> CvodeIntegrator::state() const { return as_span(nv(y_)); }

void CvodeIntegrator::derivative(std::span<double> out) const {
  // CVODE's interpolating polynomial of the last step, differentiated once at its end,
  // written straight into `out` (a vector header over its memory: no copy, no new data)
  if (static_cast<long>(out.size()) != N_VGetLength(nv(y_)))
    throw std::logic_error("CvodeIntegrator::derivative: output of the wrong length");
  N_Vector d =
      N_VMake_Serial(N_VGetLength(nv(y_)), out.data(), static_cast<SUNContext>(sunctx_));
  const int flag = CVodeGetDky(cvode_, t_, 1, d);
  N_VDestroy(d);
  if (flag != CV_SUCCESS)
    throw std::logic_error("CvodeIntegrator::derivative: CVodeGetDky failed");
}

void CvodeIntegrator::set_profile(CallbackTimes* times) {
  callback_data_.times = times;
  g_ls_times = times;
  set_solver_ops(LS_, opt_.linear, times != nullptr);
}

CvodeIntegrator::StepInfo CvodeIntegrator::step_info(int k, bool all_errors) const {
  StepInfo info;
  CVodeGetCurrentStep(cvode_, &info.h);
  CVodeGetCurrentOrder(cvode_, &info.order);
  CVodeGetLastStep(cvode_, &info.h_last);
  CVodeGetLastOrder(cvode_, &info.order_last);
  N_Vector ele = N_VClone(nv(y_)), w = N_VClone(nv(y_));
  if (CVodeGetEstLocalErrors(cvode_, ele) == CV_SUCCESS &&
      CVodeGetErrWeights(cvode_, w) == CV_SUCCESS) {
    const double* e = N_VGetArrayPointer(ele);
    const double* wt = N_VGetArrayPointer(w);
    const long n = N_VGetLength(ele);
    std::vector<std::pair<long, double>> all(n);
    for (long i = 0; i < n; ++i) all[i] = {i, std::abs(e[i] * wt[i])};
    if (all_errors) {
      info.weighted_errors.resize(n);
      for (long i = 0; i < n; ++i) info.weighted_errors[i] = all[i].second;
    }
    const auto m = std::min<std::size_t>(static_cast<std::size_t>(k), all.size());
    std::partial_sort(all.begin(), all.begin() + m, all.end(),
                      [](const auto& a, const auto& b) { return a.second > b.second; });
    info.largest_errors.assign(all.begin(), all.begin() + m);
  }
  N_VDestroy(ele);
  N_VDestroy(w);
  return info;
}

void CvodeIntegrator::advance_to(double t_out,
                                 const std::function<void(double, long)>& on_step) {
  if (t_out <= t_) return;
  check(CVodeSetStopTime(cvode_, t_out), "CVodeSetStopTime");
  while (t_ < t_out) {
    long nst = 0;
    CVodeGetNumSteps(cvode_, &nst);
    nst += before_.nst;
    if (nst >= opt_.max_steps)
      fail(CV_TOO_MUCH_WORK,
           "the step budget solver.max_steps = " + std::to_string(opt_.max_steps) +
               " is used up; raise it or loosen solver.rtol");
    double t_reached = t_;
    const int flag = CVode(cvode_, t_out, nv(y_), &t_reached, CV_ONE_STEP);
    const double t_before = t_;
    t_ = t_reached;  // on a failure: the last time reached, y_ the state there
    if (flag == CV_CONSTR_FAIL)
      fail(flag,
           "every retry of the step drove a non-negative variable (Sigma_g) "
           "below zero; a tighter solver.rtol may get past it");
    if (flag < 0) fail(flag, "");
    // Steps below the round-off of t (CVODE warns "t + h = t" and goes on) do not
    // advance the solution: where the right-hand side stops being finite just ahead (a
    // singularity), every step shrinks to fit in front of it and the run would spin
    // until solver.max_steps. Stop after kMaxStalledSteps of them.
    stalled_ = t_ - t_before <= 4.0 * DBL_EPSILON * std::abs(t_) ? stalled_ + 1 : 0;
    if (stalled_ >= kMaxStalledSteps)
      fail(CV_WARNING, "t + h = t for " + std::to_string(stalled_) +
                           " steps in a row: the step size fell below the round-off of t "
                           "and the solution cannot advance (a singularity ahead, or a "
                           "state where the right-hand side is not finite)");
    if (on_step) on_step(t_, nst + 1);
    if (flag == CV_TSTOP_RETURN) break;
  }
  t_ = t_out;
}

void CvodeIntegrator::reinit(double t, std::span<const double> y) {
  before_ = stats();
  krylov_before_ = krylov_stats();
  ++before_.nreinit;
  std::copy(y.begin(), y.end(), N_VGetArrayPointer(nv(y_)));
  clip_to_constraints();
  // A new CVODE and linear solver rather than CVodeReInit: a restart from a checkpoint
  // builds new ones, and only the same construction guarantees the same bits whatever
  // state CVodeReInit may keep (KLU's pivot order, step-size limits). The cost is a few
  // allocations and one KLU analysis per snapshot.
  free_cvode();
  create_cvode(t);
  t_ = t;
  stalled_ = 0;
}

void CvodeIntegrator::carry_stats(const SolverStats& before) {
  for (const SolverCounter& c : kSolverCounters) before_.*c.value += before.*c.value;
  if (before_.h_last == 0.0) before_.h_last = before.h_last;
}

SolverStats CvodeIntegrator::cvode_counters() const {
  SolverStats s;
  CVodeGetNumSteps(cvode_, &s.nst);
  CVodeGetNumRhsEvals(cvode_, &s.nfe);
  CVodeGetNumJacEvals(cvode_, &s.nje);
  CVodeGetNumLinSolvSetups(cvode_, &s.nsetups);
  CVodeGetNumErrTestFails(cvode_, &s.netf);
  CVodeGetNumNonlinSolvIters(cvode_, &s.nni);
  CVodeGetNumNonlinSolvConvFails(cvode_, &s.nncf);
  CVodeGetLastStep(cvode_, &s.h_last);
  // the matrix-free interface leaves the Jacobian to the preconditioner's set-up
  if (opt_.linear == LinearSolverKind::gmres) s.nje = callback_data_.n_jacobian;
  return s;
}

KrylovStats CvodeIntegrator::krylov_stats() const {
  KrylovStats s = krylov_before_;
  if (opt_.linear != LinearSolverKind::gmres) return s;
  long v = 0;
  CVodeGetNumLinIters(cvode_, &v);
  s.nli += v;
  CVodeGetNumPrecSolves(cvode_, &v);
  s.nps += v;
  CVodeGetNumLinConvFails(cvode_, &v);
  s.nlcf += v;
  return s;
}

SolverStats CvodeIntegrator::stats() const {
  SolverStats s = cvode_counters();  // nreinit 0: CVODE does not count ours
  for (const SolverCounter& c : kSolverCounters) s.*c.value += before_.*c.value;
  // Right after a reinit CVODE reports no last step: keep the one before.
  if (s.h_last == 0.0) s.h_last = before_.h_last;
  return s;
}

void CvodeIntegrator::fail(int flag, const std::string& what) {
  const auto& layout = model_.layout();
  std::ostringstream msg;
  msg << "CVODE failed with " << flag_name(flag) << " at t = " << t_ << " s ("
      << t_ / 3.156e7 << " yr)";
  if (!what.empty()) msg << ": " << what;
  if (!cvode_message_.empty()) msg << "\n  CVODE says: " << cvode_message_;
  if (!model_.last_error().empty()) msg << "\n  model says: " << model_.last_error();
  // The components that failed, each with the physical state of its cell at the last
  // time reached (DiskModel::describe), ranked by a weighted score s_i w_i (w: CVODE's
  // error weights). After a convergence failure s_i = |y_iter - y|: how far the last
  // Newton iterate of the failed step moved from y. Otherwise s_i is CVODE's local
  // error estimate (tq[2] times its correction; after an error-test failure: that of
  // the failed attempt).
  const auto n = static_cast<sunindextype>(layout.size());
  N_Vector ele = N_VClone(nv(y_)), w = N_VClone(nv(y_));
  if (CVodeGetEstLocalErrors(cvode_, ele) == CV_SUCCESS &&
      CVodeGetErrWeights(cvode_, w) == CV_SUCCESS) {
    const double* wt = N_VGetArrayPointer(w);
    const double* y = N_VGetArrayPointer(nv(y_));
    const double* iter = N_VGetArrayPointer(nv(callback_data_.newton_iterate));
    const bool newton = flag == CV_CONV_FAILURE;
    if (newton) N_VLinearSum(1.0, nv(callback_data_.newton_iterate), -1.0, nv(y_), ele);
    const double* e = N_VGetArrayPointer(ele);
    std::vector<long> idx(n);
    std::iota(idx.begin(), idx.end(), 0L);
    const auto k = std::min<std::size_t>(10, idx.size());
    const auto score = [&](long i) {
      const double x = std::abs(e[i] * wt[i]);
      return std::isnan(x) ? HUGE_VAL : x;  // non-finite iterates first
    };
    std::partial_sort(idx.begin(), idx.begin() + k, idx.end(),
                      [&](long a, long b) { return score(a) > score(b); });
    msg << (newton ? "\n  Newton iterate of the failed step, largest weighted distances "
                     "from the state:"
                   : "\n  largest weighted local errors:");
    for (std::size_t j = 0; j < k; ++j) {
      const long i = idx[j];
      msg << "\n    " << model_.describe(i, {y, static_cast<std::size_t>(n)}) << ": "
          << (newton ? "weighted distance " : "weighted error ")
          << std::abs(e[i] * wt[i]);
      if (newton) msg << ", iterate " << iter[i];
      msg << ", value " << y[i] << " " << layout.info_of(i).units;
    }
  }
  N_VDestroy(ele);
  N_VDestroy(w);
  throw SolverError(msg.str());
}

}  // namespace panoptic
