// Benchmark (not a test): block-local time stepping of the fiducial scene, built and run,
// for the speed targets of issues 3 and 7 (tests/bench/README.md, "Performance":
// `bench_fiducial --lts` bounds what blocks of B cells with their own step sizes could
// save; this measures what a simple coupling of such blocks actually takes, and what it
// costs in accuracy).
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
// With --chase the inner neighbour is not frozen: a block sees it move linearly over
// the macro step, from where it saw it at the end of the last one (no jump: the block's
// BDF history stays valid) to the neighbour's state at T0 extrapolated along its last
// macro step's secant; with --reset-overlap the overlap cells are set to their owners'
// state at every snapshot, where the blocks restart anyway.
//
// Each block's right-hand side and Jacobian are those of the whole-disk model on the
// block's cells only (CellRangeModel, tests/bench/cell_range_model.hpp, which evaluates
// the modules on a cell range; checked against the whole model's rows for every block at
// set-up), so the wall time is that of the scheme, with the bookkeeping of this prototype
// (dense output of every step, ghost interpolation). The cost is also reported as block
// steps and cell-steps (steps x cells) against the coupled run's.
//
// Usage: build/tests/bench_lts [--block B ...] [--overlap V ...] [--sub K ...]
//            [--tol-scale X] [--overlap-atol F] [--extrapolate] [--chase]
//            [--reset-overlap] [--book-faces] [--reflux] [--reflux-larger]
//            [--flux-coupling] [--mean-flux]
//            [--profile]
//            [--set key=value ...]
// (measurements: tests/bench/README.md, "Performance", and
// tests/bench/results/performance_log.md)
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
//   --chase:       the inner neighbour continuous in time, moving towards an
//                  extrapolation (above)
//   --reset-overlap: the overlap cells set to their owners' state at every snapshot
//   --book-faces:  each face between two blocks booked in both blocks' views (the mass
//                  its inner cell gains through it), and the largest defect between the
//                  two over a snapshot interval reported
//   --reflux:      that defect (of every transported variable) also put into the inner
//                  cell at every snapshot, which would conserve mass as the coupled run
//                  does
//   --reflux-larger: the same, into whichever of the face's two cells holds more dust
//   --flux-coupling: a block's outermost cell receives through its outer face not what
//                  the block computes there from its ghosts, but what the outer block
//                  booked through that face (the time derivative of that booking's dense
//                  output): both blocks then agree on the face up to the integration
//                  error of the bookings (implies --book-faces)
//   --mean-flux:   the same with the outer block's mean flux over the macro step (a
//                  constant per macro step)
//   --profile:     cell-steps per snapshot interval, coupled and blocks
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "physics/modules/dust_transport.hpp"
#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "src/solver/grid.hpp"
#include "tests/bench/cell_range_model.hpp"
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
  //! Time derivative of the cubic Hermite interpolant of component k at time tq (the
  //! recorded derivative outside the records).
  double rate_at(double tq, int k) const { return hermite(tq, k, true); }
  //! Component k's mean rate of change from the first record to the last (0 with one).
  double mean_rate(int k) const {
    const std::size_t m = t.size();
    if (m < 2) return 0.0;
    return (y[(m - 1) * n + k] - y[k]) / (t.back() - t.front());
  }
  //! Cubic Hermite interpolation of component k at time tq.
  double at(double tq, int k) const { return hermite(tq, k, false); }

 private:
  double hermite(double tq, int k, bool rate) const {
    const std::size_t m = t.size();
    const std::vector<double>& end = rate ? dy : y;
    if (m == 1 || tq <= t.front()) return end[k];
    if (tq >= t.back()) return end[(m - 1) * n + k];
    const std::size_t i =
        static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), tq) - t.begin()) -
        1;
    const double h = t[i + 1] - t[i], s = (tq - t[i]) / h;
    const double s2 = s * s, s3 = s2 * s;
    const std::size_t a = i * n + k, b = (i + 1) * n + k;
    if (rate)
      return (6 * s2 - 6 * s) * (y[a] - y[b]) / h + (3 * s2 - 4 * s + 1) * dy[a] +
             (3 * s2 - 2 * s) * dy[b];
    return (2 * s3 - 3 * s2 + 1) * y[a] + (s3 - 2 * s2 + s) * h * dy[a] +
           (-2 * s3 + 3 * s2) * y[b] + (s3 - s2) * h * dy[b];
  }
};

