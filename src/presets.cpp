// presets.cpp — the override sets of --fast and --accurate. The numbers come from the
// work-precision study (tests/bench/work_precision.py; README, "Work-precision"), which
// gives their measured costs and errors on params/fiducial.toml and erosion_40.toml.
#include "src/presets.hpp"

#include <stdexcept>

namespace panoptic {

std::vector<std::string> preset_overrides(const std::string& preset) {
  if (preset.empty()) return {};
  // cell count and tolerance only: the scene keeps its cell spacing (grid.stretch)
  if (preset == "fast") return {"grid.n_cells=250", "solver.rtol=1e-5"};
  if (preset == "accurate") return {"grid.n_cells=1000", "solver.rtol=1e-6"};
  throw std::invalid_argument("unknown preset '" + preset + "' (fast, accurate)");
}

std::vector<std::string> with_preset(const std::string& preset,
                                     const std::vector<std::string>& sets) {
  std::vector<std::string> all = preset_overrides(preset);
  all.insert(all.end(), sets.begin(), sets.end());
  return all;
}

}  // namespace panoptic
