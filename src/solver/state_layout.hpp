#pragma once
//! Layout of the CVODE state vector (spec §9, style guide "StateLayout").
//! Cell-major and interleaved: y[cell * n_cell_vars + slot], then the global variables
//! (booked masses) after the last cell. A variable exists only when the process that owns
//! it is on: modules register their variables at set-up, before the layout is frozen.
#include <optional>
#include <string>
#include <vector>

namespace panoptic {

struct VarInfo {
  std::string name;         //!< short name used in output and messages ("sigma_d")
  std::string units;        //!< cgs units of the state component
  std::string description;  //!< one line
  double abs_scale = 1.0;   //!< typical magnitude; CVODE atol = atol_rel * abs_scale
  bool nonnegative = true;  //!< CVODE constraint y >= 0
  //! false for a booked quantity that no right-hand side reads back (a quadrature such
  //! as Sigma_pl): it is integrated with the system but left out of CVODE's error test
  //! and Newton convergence test, as CVODES does with quadrature variables by default
  //! (errconQ = false). Its accuracy then follows that of the variables it integrates.
  //! (The booked global masses stay in the test: physics/modules/dust_transport.cpp says
  //! why.) Such a variable must not be `nonnegative`: without an error weight CVODE's
  //! constraint correction would clip it to zero at any size, losing the clipped amount
  //! from the budget.
  bool error_test = true;
};

class StateLayout {
 public:
  explicit StateLayout(int n_cells) : n_cells_(n_cells) {}

  //! Registers a per-cell variable; returns its slot. Only before freeze().
  int add_cell_var(VarInfo info);
  //! Registers a global variable; returns its global slot. Only before freeze().
  int add_global_var(VarInfo info);
  void freeze() { frozen_ = true; }
  //! Lets a cell hold more variables than kMaxLocalDerivs / 2, the most a module can
  //! seed as AD directions over a two-cell stencil: only for a layout whose modules seed
  //! no whole cell state (the size distribution of spec §15, physics/modules/
  //! size_distribution.hpp, whose cells hold a variable per mass bin).
  void allow_wide_cells() { wide_cells_ = true; }

  int n_cells() const { return n_cells_; }
  int n_cell_vars() const { return static_cast<int>(cell_vars_.size()); }
  int n_global_vars() const { return static_cast<int>(global_vars_.size()); }
  long size() const {
    return static_cast<long>(n_cells_) * n_cell_vars() + n_global_vars();
  }

  long index(int cell, int slot) const {
    return static_cast<long>(cell) * n_cell_vars() + slot;
  }
  long global_index(int g) const {
    return static_cast<long>(n_cells_) * n_cell_vars() + g;
  }
  const VarInfo& cell_var(int slot) const { return cell_vars_[slot]; }
  const VarInfo& global_var(int g) const { return global_vars_[g]; }
  std::optional<int> find_cell_var(const std::string& name) const;

  //! The cell of component `i`, or -1 for a global variable.
  int cell_of(long i) const;
  //! The VarInfo of component `i`.
  const VarInfo& info_of(long i) const;
  //! "sigma_d in cell 17" / "m_out_dust (global)".
  std::string describe(long i) const;
  //! "sigma_d,sigma_g|m_out_dust": compared when restarting from a checkpoint.
  std::string signature() const;

 private:
  int n_cells_;
  bool frozen_ = false;
  bool wide_cells_ = false;
  std::vector<VarInfo> cell_vars_, global_vars_;
};

}  // namespace panoptic
