// Benchmark (not a test): block-local time stepping of the fiducial scene, built and run,
// for the speed targets of issues 3 and 7 (README "Performance": `bench_fiducial --lts`
// bounds what blocks of B cells with their own step sizes could save; this measures
// what a simple coupling of such blocks actually takes, and what it costs in accuracy).
//
// The scheme (a prototype, not the product's integrator): the grid is cut into blocks of
// B neighbouring cells, each integrated by its own CVODE (BDF, KLU, the scene's
// tolerances and options) on its own cells' variables and the booked global masses fed
// by its faces. The blocks are coupled at macro steps: K per snapshot interval (all
// blocks restart at every snapshot, as `panoptic run` does). In a macro step [T0, T1]
// the blocks are advanced one after the other from the outer edge inward, in the
// direction the dust drifts (a Gauss-Seidel sweep, waveform relaxation with one pass):
// a block sees its outer neighbour's cells as they were integrated over [T0, T1]
// (cubic Hermite interpolation between that block's steps, from CVODE's state and
// derivative after each step), and its inner neighbour's cells frozen at T0. Drift is
// inward everywhere in this scene, so the advective coupling is followed in time; the
// diffusive one (and the geometric-mean Stokes number of a face, which reads both
// cells) lags by up to a macro step. The flux through a face between two blocks is
// computed by each of them from its own view of the other, so the scheme is not
// conservative; the mass defect is reported (a refluxing correction would fix it).
//
// Each block's right-hand side is evaluated by the whole-disk model on a whole-disk
// vector (the modules have no cell-range interface), so the wall time here is not that
// of such a scheme; the cost is reported as block steps and cell-steps (steps x cells),
// to be set against the coupled run's cell-steps (README: ~1.4 us per cell-step).
//
// Usage: build/tests/bench_lts [--block B ...] [--overlap V ...] [--sub K ...]
//            [--tol-scale X] [--overlap-atol F] [--extrapolate] [--profile]
//            [--set key=value ...]
// (measurements: README "Performance" and tests/bench/results/performance_log.md)
//   --block B:     cells per block (16 by default); every combination of B, V, K is run
//   --overlap V:   each block also integrates the V cells inside it and discards them, so
//                  that the lagged inner neighbour acts V cells away from its own cells
//   --sub K:       macro steps per snapshot interval (log-spaced within it)
//   --tol-scale X: rtol and atol of every block multiplied by X (CVODE's RMS norm over a
//                  block of n_b components is stricter per cell than the coupled run's
//                  over all N; X = sqrt(N / n_b) gives every block the error the coupled
//                  run allows a single limiting block, as in bench_fiducial --lts)
//   --overlap-atol F: the overlap cells' atol multiplied by F (they are discarded)
//   --extrapolate: the inner neighbour extrapolated linearly from its last step instead
//                  of frozen at the macro step's start
//   --profile:     cell-steps per snapshot interval, coupled and blocks
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "physics/dust_transport.hpp"
#include "src/config.hpp"
#include "src/cvode_integrator.hpp"
#include "src/grid.hpp"
#include "src/simulation.hpp"
#include "src/units.hpp"
#include "tests/bench/fiducial_outcome.hpp"

using namespace panoptic;

namespace {

//! A block's states after each of its steps in the current macro step (the first record
//! at the macro step's start), for the dense output its neighbours read.
struct History {
  int n = 0;  // components per record
  std::vector<double> t, y, dy;

  void push(double time, std::span<const double> v, std::span<const double> d) {
    t.push_back(time);
    y.insert(y.end(), v.begin(), v.end());
    dy.insert(dy.end(), d.begin(), d.end());
  }
  //! Keep only the last record (the start of the next macro step).
  void keep_last() {
    const std::size_t m = t.size();
    if (m <= 1) return;
    t.erase(t.begin(), t.end() - 1);
    y.erase(y.begin(), y.end() - n);
    dy.erase(dy.begin(), dy.end() - n);
  }
  //! Linear extrapolation of component k from the last record to time tq.
  double extrapolate(double tq, int k) const {
    const std::size_t m = t.size();
    return y[(m - 1) * n + k] + dy[(m - 1) * n + k] * (tq - t.back());
  }
  //! Cubic Hermite interpolation of component k at time tq.
  double at(double tq, int k) const {
    const std::size_t m = t.size();
    if (m == 1 || tq <= t.front()) return y[k];
    if (tq >= t.back()) return y[(m - 1) * n + k];
    const std::size_t i =
        static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), tq) - t.begin()) -
        1;
    const double h = t[i + 1] - t[i], s = (tq - t[i]) / h;
    const double s2 = s * s, s3 = s2 * s;
    const std::size_t a = i * n + k, b = (i + 1) * n + k;
    return (2 * s3 - 3 * s2 + 1) * y[a] + (s3 - 2 * s2 + s) * h * dy[a] +
           (-2 * s3 + 3 * s2) * y[b] + (s3 - s2) * h * dy[b];
  }
};

