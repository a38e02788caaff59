#include "src/model/pebble_monitors.hpp"

#include <cmath>

#include "physics/modules/dust_face_flux.hpp"
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/solver/grid.hpp"

namespace panoptic {

using units::kAu;

std::vector<PebbleMonitor> place_pebble_monitors(const Config& cfg, const Grid& grid,
                                                 double r_snow) {
  const int n = grid.n_cells();
  std::vector<std::pair<std::string, double>> radii;
  if (cfg.reals("pebbles.radii_au").empty()) {
    if (std::isfinite(r_snow)) radii.emplace_back("snow line", r_snow / kAu);
    for (double r : {1.0, 3.0, 10.0, 30.0}) radii.emplace_back(num(r) + " au", r);
  } else {
    for (double r : cfg.reals("pebbles.radii_au")) radii.emplace_back(num(r) + " au", r);
  }
  std::vector<PebbleMonitor> monitors;
  for (const auto& [name, r_au] : radii) {
    if (r_au <= grid.r_f(0) / kAu || r_au >= grid.r_f(n) / kAu) continue;
    int face = 1;
    for (int f = 1; f < n; ++f)
      if (std::abs(std::log(grid.r_f(f) / (r_au * kAu))) <
          std::abs(std::log(grid.r_f(face) / (r_au * kAu))))
        face = f;
    monitors.push_back({name, grid.r_f(face) / kAu, face, -1});
  }
  monitors.push_back({"r_in", grid.r_f(0) / kAu, 0, -1});
  return monitors;
}

std::vector<double> Simulation::pebble_flux(std::span<const double> y) const {
  const auto mdot = dust_->mass_flow(y);
  std::vector<double> out;
  for (const auto& mon : monitors_) out.push_back(-mdot[mon.face]);  // inward positive
  return out;
}

std::vector<double> Simulation::pebble_mass(std::span<const double> y) const {
  std::vector<double> out;
  for (const auto& mon : monitors_)
    out.push_back(y[layout_->global_index(mon.global_slot)] * dust_->mass_unit());
  return out;
}

}  // namespace panoptic
