#include "src/model/module_registry.hpp"

#include <algorithm>
#include <array>

#include "disk/viscous_gas.hpp"
#include "physics/modules/bin_planetesimals.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/modules/planetesimals.hpp"
#include "physics/modules/porous_growth.hpp"
#include "physics/modules/size_distribution.hpp"
#include "src/core/error.hpp"
#include "src/model/scene_to_physics.hpp"
#include "src/solver/grid.hpp"

namespace panoptic {
namespace {

// Viscous evolution of the gas (spec §1.2): owns Sigma_g, which the others read.
std::unique_ptr<PhysicsModule> build_viscous_gas(ModuleContext& c) {
  auto gas = std::make_unique<ViscousGas>(c.layout, c.disk, c.grid, c.sigma_g_max,
                                          c.cfg.str("gas.inner_bc") == "zero_torque");
  c.gas.slot = gas->sigma_slot();
  c.viscous = gas.get();
  return gas;
}

// Radial transport of the dust (spec §6.1, §6.3): owns Sigma_d.
std::unique_ptr<PhysicsModule> build_dust_transport(ModuleContext& c) {
  auto transport = std::make_unique<DustTransport>(
      c.layout, c.grid, c.disk, c.gas, c.viscous ? &c.viscous->stencil() : nullptr,
      c.stokes, transport_options_from_config(c.cfg), c.sigma_d_max, c.dust_mass0);
  c.codec.sigma_slot = transport->sigma_slot();
  c.transport = transport.get();
  return transport;
}

// The snow line face: the first face with silicate inside and ice outside (spec §6.3),
// or -1.
int snow_line_face(const ModuleContext& c) {
  for (int f = 1; f < c.grid.n_cells(); ++f)
    if (c.inside_snow_line[f - 1] && !c.inside_snow_line[f]) return f;
  return -1;
}

// The monitors and the snow line book global variables after every module's own.
void finish_dust_transport(ModuleContext& c) {
  // pebble-flux monitors (spec §8); r_in is booked as m_out_dust already
  for (PebbleMonitor& mon : c.monitors)
    mon.global_slot = mon.face > 0 ? c.transport->add_monitor(c.layout, mon.face)
                                   : c.transport->m_out_slot();
  const int f = snow_line_face(c);
  if (f > 0)
    c.transport->set_snowline(c.layout, f, c.cfg.real("snowline.f_ice"),
                              c.growth ? c.codec.qm_slot : -1);
}

// The porous growth model (spec §4-§6.2): owns Q_m and Q_phi, which ride with the dust.
std::unique_ptr<PhysicsModule> build_porous_growth(ModuleContext& c) {
  auto growth = std::make_unique<PorousGrowth>(
      c.layout, c.codec, c.cell_gas, *c.growth_stokes, c.species,
      growth_options_from_config(c.cfg), c.sigma_d_max);
  c.transport->add_passenger(
      c.codec.qm_slot);  // spec §6.2: Q_m, Q_phi ride with the dust
  if (c.codec.qphi_slot >= 0) c.transport->add_passenger(c.codec.qphi_slot);
  c.growth = growth.get();
  return growth;
}

// Planetesimal channels (spec §7), after the growth model whose particles they convert.
// Without growth only the SI channel can run, on the prescribed St.
std::unique_ptr<PhysicsModule> build_planetesimals(ModuleContext& c) {
  auto pl = std::make_unique<Planetesimals>(c.layout, c.codec, c.cell_gas, c.stokes,
                                            c.species, growth_options_from_config(c.cfg),
                                            planetesimal_options_from_config(c.cfg),
                                            c.sigma_d_max);
  if (c.growth) pl->use_growth_rates(c.growth);
  c.planetesimals = pl.get();
  return pl;
}

bool single_size(const Config& cfg) { return cfg.str("model.kind") == "single_size"; }

// The size distribution (spec §15, model.kind = "distribution"): owns a sigma_k per mass
// bin and cell, transported by the dust transport's flux operator, in place of the
// single-size modules.
std::unique_ptr<PhysicsModule> build_size_distribution(ModuleContext& c) {
  const Config& cfg = c.cfg;
  SizeDistributionOptions o;
  o.m_min = cfg.real("model.m_min_g");
  o.m_max = cfg.real("model.m_max_g");
  o.bins_per_decade = cfg.real("model.bins_per_decade");
  o.coagulation = cfg.flag("growth.enabled");
  o.mrn = cfg.str("model.init") == "mrn";
  o.a_max_init = cfg.real("model.a_max_init_um") * 1e-4;
  o.empty_bin_fraction = atol_sigma_from_config(cfg);
  o.growth = growth_options_from_config(cfg);
  o.porosity_track =
      o.coagulation && o.growth.porosity && cfg.str("porosity.bins") == "track";
  const double m_first = SizeDistribution::first_bin_mass(o, c.species);
  if (m_first >= o.m_max)
    cfg.fail("model.m_max_g",
             "= " + num(o.m_max) + " [g] must exceed the first bin, " + num(m_first) +
                 " g (model.m_min_g, or the smallest monomer mass); raise it");
  auto dist = std::make_unique<SizeDistribution>(
      c.layout, c.grid, c.disk, c.gas, c.viscous ? &c.viscous->stencil() : nullptr,
      c.cell_gas, c.species, transport_options_from_config(cfg), o, c.sigma_d_max,
      c.dust_mass0);
  c.distribution = dist.get();
  return dist;
}

// The pebble-flux monitors and the snow line (spec §6.3, §15.4) book global variables
// after every module's own, in the order of the single-size model's.
void finish_size_distribution(ModuleContext& c) {
  for (PebbleMonitor& mon : c.monitors)
    mon.global_slot = c.distribution->add_monitor(c.layout, mon.face);
  const int f = snow_line_face(c);
  if (f > 0) c.distribution->set_snowline(c.layout, f, c.cfg.real("snowline.f_ice"));
}

bool planetesimals_on(const Config& cfg) {
  return cfg.flag("planetesimals.coagulation") || cfg.str("planetesimals.si") != "none";
}

// Planetesimal channels per mass bin of the size distribution (spec §15.4), after it.
std::unique_ptr<PhysicsModule> build_bin_planetesimals(ModuleContext& c) {
  auto pl = std::make_unique<BinPlanetesimals>(c.layout, *c.distribution,
                                               planetesimal_options_from_config(c.cfg),
                                               c.sigma_d_max, c.codec.eps_sigma);
  c.planetesimals = pl.get();
  return pl;
}

// NEW_MODULE: one line here (build order = state layout order; a new process goes last).
// The evaluation ranks keep the order in which the right-hand sides are summed (the
// transport last): another order changes the last bits of every run.
constexpr std::array<ModuleEntry, 6> kRegistry{{
    {"viscous_gas", [](const Config& cfg) { return cfg.flag("gas.evolve"); },
     build_viscous_gas, nullptr, 0},
    {"dust_transport", single_size, build_dust_transport, finish_dust_transport, 3},
    {"porous_growth",
     [](const Config& cfg) { return single_size(cfg) && cfg.flag("growth.enabled"); },
     build_porous_growth, nullptr, 1},
    {"planetesimals",
     [](const Config& cfg) { return single_size(cfg) && planetesimals_on(cfg); },
     build_planetesimals, nullptr, 2},
    {"size_distribution", [](const Config& cfg) { return !single_size(cfg); },
     build_size_distribution, finish_size_distribution, 3},
    {"bin_planetesimals",
     [](const Config& cfg) { return !single_size(cfg) && planetesimals_on(cfg); },
     build_bin_planetesimals, nullptr, 2},
}};

}  // namespace

std::span<const ModuleEntry> module_registry() { return kRegistry; }

std::vector<std::unique_ptr<PhysicsModule>> build_modules(ModuleContext& ctx) {
  std::vector<std::pair<int, std::unique_ptr<PhysicsModule>>> built;
  std::vector<const ModuleEntry*> on;
  for (const ModuleEntry& e : module_registry())
    if (e.enabled(ctx.cfg)) {
      built.emplace_back(e.evaluation_rank, e.build(ctx));
      ctx.built.push_back(built.back().second.get());
      on.push_back(&e);
    }
  for (const ModuleEntry* e : on)
    if (e->finish) e->finish(ctx);
  std::stable_sort(built.begin(), built.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::unique_ptr<PhysicsModule>> modules;
  for (auto& [rank, m] : built) modules.push_back(std::move(m));
  return modules;
}

}  // namespace panoptic
