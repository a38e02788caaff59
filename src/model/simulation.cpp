#include "src/model/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "disk/disk_local_gas.hpp"
#include "disk/gas_disk.hpp"
#include "disk/local_gas.hpp"
#include "disk/viscous_gas.hpp"
#include "physics/contact_mechanics.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/modules/planetesimals.hpp"
#include "physics/modules/porous_growth.hpp"
#include "physics/optical_constants.hpp"
#include "physics/stokes_model.hpp"
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/run_output.hpp"
#include "src/model/scene_to_physics.hpp"

namespace panoptic {

using units::kAu;
using units::kYr;

namespace {

//! exp(-x) I_0(x), the exponentially scaled modified Bessel function (no overflow).
double i0e(double x) {
  if (x < 500.0) return std::cyl_bessel_i(0.0, x) * std::exp(-x);
  // Abramowitz & Stegun 9.7.1, three terms: relative error < 1e-9 for x >= 500.
  return (1.0 + 1.0 / (8.0 * x) + 9.0 / (128.0 * x * x)) /
         std::sqrt(2.0 * units::kPi * x);
}

//! A thin ring at r0 spread by diffusion until its Gaussian width is w, normalised to 1
//! at r0: the exact axisymmetric diffusing-ring solution
//! Sigma ∝ exp(-(r^2 + r0^2)/(4Dt)) I_0(r r0/(2Dt)) with 2Dt = w^2, so that
//! regression tests can compare with the analytic solution at all later times.
double diffused_ring(double r, double r0, double w) {
  const double x = (r - r0) / w;
  return std::exp(-0.5 * x * x) * i0e(r * r0 / (w * w)) / i0e(r0 * r0 / (w * w));
}

}  // namespace

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
  std::vector<bool> inside(n, false);
  for (int i = 0; i < n; ++i) {
    // r_snow: +inf warmer than T_sub everywhere (all silicate), 0 colder everywhere
    inside[i] = snowline && grid_.r_c(i) < r_snow;
    species_.push_back(inside[i] ? sil : ice);
  }

  // Initial dust (spec §6.4: Sigma_d = Z Sigma_g, Z_in = (1 - f_ice) Z_out, spec §1.7),
  // or a test ring on the floor.
  const double z = cfg.real("dust.dust_to_gas"), floor = cfg.real("dust.sigma_floor_rel");
  const double f_ice = cfg.real("snowline.f_ice");
  sigma_d0_.resize(n);
  for (int i = 0; i < n; ++i) {
    if (cfg.str("dust.init") == "gaussian_ring") {
      sigma_d0_[i] = cfg.real("dust.ring_sigma") *
                         diffused_ring(grid_.r_c(i), cfg.real("dust.ring_r_au") * kAu,
                                       cfg.real("dust.ring_width_au") * kAu) +
                     floor * gas_.static_sigma[i];
    } else {
      sigma_d0_[i] = (inside[i] ? 1.0 - f_ice : 1.0) * z * gas_.static_sigma[i];
    }
    dust_mass0_ += sigma_d0_[i] * grid_.area(i);
  }
  // The same dust integrated exactly (spec §1.7: Z_in inside r_snow, Z_out outside), to
  // show the cell-centre values' quadrature error (the run header).
  profile_dust_mass_ = std::numeric_limits<double>::quiet_NaN();
  if (cfg.str("dust.init") == "dust_to_gas") {
    const double r1 = grid_.r_f(0), r2 = grid_.r_f(n);
    const double rs = snowline ? std::clamp(r_snow, r1, r2) : r1;  // r_snow may be +-inf
    profile_dust_mass_ =
        z * ((1.0 - f_ice) * (rs > r1 ? disk_->mass_between(r1, rs) : 0.0) +
             (rs < r2 ? disk_->mass_between(rs, r2) : 0.0));
  }
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
  codec_->eps_sigma = 10.0 * cfg.real("solver.atol_sigma") * sigma_d_max;

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

