#pragma once
//! A scene assembled into something CVODE can integrate: grid, gas disk, the physics
//! modules the scene turns on, the state layout they register, the initial state, the
//! tolerances and the output times. This is the factory: the only place (with main.cpp)
//! that names concrete modules.
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "disk/gas_column.hpp"
#include "disk/local_gas.hpp"
#include "physics/optical_constants.hpp"
#include "src/io/output_entry.hpp"
#include "src/model/pebble_monitors.hpp"
#include "src/model/scene_to_physics.hpp"
#include "src/model/scene_validation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"
#include "src/solver/disk_model.hpp"
#include "src/solver/grid.hpp"

namespace panoptic {

class GasDisk;
class RunOutput;
class StokesModel;
class DustCarrier;
class DustTransport;
class ViscousGas;
class PorousGrowth;
class GrowthStokes;
class PlanetesimalChannels;
class SizeDistribution;
class CellGas;
struct ParticleCodec;
namespace physics {
struct Species;
struct GrowthOptions;
}  // namespace physics

// BudgetTerm: src/solver/physics_module.hpp (a module declares its own).

//! A dataset written once, at the start (/grid, /disk, /pebbles), with its units and
//! description attributes.
struct StaticField {
  std::string group, name;
  std::vector<double> values;
  std::string units, description;
};

//! "klu", "block" or "gmres" (solver.linear's choices).
const char* linear_solver_name(LinearSolverKind kind);

class Simulation {
 public:
  explicit Simulation(const Config& cfg);
  ~Simulation();

  const Config& config() const { return cfg_; }
  const Grid& grid() const { return grid_; }
  const GasDisk& disk() const { return *disk_; }
  DiskModel& model() { return *model_; }
  const DiskModel& model() const { return *model_; }
  const DustTransport& transport() const { return *transport_; }
  //! The growth module, or null when growth is off.
  const PorousGrowth* growth() const { return growth_; }
  //! The size distribution (model.kind = "distribution", spec §15), or null.
  const SizeDistribution* distribution() const { return distribution_; }
  //! A size distribution's snapshot field of the fraction of each cell's dust in the
  //! mass grid's top bin (SizeDistribution::kTopBinFractionField) and that bin's mass
  //! [g]; "" and 0 without one.
  const char* top_bin_fraction_field() const;
  double top_bin_mass() const;
  //! The largest initial Sigma_d of a cell [g cm^-2].
  double initial_sigma_d_max() const { return sigma_scale_; }
  //! The local gas the particle laws see, or null when growth is off.
  const CellGas* cell_gas() const { return cell_gas_.get(); }

  std::vector<double> initial_state() const;
  //! The solver of the Newton systems, solver.linear with "auto" resolved: block for a
  //! size distribution whose pattern the block solver takes, else KLU. Resolved once, at
  //! construction; the integrators trust it.
  LinearSolverKind linear_solver() const { return linear_solver_; }
  //! Where the gas evolves: sets the pressure-gradient parameter eta and the radial gas
  //! velocity that the particle laws see (CellGas::set_pressure_and_flow) from the gas
  //! at state y. Called where CVODE starts or restarts (every snapshot, with
  //! solver.reinit_at_snapshots), so that a restart from a checkpoint sees the same gas
  //! as the run never stopped. No-op for static gas or without growth.
  void refresh_local_gas(std::span<const double> y);
  IntegratorOptions integrator_options() const;
  //! solver.method = "implicit_euler": the floor of every component in its step rule
  //! (IntegratorOptions::step_floor; +inf: out of the rule). Distribution only.
  std::vector<double> implicit_euler_step_floors() const;
  //! Snapshot times [s], t = 0 first, t_end last.
  std::vector<double> output_times() const;

  //! The snapshot fields: those of the modules (PhysicsModule::output_fields), in the
  //! order they were built, then the model's (Sigma_g, St, the budget terms, the pebble
  //! flux).
  const std::vector<OutputField>& output_fields() const { return output_fields_; }
  //! /grid, /disk and /pebbles: written once, by prepare_output.
  std::vector<StaticField> static_fields() const;
  //! The attributes of /disk, /pebbles and /snapshots: written once, by prepare_output.
  std::vector<OutputAttribute> output_attributes() const;
  //! Writes the static fields and their attributes and declares the snapshot fields
  //! (output_fields()).
  void prepare_output(RunOutput& out) const;
  //! Every snapshot field at state y (as declared in output_fields()).
  std::map<std::string, std::vector<double>> snapshot_fields(
      std::span<const double> y) const;

