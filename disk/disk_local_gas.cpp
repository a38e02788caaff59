#include "disk/disk_local_gas.hpp"

#include "src/solver/grid.hpp"

namespace panoptic {

physics::LocalGas local_gas_at(const GasDisk& disk, double r, double sigma_g,
                               double dlnp_dlnr) {
  const ThermalParams& th = disk.thermal();
  return physics::make_local_gas(sigma_g, disk.temperature(r), r, disk.star().mass,
                                 disk.alpha(r), dlnp_dlnr, th.mu, th.sigma_mol);
}

std::vector<physics::LocalGas> local_gas_centres(const GasDisk& disk, const Grid& grid,
                                                 std::span<const double> sigma_g) {
  const std::vector<double> sigma(sigma_g.begin(), sigma_g.end());
  const auto dlnp = dlnp_dlnr_centres(disk, grid, sigma);
  std::vector<physics::LocalGas> out(sigma.size());
  for (std::size_t i = 0; i < sigma.size(); ++i)
    out[i] = local_gas_at(disk, grid.r_c(int(i)), sigma[i], dlnp[i]);
  return out;
}

}  // namespace panoptic