class Coupler;

//! One block's model: the whole-disk model seen through the block's components, with
//! the neighbours' cells filled in by the Coupler.
class BlockView : public PhysicsModule {
 public:
  //! [eval_lo, eval_hi): the cells whose rows (and faces' globals) the block needs.
  BlockView(const DiskModel& full, const Coupler& coupler, int block,
            std::vector<long> full_index, int eval_lo, int eval_hi);
  //! --book-faces: books, as the block's variables `compact` (past its whole-disk ones),
  //! what cell face - 1 gains of each transported variable `slots` through face `face`
  //! in the block's view (rows of CellRangeModel::rhs_cells on the empty range [face,
  //! face): that face alone). `prescribed` (--flux-coupling, the block's outer face): the
  //! block's cell face - 1 receives instead what the outer block booked through that face
  //! (the time derivative of its dense output), and books that.
  void add_booking(int face, const std::vector<int>& slots,
                   const std::vector<long>& compact, const Grid& grid, bool prescribed);
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
  int eval_lo() const { return eval_lo_; }
  int eval_hi() const { return eval_hi_; }

 private:
  void fill(double t, std::span<const double> y) const;
  struct Entry {
    long row, col, pos;
  };
  struct Booking {
    int face;
    double area;               // of cell face - 1 [cm^2]
    bool prescribed;           // fed by the outer block's booking
    std::vector<long> row;     // per slot: whole-disk row of cell face - 1
    std::vector<long> booked;  // per slot: the booked variable
    std::vector<long> own;     // per slot: the block's row of cell face - 1 (prescribed)
    //! per slot: the face's Jacobian entries of row[k] to take over (compact row: the
    //! booked variable, or with `prescribed` the own row, whose face terms are removed)
    std::vector<std::vector<Entry>> d;
  };
  std::vector<Booking> bookings_;
  mutable std::vector<double> face_ydot_, face_jac_;
  const DiskModel& full_;
  bench::CellRangeModel cells_;
  const Coupler& coupler_;
  int block_, eval_lo_, eval_hi_;
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
  // --chase: the inner ghost cells' (ilo - 2, ilo - 1) values at the macro step's start
  // and end, between which the block sees them move linearly (nv per cell, -1 unused)
  std::vector<double> ghost_start, ghost_target;
  // --book-faces: what cell lo - 1 gains through face lo and cell hi - 1 through face
  // hi of each transported variable, booked in this block's view (the block's variables;
  // empty: none)
  std::vector<long> q_lo, q_hi;
  // their values at the last snapshot (they run on through the restarts, so that the
  // dense output the inner block reads under --flux-coupling has no jump)
  std::vector<double> q_lo_start, q_hi_start;
};

void view_check(const DiskModel& full, const Block& b, const BlockView& view,
                const std::vector<double>& y0);

//! How the blocks are coupled (the command line's switches; see the header).
struct Coupling {
  double tol_scale = 1.0, overlap_atol_factor = 1.0;
  bool extrapolate = false;    // inner neighbours: extrapolated from T0, not frozen
  bool chase = false;          // inner neighbours: continuous, towards an extrapolation
  bool reset_overlap = false;  // overlap cells set to their owners' at every snapshot
  bool reflux = false;         // each face's defect between its two blocks put back
  bool reflux_larger = false;  // ... into the face's cell with more dust, not the inner
  bool book_faces = false;     // the faces booked in both views (the others imply it)
  bool flux_coupling = false;  // a block's outer face fed by the outer block's booking
  bool mean_flux = false;      // ... with its mean over the macro step
  bool books() const {
    return book_faces || reflux || reflux_larger || flux_coupling || mean_flux;
  }
  bool prescribed() const { return flux_coupling || mean_flux; }
};

