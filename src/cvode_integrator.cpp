#include "src/cvode_integrator.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <sstream>

#include "src/error.hpp"

namespace panoptic {
namespace {

N_Vector nv(void* p) { return static_cast<N_Vector>(p); }

std::span<const double> as_span(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))};
}
std::span<double> as_mut_span(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))};
}

// No C++ exception may cross these C callbacks: the model's *_nothrow methods return
// 0 / 1 (recoverable: CVODE retries with a smaller step) / -1 (fatal).
extern "C" int rhs_callback(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
  return static_cast<DiskModel*>(data)->rhs_nothrow(t, as_span(y), as_mut_span(ydot));
}

extern "C" int jac_callback(sunrealtype t, N_Vector y, N_Vector, SUNMatrix J, void* data,
                            N_Vector, N_Vector, N_Vector) {
  auto& model = *static_cast<DiskModel*>(data);
  // CVODE zeroed J including its index arrays: copy the cached pattern every call.
  model.pattern().copy_structure_to(SUNSparseMatrix_IndexPointers(J),
                                    SUNSparseMatrix_IndexValues(J));
  const auto nnz = static_cast<std::size_t>(model.pattern().nnz());
  return model.jacobian_nothrow(t, as_span(y), {SUNSparseMatrix_Data(J), nnz});
}

std::string flag_name(int flag) {
  char* name = CVodeGetReturnFlagName(flag);
  std::string s = name ? name : "CV_UNKNOWN";
  std::free(name);
  return s;
}

void check(int flag, const char* call) {
  if (flag < 0)
    throw SolverError(std::string("CVODE set-up failed in ") + call + ": " +
                      flag_name(flag));
}

}  // namespace

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
  atol_ = N_VNew_Serial(n, ctx);
  std::copy(y0.begin(), y0.end(), N_VGetArrayPointer(nv(y_)));
  std::copy(opt_.atol.begin(), opt_.atol.end(), N_VGetArrayPointer(nv(atol_)));

  cvode_ = CVodeCreate(CV_BDF, ctx);
  if (cvode_ == nullptr) throw SolverError("CVodeCreate failed");
  check(CVodeSetErrHandlerFn(cvode_, cvode_error_handler, this), "CVodeSetErrHandlerFn");
  check(CVodeInit(cvode_, rhs_callback, t0, nv(y_)), "CVodeInit");
  check(CVodeSVtolerances(cvode_, opt_.rtol, nv(atol_)), "CVodeSVtolerances");
  check(CVodeSetUserData(cvode_, &model_), "CVodeSetUserData");
  if (!opt_.constraints.empty() &&
      std::any_of(opt_.constraints.begin(), opt_.constraints.end(),
                  [](double c) { return c != 0.0; })) {
    constr_ = N_VNew_Serial(n, ctx);
    std::copy(opt_.constraints.begin(), opt_.constraints.end(),
              N_VGetArrayPointer(nv(constr_)));
    check(CVodeSetConstraints(cvode_, nv(constr_)), "CVodeSetConstraints");
  }
  const auto& pattern = model.pattern();
  A_ = SUNSparseMatrix(n, n, pattern.nnz(), CSC_MAT, ctx);
  LS_ = SUNLinSol_KLU(nv(y_), static_cast<SUNMatrix>(A_), ctx);
  if (A_ == nullptr || LS_ == nullptr) throw SolverError("KLU set-up failed");
  check(CVodeSetLinearSolver(cvode_, static_cast<SUNLinearSolver>(LS_),
                             static_cast<SUNMatrix>(A_)),
        "CVodeSetLinearSolver");
  check(CVodeSetJacFn(cvode_, jac_callback), "CVodeSetJacFn");
  // Our step budget is counted across calls (advance_to); CVODE's per-call limit of 500
  // only ends a call early, it is not an error (see advance_to).
  check(CVodeSetMaxNumSteps(cvode_, 5000), "CVodeSetMaxNumSteps");
  if (opt_.max_dt > 0.0) check(CVodeSetMaxStep(cvode_, opt_.max_dt), "CVodeSetMaxStep");
}