  // Modules register their variables in this order; the layout is then frozen.
  layout_ = std::make_shared<StateLayout>(n);
  std::vector<std::unique_ptr<PhysicsModule>> modules;
  const ViscousStencil* stencil = nullptr;
  if (cfg.flag("gas.evolve")) {
    auto gas = std::make_unique<ViscousGas>(*layout_, *disk_, grid_, sigma_g_max,
                                            cfg.str("gas.inner_bc") == "zero_torque");
    gas_.slot = gas->sigma_slot();
    stencil = &gas->stencil();
    viscous_ = gas.get();
    modules.push_back(std::move(gas));
  }
  const DustTransportOptions topt = transport_options_from_config(cfg);
  auto transport = std::make_unique<DustTransport>(
      *layout_, grid_, *disk_, gas_, stencil, *stokes_, topt, sigma_d_max, dust_mass0_);
  transport_ = transport.get();
  codec_->sigma_slot = transport->sigma_slot();
  if (growth) {
    auto g = std::make_unique<PorousGrowth>(*layout_, *codec_, *cell_gas_,
                                            *growth_stokes_, species_,
                                            growth_options_from_config(cfg), sigma_d_max);
    transport->add_passenger(
        codec_->qm_slot);  // spec §6.2: Q_m, Q_phi ride with the dust
    if (codec_->qphi_slot >= 0) transport->add_passenger(codec_->qphi_slot);
    growth_ = g.get();
    modules.push_back(std::move(g));
  }
  // Planetesimal channels (spec §7), after the growth model whose particles they convert.
  // Without growth only the SI channel can run, on the prescribed St.
  if (cfg.flag("planetesimals.coagulation") || cfg.str("planetesimals.si") != "none") {
    const PlanetesimalOptions po = planetesimal_options_from_config(cfg);
    auto pl =
        std::make_unique<Planetesimals>(*layout_, *codec_, *cell_gas_, *stokes_, species_,
                                        growth_options_from_config(cfg), po, sigma_d_max);
    if (growth_) pl->use_growth_rates(growth_);
    planetesimals_ = pl.get();
    modules.push_back(std::move(pl));
  }
  // Pebble-flux monitors (spec §8): the faces nearest to the requested radii.
  {
    std::vector<std::pair<std::string, double>> radii;
    if (cfg.reals("pebbles.radii_au").empty()) {
      if (std::isfinite(r_snow)) radii.emplace_back("snow line", r_snow / kAu);
      for (double r : {1.0, 3.0, 10.0, 30.0}) radii.emplace_back(num(r) + " au", r);
    } else {
      for (double r : cfg.reals("pebbles.radii_au"))
        radii.emplace_back(num(r) + " au", r);
    }
    for (const auto& [name, r_au] : radii) {
      if (r_au <= grid_.r_f(0) / kAu || r_au >= grid_.r_f(n) / kAu) continue;
      int face = 1;
      for (int f = 1; f < n; ++f)
        if (std::abs(std::log(grid_.r_f(f) / (r_au * kAu))) <
            std::abs(std::log(grid_.r_f(face) / (r_au * kAu))))
          face = f;
      monitors_.push_back(
          {name, grid_.r_f(face) / kAu, face, transport->add_monitor(*layout_, face)});
    }
    monitors_.push_back({"r_in", grid_.r_f(0) / kAu, 0, transport->m_out_slot()});
  }
  // The snow line face: the first face with silicate inside and ice outside (spec §6.3).
  for (int f = 1; f < n; ++f)
    if (inside[f - 1] && !inside[f])
      transport->set_snowline(*layout_, f, f_ice, growth ? codec_->qm_slot : -1);
  modules.push_back(std::move(transport));
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
  // m_sublimated, and those of a process added later (README, Adding a physical process)
  for (const auto& m : modules)
    for (BudgetTerm& term : m->budget_terms()) budget_terms_.push_back(std::move(term));
  layout_->freeze();
  model_ = std::make_unique<DiskModel>(layout_, std::move(modules));
  model_->set_describer(
      [this](long index, std::span<const double> y) { return describe_state(index, y); });
  check_start_is_finite();
}