class Coupler {
 public:
  Coupler(Simulation& sim, int block_size, int overlap, const Coupling& how);
  //! Integrates the scene to t_end with K macro steps per snapshot interval; returns
  //! the whole-disk state at t_end.
  std::vector<double> run(int sub);
  //! Writes the neighbours' cells of block b at time t into y_full.
  void fill_ghosts(int b, double t, std::span<double> y_full) const;
  //! --flux-coupling: the rate [g s^-1, or its log-moment's] at which block b's cell
  //! hi - 1 gains transported variable k through face hi, as its outer block booked it.
  //! None before the outer block has a dense output (the blocks' set-up).
  std::optional<double> prescribed_gain(int b, int k, double t) const {
    const Block& o = blocks_[owner_[blocks_[b].hi]];
    if (o.hist.t.empty() || o.q_lo.empty()) return std::nullopt;
    const int c = static_cast<int>(o.q_lo[k]);
    // --mean-flux: a constant over the macro step (BDF integrates it exactly within the
    // step, not across the jump to the next step's: performance_log)
    return how_.mean_flux ? o.hist.mean_rate(c) : o.hist.rate_at(t, c);
  }
  //! A solver counter (&SolverStats::nst, nfe, nje) summed over the blocks, each
  //! weighted by its cells (overlap included) or, with per_cell = false, not.
  long total(long SolverStats::*counter, bool per_cell = true) const;
  int n_blocks() const { return static_cast<int>(blocks_.size()); }
  int block_cells(int b) const { return blocks_[b].hi - blocks_[b].ilo; }
  //! Per snapshot interval: every block's cumulative step count at its end.
  std::vector<std::vector<long>> interval_steps_;
  //! The blocks' callback wall times, summed.
  CallbackTimes times_;

 private:
  std::vector<double> gather() const;
  Simulation& sim_;
  const StateLayout& layout_;
  int nv_ = 0;
  std::vector<Block> blocks_;
  std::vector<int> owner_;  // per cell: its block
  std::vector<double> base_;
  Coupling how_;
  std::vector<int> tslots_;  // the transported cell variables (sigma_d first)
  void settle_faces();

 public:
  //! --book-faces/--reflux: the largest defect of a face over a snapshot interval (the
  //! mass the outer block sent minus what the inner one received) as a share of the
  //! disk's dust mass, its inner cell, and the start of its last macro step [s]; and the
  //! sum of all of them (each a share of the disk's dust mass then)
  double worst_defect_ = 0.0, worst_defect_t_ = 0.0, sum_defect_ = 0.0;
  //! the largest defect against the dust then in the fuller of its face's two cells
  double worst_defect_face_ = 0.0;
  int worst_defect_cell_ = -1;
  void set_ghost_targets(double t0, double t1, bool fresh);
  std::vector<double> prev_base_;  // the state at the previous macro step's start
  double t_prev_ = -1.0, t0_ = 0.0, t1_ = 0.0;
};

BlockView::BlockView(const DiskModel& full, const Coupler& coupler, int block,
                     std::vector<long> full_index, int eval_lo, int eval_hi)
    : full_(full),
      cells_(full),
      coupler_(coupler),
      block_(block),
      eval_lo_(eval_lo),
      eval_hi_(eval_hi),
      full_index_(std::move(full_index)) {
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

void BlockView::add_booking(int face, const std::vector<int>& slots,
                            const std::vector<long>& compact, const Grid& grid,
                            bool prescribed) {
  const StateLayout& L = full_.layout();
  Booking bk{face, grid.area(face - 1), prescribed, {}, compact, {}, {}};
  std::vector<long> compact_of(L.size(), -1);
  for (std::size_t k = 0; k < full_index_.size(); ++k)
    compact_of[full_index_[k]] = static_cast<long>(k);
  const auto cp = full_.pattern().col_ptr();
  const auto ri = full_.pattern().row_index();
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const long row = L.index(face - 1, slots[k]);
    bk.row.push_back(row);
    bk.own.push_back(compact_of[row]);
    if (prescribed && compact_of[row] < 0)
      throw std::logic_error("bench_lts: a prescribed face outside its block");
    std::vector<Entry> d;
    for (long c = 0; c < L.size(); ++c)
      for (long p = cp[c]; p < cp[c + 1]; ++p)
        if (ri[p] == row && compact_of[c] >= 0)
          d.push_back({prescribed ? compact_of[row] : compact[k], compact_of[c], p});
    if (!prescribed)  // the booked rows' pattern (the own rows have theirs)
      for (const auto& e : d) entries_.push_back({e.row, e.col, -1});
    bk.d.push_back(std::move(d));
  }
  bookings_.push_back(std::move(bk));
  face_ydot_.assign(L.size(), 0.0);
  face_jac_.assign(full_.pattern().nnz(), 0.0);
}