class Coupler;

//! One block's model: the whole-disk model seen through the block's components, with
//! the neighbours' cells filled in by the Coupler.
class BlockView : public PhysicsModule {
 public:
  BlockView(const DiskModel& full, const Coupler& coupler, int block,
            std::vector<long> full_index);
  std::string_view name() const override { return "block"; }
  void declare_pattern(PatternBuilder& p) const override {
    for (const auto& e : entries_) p.add(e.row, e.col);
  }
  void add_rhs(double t, std::span<const double> y,
               std::span<double> ydot) const override;
  void add_jacobian(double t, std::span<const double> y,
                    JacobianValues& jac) const override;
  //! The whole-disk vector the block's components are written into (others: at T0).
  std::vector<double>& base() { return y_full_; }

 private:
  void fill(double t, std::span<const double> y) const;
  struct Entry {
    long row, col, pos;
  };
  const DiskModel& full_;
  const Coupler& coupler_;
  int block_;
  std::vector<long> full_index_;
  std::vector<Entry> entries_;
  mutable std::vector<double> y_full_, ydot_full_, jac_full_;
};

struct Block {
  int lo = 0, hi = 0;            // the cells it owns
  int ilo = 0;                   // the first cell it integrates (lo - overlap)
  std::vector<long> full_index;  // compact component -> whole-disk component
  std::unique_ptr<DiskModel> model;
  BlockView* view = nullptr;
  std::unique_ptr<CvodeIntegrator> cvode;
  History hist;
  bool advanced = false;  // integrated over the current macro step already
};

class Coupler {
 public:
  Coupler(Simulation& sim, int block_size, int overlap, double tol_scale,
          double overlap_atol_factor, bool extrapolate);
  //! Integrates the scene to t_end with K macro steps per snapshot interval; returns
  //! the whole-disk state at t_end.
  std::vector<double> run(int sub);
  //! Writes the neighbours' cells of block b at time t into y_full.
  void fill_ghosts(int b, double t, std::span<double> y_full) const;
  //! A solver counter (&SolverStats::nst, nfe, nje) summed over the blocks, each
  //! weighted by its cells (overlap included) or, with per_cell = false, not.
  long total(long SolverStats::*counter, bool per_cell = true) const;
  int n_blocks() const { return static_cast<int>(blocks_.size()); }
  int block_cells(int b) const { return blocks_[b].hi - blocks_[b].ilo; }
  //! Per snapshot interval: every block's cumulative step count at its end.
  std::vector<std::vector<long>> interval_steps_;

 private:
  std::vector<double> gather() const;
  Simulation& sim_;
  const StateLayout& layout_;
  int nv_ = 0;
  std::vector<Block> blocks_;
  std::vector<int> owner_;  // per cell: its block
  std::vector<double> base_;
  bool extrapolate_ = false;  // inner neighbours: extrapolated from T0, not frozen
};

BlockView::BlockView(const DiskModel& full, const Coupler& coupler, int block,
                     std::vector<long> full_index)
    : full_(full), coupler_(coupler), block_(block), full_index_(std::move(full_index)) {
  const long n = full.layout().size();
  std::vector<long> compact(n, -1);
  for (std::size_t k = 0; k < full_index_.size(); ++k)
    compact[full_index_[k]] = static_cast<long>(k);
  const auto cp = full.pattern().col_ptr();
  const auto ri = full.pattern().row_index();
  for (long c = 0; c < n; ++c) {
    if (compact[c] < 0) continue;
    for (long p = cp[c]; p < cp[c + 1]; ++p)
      if (compact[ri[p]] >= 0) entries_.push_back({compact[ri[p]], compact[c], p});
  }
  y_full_.assign(n, 0.0);
  ydot_full_.assign(n, 0.0);
  jac_full_.assign(full.pattern().nnz(), 0.0);
}

