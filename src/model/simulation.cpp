#include "src/model/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "disk/disk_local_gas.hpp"
#include "disk/gas_disk.hpp"
#include "disk/viscous_gas.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/modules/planetesimals.hpp"
#include "physics/modules/porous_growth.hpp"
#include "physics/modules/size_distribution.hpp"
#include "physics/stokes_model.hpp"
#include "src/core/units.hpp"
#include "src/model/initial_state.hpp"
#include "src/model/module_registry.hpp"
#include "src/model/scene_to_physics.hpp"

namespace panoptic {

using units::kAu;
using units::kYr;

Simulation::Simulation(const Config& cfg)
    : cfg_(cfg),
      grid_(cfg.real("grid.r_in_au") * kAu, cfg.real("grid.r_out_au") * kAu,
            static_cast<int>(cfg.integer("grid.n_cells")), cfg.real("grid.stretch")),
      disk_(make_disk(disk_params_from_config(cfg))) {
  const int n = grid_.n_cells();
  gas_.static_sigma.resize(n);
  for (int i = 0; i < n; ++i) gas_.static_sigma[i] = disk_->sigma_g(grid_.r_c(i));

  // Monomer species per cell (spec §1.7): silicate inside the snow line, ice outside.
  const bool snowline = cfg.flag("snowline.enabled");
  const double r_snow = disk_->r_snow();
  const auto ice = species_from_config(cfg, "ice"), sil = species_from_config(cfg, "sil");
  std::vector<char> inside(n, 0);
  for (int i = 0; i < n; ++i) {
    // r_snow: +inf warmer than T_sub everywhere (all silicate), 0 colder everywhere
    inside[i] = snowline && grid_.r_c(i) < r_snow;
    species_.push_back(inside[i] ? sil : ice);
  }

  InitialDust dust = initial_dust(cfg, grid_, *disk_, gas_.static_sigma, inside, r_snow);
  sigma_d0_ = std::move(dust.sigma_d);
  dust_mass0_ = dust.mass;
  profile_dust_mass_ = dust.profile_mass;
  const double sigma_d_max = *std::max_element(sigma_d0_.begin(), sigma_d0_.end());
  const double sigma_g_max =
      *std::max_element(gas_.static_sigma.begin(), gas_.static_sigma.end());
  sigma_scale_ = sigma_d_max;

  // The local gas of every cell and the decoder of the particle state (spec §2, §6.2).
  cell_gas_ = std::make_unique<CellGas>(
      local_gas_centres(*disk_, grid_, gas_.static_sigma), gas_);
  codec_ = std::make_unique<ParticleCodec>();
  codec_->m_ref = std::min(ice.m0, sil.m0);
  for (int i = 0; i < n; ++i)
    codec_->x_lo.push_back(std::log(species_[i].m0 / codec_->m_ref));
  // Below this Sigma_d the ratios Q/Sigma_d are noise: CVODE keeps Sigma_d and each Q to
  // about its absolute tolerance atol, so Q/Sigma_d is off by ~atol/Sigma_d. 10 atol: at
  // 1e-3 atol (before) the noise of nearly empty cells (drained inner disk, the first
  // cells inside the snow line) drove their m and phi between monomers and planetesimals
  // and CVODE's steps down to seconds (fiducial with 4096 cells, M_* = 3 M_sun,
  // dust_to_gas = 0.1 failed; the fiducial run needs 17% fewer steps with 10 atol).
  codec_->eps_sigma = 10.0 * atol_sigma_from_config(cfg) * sigma_d_max;

  // Stokes number: from the particles of the growth model (spec §2), or prescribed.
  const bool growth = cfg.flag("growth.enabled");
  if (growth) {
    auto st = std::make_unique<GrowthStokes>(*codec_, *cell_gas_, species_,
                                             growth_options_from_config(cfg).drag);
    growth_stokes_ = st.get();  // the growth module reads its cache
    stokes_ = std::move(st);
  } else {
    std::vector<double> st(n);
    for (int i = 0; i < n; ++i)
      st[i] = cfg.real("transport.St") *
              std::pow(grid_.r_c(i) / kAu, cfg.real("transport.St_slope"));
    stokes_ = std::make_unique<PrescribedStokes>(std::move(st));
  }

  // The modules the scene turns on (module_registry.cpp); they register their variables
  // as they are built, and the layout is then frozen.
  layout_ = std::make_shared<StateLayout>(n);
  monitors_ = place_pebble_monitors(cfg, grid_, r_snow);
  ModuleContext ctx{cfg,      grid_,          *disk_,      gas_,        *layout_,
                    *stokes_, growth_stokes_, *codec_,     *cell_gas_,  species_,
                    inside,   sigma_d_max,    sigma_g_max, dust_mass0_, monitors_};
  std::vector<std::unique_ptr<PhysicsModule>> modules = build_modules(ctx);
  viscous_ = ctx.viscous;
  transport_ = ctx.transport;
  growth_ = ctx.growth;
  planetesimals_ = ctx.planetesimals;
  distribution_ = ctx.distribution;
  dust_ = distribution_ ? static_cast<const DustCarrier*>(distribution_) : transport_;
  modules_in_build_order_ = ctx.built;
  // The dust mass budget (spec §8), in the column order of /timeseries/mass_budget. A
  // process that removes dust from Sigma_d adds its term here (BudgetTerm).
  const bool pl = planetesimals_ != nullptr;
  budget_terms_ = {
      {"m_dust", "on grid", "dust mass on the grid", true,
       [this](std::span<const double> y) { return dust_mass_on_grid(y); }},
      {"m_pl_coag", "planetesimals (coagulation)",
       "planetesimal mass by direct coagulation", pl,
       [this](std::span<const double> y) { return planetesimal_mass(y).first; }},
      {"m_pl_si", "planetesimals (SI)", "planetesimal mass by streaming instability", pl,
       [this](std::span<const double> y) { return planetesimal_mass(y).second; }},
  };
  // then those the modules declare, in their order: the transport's m_out_inner and
  // m_sublimated, and those of a process added later (physics/README.md, Adding a
  // physical process)
  for (const auto& m : modules)
    for (BudgetTerm& term : m->budget_terms()) budget_terms_.push_back(std::move(term));
  layout_->freeze();
  model_ = std::make_unique<DiskModel>(layout_, std::move(modules));
  linear_solver_ = resolve_linear_solver();
  output_fields_ = make_output_fields();
  model_->set_describer(
      [this](long index, std::span<const double> y) { return describe_state(index, y); });
  check_start_is_finite();
}

Simulation::~Simulation() = default;

void Simulation::refresh_local_gas(std::span<const double> y) {
  if (!cell_gas_ || !gas_.evolves()) return;
  const int n = grid_.n_cells();
  const auto& L = *layout_;
  std::vector<double> sigma(n);
  for (int i = 0; i < n; ++i) sigma[i] = y[L.index(i, gas_.slot)];
  // eta at the cell centres as for the initial gas (local_gas_centres, spec §1.4), from
  // the pressure gradient of this Sigma_g: the same bits as the initial eta at t = 0.
  const auto gas = local_gas_centres(*disk_, grid_, sigma);
  // v_g on the faces as the dust drift takes it (no flow through the outer face),
  // averaged onto the centres (spec §3 item 2).
  std::vector<double> v_face(n + 1, 0.0);
  for (int f = 0; f < n; ++f)
    v_face[f] = viscous_->stencil().face_velocity(f, sigma[f > 0 ? f - 1 : 0], sigma[f]);
  std::vector<double> eta(n), v_r_gas(n);
  for (int i = 0; i < n; ++i) {
    eta[i] = gas[i].eta;
    v_r_gas[i] = 0.5 * (v_face[i] + v_face[i + 1]);
  }
  cell_gas_->set_pressure_and_flow(eta, v_r_gas);
  if (distribution_) distribution_->refresh(y);
  if (growth_stokes_) growth_stokes_->forget();
  if (growth_) growth_->forget();
}

LinearSolverKind Simulation::resolve_linear_solver() const {
  const std::string linear = cfg_.str("solver.linear");
  if (linear == "block") return LinearSolverKind::block;
  if (linear == "gmres") return LinearSolverKind::gmres;
  if (linear == "klu") return LinearSolverKind::klu;
  // auto: a size distribution couples its bins (2 x bins variables when porous) densely
  // within a cell. GMRES with the cells' blocks as preconditioner, its solutions made
  // conservative (src/solver/conservative_gmres.hpp), costs a porous distribution
  // 0.5-0.8x the block solver's time and a compact one 0.63-0.78x, with less memory
  // (tests/bench/results/krylov_solver.md); the block solver, which factorises in half
  // KLU's time, stays by name. The single size (a few variables per cell) keeps KLU.
  return distribution_ != nullptr ? LinearSolverKind::gmres : LinearSolverKind::klu;
}

const char* linear_solver_name(LinearSolverKind kind) {
  return kind == LinearSolverKind::block   ? "block"
         : kind == LinearSolverKind::gmres ? "gmres"
                                           : "klu";
}

double Simulation::newton_coefficient() const {
  const double set = cfg_.real("solver.newton_coef");
  if (set > 0.0) return set;
  // 0 = by model kind (keys_run.cpp; tests/bench/results/porous_newton.md): single-size
  // runs at 0.03 (performance_log.md); a compact size distribution at 0.05 (the compact
  // DustPy disk to 1e5 yr: 20.8 s, against 20.0 s at 0.1 and 28.6 s at 0.03); a porous
  // one at 0.1. At 0.05 Newton failed on most steps of the fiducial distribution once
  // its planetesimals had formed, on the volume of bins at the absolute tolerance, and
  // since the bins' tolerance is the empty-bin scale the porous DustPy disk no longer
  // fails the error test at 0.1 (porous_newton.md, "The fiducial distribution's late
  // steps").
  if (distribution_ == nullptr) return 0.03;
  return distribution_->porous() ? 0.1 : 0.05;
}

IntegratorOptions Simulation::integrator_options() const {
  IntegratorOptions o;
  o.rtol = cfg_.real("solver.rtol");
  o.max_steps = cfg_.integer("solver.max_steps");
  o.max_dt = cfg_.real("solver.max_dt_yr") * kYr;
  o.newton_coef = newton_coefficient();
  o.steps_per_jacobian = cfg_.integer("solver.steps_per_jacobian");
  o.linear = linear_solver();
  if (o.linear == LinearSolverKind::gmres) o.invariant = budget_weights();
  const auto& L = *layout_;
  const double atol = atol_sigma_from_config(cfg_);
  o.atol.resize(L.size());
  o.constraints.resize(L.size());
  for (long i = 0; i < L.size(); ++i) {
    // Out of the error test: an absolute tolerance far above any value the variable
    // takes, so its error weight 1/(rtol |y| + atol) is ~0 (not 0: CVODE requires
    // positive weights).
    o.atol[i] = atol * L.info_of(i).abs_scale * (L.info_of(i).error_test ? 1.0 : 1e30);
    o.constraints[i] = L.info_of(i).nonnegative ? 1.0 : 0.0;
  }
  if (cfg_.str("solver.method") == "implicit_euler") {
    o.method = IntegrationMethod::implicit_euler;
    o.cfl = cfg_.real("solver.cfl");
    o.step_floor = implicit_euler_step_floors();
  }
  return o;
}

std::vector<double> Simulation::implicit_euler_step_floors() const {
  // DustPy's step rule (src/solver/implicit_euler_integrator.hpp) on the densities it
  // has: each bin's sigma_k above its floor 0.1 m_k / A_i (dustpy/std/dust.py
  // SigmaFloor, times the 0.1 of dustpy/simulation.py) and Sigma_g above 1e-100
  // (dustpy/simulation.py); the rest (psi_k, Sigma_pl, the booked masses) out of it.
  if (!distribution_)
    throw std::logic_error("implicit_euler step floors without a size distribution");
  constexpr double kGasFloor = 1e-100;
  const StateLayout& L = *layout_;
  std::vector<double> floor(static_cast<std::size_t>(L.size()),
                            std::numeric_limits<double>::infinity());
  const auto& m = distribution_->mass_grid().m;
  for (int i = 0; i < grid_.n_cells(); ++i) {
    for (int k = 0; k < distribution_->n_bins(); ++k)
      floor[L.index(i, distribution_->bin_slot(k))] = 0.1 * m[k] / grid_.area(i);
    if (gas_.evolves()) floor[L.index(i, gas_.slot)] = kGasFloor;
  }
  return floor;
}

std::vector<double> Simulation::output_times() const {
  std::vector<double> t_yr{0.0};
  const double t_end = cfg_.real("output.t_end_yr");
  const auto& listed = cfg_.reals("output.times_yr");
  if (!listed.empty()) {
    t_yr.insert(t_yr.end(), listed.begin(), listed.end());
  } else {
    const double t0 = cfg_.real("output.t_first_yr");
    const long m = cfg_.integer("output.n_snapshots");
    for (long k = 0; k < m; ++k)
      t_yr.push_back(m == 1 ? t_end
                            : t0 * std::pow(t_end / t0, double(k) / double(m - 1)));
  }
  if (t_yr.back() < t_end) t_yr.push_back(t_end);
  t_yr.back() = t_end;  // exact end time
  std::vector<double> t;
  for (double x : t_yr)
    if (t.empty() || x * kYr > t.back()) t.push_back(x * kYr);
  return t;
}

const char* Simulation::top_bin_fraction_field() const {
  return distribution_ != nullptr ? SizeDistribution::kTopBinFractionField : "";
}

double Simulation::top_bin_mass() const {
  return distribution_ != nullptr ? distribution_->mass_grid().m.back() : 0.0;
}

double Simulation::dust_mass_on_grid(std::span<const double> y) const {
  double m = 0.0;
  for (int i = 0; i < grid_.n_cells(); ++i) m += dust_->sigma_d(i, y) * grid_.area(i);
  return m;
}

std::vector<double> Simulation::sigma_pl(std::span<const double> y, bool si) const {
  if (!planetesimals_) return {};
  const int slot = si ? planetesimals_->si_slot() : planetesimals_->coag_slot();
  if (slot < 0) return {};
  std::vector<double> out(grid_.n_cells());
  for (int i = 0; i < grid_.n_cells(); ++i) out[i] = y[layout_->index(i, slot)];
  return out;
}

std::pair<double, double> Simulation::planetesimal_mass(std::span<const double> y) const {
  double m[2] = {0.0, 0.0};
  for (int c = 0; c < 2; ++c) {
    const auto sig = sigma_pl(y, c == 1);
    for (std::size_t i = 0; i < sig.size(); ++i) m[c] += sig[i] * grid_.area(int(i));
  }
  return {m[0], m[1]};
}

std::vector<double> Simulation::budget_masses(std::span<const double> y) const {
  std::vector<double> m;
  for (const auto& term : budget_terms_) m.push_back(term.mass(y));
  return m;
}

std::vector<double> Simulation::budget_weights() const {
  const long n = layout_->size();
  std::vector<double> c(static_cast<std::size_t>(n)), e(static_cast<std::size_t>(n), 0.0);
  for (long j = 0; j < n; ++j) {
    e[j] = 1.0;
    for (const auto& term : budget_terms_) c[j] += term.mass(e);
    e[j] = 0.0;
  }
  return c;
}

double Simulation::budget_error(std::span<const double> y) const {
  double total = 0.0;
  for (const double m : budget_masses(y)) total += m;
  return std::abs(total - dust_mass0_) / dust_mass0_;
}

}  // namespace panoptic
