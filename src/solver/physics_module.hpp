#pragma once
//! A physical process as seen by the integrator (Cantera getJacobianElements; DustPy's
//! J_hyd + J_coag + ...). Modules *add* their terms to ydot and J, never overwrite, so a
//! scene's model is the sum of the modules it turns on and a process that is off costs
//! nothing.
//!
//! NEW_PROCESS: derive from PhysicsModule (a process whose terms are local to a cell or
//! a face: from CellRangeForm, physics/modules/cell_range_form.hpp), register its
//! variables with the StateLayout in its constructor, declare its snapshot fields
//! (output_fields) and budget terms (budget_terms), add its line to the registry
//! (src/model/module_registry.cpp), its keys to a scene key table (src/scene/keys_*.cpp)
//! and its cross-key rules to src/model/scene_validation.cpp (physics/README.md, Adding a
//! physical process).
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "src/solver/sparsity.hpp"

namespace panoptic {

//! One term of the dust mass budget (spec §8): a place where part of the initial dust
//! mass is now (on the grid, in planetesimals, through r_in, sublimated, ...). The terms
//! sum to the initial dust mass up to the integration error, so a process that removes
//! dust from Sigma_d books what it removes and declares a term (PhysicsModule::
//! budget_terms; the built-in ones in Simulation's constructor): the term is then
//! written to /snapshots/<name> (when `in_snapshots`), to a column of
//! /timeseries/mass_budget, and counted in the budget error, the printed budget and
//! /summary/budget_error.
struct BudgetTerm {
  std::string name;          //!< dataset and column name ("m_out_inner")
  std::string label;         //!< short text for the printed budget ("through r_in")
  std::string description;   //!< dataset description
  bool in_snapshots = true;  //!< false: a column of the time series only (process off)
  std::function<double(std::span<const double>)> mass;  //!< [g] at state y
};

//! One field of the snapshots, /snapshots/<name>, a row per snapshot (style guide,
//! "Output"): declared by the module that owns it (PhysicsModule::output_fields) or by
//! the model (Simulation::output_fields), written with its units and description
//! attributes and listed by `panoptic reference --outputs`.
struct OutputField {
  std::string name;         //!< dataset name ("sigma_d")
  std::size_t width = 0;    //!< values per snapshot (0: one scalar)
  std::string units;        //!< units attribute ("" for a pure number)
  std::string description;  //!< description attribute
  //! The values at state y, in `units`.
  std::function<std::vector<double>(std::span<const double>)> fill;
  //! Written deflated (src/io/h5.hpp, create_stack): set by the model for the fields
  //! wider than the grid (Simulation::make_output_fields).
  bool compressed = false;
};

class PhysicsModule {
 public:
  virtual ~PhysicsModule() = default;
  virtual std::string_view name() const = 0;
  //! Declare every (row, col) this module may ever write. Called once, at set-up.
  virtual void declare_pattern(PatternBuilder& pattern) const = 0;
  //! ydot += F(t, y).
  virtual void add_rhs(double t, std::span<const double> y,
                       std::span<double> ydot) const = 0;
  //! J += dF/dy (t, y), exact.
  virtual void add_jacobian(double t, std::span<const double> y,
                            JacobianValues& jac) const = 0;

  //! The mass-budget terms this module books (a sink of dust: what it has removed, at
  //! state y, in g), after the built-in ones in Simulation::budget_terms(); none by
  //! default. The module is built only when its process is on, so its terms are written
  //! to the snapshots (in_snapshots = true).
  virtual std::vector<BudgetTerm> budget_terms() const { return {}; }
  //! The snapshot fields this module owns (OutputField), written after every snapshot;
  //! none by default.
  virtual std::vector<OutputField> output_fields() const { return {}; }
};

}  // namespace panoptic
