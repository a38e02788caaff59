// presets.cpp — the override sets of --fast and --accurate. The numbers come from the
// work-precision study (tests/bench/work_precision.py; tests/bench/README.md,
// "Work-precision"), which gives their measured costs and errors on params/fiducial.toml
// and erosion_40.toml.
#include "src/scene/presets.hpp"

#include <stdexcept>

namespace panoptic {

std::vector<std::string> preset_overrides(const std::string& preset) {
  if (preset.empty()) return {};
  // Cell count and tolerance only: the scene keeps its cell spacing (grid.stretch).
  // fast: at 250 cells the grid's error (5 % in the planetesimal mass) dwarfs the time
  // error, and rtol 1e-4 gives nearly the largest error of 1e-5 in every round-off draw
  // (5.1 against 5.0 %) for 13 % less time
  // (tests/bench/results/roundoff_scatter_presets.md).
  //
  // accurate: 1e-6 gives the same outcomes as 1e-5 at 1000 cells on the two measured
  // scenes (1.2-1.3x the time); kept as a margin for scenes without a work-precision
  // study, so that --accurate never loosens a scene's own tolerance
  // (compact_fragmentation uses the default 1e-6). Its steps are short enough that a
  // Jacobian kept for CVODE's own 51 steps rarely stalls Newton: the fresher ones of
  // solver.steps_per_jacobian = 10 cost more than they save there (fiducial: 10.75
  // against 10.05 s, bench_fiducial --runs 3; tests/bench/README.md, Performance).
  if (preset == "fast") return {"grid.n_cells=250", "solver.rtol=1e-4"};
  if (preset == "accurate")
    return {"grid.n_cells=1000", "solver.rtol=1e-6", "solver.steps_per_jacobian=0"};
  throw std::invalid_argument("unknown preset '" + preset + "' (fast, accurate)");
}

std::vector<std::string> with_preset(const std::string& preset,
                                     const std::vector<std::string>& sets) {
  std::vector<std::string> all = preset_overrides(preset);
  all.insert(all.end(), sets.begin(), sets.end());
  return all;
}

}  // namespace panoptic
