// The worker threads of `panoptic run --threads N` (src/core/worker_threads.hpp):
// parallel_for visits every index once and hands an exception back, parallel_bands
// covers a range once, and the cell-local work they share (the porous size distribution's
// coefficients, engine rates and Jacobian blocks, the GMRES preconditioner's cell blocks,
// the product J v by bands of rows) gives the same bits on any number of threads.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/modules/size_distribution.hpp"
#include "src/core/units.hpp"
#include "src/core/worker_threads.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cell_block_preconditioner.hpp"
#include "tests/unit/support/jacobian_check.hpp"

namespace panoptic {
namespace {

// Restores one worker thread when a test ends, whatever it set.
struct ThreadsGuard {
  explicit ThreadsGuard(int n) { set_worker_threads(n); }
  ~ThreadsGuard() { set_worker_threads(1); }
};

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(WorkerThreads, ParallelForCallsEveryIndexOnceOnAWorkerOfItsOwn) {
  const ThreadsGuard threads(3);
  ASSERT_EQ(worker_threads(), 3);
  const int n = 1000;
  std::vector<int> calls(n, 0), worker(n, -1);
  parallel_for(n, [&](int i, int w) {
    ++calls[static_cast<std::size_t>(i)];
    worker[static_cast<std::size_t>(i)] = w;
  });
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(calls[static_cast<std::size_t>(i)], 1) << i;
    EXPECT_GE(worker[static_cast<std::size_t>(i)], 0) << i;
    EXPECT_LT(worker[static_cast<std::size_t>(i)], 3) << i;
  }
  set_worker_threads(0);  // below 1: one thread
  EXPECT_EQ(worker_threads(), 1);
}

TEST(WorkerThreads, ParallelBandsCoverTheRangeOnceInOrder) {
  for (int threads : {1, 3, 7}) {
    const ThreadsGuard guard(threads);
    const auto t = static_cast<std::size_t>(threads);
    for (std::size_t n : {0u, 1u, 5u, 1000u}) {
      std::vector<int> hits(n, 0);
      std::atomic<int> calls{0}, of_the_rule{0};
      parallel_bands(n, [&](std::size_t lo, std::size_t hi) {
        for (std::size_t k = lo; k < hi; ++k) ++hits[k];
        ++calls;
        for (std::size_t b = 0; b < t; ++b)  // band b is [n b / t, n (b + 1) / t)
          if (lo == n * b / t && hi == n * (b + 1) / t) {
            ++of_the_rule;
            break;
          }
      });
      for (std::size_t k = 0; k < n; ++k) EXPECT_EQ(hits[k], 1) << threads << " " << n;
      EXPECT_EQ(calls.load(), threads) << n;
      EXPECT_EQ(of_the_rule.load(), threads) << n;
    }
  }
}

TEST(WorkerThreads, AnExceptionOfOneCallIsRethrownOnceAllHaveRun) {
  for (int threads : {1, 3}) {
    const ThreadsGuard guard(threads);
    std::vector<int> calls(100, 0);
    EXPECT_THROW(parallel_for(100,
                              [&](int i, int) {
                                if (i == 17) throw std::runtime_error("cell 17");
                                ++calls[static_cast<std::size_t>(i)];
                              }),
                 std::runtime_error)
        << threads;
    // one thread stops at the throw; several finish the other cells
    EXPECT_EQ(calls[16], 1) << threads;
  }
}

// The porous distribution scene (50 bins, 12 cells) at a state with every bin filled and
// u from 1 to ~1e3: its right-hand side, Jacobian, J y and preconditioner solve on 1 and
// on 3 threads.
TEST(WorkerThreads, PorousDistributionGivesTheSameBitsOnAnyNumberOfThreads) {
  const std::vector<std::string> sets{"porosity.enabled=true"};
  const Config cfg = load_scene(
      std::string(PANOPTIC_SOURCE_DIR) + "/params/tests/distribution_small.toml", sets);
  struct Result {
    std::vector<double> ydot, jac, product, solved;
  };
  auto evaluate = [&](int threads) {
    const ThreadsGuard guard(threads);
    Simulation sim(cfg);
    const auto& model = sim.model();
    const auto& layout = model.layout();
    const auto* d = sim.distribution();
    auto y = testing::perturbed_state(sim, 5);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> ln_u(0.0, 7.0);
    for (int i = 0; i < layout.n_cells(); ++i)
      for (int k = 0; k < d->n_bins(); ++k)
        y[layout.index(i, d->psi_slot(k))] =
            std::exp(ln_u(rng)) * y[layout.index(i, d->bin_slot(k))];
    Result r;
    r.ydot.assign(y.size(), 0.0);
    model.rhs(0.0, y, r.ydot);
    r.jac.assign(static_cast<std::size_t>(model.pattern().nnz()), 0.0);
    model.jacobian(0.0, y, r.jac);
    r.product.assign(y.size(), 0.0);  // J y, GMRES's product, by bands of rows
    model.pattern().multiply(r.jac, y, r.product);
    CellBlockPreconditioner pre(model.pattern(), layout.n_cells(), layout.n_cell_vars());
    EXPECT_TRUE(pre.setup(r.jac, 10.0 * units::kYr));
    r.solved = r.ydot;
    EXPECT_TRUE(pre.solve(r.solved));
    return r;
  };
  const Result one = evaluate(1);
  // three times: a race between the threads shows in some evaluations, not in all
  for (int repeat = 0; repeat < 3; ++repeat) {
    const Result three = evaluate(3);
    EXPECT_TRUE(same_bits(one.ydot, three.ydot)) << repeat;
    EXPECT_TRUE(same_bits(one.jac, three.jac)) << repeat;
    EXPECT_TRUE(same_bits(one.product, three.product)) << repeat;
    EXPECT_TRUE(same_bits(one.solved, three.solved)) << repeat;
  }
  // the state is one where the work matters: rates and couplings are not all zero
  double largest = 0.0;
  for (double v : one.jac) largest = std::max(largest, std::abs(v));
  EXPECT_GT(largest, 0.0);
}

}  // namespace
}  // namespace panoptic
