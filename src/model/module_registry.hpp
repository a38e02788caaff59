#pragma once
//! The registry of grid modules: for every physical process, when the scene turns it on
//! and how it is built. A new process is one module file (physics/modules/), one key
//! table (src/scene/scene_keys.cpp), one line in module_registry() (module_registry.cpp)
//! and its tests (src/model/README.md).
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "disk/gas_column.hpp"
#include "src/model/pebble_monitors.hpp"
#include "src/scene/config.hpp"
#include "src/solver/physics_module.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

class GasDisk;
class Grid;
class StokesModel;
class GrowthStokes;
class CellGas;
struct ParticleCodec;
class ViscousGas;
class DustTransport;
class PorousGrowth;
class PlanetesimalChannels;
class SizeDistribution;
namespace physics {
struct Species;
}  // namespace physics

//! What the modules are built from, and the modules built so far: a module that needs
//! another finds it here, built before it (registry order).
struct ModuleContext {
  const Config& cfg;
  const Grid& grid;
  const GasDisk& disk;
  GasColumn& gas;  //!< its Sigma_g slot is set by the module that evolves the gas
  StateLayout& layout;
  const StokesModel& stokes;
  const GrowthStokes* growth_stokes;  //!< the growth model's St, null without growth
  ParticleCodec& codec;               //!< the particle decoder; modules fill its slots
  const CellGas& cell_gas;
  const std::vector<physics::Species>& species;  //!< per cell
  std::span<const char> inside_snow_line;        //!< per cell: silicate (1) or ice (0)
  double sigma_d_max;  //!< largest initial Sigma_d [g cm^-2] (tolerance scale)
  double sigma_g_max;  //!< largest initial Sigma_g [g cm^-2] (tolerance scale)
  double dust_mass0;   //!< initial dust mass on the grid [g]
  //! The pebble-flux monitors (faces placed); their slots are filled by the transport.
  std::vector<PebbleMonitor>& monitors;

  //! The modules built, in registry order (build_modules fills it).
  std::vector<const PhysicsModule*> built = {};
  ViscousGas* viscous = nullptr;
  DustTransport* transport = nullptr;
  PorousGrowth* growth = nullptr;
  PlanetesimalChannels* planetesimals = nullptr;  //!< single-size or per bin
  SizeDistribution* distribution = nullptr;
};

struct ModuleEntry {
  std::string_view name;               //!< the module's name()
  bool (*enabled)(const Config& cfg);  //!< whether the scene turns it on
  std::unique_ptr<PhysicsModule> (*build)(ModuleContext& ctx);
  //! Called once every module is built, in registry order (what registers its state
  //! variables after the others'), or null.
  void (*finish)(ModuleContext& ctx);
  //! Its place in DiskModel's sum of the right-hand sides (0 first).
  int evaluation_rank;
};

//! Every process, in the order the modules are built: this order sets the state layout
//! (the modules register their variables as they are built), so a new process goes last.
std::span<const ModuleEntry> module_registry();

//! Builds the modules the scene turns on, in registry order, then finishes them, and
//! returns them in evaluation order.
std::vector<std::unique_ptr<PhysicsModule>> build_modules(ModuleContext& ctx);

}  // namespace panoptic
