// The N_Vector operations panoptic installs on CVODE's vectors
// (src/solver/serial_vector_ops.hpp) against the library's N_V*_Serial, bit for bit, on
// vectors holding every kind of value (signed zeros, subnormals, huge, infinite, NaN) and
// for every special case the library tells apart (coefficients 0, +-1, equal or opposite;
// the output aliasing an input).
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "src/solver/serial_vector_ops.hpp"

namespace panoptic {
namespace {

constexpr sunindextype kN = 257;

class SerialVectorOps : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(SUNContext_Create(nullptr, &ctx_), 0);
    lib_ = N_VNew_Serial(kN, ctx_);
    ours_ = N_VNew_Serial(kN, ctx_);
    install_serial_vector_ops(ours_);
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    const double special[] = {0.0,
                              -0.0,
                              1.0,
                              -1.0,
                              std::numeric_limits<double>::denorm_min(),
                              1e300,
                              -1e-300,
                              std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::quiet_NaN()};
    for (int k = 0; k < 3; ++k) {
      std::vector<double> v(kN);
      for (auto& x : v) x = u(rng) * std::pow(10.0, static_cast<int>(u(rng) * 3));
      for (std::size_t i = 0; i < std::size(special); ++i)
        v[(7 * i + 3 * k) % kN] = special[i];
      values_.push_back(v);
    }
  }
  void TearDown() override {
    N_VDestroy(lib_);
    N_VDestroy(ours_);
    SUNContext_Free(&ctx_);
  }
  // A fresh pair of vectors holding values_[k], one with the library's operations and
  // one with ours.
  struct Pair {
    N_Vector lib, ours;
  };
  Pair make(int k) {
    Pair p{N_VClone(lib_), N_VClone(ours_)};
    std::memcpy(N_VGetArrayPointer(p.lib), values_[k].data(), kN * sizeof(double));
    std::memcpy(N_VGetArrayPointer(p.ours), values_[k].data(), kN * sizeof(double));
    made_.push_back(p.lib);
    made_.push_back(p.ours);
    return p;
  }
  static void expect_same_bits(N_Vector a, N_Vector b, const std::string& what) {
    EXPECT_EQ(
        std::memcmp(N_VGetArrayPointer(a), N_VGetArrayPointer(b), kN * sizeof(double)), 0)
        << what;
  }
  static void expect_same_bits(double a, double b, const std::string& what) {
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << what << ": " << a << " vs " << b;
  }
  ~SerialVectorOps() override {
    for (N_Vector v : made_) N_VDestroy(v);
  }

  SUNContext ctx_ = nullptr;
  N_Vector lib_ = nullptr, ours_ = nullptr;
  std::vector<std::vector<double>> values_;
  std::vector<N_Vector> made_;
};

TEST_F(SerialVectorOps, InstalledOnTheVectorAndItsClones) {
  N_Vector c = N_VClone(ours_);
  EXPECT_NE(c->ops->nvlinearsum, lib_->ops->nvlinearsum);
  EXPECT_EQ(c->ops->nvlinearsum, ours_->ops->nvlinearsum);
  N_VDestroy(c);
}

TEST_F(SerialVectorOps, LinearSumInEveryCaseAndAliasing) {
  const double coefs[] = {0.0, 1.0, -1.0, 0.37, -0.37, 2.5, -1e-3};
  for (const double a : coefs)
    for (const double b : coefs)
      for (int alias = 0; alias < 3; ++alias) {  // z separate, z = x, z = y
        const Pair x = make(0), y = make(1), z = make(2);
        const Pair& zl = alias == 1 ? x : alias == 2 ? y : z;
        N_VLinearSum(a, x.lib, b, y.lib, zl.lib);
        N_VLinearSum(a, x.ours, b, y.ours, zl.ours);
        expect_same_bits(zl.lib, zl.ours,
                         "a = " + std::to_string(a) + ", b = " + std::to_string(b) +
                             ", alias " + std::to_string(alias));
      }
}