void BlockView::fill(double t, std::span<const double> y) const {
  for (std::size_t k = 0; k < full_index_.size(); ++k) y_full_[full_index_[k]] = y[k];
  coupler_.fill_ghosts(block_, t, y_full_);
}

void BlockView::add_rhs(double t, std::span<const double> y,
                        std::span<double> ydot) const {
  fill(t, y);
  cells_.rhs_cells(t, y_full_, ydot_full_, eval_lo(), eval_hi());
  for (std::size_t k = 0; k < full_index_.size(); ++k)
    ydot[k] += ydot_full_[full_index_[k]];
  for (const Booking& bk : bookings_) {
    cells_.rhs_cells(t, y_full_, face_ydot_, bk.face, bk.face);
    for (std::size_t k = 0; k < bk.row.size(); ++k) {
      const auto gain = bk.prescribed
                            ? coupler_.prescribed_gain(block_, static_cast<int>(k), t)
                            : std::nullopt;
      if (!gain) {
        ydot[bk.booked[k]] += face_ydot_[bk.row[k]] * bk.area;
        continue;
      }
      ydot[bk.own[k]] += *gain / bk.area - face_ydot_[bk.row[k]];
      ydot[bk.booked[k]] += *gain;
    }
  }
}

void BlockView::add_jacobian(double t, std::span<const double> y,
                             JacobianValues& jac) const {
  fill(t, y);
  cells_.jacobian_cells(t, y_full_, jac_full_, eval_lo(), eval_hi());
  for (const auto& e : entries_)
    if (e.pos >= 0) jac.add(e.row, e.col, jac_full_[e.pos]);
  for (const Booking& bk : bookings_) {
    cells_.jacobian_cells(t, y_full_, face_jac_, bk.face, bk.face);
    for (const auto& d : bk.d)
      for (const auto& e : d)
        jac.add(e.row, e.col,
                bk.prescribed ? -face_jac_[e.pos] : face_jac_[e.pos] * bk.area);
  }
}

Coupler::Coupler(Simulation& sim, int block_size, int overlap, const Coupling& how)
    : sim_(sim), layout_(sim.model().layout()), nv_(layout_.n_cell_vars()), how_(how) {
  const double tol_scale = how.tol_scale;
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
  for (const char* name : {"sigma_d", "q_m", "q_phi"})
    if (const auto slot = layout_.find_cell_var(name)) tslots_.push_back(*slot);
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
    long n_comp = static_cast<long>(b.full_index.size());
    if (how_.books()) {
      // booked quadratures: read by no right-hand side, in the error test (atol below)
      const VarInfo booked{"face_gain", "g", "gained through a block face", 1.0, false};
      for (std::size_t k = 0; k < tslots_.size() && b.lo > 0; ++k)
        bl->add_global_var(booked), b.q_lo.push_back(n_comp++);
      for (std::size_t k = 0; k < tslots_.size() && b.hi < n; ++k)
        bl->add_global_var(booked), b.q_hi.push_back(n_comp++);
    }
    bl->freeze();
    // Its own cells and overlap, and the face inside its owned cells, which feeds the
    // globals it owns with no overlap (CellRangeModel::rhs_cells: cells [lo, hi) read the
    // faces lo..hi).
    auto view =
        std::make_unique<BlockView>(full, *this, static_cast<int>(bi), b.full_index,
                                    std::max(0, std::min(b.ilo, b.lo - 1)), b.hi);
    view_check(full, b, *view, y0);
    if (!b.q_lo.empty()) view->add_booking(b.lo, tslots_, b.q_lo, sim.grid(), false);
    if (!b.q_hi.empty())
      view->add_booking(b.hi, tslots_, b.q_hi, sim.grid(), how_.prescribed());
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
                         (overlap_cell ? how.overlap_atol_factor : 1.0));
      if (!full_opt.constraints.empty())
        opt.constraints.push_back(full_opt.constraints[k]);
    }
    std::vector<double> yb;
    for (long k : b.full_index) yb.push_back(y0[k]);
    // The booked face quantities are in the error test, as the product's booked global
    // masses are (physics/modules/dust_transport.cpp): out of it, CVODE's Newton
    // iteration stops before they converge (its corrections are scaled when gamma has
    // changed since the last set-up), and a booking then misses ~0.3 % of what its rows
    // integrate. atol: that of the variable in the face's inner cell, times the cell's
    // area.
    const auto book_atol = [&](int face, std::size_t k) {
      const long row = layout_.index(face - 1, tslots_[k]);
      return full_opt.atol[row] * tol_scale * sim.grid().area(face - 1);
    };
    for (std::size_t k = 0; k < b.q_lo.size(); ++k)
      opt.atol.push_back(book_atol(b.lo, k));
    for (std::size_t k = 0; k < b.q_hi.size(); ++k)
      opt.atol.push_back(book_atol(b.hi, k));
    while (static_cast<long>(yb.size()) < n_comp) {  // the booked face quantities
      yb.push_back(0.0);
      if (!opt.constraints.empty()) opt.constraints.push_back(0.0);
    }
    b.view->base() = base_;
    b.cvode = std::make_unique<CvodeIntegrator>(*b.model, 0.0, yb, opt);
    b.cvode->set_profile(&times_);
    b.q_lo_start.assign(b.q_lo.size(), 0.0);
    b.q_hi_start.assign(b.q_hi.size(), 0.0);
    b.hist.n = static_cast<int>(yb.size());
    std::vector<double> d(yb.size());
    b.model->rhs(0.0, yb, d);
    b.hist.push(0.0, yb, d);
  }
}

