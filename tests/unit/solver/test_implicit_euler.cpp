// ImplicitEulerIntegrator (solver.method = "implicit_euler", DustPy's step): one step of
// y' = A y against (I - dt A)^-1 y_n from a dense LU; first-order convergence to the
// exact solution of a decay chain as solver.cfl falls; conservation to round-off on a
// conservative nonlinear system with an outflow booked in a global; DustPy's step-size
// rule against a hand computation; a restart from a mid-run state continues bit for bit.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/solver/disk_model.hpp"
#include "src/solver/implicit_euler_integrator.hpp"

using namespace panoptic;

namespace {

//! y' = A y for a fixed matrix A over the whole state (cells then globals): its pattern
//! is A's non-zeros, its Jacobian A.
class LinearSystem : public PhysicsModule {
 public:
  LinearSystem(StateLayout& layout, int vars_per_cell, int globals, Eigen::MatrixXd a)
      : a_(std::move(a)) {
    // names from a table: GCC 12's -Wrestrict misfires on "y" + std::to_string(v)
    static const char* const kNames[] = {"y0", "y1", "y2", "y3"};
    for (int v = 0; v < vars_per_cell; ++v)
      layout.add_cell_var({kNames[v], "", "", 1.0, false});
    for (int g = 0; g < globals; ++g)
      layout.add_global_var({kNames[g], "", "", 1.0, false});
  }
  std::string_view name() const override { return "linear"; }
  void declare_pattern(PatternBuilder& p) const override {
    for (long i = 0; i < a_.rows(); ++i)
      for (long j = 0; j < a_.cols(); ++j)
        if (a_(i, j) != 0.0) p.add(i, j);
  }
  void add_rhs(double, std::span<const double> y, std::span<double> ydot) const override {
    const Eigen::VectorXd f =
        a_ * Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<long>(y.size()));
    for (long i = 0; i < f.size(); ++i) ydot[i] += f[i];
  }
  void add_jacobian(double, std::span<const double>, JacobianValues& jac) const override {
    for (long i = 0; i < a_.rows(); ++i)
      for (long j = 0; j < a_.cols(); ++j)
        if (a_(i, j) != 0.0) jac.add(i, j, a_(i, j));
  }

 private:
  Eigen::MatrixXd a_;
};

std::unique_ptr<DiskModel> linear_model(int cells, int vars, int globals,
                                        const Eigen::MatrixXd& a) {
  auto layout = std::make_shared<StateLayout>(cells);
  std::vector<std::unique_ptr<PhysicsModule>> mods;
  mods.push_back(std::make_unique<LinearSystem>(*layout, vars, globals, a));
  layout->freeze();
  return std::make_unique<DiskModel>(layout, std::move(mods));
}

//! Three cells of two variables: a decaying, coupled block per cell and a flow of each
//! variable to the cell on its left (the block-banded shape of the transport).
Eigen::MatrixXd three_cell_matrix() {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(6, 6);
  for (int c = 0; c < 3; ++c) {
    const int i = 2 * c;
    a(i, i) = -2.0 - c;
    a(i, i + 1) = 0.5;
    a(i + 1, i) = 1.5;
    a(i + 1, i + 1) = -1.0 - 0.5 * c;
    if (c > 0) {
      a(i - 2, i) = 0.7;
      a(i - 1, i + 1) = 0.3;
    }
  }
  return a;
}

IntegratorOptions euler_options(double cfl) {
  IntegratorOptions opt;
  opt.method = IntegrationMethod::implicit_euler;
  opt.cfl = cfl;
  return opt;
}

// Decay chain y0' = -a y0, y1' = a y0 - b y1 (one cell): exact solution from y = (1, 0).
constexpr double kA = 1.0, kB = 3.0;
double chain_y1(double t) {
  return kA / (kB - kA) * (std::exp(-kA * t) - std::exp(-kB * t));
}