void Simulation::check_start_is_finite() const {
  // Keys inside their ranges can still combine into a disk or an initial state that is
  // not finite (dust.dust_to_gas = 1e308, star.luminosity_lsun = 1e308, an LBP r_c_au of
  // 1e-6 au...), which CVODE reported only as a failed first right-hand side, naming no
  // key. Said here, before any output is written, as bad input.
  const auto fail = [&](int cell, const std::string& what, double value) {
    std::ostringstream m;
    m << what << " = " << value << " at r = " << grid_.r_c(cell) / kAu << " au (cell "
      << cell
      << "): the scene's values, each inside its range, give a disk or an initial state "
         "that is not finite and positive there; bring the disk.*, star.*, dust.*, "
         "material.* and grid.* values nearer to physical ones (a grid reaching far "
         "beyond an LBP disk's r_c_au has no gas there; panoptic check prints the "
         "resolved scene)";
    // the likely culprits: values the scene set far from their defaults (1e308, 1e-300)
    std::string far;
    for (const KeySpec& spec : scene_keys()) {
      if (spec.type != KeyType::kReal || !cfg_.user_set(spec.key)) continue;
      const double v = cfg_.real(spec.key), d = default_real(spec.key);
      if (d != 0.0 && v != 0.0 && std::abs(std::log10(std::abs(v / d))) > 3.0)
        far += (far.empty() ? "" : ", ") + spec.key + " = " + num(v) + " (default " +
               spec.default_toml + ", " + cfg_.where(spec.key) + ")";
    }
    if (!far.empty()) m << "; set far from their defaults (over 1e3 x): " << far;
    throw ConfigError(m.str());
  };
  const auto bad = [](double v) { return !(std::isfinite(v) && v > 0.0); };
  for (int i = 0; i < grid_.n_cells(); ++i) {
    const double r = grid_.r_c(i);
    if (bad(gas_.static_sigma[i])) fail(i, "Sigma_g [g cm^-2]", gas_.static_sigma[i]);
    if (bad(disk_->temperature(r))) fail(i, "T [K]", disk_->temperature(r));
    if (!(std::isfinite(sigma_d0_[i]) && sigma_d0_[i] >= 0.0))
      fail(i, "initial Sigma_d [g cm^-2]", sigma_d0_[i]);
    if (cell_gas_) {
      const auto& g = cell_gas_->reference(i);
      for (const auto& [name, v] : {std::pair{"rho_g [g cm^-3]", g.rho_g},
                                    {"mean free path [cm]", g.mfp},
                                    {"nu_mol [cm^2 s^-1]", g.nu_mol},
                                    {"c_s [cm s^-1]", g.c_s},
                                    {"H_g [cm]", g.h_g}})
        if (bad(v)) fail(i, name, v);
      if (!std::isfinite(g.eta)) fail(i, "eta", g.eta);
    }
  }
  const auto y0 = initial_state();
  std::vector<double> f(y0.size());
  model_->rhs(0.0, y0, f);
  const auto& L = *layout_;
  for (long k = 0; k < L.size(); ++k)
    if (!std::isfinite(y0[k]) || !std::isfinite(f[k])) {
      const int cell = L.cell_of(k);
      const std::string what = (std::isfinite(y0[k]) ? "d/dt of " : "initial ") +
                               L.info_of(k).name + " [" + L.info_of(k).units +
                               (std::isfinite(y0[k]) ? " s^-1]" : "]");
      fail(cell < 0 ? 0 : cell, what, std::isfinite(y0[k]) ? f[k] : y0[k]);
    }
}

std::string Simulation::describe_state(long index, std::span<const double> y) const {
  const auto& L = *layout_;
  const int i = L.cell_of(index);
  if (i < 0 || y.size() < static_cast<std::size_t>(L.size())) return "";
  const double* yc = &y[L.index(i, 0)];
  std::ostringstream s;
  s.precision(4);
  s << "r = " << grid_.r_c(i) / kAu << " au, Sigma_d = " << yc[transport_->sigma_slot()]
    << " g cm^-2";
  if (gas_.evolves()) s << ", Sigma_g = " << gas_.sigma(i, yc) << " g cm^-2";
  if (growth_) s << ", m = " << codec_->mass(i, yc) << " g, phi = " << codec_->phi(yc);
  s << ", St = " << stokes_->St(i, yc);
  return s.str();
}

