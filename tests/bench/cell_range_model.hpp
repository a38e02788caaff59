#pragma once
//! The whole-disk model evaluated on a range of cells, for block-local time stepping
//! (tests/bench/bench_lts.cpp, a prototype on no path of `panoptic run`): the rows of
//! cells [lo, hi) and of the globals fed through the faces lo..hi. The modules with local
//! or face-by-face terms (DustTransport, PorousGrowth, Planetesimals) have a range form
//! (physics/modules/cell_range_form.hpp: their add_rhs / add_jacobian are that form on
//! every cell); any other module is evaluated on the whole grid. Kept out of the module
//! seam (PhysicsModule, DiskModel), which every run uses.
#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>

#include "physics/modules/dust_transport.hpp"
#include "physics/modules/planetesimals.hpp"
#include "physics/modules/porous_growth.hpp"
#include "src/solver/disk_model.hpp"

namespace panoptic::bench {

class CellRangeModel {
 public:
  explicit CellRangeModel(const DiskModel& model) : model_(model) {}

  //! The model's rhs() on the rows of cells [lo, hi) and the globals its faces lo..hi
  //! feed; the other rows of ydot are left undefined. Throws std::invalid_argument for
  //! a range not within [0, n).
  void rhs_cells(double t, std::span<const double> y, std::span<double> ydot, int lo,
                 int hi) const {
    // The rows the modules' range loops write besides their own (the faces' other
    // cells) are cleared too; a module without a range loop writes every row, and the
    // rows outside [lo - 1, hi + 1) then hold sums of earlier calls: undefined.
    const StateLayout& layout = model_.layout();
    const int n = layout.n_cells();
    check_range(lo, hi, n);
    std::fill(ydot.begin() + layout.index(std::max(0, lo - 1), 0),
              ydot.begin() + layout.index(std::min(n, hi + 1), 0), 0.0);
    std::fill(ydot.begin() + layout.index(n, 0), ydot.end(), 0.0);  // the globals
    for (const auto& m : model_.modules())
      if (!with_range_form(*m,
                           [&](const auto& r) { r.add_rhs_cells(t, y, ydot, lo, hi); }))
        m->add_rhs(t, y, ydot);
  }

  //! The model's jacobian() on the same rows; the other values are left undefined.
  void jacobian_cells(double t, std::span<const double> y, std::span<double> values,
                      int lo, int hi) const {
    // The modules write the columns of the cells lo - 2 .. hi + 1 (a face reads two
    // cells each side) and of the globals: those are cleared, in the pattern's column
    // order.
    const StateLayout& layout = model_.layout();
    const int n = layout.n_cells();
    check_range(lo, hi, n);
    const auto cp = model_.pattern().col_ptr();
    std::fill(values.begin() + cp[layout.index(std::max(0, lo - 2), 0)],
              values.begin() + cp[layout.index(std::min(n, hi + 2), 0)], 0.0);
    std::fill(values.begin() + cp[layout.index(n, 0)], values.end(), 0.0);
    JacobianValues jac(model_.pattern(), values);
    for (const auto& m : model_.modules())
      if (!with_range_form(
              *m, [&](const auto& r) { r.add_jacobian_cells(t, y, jac, lo, hi); }))
        m->add_jacobian(t, y, jac);
  }

 private:
  //! Calls f(module) as its concrete type if it has a range form; false if it has none.
  template <class F>
  static bool with_range_form(const PhysicsModule& m, F&& f) {
    if (const auto* p = dynamic_cast<const DustTransport*>(&m)) {
      f(*p);
      return true;
    }
    if (const auto* p = dynamic_cast<const PorousGrowth*>(&m)) {
      f(*p);
      return true;
    }
    if (const auto* p = dynamic_cast<const Planetesimals*>(&m)) {
      f(*p);
      return true;
    }
    return false;
  }

  static void check_range(int lo, int hi, int n) {
    if (lo < 0 || hi > n || lo > hi)
      throw std::invalid_argument("CellRangeModel: cell range [" + std::to_string(lo) +
                                  ", " + std::to_string(hi) + ") is not within [0, " +
                                  std::to_string(n) + ")");
  }

  const DiskModel& model_;
};

}  // namespace panoptic::bench