//! Per cell two densities on areas w_c: a quadratic conversion y0 -> y1 (mass-
//! conserving, nonlinear: the Jacobian is not the matrix of the step), and a flow of
//! each to the inner cell, the innermost cell's into a global that books it (the
//! engine's m_out). Budget: sum_c w_c (y0 + y1) + g.
constexpr int kCells = 4;
class Conservative : public PhysicsModule {
 public:
  explicit Conservative(StateLayout& layout) : layout_(layout) {
    layout.add_cell_var({"y0", "", "", 1.0, false});
    layout.add_cell_var({"y1", "", "", 1.0, false});
    layout.add_global_var({"out", "", "", 1.0, false});
  }
  std::string_view name() const override { return "conservative"; }
  double area(int c) const { return 1.0 + 0.37 * c * c; }
  void declare_pattern(PatternBuilder& p) const override {
    for (int c = 0; c < kCells; ++c)
      for (int v = 0; v < 2; ++v) {
        const long i = layout_.index(c, v);
        p.add(i, i);
        p.add(layout_.index(c, 1), layout_.index(c, 0));
        p.add(c > 0 ? layout_.index(c - 1, v) : layout_.global_index(0), i);
      }
  }
  void add_rhs(double, std::span<const double> y, std::span<double> ydot) const override {
    for (int c = 0; c < kCells; ++c) {
      const long i0 = layout_.index(c, 0), i1 = layout_.index(c, 1);
      const double conversion = kConvert * y[i0] * y[i0];
      ydot[i0] -= conversion;
      ydot[i1] += conversion;
      for (const long i : {i0, i1}) {
        const double mass_flow = kFlow * area(c) * y[i];
        ydot[i] -= mass_flow / area(c);
        if (c > 0)
          ydot[i - layout_.n_cell_vars()] += mass_flow / area(c - 1);
        else
          ydot[layout_.global_index(0)] += mass_flow;
      }
    }
  }
  void add_jacobian(double, std::span<const double> y,
                    JacobianValues& jac) const override {
    for (int c = 0; c < kCells; ++c) {
      const long i0 = layout_.index(c, 0), i1 = layout_.index(c, 1);
      jac.add(i0, i0, -2.0 * kConvert * y[i0]);
      jac.add(i1, i0, 2.0 * kConvert * y[i0]);
      for (const long i : {i0, i1}) {
        jac.add(i, i, -kFlow);
        if (c > 0)
          jac.add(i - layout_.n_cell_vars(), i, kFlow * area(c) / area(c - 1));
        else
          jac.add(layout_.global_index(0), i, kFlow * area(c));
      }
    }
  }

 private:
  static constexpr double kConvert = 3.0, kFlow = 0.4;
  const StateLayout& layout_;
};
}  // namespace

TEST(ImplicitEuler, OneStepOfALinearSystemIsTheImplicitEulerStep) {
  const Eigen::MatrixXd a = three_cell_matrix();
  const auto model = linear_model(3, 2, 0, a);
  const std::vector<double> y0{1.0, 0.2, 0.5, 0.9, 0.3, 0.4};
  // cfl 10: the rule's step (several times 1/|rate|) is longer than dt, so the output
  // time sets the one step
  ImplicitEulerIntegrator euler(*model, 0.0, y0, euler_options(10.0));
  const double dt = 0.05;
  euler.advance_to(dt);
  const Eigen::VectorXd expected =
      (Eigen::MatrixXd::Identity(6, 6) - dt * a)
          .partialPivLu()
          .solve(Eigen::Map<const Eigen::VectorXd>(y0.data(), 6));
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(euler.state()[i], expected[i], 1e-14 * std::abs(expected[i])) << i;
  EXPECT_EQ(euler.time(), dt);
  const SolverStats s = euler.stats();
  EXPECT_EQ(s.nst, 1);
  EXPECT_EQ(s.nfe, 1);
  EXPECT_EQ(s.nje, 1);
  EXPECT_EQ(s.nsetups, 1);
  EXPECT_EQ(s.h_last, dt);
}

TEST(ImplicitEuler, ConvergesAtFirstOrderAsTheCflFalls) {
  Eigen::MatrixXd a(2, 2);
  a << -kA, 0.0, kA, -kB;
  const auto model = linear_model(1, 2, 0, a);
  const std::vector<double> y0{1.0, 0.0};
  const double t_end = 2.0;
  std::vector<double> errors;
  for (const double cfl : {0.04, 0.02, 0.01, 0.005}) {
    ImplicitEulerIntegrator euler(*model, 0.0, y0, euler_options(cfl));
    euler.advance_to(t_end);
    errors.push_back(std::hypot(euler.state()[0] - std::exp(-kA * t_end),
                                euler.state()[1] - chain_y1(t_end)));
  }
  // measured: errors 5.8e-3, 2.9e-3, 1.5e-3, 7.3e-4; orders 0.99, 1.00, 1.00
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log2(errors[k - 1] / errors[k]);
    EXPECT_GT(order, 0.95) << "cfl step " << k;
    EXPECT_LT(order, 1.05) << "cfl step " << k;
  }
  EXPECT_LT(errors.back(), 1e-3);
}

TEST(ImplicitEuler, ConservesABookedBudgetToRoundOff) {
  auto layout = std::make_shared<StateLayout>(kCells);
  std::vector<std::unique_ptr<PhysicsModule>> mods;
  mods.push_back(std::make_unique<Conservative>(*layout));
  const auto* module = static_cast<const Conservative*>(mods.back().get());
  layout->freeze();
  DiskModel model(layout, std::move(mods));
  std::vector<double> y0(static_cast<std::size_t>(layout->size()), 0.0);
  for (int c = 0; c < kCells; ++c) y0[layout->index(c, 0)] = 1.0 + c;
  const auto budget = [&](std::span<const double> y) {
    double m = y[layout->global_index(0)];
    for (int c = 0; c < kCells; ++c)
      m += module->area(c) * (y[layout->index(c, 0)] + y[layout->index(c, 1)]);
    return m;
  };
  ImplicitEulerIntegrator euler(model, 0.0, y0, euler_options(0.1));
  euler.advance_to(20.0);
  EXPECT_GT(euler.stats().nst, 100);
  EXPECT_GT(euler.state()[layout->global_index(0)], 0.5 * budget(y0));  // it flowed
  // measured 2.2e-16 after 119 steps
  EXPECT_LT(std::abs(budget(euler.state()) / budget(y0) - 1.0), 1e-14);
}