TEST_F(SerialVectorOps, ElementWiseOperations) {
  for (const double c : {0.0, 1.0, -1.0, 0.3, -7.0})
    for (const bool in_place : {false, true}) {
      Pair x = make(0), z = make(1);
      const Pair& out = in_place ? x : z;
      N_VScale(c, x.lib, out.lib);
      N_VScale(c, x.ours, out.ours);
      expect_same_bits(out.lib, out.ours, "scale " + std::to_string(c));
    }
  {
    Pair z = make(0);
    N_VConst(-2.5, z.lib);
    N_VConst(-2.5, z.ours);
    expect_same_bits(z.lib, z.ours, "const");
  }
  {
    Pair x = make(0), y = make(1), z = make(2);
    N_VProd(x.lib, y.lib, z.lib);
    N_VProd(x.ours, y.ours, z.ours);
    expect_same_bits(z.lib, z.ours, "prod");
    N_VDiv(x.lib, y.lib, z.lib);
    N_VDiv(x.ours, y.ours, z.ours);
    expect_same_bits(z.lib, z.ours, "div");
    N_VAbs(x.lib, z.lib);
    N_VAbs(x.ours, z.ours);
    expect_same_bits(z.lib, z.ours, "abs");
    N_VInv(y.lib, z.lib);
    N_VInv(y.ours, z.ours);
    expect_same_bits(z.lib, z.ours, "inv");
    N_VAddConst(x.lib, 0.125, z.lib);
    N_VAddConst(x.ours, 0.125, z.ours);
    expect_same_bits(z.lib, z.ours, "addconst");
    N_VCompare(0.5, x.lib, z.lib);
    N_VCompare(0.5, x.ours, z.ours);
    expect_same_bits(z.lib, z.ours, "compare");
    const Pair w = make(2);
    EXPECT_EQ(N_VInvTest(x.lib, w.lib), N_VInvTest(x.ours, w.ours));
    expect_same_bits(w.lib, w.ours, "invtest");
  }
}

TEST_F(SerialVectorOps, ReductionsInTheLibrarysOrder) {
  // finite values only where a NaN or an infinity would make every result equal
  for (int k = 0; k < 2; ++k) {
    const Pair x = make(k), y = make(2);
    for (N_Vector v : {x.lib, x.ours, y.lib, y.ours})
      for (sunindextype i = 0; i < kN; ++i) {
        double& e = N_VGetArrayPointer(v)[i];
        if (!std::isfinite(e) || std::fabs(e) > 1e100) e = 0.5;
      }
    expect_same_bits(N_VDotProd(x.lib, y.lib), N_VDotProd(x.ours, y.ours), "dotprod");
    expect_same_bits(N_VMaxNorm(x.lib), N_VMaxNorm(x.ours), "maxnorm");
    expect_same_bits(N_VMin(x.lib), N_VMin(x.ours), "min");
    expect_same_bits(N_VWL2Norm(x.lib, y.lib), N_VWL2Norm(x.ours, y.ours), "wl2norm");
    expect_same_bits(N_VL1Norm(x.lib), N_VL1Norm(x.ours), "l1norm");
    expect_same_bits(N_VMinQuotient(x.lib, y.lib), N_VMinQuotient(x.ours, y.ours),
                     "minquotient");
  }
  // and with the special values in (NaN propagation and comparisons as the library's)
  const Pair x = make(0), y = make(1);
  expect_same_bits(N_VMaxNorm(x.lib), N_VMaxNorm(x.ours), "maxnorm, specials");
  expect_same_bits(N_VMin(x.lib), N_VMin(x.ours), "min, specials");
  expect_same_bits(N_VMinQuotient(x.lib, y.lib), N_VMinQuotient(x.ours, y.ours),
                   "minquotient, specials");
}

TEST_F(SerialVectorOps, ConstraintMask) {
  const Pair c = make(0), x = make(1), m = make(2);
  const double kinds[] = {0.0, 1.0, -1.0, 2.0, -2.0};
  for (N_Vector v : {c.lib, c.ours})
    for (sunindextype i = 0; i < kN; ++i) N_VGetArrayPointer(v)[i] = kinds[i % 5];
  EXPECT_EQ(N_VConstrMask(c.lib, x.lib, m.lib), N_VConstrMask(c.ours, x.ours, m.ours));
  expect_same_bits(m.lib, m.ours, "constrmask");
  // and a state that meets every constraint
  for (N_Vector v : {x.lib, x.ours})
    for (sunindextype i = 0; i < kN; ++i)
      N_VGetArrayPointer(v)[i] = kinds[i % 5] < 0.0 ? -1.0 : 1.0;
  EXPECT_EQ(N_VConstrMask(c.lib, x.lib, m.lib), SUNTRUE);
  EXPECT_EQ(N_VConstrMask(c.ours, x.ours, m.ours), SUNTRUE);
  expect_same_bits(m.lib, m.ours, "constrmask, met");
}

}  // namespace
}  // namespace panoptic
