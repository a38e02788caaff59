#pragma once
//! What the splitting and local-time-stepping benchmarks compare with the coupled run:
//! the planetesimal mass, the pebble mass through the snow line, the dust budget and
//! Sigma_d on the grid, read from a whole-disk state (bench_split, bench_lts).
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/solver/grid.hpp"

namespace panoptic {

struct FiducialOutcome {
  double m_pl = 0.0;        //!< planetesimals, both channels [M_earth]
  double m_peb_snow = 0.0;  //!< cumulative dust mass through the snow line [M_earth]
  double budget = 0.0;      //!< Simulation::budget_error
  std::vector<double> sigma_d;
};

inline FiducialOutcome measure_outcome(const Simulation& sim, std::span<const double> y) {
  const StateLayout& L = sim.model().layout();
  FiducialOutcome o;
  const int sd = *L.find_cell_var("sigma_d");
  for (int i = 0; i < L.n_cells(); ++i) o.sigma_d.push_back(y[L.index(i, sd)]);
  const auto [coag, si] = sim.planetesimal_mass(y);  // [g]
  o.m_pl = (coag + si) / units::kMearth;
  const auto masses = sim.pebble_mass(y);  // [g], in the order of pebble_monitors()
  for (std::size_t k = 0; k < masses.size(); ++k)
    if (sim.pebble_monitors()[k].name == "snow line")
      o.m_peb_snow = masses[k] / units::kMearth;
  o.budget = sim.budget_error(y);
  return o;
}

//! Mass-weighted L1 distance of Sigma_d from the reference's, relative to its mass.
inline double sigma_l1(const Grid& g, const std::vector<double>& sigma,
                       const std::vector<double>& ref) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    num += std::abs(sigma[i] - ref[i]) * g.area(static_cast<int>(i));
    den += ref[i] * g.area(static_cast<int>(i));
  }
  return num / den;
}

}  // namespace panoptic