void BlockView::fill(double t, std::span<const double> y) const {
  for (std::size_t k = 0; k < full_index_.size(); ++k) y_full_[full_index_[k]] = y[k];
  coupler_.fill_ghosts(block_, t, y_full_);
}

void BlockView::add_rhs(double t, std::span<const double> y,
                        std::span<double> ydot) const {
  fill(t, y);
  full_.rhs(t, y_full_, ydot_full_);
  for (std::size_t k = 0; k < full_index_.size(); ++k)
    ydot[k] += ydot_full_[full_index_[k]];
}

void BlockView::add_jacobian(double t, std::span<const double> y,
                             JacobianValues& jac) const {
  fill(t, y);
  full_.jacobian(t, y_full_, jac_full_);
  for (const auto& e : entries_) jac.add(e.row, e.col, jac_full_[e.pos]);
}

Coupler::Coupler(Simulation& sim, int block_size, int overlap, double tol_scale,
                 double overlap_atol_factor, bool extrapolate)
    : sim_(sim),
      layout_(sim.model().layout()),
      nv_(layout_.n_cell_vars()),
      extrapolate_(extrapolate) {
  const int n = layout_.n_cells();
  const DiskModel& full = sim.model();
  // Each booked global belongs to the block that owns the cell its face takes mass
  // from: the outer cell of its face (the largest cell its row reads), r_in's to block 0.
  const int ng = layout_.n_global_vars();
  std::vector<int> global_cell(ng, -1);
  const auto cp = full.pattern().col_ptr();
  const auto ri = full.pattern().row_index();
  for (long c = 0; c < layout_.size(); ++c) {
    const int cell = layout_.cell_of(c);
    for (long p = cp[c]; p < cp[c + 1]; ++p) {
      const long r = ri[p];
      if (layout_.cell_of(r) >= 0) continue;
      const int g = static_cast<int>(r - layout_.global_index(0));
      global_cell[g] = std::max(global_cell[g], cell);
    }
  }
  global_cell[sim.transport().m_out_slot()] = 0;
  const IntegratorOptions full_opt = sim.integrator_options();
  const std::vector<double> y0 = sim.initial_state();
  base_ = y0;
  owner_.assign(n, 0);
  for (int lo = 0; lo < n; lo += block_size) {
    Block b;
    b.lo = lo;
    b.hi = std::min(n, lo + block_size);
    b.ilo = std::max(0, lo - overlap);
    for (int i = b.lo; i < b.hi; ++i) owner_[i] = static_cast<int>(blocks_.size());
    blocks_.push_back(std::move(b));
  }
  for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
    Block& b = blocks_[bi];
    auto bl = std::make_shared<StateLayout>(b.hi - b.ilo);
    for (int s = 0; s < nv_; ++s) bl->add_cell_var(layout_.cell_var(s));
    for (int i = b.ilo; i < b.hi; ++i)
      for (int s = 0; s < nv_; ++s) b.full_index.push_back(layout_.index(i, s));
    for (int g = 0; g < ng; ++g)
      if (global_cell[g] >= 0 && owner_[global_cell[g]] == static_cast<int>(bi)) {
        bl->add_global_var(layout_.global_var(g));
        b.full_index.push_back(layout_.global_index(g));
      }
    bl->freeze();
    auto view =
        std::make_unique<BlockView>(full, *this, static_cast<int>(bi), b.full_index);
    b.view = view.get();
    std::vector<std::unique_ptr<PhysicsModule>> mods;
    mods.push_back(std::move(view));
    b.model = std::make_unique<DiskModel>(bl, std::move(mods));
    IntegratorOptions opt = full_opt;
    opt.rtol *= tol_scale;
    opt.atol.clear();
    opt.constraints.clear();
    for (long k : b.full_index) {
      const int cell = layout_.cell_of(k);
      const bool overlap_cell = cell >= 0 && cell < b.lo;
      opt.atol.push_back(full_opt.atol[k] * tol_scale *
                         (overlap_cell ? overlap_atol_factor : 1.0));
      if (!full_opt.constraints.empty())
        opt.constraints.push_back(full_opt.constraints[k]);
    }
    std::vector<double> yb;
    for (long k : b.full_index) yb.push_back(y0[k]);
    b.view->base() = base_;
    b.cvode = std::make_unique<CvodeIntegrator>(*b.model, 0.0, yb, opt);
    b.hist.n = static_cast<int>(yb.size());
    std::vector<double> d(yb.size());
    b.model->rhs(0.0, yb, d);
    b.hist.push(0.0, yb, d);
  }
}

