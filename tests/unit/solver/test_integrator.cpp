// CVODE + KLU on problems with known solutions: linear decay y' = -k y for k from 1e-6 to
// 1e6 s^-1 against exp(-k t), and the stiff Robertson kinetics against its reference
// values (Hairer & Wanner; SUNDIALS cvRoberts_dns example output).
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "src/core/error.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "src/solver/disk_model.hpp"
#include "tests/unit/support/robertson.hpp"

using namespace panoptic;

namespace {

//! A test module of one cell variable y, in `units`.
class OneVariableModule : public PhysicsModule {
 public:
  OneVariableModule(StateLayout& layout, std::string_view name, const char* units)
      : name_(name) {
    layout.add_cell_var({"y", units, "", 1.0, true});
  }
  std::string_view name() const override { return name_; }

 private:
  std::string_view name_;
};

//! The model of the one module M, built as M(layout, args...), on `n_cells` cells.
template <class M, class... Args>
std::unique_ptr<DiskModel> one_module_model(int n_cells, Args&&... args) {
  auto layout = std::make_shared<StateLayout>(n_cells);
  std::vector<std::unique_ptr<PhysicsModule>> mods;
  mods.push_back(std::make_unique<M>(*layout, std::forward<Args>(args)...));
  layout->freeze();
  return std::make_unique<DiskModel>(layout, std::move(mods));
}

class Decay : public OneVariableModule {
 public:
  Decay(StateLayout& layout, double k) : OneVariableModule(layout, "decay", ""), k_(k) {}
  void declare_pattern(PatternBuilder& p) const override { p.add(0, 0); }
  void add_rhs(double, std::span<const double> y, std::span<double> ydot) const override {
    ydot[0] += -k_ * y[0];
  }
  void add_jacobian(double, std::span<const double>, JacobianValues& jac) const override {
    jac.add(0, 0, -k_);
  }

