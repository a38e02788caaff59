#include "physics/modules/dust_face_flux.hpp"

#include <cmath>
#include <stdexcept>

#include "disk/gas_disk.hpp"

namespace panoptic {

DustFaceFlux::DustFaceFlux(const Grid& grid, const GasDisk& disk, const GasColumn& gas,
                           const ViscousStencil* viscous, DustTransportOptions options)
    : grid_(grid), gas_(gas), viscous_(viscous), opt_(options) {
  const int n = grid.n_cells();
  two_pi_r_.resize(n);
  two_pi_rc_.resize(n);
  dr_.resize(n);
  d_gas_.resize(n);
  hr2vk_.resize(n);
  eta_vk_static_.resize(n);
  ln_cs_omega_.resize(n);
  for (int i = 0; i < n; ++i)
    ln_cs_omega_[i] = std::log(disk.c_s(grid.r_c(i)) * disk.omega_k(grid.r_c(i)));
  for (int f = 0; f < n; ++f) {
    const double r = grid.r_f(f);
    const double hr = disk.h_g(r) / r;
    two_pi_r_[f] = 2.0 * units::kPi * r;
    two_pi_rc_[f] = 2.0 * units::kPi * grid.r_c(f);
    dr_[f] = f > 0 ? grid.r_c(f) - grid.r_c(f - 1) : grid.r_c(0) - grid.r_f(0);
    d_gas_[f] = disk.nu(r);  // Schmidt number 1 (spec §1.5)
    hr2vk_[f] = hr * hr * disk.v_k(r);
    // eta v_K (spec §1.4), the gradient from the two neighbouring centres (at the inner
    // face: the gradient of the first interior face).
    const int a = f > 0 ? f - 1 : 0;
    const double dlnp =
        (std::log(gas.static_sigma[a + 1]) - std::log(gas.static_sigma[a]) +
         ln_cs_omega_[a + 1] - ln_cs_omega_[a]) /
        grid.dlnr_centres(a + 1);
    eta_vk_static_[f] = pressure_gradient_eta(hr2vk_[f], dlnp);
  }
  if (gas.evolves() && viscous == nullptr)
    throw std::logic_error("DustFaceFlux: evolving gas needs the viscous stencil");
}

}  // namespace panoptic
