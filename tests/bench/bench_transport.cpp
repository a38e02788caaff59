// Benchmark (not a test): wall time per cell per CVODE step for dust transport alone
// (fiducial scene, prescribed St), N = 100 to 10^4 cells, median of 5 runs each.
// Usage: build/tests/bench_transport [t_end_yr]   (default 1e5)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "src/core/units.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/cvode_integrator.hpp"

using namespace panoptic;

int main(int argc, char** argv) {
  // one optional argument, a positive number of years ("--help" was read as 0 yr)
  char* end = nullptr;
  const double t_end_yr = argc > 1 ? std::strtod(argv[1], &end) : 1e5;
  if (argc > 2 || (argc > 1 && (end == argv[1] || *end != '\0' || !(t_end_yr > 0.0)))) {
    std::fprintf(stderr,
                 "usage: bench_transport [t_end_yr]   (a number > 0; default 1e5)\n");
    return 2;
  }
  const std::string scene = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  std::printf(
      "dust transport alone (params/fiducial.toml, prescribed St), to %.0e yr, "
      "median of 5 runs\n",
      t_end_yr);
  std::printf("%8s %8s %8s %8s %12s %16s\n", "N", "steps", "RHS", "Jac", "wall [s]",
              "us/(cell step)");
  for (int n : {100, 300, 1000, 3000, 10000}) {
    const std::vector<std::string> sets{"grid.n_cells=" + std::to_string(n),
                                        "growth.enabled=false",
                                        "porosity.enabled=false",
                                        "planetesimals.coagulation=false",
                                        "planetesimals.si=\"none\"",
                                        "transport.St=0.01"};
    const Config cfg = load_scene(scene, sets);
    std::vector<double> walls;
    SolverStats stats;
    for (int rep = 0; rep < 5; ++rep) {
      Simulation sim(cfg);
      const auto y0 = sim.initial_state();
      const auto t0 = std::chrono::steady_clock::now();
      CvodeIntegrator cvode(sim.model(), 0.0, y0, sim.integrator_options());
      cvode.advance_to(t_end_yr * units::kYr);
      walls.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      stats = cvode.stats();
    }
    std::sort(walls.begin(), walls.end());
    const double wall = walls[walls.size() / 2];
    std::printf("%8d %8ld %8ld %8ld %12.4f %16.3f\n", n, stats.nst, stats.nfe, stats.nje,
                wall, 1e6 * wall / (double(n) * double(stats.nst)));
  }
  return 0;
}