void Coupler::fill_ghosts(int bi, double t, std::span<double> y_full) const {
  const Block& b = blocks_[bi];
  const int n = layout_.n_cells();
  for (int c : {b.ilo - 2, b.ilo - 1, b.hi, b.hi + 1}) {
    if (c < 0 || c >= n) continue;
    const Block& o = blocks_[owner_[c]];
    for (int s = 0; s < nv_; ++s)
      y_full[layout_.index(c, s)] = o.advanced ? o.hist.at(t, (c - o.ilo) * nv_ + s)
                                    : extrapolate_ && !o.hist.t.empty()
                                        ? o.hist.extrapolate(t, (c - o.ilo) * nv_ + s)
                                        : base_[layout_.index(c, s)];
  }
}

std::vector<double> Coupler::gather() const {
  std::vector<double> y = base_;
  for (const Block& b : blocks_) {
    const auto s = b.cvode->state();
    for (std::size_t k = 0; k < b.full_index.size(); ++k) {
      const int cell = layout_.cell_of(b.full_index[k]);
      if (cell < 0 || cell >= b.lo) y[b.full_index[k]] = s[k];  // not the overlap
    }
  }
  return y;
}

std::vector<double> Coupler::run(int sub) {
  const auto times = sim_.output_times();
  for (std::size_t k = 1; k < times.size(); ++k) {
    const double ta = times[k - 1], tb = times[k];
    for (int j = 1; j <= sub; ++j) {
      const double t1 = j == sub   ? tb
                        : ta > 0.0 ? ta * std::pow(tb / ta, double(j) / sub)
                                   : ta + (tb - ta) * double(j) / sub;
      for (Block& b : blocks_) {
        b.advanced = false;
        std::copy(base_.begin(), base_.end(), b.view->base().begin());
      }
      for (int bi = n_blocks() - 1; bi >= 0; --bi) {
        Block& b = blocks_[bi];
        b.hist.keep_last();
        std::vector<double> d(b.full_index.size());
        b.cvode->advance_to(t1, [&](double t, long) {
          b.cvode->derivative(d);
          b.hist.push(t, b.cvode->state(), d);
        });
        b.advanced = true;
      }
      base_ = gather();
    }
    std::vector<long> per_block;
    for (const Block& b : blocks_) per_block.push_back(b.cvode->stats().nst);
    interval_steps_.push_back(per_block);
    for (Block& b : blocks_) {
      const std::vector<double> yb(b.cvode->state().begin(), b.cvode->state().end());
      b.cvode->reinit(tb, yb);
    }
  }
  return base_;
}