TEST(ImplicitEuler, StepSizeRuleByHand) {
  // DustPy's rule: cfl min y/|f| over f < 0 and y above its floor
  const std::vector<double> y{1.0, 2.0, 1e-30, 5.0, 4.0};
  const std::vector<double> f{-0.5, -8.0, -1.0, 3.0, 0.0};
  const std::vector<double> floor{0.0, 0.0, 1e-20, 0.0, 0.0};
  long limiting = -2;
  // candidates 1/0.5 = 2 and 2/8 = 0.25; y[2] is below its floor, y[3] grows, y[4]
  // stands still
  EXPECT_DOUBLE_EQ(ImplicitEulerIntegrator::step_size(y, f, floor, 0.1, &limiting),
                   0.025);
  EXPECT_EQ(limiting, 1);
  // without floors y[2] (1e-30/1) sets it
  EXPECT_DOUBLE_EQ(ImplicitEulerIntegrator::step_size(y, f, {}, 0.1, &limiting), 1e-31);
  EXPECT_EQ(limiting, 2);
  // an infinite floor leaves a component out; nothing shrinking: no limit
  const std::vector<double> out{0.0, std::numeric_limits<double>::infinity(), 1e-20, 0.0,
                                0.0};
  EXPECT_DOUBLE_EQ(ImplicitEulerIntegrator::step_size(y, f, out, 0.1), 0.2);
  const std::vector<double> growing{1.0, 2.0, 0.0, 3.0, 0.0};
  EXPECT_EQ(ImplicitEulerIntegrator::step_size(y, growing, {}, 0.1, &limiting),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(limiting, -1);
}

TEST(ImplicitEuler, TheIntegratorTakesTheRulesStepCutAtMaxDtAndTheOutputTime) {
  Eigen::MatrixXd a(2, 2);
  a << -kA, 0.0, kA, -kB;
  const auto model = linear_model(1, 2, 0, a);
  const std::vector<double> y0{1.0, 0.0};
  // y1 grows at first: the rule's step is cfl y0/(a y0) = cfl/a
  ImplicitEulerIntegrator euler(*model, 0.0, y0, euler_options(0.2));
  euler.advance_to(1.0, [&](double t, long nst) {
    if (nst == 1) {
      EXPECT_DOUBLE_EQ(t, 0.2 / kA);
      EXPECT_EQ(euler.limiting_component(), 0);
    }
  });
  EXPECT_LE(euler.stats().h_last, 0.2 / kA);  // the last step ends on t = 1
  EXPECT_EQ(euler.time(), 1.0);
  IntegratorOptions capped = euler_options(0.2);
  capped.max_dt = 0.05;
  ImplicitEulerIntegrator slow(*model, 0.0, y0, capped);
  slow.advance_to(1.0);
  EXPECT_GE(slow.stats().nst, 20);  // 21: a last step of the sum's round-off
  EXPECT_LE(slow.stats().nst, 21);
  EXPECT_LE(slow.stats().h_last, 0.05);
  EXPECT_EQ(slow.limiting_component(), -1);
}

TEST(ImplicitEuler, ARestartFromAMidRunStateContinuesBitForBit) {
  const auto model = linear_model(3, 2, 0, three_cell_matrix());
  const std::vector<double> y0{1.0, 0.2, 0.5, 0.9, 0.3, 0.4};
  ImplicitEulerIntegrator run(*model, 0.0, y0, euler_options(0.1));
  run.advance_to(0.7);
  const std::vector<double> y_mid(run.state().begin(), run.state().end());
  run.reinit(0.7, y_mid);  // as the run loop does at every snapshot
  run.advance_to(2.0);
  ImplicitEulerIntegrator again(*model, 0.7, y_mid, euler_options(0.1));
  again.carry_stats(SolverStats{});
  again.advance_to(2.0);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(again.state()[i], run.state()[i]) << i;
}

TEST(ImplicitEuler, RefusesAPatternTheBlockSolverCannotTake) {
  // a cell row that reads the global: BlockBandedLU::refusal
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3, 3);
  a(0, 0) = a(1, 1) = a(2, 2) = -1.0;
  a(0, 2) = 0.5;
  const auto model = linear_model(2, 1, 1, a);
  const std::vector<double> y0{1.0, 1.0, 0.0};
  try {
    ImplicitEulerIntegrator euler(*model, 0.0, y0, euler_options(0.1));
    ADD_FAILURE() << "expected a refusal";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    for (const char* part : {"solver.method = \"implicit_euler\"",
                             "depends on global variable 0", "solver.method = \"bdf\""})
      EXPECT_NE(msg.find(part), std::string::npos) << msg;
  }
}
