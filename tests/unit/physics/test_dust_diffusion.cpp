// Turbulent diffusion acts on the dust-to-gas ratio, not on Sigma_d (spec §6.1: the flux
// is -D_d Sigma_g d(Sigma_d/Sigma_g)/dr). A disk with the same dust-to-gas ratio
// everywhere is therefore a steady state of diffusion, whatever Sigma_g(r) and D(r) are,
// while a flat Sigma_d on a falling Sigma_g is not. The diffusing-ring regression test
// runs on a flat Sigma_g (ring_diffusion.toml, p = 0), where both forms agree; these
// checks fail for diffusion written on Sigma_d.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/modules/dust_transport.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"

namespace panoptic {
namespace {

// MMSN gas (Sigma_g ∝ r^-1.5, T ∝ r^-1/2: D varies with r), diffusion alone, a
// prescribed St, no snow line (whose composition step would change the ratio).
Config diffusion_scene(const std::string& extra) {
  const std::string file = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> sets{"grid.n_cells=50",
                                      "growth.enabled=false",
                                      "porosity.enabled=false",
                                      "transport.drift=false",
                                      "transport.St=0.1",
                                      "snowline.enabled=false",
                                      "planetesimals.coagulation=false",
                                      "planetesimals.si=none",
                                      extra};
  return load_scene(file, sets);
}

// d Sigma_d/dt of every cell at state y, and the largest |d Sigma_d/dt| / Sigma_d.
std::vector<double> sigma_rates(const Simulation& sim, const std::vector<double>& y,
                                double& largest_rel) {
  const auto& L = sim.model().layout();
  std::vector<double> ydot(y.size());
  sim.model().rhs(0.0, y, ydot);
  std::vector<double> rate(L.n_cells());
  largest_rel = 0.0;
  for (int i = 0; i < L.n_cells(); ++i) {
    const long k = L.index(i, sim.transport().sigma_slot());
    rate[i] = ydot[k];
    largest_rel = std::max(largest_rel, std::abs(ydot[k]) / y[k]);
  }
  return rate;
}

TEST(DustDiffusion, UniformDustToGasRatioIsSteadyAndFlatSigmaDIsNot) {
  for (const std::string gas : {"disk.p=1.5", "disk.p=0.8"}) {
    Simulation sim(diffusion_scene(gas));
    const auto& L = sim.model().layout();
    const int sd = sim.transport().sigma_slot();
    // Sigma_d flat where Sigma_g falls with r: the ratio rises outward, diffusion moves
    // dust inward (down the ratio's gradient): the outermost cell loses dust, the
    // innermost (no diffusion through r_in, spec §6.3) gains it. Its largest relative
    // rate is the scale of the check below.
    auto y = sim.initial_state();
    for (int i = 0; i < L.n_cells(); ++i) y[L.index(i, sd)] = 1.0;
    double flat = 0.0;
    const auto rate = sigma_rates(sim, y, flat);
    EXPECT_LT(rate[L.n_cells() - 1], 0.0) << gas;
    EXPECT_GT(rate[0], 0.0) << gas;
    // Sigma_d = 0.01 Sigma_g in every cell: steady to round-off
    double uniform = 0.0;
    sigma_rates(sim, sim.initial_state(), uniform);
    EXPECT_LT(uniform, 1e-12 * flat) << gas << ": a uniform dust-to-gas ratio diffuses";
    std::printf(
        "%s: largest |dSigma_d/dt| / Sigma_d %.2e s^-1 (flat Sigma_d), %.2e "
        "(uniform ratio)\n",
        gas.c_str(), flat, uniform);
  }
}

}  // namespace
}  // namespace panoptic