Simulation::~Simulation() = default;

std::vector<double> Simulation::initial_state() const {
  const auto& L = *layout_;
  std::vector<double> y(L.size(), 0.0);
  for (int i = 0; i < grid_.n_cells(); ++i) {
    y[L.index(i, transport_->sigma_slot())] = sigma_d0_[i];
    if (gas_.evolves()) y[L.index(i, gas_.slot)] = gas_.static_sigma[i];
    // monomers everywhere (spec §6.4): m = m0 of the cell's species, phi = 1
    if (growth_) y[L.index(i, codec_->qm_slot)] = sigma_d0_[i] * codec_->x_lo[i];
  }
  return y;
}

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
  if (growth_stokes_) growth_stokes_->forget();
  if (growth_) growth_->forget();
}

IntegratorOptions Simulation::integrator_options() const {
  IntegratorOptions o;
  o.rtol = cfg_.real("solver.rtol");
  o.max_steps = cfg_.integer("solver.max_steps");
  o.max_dt = cfg_.real("solver.max_dt_yr") * kYr;
  o.newton_coef = cfg_.real("solver.newton_coef");
  o.steps_per_jacobian = cfg_.integer("solver.steps_per_jacobian");
  const auto& L = *layout_;
  const double atol = cfg_.real("solver.atol_sigma");
  o.atol.resize(L.size());
  o.constraints.resize(L.size());
  for (long i = 0; i < L.size(); ++i) {
    // Out of the error test: an absolute tolerance far above any value the variable
    // takes, so its error weight 1/(rtol |y| + atol) is ~0 (not 0: CVODE requires
    // positive weights).
    o.atol[i] = atol * L.info_of(i).abs_scale * (L.info_of(i).error_test ? 1.0 : 1e30);
    o.constraints[i] = L.info_of(i).nonnegative ? 1.0 : 0.0;
  }
  return o;
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

void Simulation::prepare_output(RunOutput& out) const {
  const int n = grid_.n_cells();
  std::vector<double> r_c(n), r_f(n + 1), T(n), cs(n), om(n), hg(n), alpha(n);
  for (int i = 0; i <= n; ++i) r_f[i] = grid_.r_f(i) / kAu;
  for (int i = 0; i < n; ++i) {
    const double r = grid_.r_c(i);
    r_c[i] = r / kAu;
    T[i] = disk_->temperature(r);
    cs[i] = disk_->c_s(r);
    om[i] = disk_->omega_k(r);
    hg[i] = disk_->h_g(r);
    alpha[i] = disk_->alpha();
  }
  out.write_static("grid", "r_c", r_c, "au",
                   "cell centres (geometric mean of the faces)");
  out.write_static("grid", "r_f", r_f, "au",
                   "cell faces (log-spaced, or stretched by grid.stretch)");
  out.write_static("grid", "area", grid_.areas(), "cm^2", "annulus area of each cell");
  out.write_static("disk", "T", T, "K", "midplane temperature");
  out.write_static("disk", "c_s", cs, "cm s^-1", "isothermal sound speed");
  out.write_static("disk", "omega_k", om, "s^-1", "Keplerian angular frequency");
  out.write_static("disk", "h_g", hg, "cm", "gas pressure scale height");
  out.write_static("disk", "alpha", alpha, "", "turbulence parameter");
  out.write_static("disk", "eta", eta_centres(*disk_, grid_, gas_.static_sigma), "",
                   "pressure-gradient parameter of the initial gas (spec §1.4)");
  out.set_group_attr("disk", "r_snow_au", disk_->r_snow() / kAu);
  out.add_field("sigma_d", n, "g cm^-2", "dust surface density");
  out.add_field("sigma_g", n, "g cm^-2", "gas surface density");
  out.add_field("St", n, "", "Stokes number of the dust");
  out.add_field("v_r", n + 1, "cm s^-1", "dust radial velocity on the faces");
  out.add_field("mdot_d", n + 1, "g s^-1",
                "dust mass flow through the faces, positive outward");
  {
    std::string names;
    for (const auto& term : budget_terms_)
      if (term.in_snapshots) {
        out.add_field(term.name, 0, "g", term.description);
        names += (names.empty() ? "" : ";") + term.name;
      }
    out.set_group_attr_string("snapshots", "budget_terms", names);
  }
  {
    std::vector<double> r_mon;
    std::string names;
    for (const auto& mon : monitors_) {
      r_mon.push_back(mon.r_au);
      names += (names.empty() ? "" : ";") + mon.name;
    }
    out.write_static("pebbles", "r_au", r_mon, "au",
                     "radii (faces) where the pebble flux is recorded; attribute names");
    out.set_group_attr_string("pebbles", "names", names);
    out.add_field("m_through", monitors_.size(), "g",
                  "cumulative dust mass that crossed each /pebbles/r_au inward");
    out.add_field("pebble_flux", monitors_.size(), "g s^-1",
                  "inward dust mass flow through each /pebbles/r_au");
  }
  if (planetesimals_) {
    out.add_field("sigma_pl", n, "g cm^-2", "planetesimal surface density, all channels");
    if (planetesimals_->coag_slot() >= 0)
      out.add_field("sigma_pl_coag", n, "g cm^-2", "planetesimals by direct coagulation");
    if (planetesimals_->si_slot() >= 0)
      out.add_field("sigma_pl_si", n, "g cm^-2",
                    "planetesimals by streaming instability");
    out.add_field(
        "t_first_pl", n, "yr",
        "time of first planetesimal formation in each cell so far (NaN: not yet; "
        "formed: Sigma_pl > /summary/formed_threshold)");
  }
  if (gas_.evolves())
    out.add_field("m_out_gas", 0, "g", "cumulative gas accreted through r_in");
  if (growth_) {
    out.add_field("m", n, "g", "mass of the mass-dominating particle");
    out.add_field("phi", n, "", "filling factor of the mass-dominating particle");
    out.add_field("a", n, "cm", "radius of the mass-dominating particle");
    out.add_field("rho_int", n, "g cm^-3", "internal density phi rho0");
    out.add_field("dv", n, "cm s^-1", "collision speed used for growth (spec §3)");
    out.add_field("t_grow", n, "yr", "growth time m/|dm/dt| (inf: growth halted)");
    if (growth_->options().eroding())
      out.add_field(
          "dv_ls", n, "cm s^-1",
          "collision speed against the small projectiles, which erosion compares "
          "with v_eros (spec §3, §5.1-§5.2)");
  }
}

std::map<std::string, std::vector<double>> Simulation::snapshot_fields(
    std::span<const double> y) const {
  const int n = grid_.n_cells();
  const auto& L = *layout_;
  std::map<std::string, std::vector<double>> f;
  std::vector<double> sd(n), sg(n), st(n);
  for (int i = 0; i < n; ++i) {
    const double* yc = &y[L.index(i, 0)];
    sd[i] = yc[transport_->sigma_slot()];
    sg[i] = gas_.sigma(i, yc);
    st[i] = stokes_->St(i, yc);
  }
  f["sigma_d"] = std::move(sd);
  f["sigma_g"] = std::move(sg);
  f["St"] = std::move(st);
  f["v_r"] = transport_->face_velocity(y);
  f["mdot_d"] = transport_->mass_flow(y);
  {
    const auto masses = budget_masses(y);
    for (std::size_t k = 0; k < budget_terms_.size(); ++k)
      if (budget_terms_[k].in_snapshots) f[budget_terms_[k].name] = {masses[k]};
  }
  f["m_through"] = pebble_mass(y);
  f["pebble_flux"] = pebble_flux(y);
  if (planetesimals_) {
    auto c = sigma_pl(y, false), s = sigma_pl(y, true);
    std::vector<double> total(n, 0.0);
    for (int i = 0; i < n; ++i)
      total[i] = (c.empty() ? 0.0 : c[i]) + (s.empty() ? 0.0 : s[i]);
    f["sigma_pl"] = std::move(total);
    if (!c.empty()) f["sigma_pl_coag"] = std::move(c);
    if (!s.empty()) f["sigma_pl_si"] = std::move(s);
  }
  if (gas_.evolves())
    f["m_out_gas"] = {y[L.global_index(viscous_->m_out_slot())] * viscous_->mass_unit()};
  if (growth_) {
    const bool erosion = growth_->options().eroding();
    std::vector<double> m(n), phi(n), a(n), rho(n), dv(n), tg(n), dv_ls(erosion ? n : 0);
    for (int i = 0; i < n; ++i) {
      const double* yc = &y[L.index(i, 0)];
      const auto r = growth_->rates(i, y);
      m[i] = codec_->mass(i, yc);
      phi[i] = codec_->phi(yc);
      a[i] = r.a;
      rho[i] = phi[i] * species_[i].rho0;
      dv[i] = r.dv;
      if (erosion) dv_ls[i] = r.dv_ls;
      // +inf where growth has halted exactly (a saturated erosion switch gives dm/dt = 0)
      tg[i] = r.dm_dt != 0.0 ? m[i] / std::abs(r.dm_dt) / kYr
                             : std::numeric_limits<double>::infinity();
    }
    f["m"] = std::move(m);
    f["phi"] = std::move(phi);
    f["a"] = std::move(a);
    f["rho_int"] = std::move(rho);
    f["dv"] = std::move(dv);
    f["t_grow"] = std::move(tg);
    if (erosion) f["dv_ls"] = std::move(dv_ls);
  }
  return f;
}

double Simulation::dust_mass_on_grid(std::span<const double> y) const {
  double m = 0.0;
  for (int i = 0; i < grid_.n_cells(); ++i)
    m += y[layout_->index(i, transport_->sigma_slot())] * grid_.area(i);
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

std::vector<double> Simulation::pebble_flux(std::span<const double> y) const {
  const auto mdot = transport_->mass_flow(y);
  std::vector<double> out;
  for (const auto& mon : monitors_) out.push_back(-mdot[mon.face]);  // inward positive
  return out;
}

std::vector<double> Simulation::pebble_mass(std::span<const double> y) const {
  std::vector<double> out;
  for (const auto& mon : monitors_)
    out.push_back(y[layout_->global_index(mon.global_slot)] * transport_->mass_unit());
  return out;
}

std::vector<double> Simulation::budget_masses(std::span<const double> y) const {
  std::vector<double> m;
  for (const auto& term : budget_terms_) m.push_back(term.mass(y));
  return m;
}

double Simulation::budget_error(std::span<const double> y) const {
  double total = 0.0;
  for (const double m : budget_masses(y)) total += m;
  return std::abs(total - dust_mass0_) / dust_mass0_;
}

std::string Simulation::summary() const {
  std::ostringstream s;
  const auto& L = *layout_;
  const int n = grid_.n_cells();
  s << "grid: " << n << " cells, " << grid_.r_f(0) / kAu << " - " << grid_.r_f(n) / kAu
    << " au (dr/r = ";
  if (grid_.stretch() == 0.0)
    s << std::expm1(grid_.dlnr(0)) << ")\n";
  else
    s << std::expm1(grid_.dlnr(0)) << " at r_in to " << std::expm1(grid_.dlnr(n - 1))
      << " at r_out, stretch " << grid_.stretch() << ")\n";
  s << "gas disk: " << disk_->name()
    << (gas_.evolves() ? ", viscously evolving" : ", static") << ", ";
  {  // the profile's gas on the grid's span (spec §1.2; for LBP, its share of M_disk)
    const double m_gas = disk_->mass_between(grid_.r_f(0), grid_.r_f(n));
    s << m_gas / units::kMsun << " M_sun between r_in and r_out";
    if (cfg_.str("disk.model") == "lbp")
      s << " (" << 100.0 * m_gas / (cfg_.real("disk.m_disk_msun") * units::kMsun)
        << " % of disk.m_disk_msun)";
    s << "; ";
  }
  const double r_snow_au = disk_->r_snow() / kAu;
  if (!cfg_.flag("snowline.enabled"))
    s << "snow line off (icy solids everywhere)\n";
  else if (std::isinf(r_snow_au))
    s << "no snow line: warmer than disk.T_sub everywhere (all silicate)\n";
  else if (r_snow_au == 0.0)
    s << "no snow line: colder than disk.T_sub everywhere (all ice)\n";
  else {
    // where T = T_sub may lie off the grid (a warm disk with q > 0: 3.5e5 au was printed
    // as if it were a snow line of the run)
    s << "snow line at " << r_snow_au << " au";
    if (r_snow_au * kAu >= grid_.r_f(n))
      s << " (beyond the outer edge: all silicate on the grid)";
    else if (r_snow_au * kAu <= grid_.r_f(0))
      s << " (inside the inner edge: all ice on the grid)";
    s << "\n";
  }
  s << "state: " << L.size() << " variables; per cell:";
  for (int k = 0; k < L.n_cell_vars(); ++k) s << " " << L.cell_var(k).name;
  s << "; global:";
  for (int k = 0; k < L.n_global_vars(); ++k) s << " " << L.global_var(k).name;
  s << "\nmodules:";
  for (const auto& m : model_->modules()) s << " " << m->name();
  s << "\nJacobian: " << model_->pattern().nnz() << " structural non-zeros\n";
  s << "initial dust mass: " << dust_mass0_ / units::kMearth << " M_earth";
  // the cells' centre values against the profile's exact mass: second order in the width
  if (std::isfinite(profile_dust_mass_)) {
    const double excess = dust_mass0_ / profile_dust_mass_ - 1.0;
    std::ostringstream pct;
    pct << std::showpos << std::setprecision(2) << 100.0 * excess << " %";
    s << " (cell-centre values; the profile holds " << profile_dust_mass_ / units::kMearth
      << " on the grid's span: " << pct.str() << ")";
    if (std::abs(excess) > 0.01)
      s << "\nWARNING: the cells misstate the initial dust mass by " << pct.str()
        << " (cell-centre values of the profile); raise grid.n_cells";
  }
  s << "\n";
  // log-spaced snapshots between equal ends fall on one time (a quick run shortened
  // with output.t_end_yr = t_first_yr): said, not refused
  if (cfg_.reals("output.times_yr").empty() && cfg_.integer("output.n_snapshots") > 1 &&
      cfg_.real("output.t_first_yr") == cfg_.real("output.t_end_yr"))
    s << "WARNING: output.n_snapshots = " << cfg_.integer("output.n_snapshots")
      << " with output.t_first_yr = t_end_yr = " << cfg_.real("output.t_end_yr")
      << " yr: one snapshot after t = 0; lower t_first_yr for more\n";
  if (growth_) {  // spec §0: the contact mechanics behind the collision parameters
    s << physics::contact_summary("ice", material_from_config(cfg_, "ice")) << "\n";
    s << physics::contact_summary("silicate", material_from_config(cfg_, "sil")) << "\n";
    // spec §5.3 has bouncing at every speed for phi >= phi_bounce, and monomers start at
    // phi = 1 (README, "What works").
    if (cfg_.flag("bouncing.enabled"))
      s << "WARNING: bouncing.enabled: particles with phi >= bouncing.phi_bounce = "
        << cfg_.real("bouncing.phi_bounce")
        << " do not stick at any speed (spec §5.3 has no speed or mass threshold): "
        << (cfg_.flag("porosity.enabled")
                ? "the monomers (phi = 1) grow only once hit-and-stick has lowered phi "
                  "below it, and then never bounce"
                : "with porosity off nothing grows")
        << "\n";
    // refresh_local_gas runs where CVODE restarts (README, "What works")
    if (gas_.evolves() && !cfg_.flag("solver.reinit_at_snapshots"))
      s << "WARNING: gas.evolve with solver.reinit_at_snapshots = false: the pressure "
           "gradient (eta) and gas velocity that the particle laws see are set once, at "
           "the start, and not from the evolving gas at every snapshot; set "
           "solver.reinit_at_snapshots = true to follow the gas\n";
  }
  return s.str();
}

}  // namespace panoptic