long Coupler::total(long SolverStats::*counter, bool per_cell) const {
  long s = 0;
  for (int b = 0; b < n_blocks(); ++b)
    s += blocks_[b].cvode->stats().*counter * (per_cell ? block_cells(b) : 1);
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> blocks, subs, overlaps;
  double tol_scale = 1.0, overlap_atol = 1.0;
  bool extrapolate = false, profile = false;
  std::vector<std::string> sets;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--block") && i + 1 < argc) {
      blocks.push_back(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--sub") && i + 1 < argc) {
      subs.push_back(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--tol-scale") && i + 1 < argc) {
      tol_scale = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--overlap") && i + 1 < argc) {
      overlaps.push_back(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--overlap-atol") && i + 1 < argc) {
      overlap_atol = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--profile")) {
      profile = true;
    } else if (!std::strcmp(argv[i], "--extrapolate")) {
      extrapolate = true;
    } else if (!std::strcmp(argv[i], "--set") && i + 1 < argc) {
      sets.emplace_back(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: bench_lts [--block B ...] [--sub K ...] [--tol-scale X] "
                   "[--set key=value ...]\n");
      return 2;
    }
  }
  if (blocks.empty()) blocks = {16};
  if (subs.empty()) subs = {1};
  if (overlaps.empty()) overlaps = {0};
  const std::string scene = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const Config cfg = load_scene(scene, sets);
  Simulation sim(cfg);
  const int n = sim.grid().n_cells();

  // the coupled run, as panoptic run integrates it
  const auto times = sim.output_times();
  auto t0 = std::chrono::steady_clock::now();
  CvodeIntegrator cvode(sim.model(), times.front(), sim.initial_state(),
                        sim.integrator_options());
  std::vector<long> ref_steps;  // cumulative, at the end of every snapshot interval
  for (std::size_t k = 1; k < times.size(); ++k) {
    cvode.advance_to(times[k]);
    const std::vector<double> y(cvode.state().begin(), cvode.state().end());
    cvode.reinit(times[k], y);
    ref_steps.push_back(cvode.stats().nst);
  }
  const double wall_ref = seconds_since(t0);
  const FiducialOutcome ref = measure_outcome(sim, cvode.state());
  const long ref_cell_steps = cvode.stats().nst * n;
  std::printf("params/fiducial.toml to %g yr, %d cells", cfg.real("output.t_end_yr"), n);
  for (const auto& s : sets) std::printf(", %s", s.c_str());
  std::printf(
      "\ncoupled: %ld steps = %.3g cell-steps, %ld RHS, %.2f s; m_pl = %.5g M_earth, "
      "pebbles through the snow line %.5g M_earth, budget %.1e\n\n",
      cvode.stats().nst, double(ref_cell_steps), cvode.stats().nfe, wall_ref, ref.m_pl,
      ref.m_peb_snow, ref.budget);
  std::printf(
      "| B | overlap | blocks | macro per snapshot | tol scale | block steps | "
      "cell-steps | vs "
      "coupled | cell-RHS vs coupled | cell-Jac vs coupled | m_pl error | m_peb_snow "
      "error | Sigma_d(t_end) "
      "L1 | budget | wall [s] "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const Grid& g = sim.grid();
  for (int bsize : blocks) {
    for (int ov : overlaps)
      for (int sub : subs) {
        t0 = std::chrono::steady_clock::now();
        Coupler lts(sim, bsize, ov, tol_scale, overlap_atol, extrapolate);
        std::vector<double> y;
        try {
          y = lts.run(sub);
        } catch (const std::exception& e) {
          std::printf("| %d | %d | %d | %d | %g | failed: %s |\n", bsize, ov,
                      lts.n_blocks(), sub, tol_scale, e.what());
          std::fflush(stdout);
          continue;
        }
        const double wall = seconds_since(t0);
        const FiducialOutcome o = measure_outcome(sim, y);
        std::printf(
            "| %d | %d | %d | %d | %g | %ld | %.3g | %.3f | %.3f | %.3f | %.2e | %.2e | "
            "%.2e | %.1e | %.1f |\n",
            bsize, ov, lts.n_blocks(), sub, tol_scale,
            lts.total(&SolverStats::nst, false), double(lts.total(&SolverStats::nst)),
            double(lts.total(&SolverStats::nst)) / double(ref_cell_steps),
            double(lts.total(&SolverStats::nfe)) / double(cvode.stats().nfe * n),
            double(lts.total(&SolverStats::nje)) / double(cvode.stats().nje * n),
            std::abs(o.m_pl / ref.m_pl - 1.0),
            std::abs(o.m_peb_snow / ref.m_peb_snow - 1.0),
            sigma_l1(g, o.sigma_d, ref.sigma_d), o.budget, wall);
        if (profile) {
          std::printf(
              "\n  | interval ends [yr] | coupled cell-steps | blocks' cell-steps | most "
              "steps: block (cells) | its steps |\n  |---|---|---|---|---|\n");
          for (std::size_t k = 0; k < ref_steps.size(); ++k) {
            long cs = 0, best = 0;
            int arg = 0;
            for (int b = 0; b < lts.n_blocks(); ++b) {
              const long st =
                  lts.interval_steps_[k][b] - (k ? lts.interval_steps_[k - 1][b] : 0);
              cs += st * lts.block_cells(b);
              if (st > best) best = st, arg = b;
            }
            std::printf("  | %.4g | %ld | %ld | %d (%d) | %ld |\n",
                        times[k + 1] / units::kYr,
                        (ref_steps[k] - (k ? ref_steps[k - 1] : 0)) * n, cs, arg,
                        lts.block_cells(arg), best);
          }
          std::printf("\n");
        }
        std::fflush(stdout);
      }
  }
  return 0;
}
