#include "disk/viscous_gas.hpp"

#include <cmath>

#include "disk/gas_disk.hpp"
#include "src/core/units.hpp"
#include "src/solver/grid.hpp"

namespace panoptic {

ViscousStencil make_viscous_stencil(const GasDisk& disk, const Grid& grid,
                                    bool zero_torque) {
  const int n = grid.n_cells();
  ViscousStencil s;
  s.zero_torque = zero_torque;
  s.g_coef.resize(n);
  s.face_coef.resize(n);
  for (int i = 0; i < n; ++i) s.g_coef[i] = disk.nu(grid.r_c(i)) * std::sqrt(grid.r_c(i));
  // Inner face, F = face_coef[0] g_0 Sigma_0 with g_0 = nu_0 r_c0^(1/2):
  //   zero torque: F = -(3/r_f^(1/2)) (g_0 - 0)/(r_c0 - r_f0), one-sided difference;
  //   free flow:   2 pi r_f F = -3 pi nu_0 Sigma_0  ->  F = -3 g_0 Sigma_0/(2 r_f
  //   r_c0^(1/2)).
  s.face_coef[0] = zero_torque
                       ? -3.0 / (std::sqrt(grid.r_f(0)) * (grid.r_c(0) - grid.r_f(0)))
                       : -1.5 / (grid.r_f(0) * std::sqrt(grid.r_c(0)));
  for (int f = 1; f < n; ++f)
    s.face_coef[f] = -3.0 / (std::sqrt(grid.r_f(f)) * (grid.r_c(f) - grid.r_c(f - 1)));
  return s;
}

ViscousGas::ViscousGas(StateLayout& layout, const GasDisk& disk, const Grid& grid,
                       double sigma_scale, bool zero_torque)
    : layout_(layout),
      grid_(grid),
      stencil_(make_viscous_stencil(disk, grid, zero_torque)) {
  slot_ = layout.add_cell_var(
      {"sigma_g", "g cm^-2", "gas surface density", sigma_scale, true});
  double m = 0.0;
  for (int i = 0; i < grid.n_cells(); ++i) m += disk.sigma_g(grid.r_c(i)) * grid.area(i);
  mass_unit_ = m;
  const double area_total =
      units::kPi * grid.r_f(grid.n_cells()) * grid.r_f(grid.n_cells());
  g_out_ =
      layout.add_global_var({"m_out_gas", "initial gas mass",
                             "gas mass accreted through r_in, in units of the initial "
                             "gas mass on the grid",
                             sigma_scale * area_total / m, false});
}

void ViscousGas::declare_pattern(PatternBuilder& p) const {
  const int n = grid_.n_cells();
  for (int f = 0; f < n; ++f) {  // face f couples cells a and b (see ViscousStencil)
    const long a = layout_.index(f > 0 ? f - 1 : 0, slot_);
    const long b = layout_.index(f > 0 ? f : 1, slot_);
    const long row_out = f > 0 ? a : layout_.global_index(g_out_);
    for (long row : {row_out, layout_.index(f, slot_)})
      for (long col : {a, b}) p.add(row, col);
  }
}

void ViscousGas::add_rhs(double, std::span<const double> y,
                         std::span<double> ydot) const {
  const int n = grid_.n_cells();
  for (int f = 0; f < n; ++f) {
    const double sa = y[layout_.index(f > 0 ? f - 1 : 0, slot_)];
    const double sb = y[layout_.index(f > 0 ? f : 1, slot_)];
    const double mdot = 2.0 * units::kPi * grid_.r_f(f) * stencil_.face_flux(f, sa, sb);
    ydot[layout_.index(f, slot_)] += mdot / grid_.area(f);
    if (f > 0)
      ydot[layout_.index(f - 1, slot_)] -= mdot / grid_.area(f - 1);
    else
      ydot[layout_.global_index(g_out_)] -= mdot / mass_unit_;  // outflow (< 0) books +
  }
}

void ViscousGas::add_jacobian(double, std::span<const double>,
                              JacobianValues& jac) const {
  // The flux is linear in Sigma_g: dMdot/dSigma_a and dMdot/dSigma_b are constants.
  const int n = grid_.n_cells();
  for (int f = 0; f < n; ++f) {
    const double c = 2.0 * units::kPi * grid_.r_f(f) * stencil_.face_coef[f];
    const long a = layout_.index(f > 0 ? f - 1 : 0, slot_);
    const long b = layout_.index(f > 0 ? f : 1, slot_);
    double d_a, d_b;
    if (f == 0) {  // F = coef g_0 Sigma_0
      d_a = c * stencil_.g_coef[0];
      d_b = 0.0;
    } else {
      d_a = -c * stencil_.g_coef[f - 1];
      d_b = c * stencil_.g_coef[f];
    }
    const long self = layout_.index(f, slot_);
    jac.add(self, a, d_a / grid_.area(f));
    jac.add(self, b, d_b / grid_.area(f));
    if (f > 0) {
      jac.add(a, a, -d_a / grid_.area(f - 1));
      jac.add(a, b, -d_b / grid_.area(f - 1));
    } else {
      jac.add(layout_.global_index(g_out_), a, -d_a / mass_unit_);
      jac.add(layout_.global_index(g_out_), b, -d_b / mass_unit_);
    }
  }
}

std::vector<OutputField> ViscousGas::output_fields() const {
  return {{"m_out_gas", 0, "g", "cumulative gas accreted through r_in",
           [this](std::span<const double> y) {
             return std::vector<double>{y[layout_.global_index(g_out_)] * mass_unit_};
           }}};
}

}  // namespace panoptic