// --chase: over a macro step [T0, T1] a block sees each inner ghost component move
// linearly from where it saw it at the end of the last macro step (continuity: its BDF
// history sees no jump) to the owner's state at T0 extrapolated to T1 along the secant
// of the owner's last macro step (the change limited to half the value); at a snapshot,
// where every block restarts anyway, the start is the owner's state.
void Coupler::set_ghost_targets(double t0, double t1, bool fresh) {
  const bool have_prev = !prev_base_.empty() && t_prev_ < t0 && t_prev_ >= 0.0;
  for (Block& b : blocks_) {
    b.ghost_start.assign(2 * nv_, -1.0);
    if (b.ghost_target.empty()) b.ghost_target.assign(2 * nv_, 0.0);
    for (int j = 0; j < 2; ++j) {
      const int c = b.ilo - 2 + j;
      if (c < 0) continue;
      for (int s = 0; s < nv_; ++s) {
        const long k = layout_.index(c, s);
        const double y0 = base_[k];
        b.ghost_start[j * nv_ + s] = fresh ? y0 : b.ghost_target[j * nv_ + s];
        double target = y0;
        if (have_prev) {
          const double d = (y0 - prev_base_[k]) * (t1 - t0) / (t0 - t_prev_);
          const double lim = 0.5 * std::abs(y0);
          target = y0 + std::clamp(d, -lim, lim);
        }
        b.ghost_target[j * nv_ + s] = target;
      }
    }
  }
  t0_ = t0;
  t1_ = t1;
}

//! The block's rows from CellRangeModel::rhs_cells/jacobian_cells equal the whole model's
//! (at the initial state and a state with growth under way): a block evaluates only its
//! cells, and must still get every row it owns.
void view_check(const DiskModel& full, const Block& b, const BlockView& view,
                const std::vector<double>& y0) {
  std::vector<double> y = y0;
  for (std::size_t k = 0; k < y.size(); ++k)  // a state away from the smooth profile
    y[k] *= 1.0 + 0.3 * std::sin(1.7 * double(k));
  std::vector<double> f(y.size()), fc(y.size());
  std::vector<double> j(full.pattern().nnz()), jc(j.size());
  full.rhs(0.0, y, f);
  const bench::CellRangeModel cells(full);
  cells.rhs_cells(0.0, y, fc, view.eval_lo(), view.eval_hi());
  full.jacobian(0.0, y, j);
  cells.jacobian_cells(0.0, y, jc, view.eval_lo(), view.eval_hi());
  std::vector<char> mine(y.size(), 0);
  for (long k : b.full_index) {
    mine[k] = 1;
    if (f[k] != fc[k]) {
      std::fprintf(stderr,
                   "bench_lts: block of cells [%d, %d) (evaluated on [%d, %d)): row of "
                   "%s is %.17g, the whole model's %.17g\n",
                   b.lo, b.hi, view.eval_lo(), view.eval_hi(),
                   full.layout().describe(k).c_str(), fc[k], f[k]);
      std::exit(1);
    }
  }
  const auto cp = full.pattern().col_ptr();
  const auto ri = full.pattern().row_index();
  for (long c = 0; c < static_cast<long>(y.size()); ++c)
    for (long p = cp[c]; p < cp[c + 1]; ++p)
      if (mine[ri[p]] && mine[c] && j[p] != jc[p]) {
        std::fprintf(stderr,
                     "bench_lts: block Jacobian differs from the whole model's\n");
        std::exit(1);
      }
}