  double dust_mass_on_grid(std::span<const double> y) const;  //!< [g]
  double initial_dust_mass() const { return dust_mass0_; }    //!< [g]
  //! The dust mass of the initial profile itself on r_in..r_out, integrated exactly
  //! (GasDisk::mass_between, split at the snow line) [g]: initial_dust_mass() is its
  //! cell-centre quadrature, second order in the cell width. NaN for dust.init =
  //! "gaussian_ring".
  double profile_dust_mass() const { return profile_dust_mass_; }
  //! Planetesimal mass per channel {coagulation, SI} [g] (0 for a channel that is off).
  std::pair<double, double> planetesimal_mass(std::span<const double> y) const;
  //! Sigma_pl per channel at the cell centres [g cm^-2] (empty when off).
  std::vector<double> sigma_pl(std::span<const double> y, bool si) const;
  const PlanetesimalChannels* planetesimals() const { return planetesimals_; }
  const std::vector<PebbleMonitor>& pebble_monitors() const { return monitors_; }
  //! Pebble flux (inward mass flow) through every monitor [g s^-1].
  std::vector<double> pebble_flux(std::span<const double> y) const;
  //! Cumulative dust mass through every monitor [g].
  std::vector<double> pebble_mass(std::span<const double> y) const;
  //! The terms of the dust mass budget, in the order of /timeseries/mass_budget's
  //! columns (the error column comes after them).
  const std::vector<BudgetTerm>& budget_terms() const { return budget_terms_; }
  //! The mass of every budget term at state y [g].
  std::vector<double> budget_masses(std::span<const double> y) const;
  //! The weights c of the budget's sum, c . y = sum of budget_masses(y) [g per unit of
  //! each component]: the terms are linear in y (each books a mass), so c_j is their sum
  //! at the unit vector e_j.
  std::vector<double> budget_weights() const;
  //! |sum of the budget terms - initial| / initial.
  double budget_error(std::span<const double> y) const;
  //! One-paragraph summary for `panoptic check` and the run header.
  std::string summary() const;
  //! The physical state of the cell of component `index` at state y, for failure
  //! messages: "r = 3.1 au, Sigma_d = 0.2 g cm^-2, m = 5e3 g, phi = 1e-3, St = 0.02"
  //! (empty for a global variable). The DiskModel's describer.
  std::string describe_state(long index, std::span<const double> y) const;

 private:
  //! Throws ConfigError when the gas disk, the local gas, the initial state or its
  //! right-hand side is not finite (and positive where it must be) in some cell.
  void check_start_is_finite() const;
  std::vector<OutputField> make_output_fields() const;
  LinearSolverKind resolve_linear_solver() const;
  //! solver.newton_coef, its 0 resolved by the model kind.
  double newton_coefficient() const;
  Config cfg_;
  Grid grid_;
  std::unique_ptr<GasDisk> disk_;
  GasColumn gas_;
  std::unique_ptr<StokesModel> stokes_;
  std::shared_ptr<StateLayout> layout_;
  const DustTransport* transport_ = nullptr;
  const ViscousGas* viscous_ = nullptr;
  // Growth model (growth.enabled): species per cell, the local gas, the state decoder.
  std::vector<physics::Species> species_;
  std::unique_ptr<CellGas> cell_gas_;
  std::unique_ptr<ParticleCodec> codec_;
  const PorousGrowth* growth_ = nullptr;
  const GrowthStokes* growth_stokes_ = nullptr;
  const PlanetesimalChannels* planetesimals_ = nullptr;
  const SizeDistribution* distribution_ = nullptr;
  //! The module that carries the dust: distribution_ if built, else transport_.
  const DustCarrier* dust_ = nullptr;
  std::vector<PebbleMonitor> monitors_;
  std::vector<BudgetTerm> budget_terms_;
  std::unique_ptr<DiskModel> model_;
  std::vector<const PhysicsModule*> modules_in_build_order_;
  std::vector<OutputField> output_fields_;
  LinearSolverKind linear_solver_ = LinearSolverKind::klu;
  std::vector<double> sigma_d0_;
  double sigma_scale_ = 1.0, dust_mass0_ = 0.0, profile_dust_mass_ = 0.0;
};

}  // namespace panoptic