CvodeIntegrator::~CvodeIntegrator() {
  // Reverse order of creation.
  CVodeFree(&cvode_);
  SUNLinSolFree(static_cast<SUNLinearSolver>(LS_));
  SUNMatDestroy(static_cast<SUNMatrix>(A_));
  if (constr_) N_VDestroy(nv(constr_));
  N_VDestroy(nv(atol_));
  N_VDestroy(nv(y_));
  SUNContext ctx = static_cast<SUNContext>(sunctx_);
  SUNContext_Free(&ctx);
}

std::span<const double> CvodeIntegrator::state() const { return as_span(nv(y_)); }

void CvodeIntegrator::advance_to(double t_out,
                                 const std::function<void(double, long)>& on_step) {
  if (t_out <= t_) return;
  check(CVodeSetStopTime(cvode_, t_out), "CVodeSetStopTime");
  while (t_ < t_out) {
    long nst = 0;
    CVodeGetNumSteps(cvode_, &nst);
    if (nst >= opt_.max_steps)
      fail(CV_TOO_MUCH_WORK,
           "the step budget solver.max_steps = " + std::to_string(opt_.max_steps) +
               " is used up; raise it or loosen solver.rtol");
    double t_reached = t_;
    const int flag = CVode(cvode_, t_out, nv(y_), &t_reached, CV_ONE_STEP);
    if (flag < 0) fail(flag, "");
    t_ = t_reached;
    if (on_step) on_step(t_, nst + 1);
    if (flag == CV_TSTOP_RETURN) break;
  }
  t_ = t_out;
}

void CvodeIntegrator::reinit(double t, std::span<const double> y) {
  std::copy(y.begin(), y.end(), N_VGetArrayPointer(nv(y_)));
  check(CVodeReInit(cvode_, t, nv(y_)), "CVodeReInit");
  t_ = t;
  ++nreinit_;
}

SolverStats CvodeIntegrator::stats() const {
  SolverStats s;
  CVodeGetNumSteps(cvode_, &s.nst);
  CVodeGetNumRhsEvals(cvode_, &s.nfe);
  CVodeGetNumJacEvals(cvode_, &s.nje);
  CVodeGetNumLinSolvSetups(cvode_, &s.nsetups);
  CVodeGetNumErrTestFails(cvode_, &s.netf);
  CVodeGetNumNonlinSolvIters(cvode_, &s.nni);
  CVodeGetNumNonlinSolvConvFails(cvode_, &s.nncf);
  CVodeGetLastStep(cvode_, &s.h_last);
  s.nreinit = nreinit_;
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
  // Components with the largest weighted local error estimate |ele_i| w_i.
  const auto n = static_cast<sunindextype>(layout.size());
  N_Vector ele = N_VClone(nv(y_)), w = N_VClone(nv(y_));
  if (CVodeGetEstLocalErrors(cvode_, ele) == CV_SUCCESS &&
      CVodeGetErrWeights(cvode_, w) == CV_SUCCESS) {
    const double* e = N_VGetArrayPointer(ele);
    const double* wt = N_VGetArrayPointer(w);
    const double* y = N_VGetArrayPointer(nv(y_));
    std::vector<long> idx(n);
    std::iota(idx.begin(), idx.end(), 0L);
    const auto k = std::min<std::size_t>(10, idx.size());
    std::partial_sort(idx.begin(), idx.begin() + k, idx.end(), [&](long a, long b) {
      return std::abs(e[a] * wt[a]) > std::abs(e[b] * wt[b]);
    });
    msg << "\n  largest weighted local errors:";
    for (std::size_t j = 0; j < k; ++j) {
      const long i = idx[j];
      msg << "\n    " << layout.describe(i) << ": weighted error "
          << std::abs(e[i] * wt[i]) << ", value " << y[i] << " "
          << layout.info_of(i).units;
    }
  }
  N_VDestroy(ele);
  N_VDestroy(w);
  throw SolverError(msg.str());
}

}  // namespace panoptic