void Coupler::fill_ghosts(int bi, double t, std::span<double> y_full) const {
  const Block& b = blocks_[bi];
  const int n = layout_.n_cells();
  for (int c : {b.ilo - 2, b.ilo - 1, b.hi, b.hi + 1}) {
    if (c < 0 || c >= n) continue;
    const Block& o = blocks_[owner_[c]];
    if (how_.chase && c < b.ilo && !o.advanced && !b.ghost_start.empty()) {
      const double w = std::clamp((t - t0_) / (t1_ - t0_), 0.0, 1.0);
      const int j = c - (b.ilo - 2);
      for (int s = 0; s < nv_; ++s)
        y_full[layout_.index(c, s)] =
            (1.0 - w) * b.ghost_start[j * nv_ + s] + w * b.ghost_target[j * nv_ + s];
      continue;
    }
    for (int s = 0; s < nv_; ++s)
      y_full[layout_.index(c, s)] = o.advanced ? o.hist.at(t, (c - o.ilo) * nv_ + s)
                                    : how_.extrapolate && !o.hist.t.empty()
                                        ? o.hist.extrapolate(t, (c - o.ilo) * nv_ + s)
                                        : base_[layout_.index(c, s)];
  }
}

// --book-faces, at a snapshot (where the blocks restart): the defect of each face
// between two blocks since the last snapshot, what the outer block booked through it
// minus what the inner block's cell received in its own view (Sigma_d, Q_m, Q_phi), is
// measured against the disk's dust; with --reflux it is also put into that cell, so that
// mass would be conserved at every snapshot as in the coupled run, each face's flux
// being the outer block's (the upwind side of the drift). The bookings' values here
// become the starts of the next interval's.
void Coupler::settle_faces() {
  const int sd = tslots_[0];
  double disk_dust = 0.0;  // [g]
  for (int i = 0; i < layout_.n_cells(); ++i)
    disk_dust += base_[layout_.index(i, sd)] * sim_.grid().area(i);
  for (Block& inner : blocks_) {
    if (inner.q_hi.empty()) continue;
    const Block& outer = blocks_[owner_[inner.hi]];
    int c = inner.hi - 1;
    // --reflux-larger: the face's cell with more dust takes the defect (the outer,
    // upwind cell where the inner one is drained), so that no correction empties a cell
    if (how_.reflux_larger &&
        base_[layout_.index(inner.hi, sd)] * sim_.grid().area(inner.hi) >
            base_[layout_.index(c, sd)] * sim_.grid().area(c))
      c = inner.hi;
    for (std::size_t k = 0; k < tslots_.size(); ++k) {
      const double defect =  // [g], or the log-moment's
          (outer.cvode->state()[outer.q_lo[k]] - outer.q_lo_start[k]) -
          (inner.cvode->state()[inner.q_hi[k]] - inner.q_hi_start[k]);
      if (k == 0) {
        const double share = std::abs(defect) / disk_dust;
        const double face_dust =  // [g] the more of the face's two cells
            std::max(
                base_[layout_.index(inner.hi - 1, sd)] * sim_.grid().area(inner.hi - 1),
                base_[layout_.index(inner.hi, sd)] * sim_.grid().area(inner.hi));
        worst_defect_face_ = std::max(worst_defect_face_, std::abs(defect) / face_dust);
        sum_defect_ += share;
        if (share > worst_defect_) {
          worst_defect_ = share;
          worst_defect_cell_ = c;
          worst_defect_t_ = t_prev_;
        }
      }
      if (how_.reflux || how_.reflux_larger)
        base_[layout_.index(c, tslots_[k])] += defect / sim_.grid().area(c);
    }
  }
  for (Block& b : blocks_) {
    b.q_lo_start.clear();
    b.q_hi_start.clear();
    for (long q : b.q_lo) b.q_lo_start.push_back(b.cvode->state()[q]);
    for (long q : b.q_hi) b.q_hi_start.push_back(b.cvode->state()[q]);
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
    double b_t0 = ta;
    for (int j = 1; j <= sub; ++j) {
      const double t1 = j == sub   ? tb
                        : ta > 0.0 ? ta * std::pow(tb / ta, double(j) / sub)
                                   : ta + (tb - ta) * double(j) / sub;
      for (Block& b : blocks_) {
        b.advanced = false;
        std::copy(base_.begin(), base_.end(), b.view->base().begin());
      }
      const double t0 = j == 1 ? ta : b_t0;
      if (how_.chase) set_ghost_targets(t0, t1, j == 1);
      for (int bi = n_blocks() - 1; bi >= 0; --bi) {
        Block& b = blocks_[bi];
        b.hist.keep_last();
        std::vector<double> d(b.cvode->state().size());
        try {
          b.cvode->advance_to(t1, [&](double t, long) {
            b.cvode->derivative(d);
            b.hist.push(t, b.cvode->state(), d);
          });
        } catch (const std::exception& e) {
          throw std::runtime_error(std::string(e.what()) + " (block of cells [" +
                                   std::to_string(b.lo) + ", " + std::to_string(b.hi) +
                                   "))");
        }
        b.advanced = true;
      }
      prev_base_ = base_;
      t_prev_ = t0;
      b_t0 = t1;
      base_ = gather();
    }
    std::vector<long> per_block;
    for (const Block& b : blocks_) per_block.push_back(b.cvode->stats().nst);
    interval_steps_.push_back(per_block);
    if (how_.books()) settle_faces();
    for (Block& b : blocks_) {
      std::vector<double> yb(b.cvode->state().begin(), b.cvode->state().end());
      for (std::size_t k = 0; k < b.full_index.size(); ++k) {  // refluxed owned cells
        const int cell = layout_.cell_of(b.full_index[k]);
        if (cell >= b.lo) yb[k] = base_[b.full_index[k]];
      }
      if (how_.reset_overlap)
        for (std::size_t k = 0; k < b.full_index.size(); ++k) {
          const int cell = layout_.cell_of(b.full_index[k]);
          if (cell >= 0 && cell < b.lo) yb[k] = base_[b.full_index[k]];
        }
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

void print_defect(const Coupler& lts) {
  if (lts.worst_defect_cell_ < 0) return;
  std::printf(
      "  (largest face defect over a snapshot interval, the mass the outer block sent "
      "less what the inner one received: %.3g of the disk's dust mass, into cell %d, in "
      "the interval ending after %.4g yr; the sum of all: %.3g; the largest against the "
      "dust in the fuller of the face's two cells: %.3g)\n",
      lts.worst_defect_, lts.worst_defect_cell_, lts.worst_defect_t_ / units::kYr,
      lts.sum_defect_, lts.worst_defect_face_);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> blocks, subs, overlaps;
  Coupling how;
  bool profile = false;
  std::vector<std::string> sets;
  const std::pair<const char*, bool*> switches[] = {
      {"--profile", &profile},           {"--extrapolate", &how.extrapolate},
      {"--chase", &how.chase},           {"--reset-overlap", &how.reset_overlap},
      {"--reflux", &how.reflux},         {"--reflux-larger", &how.reflux_larger},
      {"--book-faces", &how.book_faces}, {"--flux-coupling", &how.flux_coupling},
      {"--mean-flux", &how.mean_flux}};
  const auto switch_named = [&](const char* arg) -> bool* {
    for (const auto& [name, flag] : switches)
      if (!std::strcmp(arg, name)) return flag;
    return nullptr;
  };
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--block") && i + 1 < argc) {
      blocks.push_back(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--sub") && i + 1 < argc) {
      subs.push_back(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--tol-scale") && i + 1 < argc) {
      how.tol_scale = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--overlap") && i + 1 < argc) {
      overlaps.push_back(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--overlap-atol") && i + 1 < argc) {
      how.overlap_atol_factor = std::atof(argv[++i]);
    } else if (bool* flag = switch_named(argv[i])) {
      *flag = true;
    } else if (!std::strcmp(argv[i], "--set") && i + 1 < argc) {
      sets.emplace_back(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: bench_lts [--block B ...] [--overlap V ...] [--sub K ...] "
                   "[--tol-scale X] [--overlap-atol F] [--extrapolate] [--chase] "
                   "[--reset-overlap] [--book-faces] [--reflux] [--reflux-larger] "
                   "[--flux-coupling] [--mean-flux] "
                   "[--profile] [--set key=value ...]\n");
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
  CallbackTimes ref_times;
  cvode.set_profile(&ref_times);
  std::vector<long> ref_steps;  // cumulative, at the end of every snapshot interval
  for (std::size_t k = 1; k < times.size(); ++k) {
    cvode.advance_to(times[k]);
    const std::vector<double> y(cvode.state().begin(), cvode.state().end());
    cvode.reinit(times[k], y);
    ref_steps.push_back(cvode.stats().nst);
  }
  const double wall_ref = seconds_since(t0);
  std::printf(
      "coupled run's wall in RHS %.3f s, Jacobian %.3f s, KLU set-up %.3f s, solve %.3f "
      "s; "
      "the rest %.3f s\n",
      ref_times.rhs_s, ref_times.jac_s, ref_times.lsetup_s, ref_times.lsolve_s,
      wall_ref - ref_times.rhs_s - ref_times.jac_s - ref_times.lsetup_s -
          ref_times.lsolve_s);
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
        Coupler lts(sim, bsize, ov, how);
        std::vector<double> y;
        try {
          y = lts.run(sub);
        } catch (const std::exception& e) {
          std::printf("| %d | %d | %d | %d | %g | failed: %s |\n", bsize, ov,
                      lts.n_blocks(), sub, how.tol_scale, e.what());
          print_defect(lts);
          std::fflush(stdout);
          continue;
        }
        const double wall = seconds_since(t0);
        const FiducialOutcome o = measure_outcome(sim, y);
        std::printf(
            "| %d | %d | %d | %d | %g | %ld | %.3g | %.3f | %.3f | %.3f | %.2e | %.2e | "
            "%.2e | %.1e | %.1f |\n",
            bsize, ov, lts.n_blocks(), sub, how.tol_scale,
            lts.total(&SolverStats::nst, false), double(lts.total(&SolverStats::nst)),
            double(lts.total(&SolverStats::nst)) / double(ref_cell_steps),
            double(lts.total(&SolverStats::nfe)) / double(cvode.stats().nfe * n),
            double(lts.total(&SolverStats::nje)) / double(cvode.stats().nje * n),
            std::abs(o.m_pl / ref.m_pl - 1.0),
            std::abs(o.m_peb_snow / ref.m_peb_snow - 1.0),
            sigma_l1(g, o.sigma_d, ref.sigma_d), o.budget, wall);
        const CallbackTimes& tm = lts.times_;
        std::printf(
            "  (blocks' wall in RHS %.3f s, Jacobian %.3f s, KLU set-up %.3f s, solve "
            "%.3f "
            "s; the rest %.3f s)\n",
            tm.rhs_s, tm.jac_s, tm.lsetup_s, tm.lsolve_s,
            wall - tm.rhs_s - tm.jac_s - tm.lsetup_s - tm.lsolve_s);
        std::printf(
            "  (failures, per block and in the coupled run: error tests %.1f / %ld, "
            "Newton %.1f / %ld; Jacobians %.1f / %ld)\n",
            double(lts.total(&SolverStats::netf, false)) / lts.n_blocks(),
            cvode.stats().netf,
            double(lts.total(&SolverStats::nncf, false)) / lts.n_blocks(),
            cvode.stats().nncf,
            double(lts.total(&SolverStats::nje, false)) / lts.n_blocks(),
            cvode.stats().nje);
        print_defect(lts);
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
