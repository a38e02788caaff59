#include "src/run/report.hpp"

#include <cmath>
#include <cstdio>

#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/run/run.hpp"
#include "src/scene/config.hpp"

namespace fs = std::filesystem;

namespace panoptic {

void warn_unused_keys(const Config& cfg) {
  if (const std::string w = empty_scene_warning(cfg); !w.empty())
    std::fprintf(stderr, "%s\n", w.c_str());
  for (const std::string& w : unused_key_warnings(cfg))
    std::fprintf(stderr, "%s\n", w.c_str());
}

std::string restart_command(const RunArgs& a, const fs::path& chk) {
  const auto quote = [](const std::string& s) {
    if (s.find_first_of(" \t\"'$`\\*?[]()<>|;&!#~{}") == std::string::npos) return s;
    std::string q = "'";
    for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  // with no scene file: the checkpoint holds the scene, its --set options included
  std::string cmd = quote(a.program) + " run " +
                    (a.scene.empty() ? "" : quote(a.scene) + " ") + "--restart " +
                    quote(chk.string());
  for (const std::string& s : a.overrides) cmd += " --set " + quote(s);
  if (!a.output.empty()) cmd += " -o " + quote(a.output);
  if (a.threads > 1) cmd += " --threads " + std::to_string(a.threads);
  return cmd;
}

void print_budget(const Simulation& sim, std::span<const double> y) {
  const auto masses = sim.budget_masses(y);
  std::string terms;
  double total = 0.0;
  char buf[96];
  for (std::size_t k = 0; k < masses.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%s%s %.6g", k ? " + " : "",
                  sim.budget_terms()[k].label.c_str(), masses[k] / units::kMearth);
    terms += buf;
    total += masses[k];
  }
  const double m0 = sim.initial_dust_mass();  // the error as Simulation::budget_error
  const double error = std::abs(total - m0) / m0;
  std::printf("dust budget [M_earth]: %s = %.6g; initial %.6g; relative error %.2e\n",
              terms.c_str(), total / units::kMearth, m0 / units::kMearth, error);
  // The terms are integrated with the state, so the budget closes to round-off (<= 7e-14
  // over every scene and the extremes matrix) when the Newton systems are solved
  // directly, and with GMRES, whose solutions are corrected to keep the budget's
  // invariant (src/solver/conservative_gmres.hpp, conservative_spgmr_solve): more means a
  // sink or source that is not booked as a budget term, a bug of the model, not of the
  // integration.
  const double limit = 1e-10;
  if (!(error <= limit))
    std::printf(
        "WARNING: the dust budget does not close (%.2e > %.0e): some dust leaves or "
        "enters the grid without a budget term; a module's sink or source is not booked "
        "(physics/README.md, Adding a physical process)\n",
        error, limit);
}

}  // namespace panoptic
