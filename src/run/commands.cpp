#include "src/run/commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/model/scene_validation.hpp"
#include "src/model/simulation.hpp"
#include "src/model/track.hpp"
#include "src/run/report.hpp"
#include "src/scene/config.hpp"

namespace panoptic {

int check_scene(const std::string& scene, const std::vector<std::string>& overrides) {
  const Config cfg = load_scene(scene, overrides);
  validate_scene(cfg);
  warn_unused_keys(cfg);
  Simulation sim(cfg);
  std::printf("# scene %s is valid.\n", scene.c_str());
  std::string summary = sim.summary(), commented;
  for (std::size_t a = 0, b; a < summary.size(); a = b + 1) {
    b = summary.find('\n', a);
    if (b == std::string::npos) b = summary.size();
    commented += "# " + summary.substr(a, b - a) + "\n";
  }
  std::printf("%s\n%s", commented.c_str(), cfg.resolved_toml().c_str());
  return 0;
}

int track_command(const std::string& scene, const std::vector<std::string>& overrides,
                  double r0_au, double a_stop_cm, double t_max_yr) {
  const Config cfg = load_scene(scene, overrides);
  validate_scene(cfg);
  if (!(r0_au > cfg.real("grid.r_in_au") && r0_au <= 1e6))
    throw ConfigError(
        "--r0-au " + num(r0_au) + ": must be > the inner edge grid.r_in_au = " +
        num(cfg.real("grid.r_in_au")) + " and <= 1e6 [au]; release the particle there");
  // a time or size of 0, below, NaN or inf ended the track at once with exit 0 (or
  // failed in CVODE)
  if (!(t_max_yr >= 1e-6 && t_max_yr <= 1e12))
    throw ConfigError("--t-max-yr " + num(t_max_yr) +
                      ": must be >= 1e-6 and <= 1e12 [yr]");
  if (!(a_stop_cm > 0.0 && std::isfinite(a_stop_cm)))
    throw ConfigError("--a-stop-cm " + num(a_stop_cm) + ": must be a radius > 0 [cm]");
  const TrackResult res =
      track_particle(cfg, r0_au * units::kAu, a_stop_cm, t_max_yr * units::kYr);
  std::printf("# panoptic track %s: monomer released at %.4g au (%ld CVODE steps)\n",
              scene.c_str(), r0_au, res.steps);
  std::printf("# %12s %10s %12s %12s %12s %12s\n", "t [yr]", "r [au]", "m [g]", "phi",
              "a [cm]", "St");
  // about 40 rows, log-spaced in time; the last the stop itself (interpolated to
  // a = a_stop) when the particle got there, not the step that went past it
  const auto row = [](const TrackPoint& p) {
    std::printf("  %12.5g %10.4g %12.5g %12.5g %12.5g %12.5g\n", p.t / units::kYr,
                p.r / units::kAu, p.m, p.phi, p.a, p.St);
  };
  const std::size_t n_rows = res.points.size() - (res.reached ? 1 : 0);
  double next = 0.0;
  for (std::size_t k = 0; k < n_rows; ++k) {
    const TrackPoint& p = res.points[k];
    if (p.t < next && (res.reached || k + 1 != n_rows)) continue;
    row(p);
    next = std::max(p.t * 1.25, 1.0 * units::kYr);
  }
  if (res.reached) row(res.at_stop);
  if (res.reached)
    std::printf("reached a = %.4g cm at t = %.4g yr, r = %.4g au\n", a_stop_cm,
                res.at_stop.t / units::kYr, res.at_stop.r / units::kAu);
  else
    std::printf(
        "did not reach a = %.4g cm (last: t = %.4g yr, r = %.4g au, a = %.4g cm)\n",
        a_stop_cm, res.points.back().t / units::kYr, res.points.back().r / units::kAu,
        res.points.back().a);
  return 0;
}

}  // namespace panoptic