 private:
  double k_;
};

//! y' = -k y as a one-variable model, and the tolerances the decay tests use.
std::unique_ptr<DiskModel> decay_model(double k) { return one_module_model<Decay>(1, k); }
IntegratorOptions decay_options() {
  IntegratorOptions opt;
  opt.rtol = 1e-10;
  opt.atol = {1e-14};
  return opt;
}
constexpr double kDecayY0[1] = {1.0};

//! The message of the SolverError that advancing `cvode` to `t` throws; "" (and a test
//! failure) when it throws none.
std::string solver_error_of(CvodeIntegrator& cvode, double t) {
  try {
    cvode.advance_to(t);
  } catch (const SolverError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a SolverError";
  return "";
}
}  // namespace

TEST(Integrator, LinearDecayOverTwelveDecades) {
  for (double k : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
    const auto model = decay_model(k);
    CvodeIntegrator cvode(*model, 0.0, kDecayY0, decay_options());
    const double t = 5.0 / k;  // e^-5
    cvode.advance_to(t);
    EXPECT_DOUBLE_EQ(cvode.time(), t);
    // measured 4.8e-11 for every k (rtol 1e-10 over 5 e-folds)
    EXPECT_NEAR(cvode.state()[0], std::exp(-5.0), 1e-9) << "k = " << k;
    EXPECT_GT(cvode.stats().nje, 0) << "the analytic Jacobian was never used";
  }
}

TEST(Integrator, DerivativeAfterEachStepIsTheSlopeOfTheSolution) {
  // y' = -k y: after every internal step the derivative of CVODE's interpolant at the
  // step's end is -k y to about the integration tolerance (relative 1e-6 here, where a
  // derivative of the wrong order or sign would be off by O(1)).
  const double k = 2.0;
  const auto model = decay_model(k);
  CvodeIntegrator cvode(*model, 0.0, kDecayY0, decay_options());
  std::vector<double> d(1);
  long checked = 0;
  cvode.advance_to(3.0, [&](double, long) {
    cvode.derivative(d);
    const double y = cvode.state()[0];
    EXPECT_NEAR(d[0] / (-k * y), 1.0, 1e-6) << "t = " << cvode.time();
    ++checked;
  });
  EXPECT_GT(checked, 10);
}

namespace {
//! Robertson's tolerances in these tests: rtol as given, atol scaled to each component
//! (y2 stays below ~4e-5).
IntegratorOptions robertson_options(double rtol) {
  IntegratorOptions opt;
  opt.rtol = rtol;
  opt.atol = {1e-12, 1e-16, 1e-12};
  return opt;
}
constexpr double kRobertsonY0[3] = {1.0, 0.0, 0.0};
}  // namespace

TEST(Integrator, StiffRobertsonWithKlu) {
  const auto model = robertson_model();
  CvodeIntegrator cvode(*model, 0.0, kRobertsonY0, robertson_options(1e-8));
  cvode.advance_to(4e10);
  // Late-time asymptotics, worked out by hand: y2 is quasi-steady, 0.04 y1 = 1e4 y2 y3
  // (y3 ~ 1), so y2 = 4e-6 y1; then d(y1 + y2)/dt = -3e7 y2^2 = -4.8e-4 y1^2 gives
  // y1 = 1/(4.8e-4 t) = 5.208e-8 at t = 4e10 (cvRoberts_dns
  // prints 5.2083e-08, 2.0833e-13).
  const auto y = cvode.state();
  const double y1 = 1.0 / (4.8e-4 * 4e10);
  // measured 6.0e-5 off for both (the asymptotic form's own error is of that order)
  EXPECT_NEAR(y[0] / y1, 1.0, 5e-4);
  EXPECT_NEAR(y[1] / (4e-6 * y1), 1.0, 5e-4);
  EXPECT_NEAR(y[0] + y[1] + y[2], 1.0, 1e-12);  // linear invariant kept by BDF
  EXPECT_LT(cvode.stats().nst, 2000);
}

TEST(Integrator, StepInfoHoldsTheErrorTestOfTheLastStep) {
  // bench_fiducial --lts rests on step_info(k, true): the weighted local errors of the
  // step just accepted, whose root mean square is CVODE's error-test norm (<= 1 for an
  // accepted step, > 0 once the step did something), with that step's size and order.
  const auto model = robertson_model();
  CvodeIntegrator cvode(*model, 0.0, kRobertsonY0, robertson_options(1e-6));
  std::vector<double> norms;
  double t_prev = 0.0;
  cvode.advance_to(4e2, [&](double t, long) {
    const auto info = cvode.step_info(2, true);
    ASSERT_EQ(info.weighted_errors.size(), 3u);
    double s2 = 0.0;
    for (double e : info.weighted_errors) s2 += e * e;
    const double norm = std::sqrt(s2 / 3.0);
    EXPECT_LE(norm, 1.0) << "t = " << t;
    EXPECT_GT(norm, 0.0) << "t = " << t;
    EXPECT_NEAR(info.h_last, t - t_prev, 1e-12 * t) << "t = " << t;
    EXPECT_GE(info.order_last, 1);
    EXPECT_LE(info.order_last, 5);
    EXPECT_EQ(info.largest_errors.size(), 2u);
    EXPECT_EQ(
        info.largest_errors[0].second,
        *std::max_element(info.weighted_errors.begin(), info.weighted_errors.end()));
    t_prev = t;
    norms.push_back(norm);
  });
  ASSERT_GT(norms.size(), 20u);
  // CVODE sizes its steps to bring this norm near 1/6 (its BIAS2), not near the ~1e-6
  // an unweighted error would have here.
  std::sort(norms.begin(), norms.end());
  EXPECT_GT(norms[norms.size() / 2], 0.01);
}

//! The Robertson problem at rtol 1e-6 to t = 4e5 with the options `set` changes: the
//! solver's counts and y1 at the end.
template <class Set>
std::pair<SolverStats, double> robertson_run(Set set) {
  const auto model = robertson_model();
  IntegratorOptions opt = robertson_options(1e-6);
  set(opt);
  CvodeIntegrator cvode(*model, 0.0, kRobertsonY0, opt);
  cvode.advance_to(4e5);
  return {cvode.stats(), cvode.state()[0]};
}

TEST(Integrator, NewtonCoefficientReachesCvode) {
  // solver.newton_coef is CVODE's nonlinear convergence coefficient: a much tighter one
  // must take more Newton iterations per step on the nonlinear Robertson problem and
  // give the same answer (both are well inside the tolerance of the other).
  const auto its_per_step = [](const SolverStats& s) {
    return static_cast<double>(s.nni) / static_cast<double>(s.nst);
  };
  const auto [loose, loose_y1] =
      robertson_run([](IntegratorOptions& o) { o.newton_coef = 1.0; });
  const auto [tight, tight_y1] =
      robertson_run([](IntegratorOptions& o) { o.newton_coef = 1e-4; });
  EXPECT_GT(its_per_step(tight), 1.2 * its_per_step(loose));
  EXPECT_NEAR(tight_y1 / loose_y1, 1.0, 1e-4);
}

TEST(Integrator, StepsPerJacobianReachesCvode) {
  // solver.steps_per_jacobian = k: a Newton-matrix set-up at least every k steps, with a
  // fresh Jacobian at the first set-up k or more steps after the last one (so a
  // Jacobian serves k to 2k - 1 steps; set-ups for a changed step size come between).
  // At 1 every step starts from a fresh one; CVODE's own (0) lets one serve ~50 steps.
  // All give the same answer within the tolerance.
  const auto every = [](long k) {
    return robertson_run([k](IntegratorOptions& o) { o.steps_per_jacobian = k; });
  };
  const auto [fresh, fresh_y1] = every(1);
  const auto [every5, every5_y1] = every(5);
  const auto [own, own_y1] = every(0);
  EXPECT_GE(fresh.nje, fresh.nst);  // at least one per step (more after failures)
  EXPECT_GE(every5.nje, every5.nst / 9);
  EXPECT_LT(every5.nje, every5.nst / 2);
  EXPECT_LT(own.nje, own.nst / 10);
  EXPECT_NEAR(fresh_y1 / own_y1, 1.0, 1e-4);
  EXPECT_NEAR(every5_y1 / own_y1, 1.0, 1e-4);
}

TEST(Integrator, StepBudgetGivesSolverError) {
  const auto model_of_decay = decay_model(1.0);
  DiskModel& model = *model_of_decay;
  IntegratorOptions opt;
  opt.atol = {1e-14};
  opt.max_steps = 5;
  const double y0[1] = {1.0};
  CvodeIntegrator cvode(model, 0.0, y0, opt);
  const std::string msg = solver_error_of(cvode, 100.0);
  EXPECT_NE(msg.find("CV_TOO_MUCH_WORK"), std::string::npos) << msg;
  EXPECT_NE(msg.find("solver.max_steps"), std::string::npos) << msg;
  EXPECT_NE(msg.find("y in cell 0"), std::string::npos) << msg;
}

namespace {

//! y' = -y until t = 1, a non-finite right-hand side after: CVODE shrinks its steps to
//! fit in front of t = 1 and would never get past it.
class NonFiniteAfterOne : public OneVariableModule {
 public:
  explicit NonFiniteAfterOne(StateLayout& layout)
      : OneVariableModule(layout, "non_finite_after_one", "g") {}
  void declare_pattern(PatternBuilder& p) const override { p.add(0, 0); }
  void add_rhs(double t, std::span<const double> y,
               std::span<double> ydot) const override {
    ydot[0] += t < 1.0 ? -y[0] : std::nan("");
  }
  void add_jacobian(double, std::span<const double>, JacobianValues& jac) const override {
    jac.add(0, 0, -1.0);
  }
};

}  // namespace

TEST(Integrator, StalledStepsStopWithTheStateOfTheFailingCell) {
  const auto stalling = one_module_model<NonFiniteAfterOne>(1);
  DiskModel& model = *stalling;
  model.set_describer([](long i, std::span<const double> y) {
    return "physical state y = " + std::to_string(y[i]);
  });
  IntegratorOptions opt;
  opt.atol = {1e-10};
  const double y0[1] = {1.0};
  CvodeIntegrator cvode(model, 0.0, y0, opt);
  const std::string msg = solver_error_of(cvode, 2.0);
  EXPECT_NE(msg.find("CV_WARNING (t + h = t)"), std::string::npos) << msg;
  // the model's message and the error list name the cell, the variable and its state
  EXPECT_NE(msg.find("non-finite right-hand side for y in cell 0 (physical state y = "),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("y in cell 0 (physical state y = 0.3678"), std::string::npos) << msg;
  EXPECT_NEAR(cvode.time(), 1.0, 1e-12);
  EXPECT_LT(cvode.stats().nst, 2000) << "stopped long before solver.max_steps";
}

// The state vector's norm (weighted_rms_norm, four partial sums) against N_VWrmsNorm of
// SUNDIALS' serial vector and a long-double sum, for lengths that are and are not
// multiples of four.
TEST(Integrator, WeightedRmsNormMatchesSundials) {
  SUNContext ctx = nullptr;
  ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
  for (int n : {1, 2, 3, 4, 5, 7, 8, 13, 1050, 1051}) {
    std::vector<double> x(n), w(n);
    long double sum = 0.0L;
    for (int i = 0; i < n; ++i) {
      x[i] = std::sin(1.3 * i + 0.2) * std::pow(10.0, (i % 7) - 3);
      w[i] = 1.0 / (1e-5 * std::abs(std::cos(0.7 * i)) + 1e-12 * (i % 3 + 1));
      sum += static_cast<long double>(x[i] * w[i]) * (x[i] * w[i]);
    }
    const double expect = static_cast<double>(std::sqrt(sum / n));
    const double got = weighted_rms_norm(x, w);
    EXPECT_NEAR(got, expect, 1e-15 * expect) << "n " << n;
    N_Vector xv = N_VMake_Serial(n, x.data(), ctx), wv = N_VMake_Serial(n, w.data(), ctx);
    EXPECT_NEAR(got, N_VWrmsNorm(xv, wv), 1e-15 * expect) << "n " << n;
    N_VDestroy(xv);
    N_VDestroy(wv);
  }
  SUNContext_Free(&ctx);
}

namespace {

//! Two cells of y; its Jacobian writes d(y of cell 1)/d(y of cell 0), which its pattern
//! does not declare (the mistake a new module makes).
class UndeclaredCoupling : public OneVariableModule {
 public:
  explicit UndeclaredCoupling(StateLayout& layout)
      : OneVariableModule(layout, "undeclared_coupling", "g") {}
  void declare_pattern(PatternBuilder& p) const override {
    p.add(0, 0);
    p.add(1, 1);
  }
  void add_rhs(double, std::span<const double> y, std::span<double> ydot) const override {
    ydot[0] -= y[0];
    ydot[1] += y[0] - y[1];
  }
  void add_jacobian(double, std::span<const double>, JacobianValues& jac) const override {
    jac.add(0, 0, -1.0);
    jac.add(1, 1, -1.0);
    jac.add(1, 0, 1.0);  // not declared
  }
};

}  // namespace

TEST(DiskModel, AnUndeclaredJacobianEntryNamesTheModuleAndTheVariables) {
  const auto coupled = one_module_model<UndeclaredCoupling>(2);
  const DiskModel& model = *coupled;
  const StateLayout* layout = &model.layout();
  const double y[2] = {1.0, 0.5};
  std::vector<double> values(model.pattern().nnz());
  try {
    model.jacobian(0.0, y, values);
    FAIL() << "expected a logic_error";
  } catch (const std::logic_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("module undeclared_coupling wrote the Jacobian entry d("),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find(layout->describe(1)), std::string::npos) << msg;
    EXPECT_NE(msg.find(layout->describe(0)), std::string::npos) << msg;
    EXPECT_NE(msg.find("declare_pattern"), std::string::npos) << msg;
  }
}
