// The dust face fluxes of physics/modules/dust_transport.cpp against numbers worked out
// independently (mpmath, 30 digits) from spec §6.1 and the finite-volume form described
// in physics/modules/dust_transport.hpp, on a 3-cell log-spaced grid from 3 to 9 au
// (faces 3, 4.3267, 6.2403, 9 au; centres the geometric means of their faces), MMSN gas
// (spec §1.2 A, §1.3: T = 280 r^-1/2 K, mu = 2.34, M = 1 M_sun), alpha = 1e-3, prescribed
// St (0.05, 0.2, 0.8) per cell, so St on the interior faces is the geometric mean of the
// neighbours: 0.1 and 0.4 (the inner face takes the first cell's 0.05).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "disk/gas_column.hpp"
#include "disk/gas_disk.hpp"
#include "disk/viscous_gas.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/stokes_model.hpp"
#include "src/core/units.hpp"
#include "src/solver/grid.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {
namespace {

using units::kAu;

PowerLawDisk mmsn() {
  ThermalParams th;  // T_1au = 280 K, q = 1/2, mu = 2.34, alpha = 1e-3 (spec §10.1)
  return PowerLawDisk({units::kMsun, units::kLsun}, th, 1700.0, 1.5);
}

const std::vector<double> kSt{0.05, 0.2, 0.8};

// spec §6.1 diffusion term, F_d = -D_d Sigma_g d(Sigma_d/Sigma_g)/dr, D_d = alpha c_s H/
// (1 + St^2), on the faces of the finite volumes: the face gets D_g = alpha c_s H at r_f,
// St_f and Sigma_g,f as geometric means of the neighbours, and the concentration gradient
// (eps_b - eps_a)/(r_c(b) - r_c(a)) between the two centres; no diffusion through r_in
// (spec §6.3), none through the closed r_out. The middle cell then changes at
//   dSigma_d/dt = (2 pi r_f1 F_1 - 2 pi r_f2 F_2)/(pi (r_f2^2 - r_f1^2)).
// Static MMSN gas, eps = Sigma_d/Sigma_g = 0.01 + 0.002 (r/au) (linear in r), drift off.
// Independent numbers: mpmath (30 digits) from the formula above. Measured relative
// error 2.2e-16, 2.8e-14, 3.3e-16 in cells 0, 1, 2 (ydot[1] is the difference of two
// fluxes ~40x larger); tolerance 1e-12. The wrong face distance r_f(f+1) - r_f(f) gives
// ydot[1] x 0.833 (mpmath).
TEST(DustTransportFlux, DiffusiveFluxOfALinearDustToGasRatio) {
  const auto disk = mmsn();
  const Grid grid(3.0 * kAu, 9.0 * kAu, 3);
  GasColumn gas;
  for (int i = 0; i < 3; ++i) gas.static_sigma.push_back(disk.sigma_g(grid.r_c(i)));
  StateLayout layout(3);
  PrescribedStokes stokes(kSt);
  DustTransportOptions opt;
  opt.drift = false;
  opt.diffusion = true;
  DustTransport transport(layout, grid, disk, gas, nullptr, stokes, opt, 1.0, 1.0);
  layout.freeze();
  std::vector<double> y(layout.size(), 0.0), ydot(layout.size(), 0.0);
  const int sd = transport.sigma_slot();
  for (int i = 0; i < 3; ++i)
    y[layout.index(i, sd)] =
        (0.01 + 0.002 * grid.r_c(i) / kAu) * disk.sigma_g(grid.r_c(i));
  // Sigma_d from mpmath: a check on the set-up (grid centres, MMSN profile)
  const double sigma_d[] = {4.2771757536429947, 2.9267957320213885, 2.0706282432937352};
  for (int i = 0; i < 3; ++i)
    ASSERT_NEAR(y[layout.index(i, sd)] / sigma_d[i], 1.0, 1e-13);
  transport.add_rhs(0.0, y, ydot);
  const double want[] = {3.1915958896191632e-13, 7.0033348266389437e-15,
                         -7.7131151989432664e-14};
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(ydot[layout.index(i, sd)] / want[i], 1.0, 1e-12) << "cell " << i;
  // nothing leaves: the fluxes cancel in the total (round-off of 3e-13 / 1e-15)
  double total = 0.0;
  for (int i = 0; i < 3; ++i) total += ydot[layout.index(i, sd)] * grid.area(i);
  EXPECT_NEAR(total, 0.0, 1e-13 * std::abs(want[0]) * grid.area(0));
}

// spec §6.1: v_r = -2 St eta v_K/(1 + St^2) + v_g/(1 + St^2), on every face, with gas
// that evolves: Sigma_g is a state variable, here MMSN x (1, 1.3, 0.7) (not the
// profile, so that eta must come from the state), and the gas flux through the faces is
// set through a hand-made viscous stencil to F_g = (-3e5, -2e5, +1.5e5) g cm^-1 s^-1 on
// faces 0, 1, 2. The face gas speed is v_g = F_g/Sigma_g,f, Sigma_g,f the geometric mean
// of the neighbours (face 0: the first cell's); eta = -1/2 (H/r)^2 dlnP/dlnr (spec §1.4)
// with H/r and v_K at the face and dlnP/dlnr = [ln(Sigma_b/Sigma_a) + ln(c_s Omega)_b -
// ln(c_s Omega)_a]/ln(r_c,b/r_c,a) between the centres either side (face 0: cells 0 and
// 1), P = Sigma c_s Omega/sqrt(2 pi) (spec §1.3). mpmath (30 digits):
//   face 0: eta v_K = 4198.284 cm/s, v_g = -1206.798 cm/s, v = -1622.5698305324917
//   face 1: eta v_K = 4198.284,      v_g =  -928.650,      v = -1750.7984855003208
//   face 2: eta v_K = 8186.628,      v_g = +1441.866,      v = -4402.9630298333532
// (the gas term is 0.3-3x the drift term here, of both signs). Measured relative error
// <= 6.7e-16; tolerance 1e-12 (the stencil coefficients are set from F_g by division).
TEST(DustTransportFlux, FaceVelocityWithMovingGas) {
  const auto disk = mmsn();
  const Grid grid(3.0 * kAu, 9.0 * kAu, 3);
  StateLayout layout(3);
  GasColumn gas;
  gas.slot = layout.add_cell_var({"sigma_g", "g cm^-2", "gas", 1.0, true});
  for (int i = 0; i < 3; ++i) gas.static_sigma.push_back(disk.sigma_g(grid.r_c(i)));
  const double sigma_g[] = {248.59175800213746, 186.58187392111328, 58.004743533832075};
  const double f_gas[] = {-3e5, -2e5, 1.5e5};
  // F_g(face 0) = face_coef[0] g_coef[0] Sigma_0; F_g(f) = face_coef[f] (g_coef[f]
  // Sigma_f - g_coef[f-1] Sigma_{f-1}): g_coef = (1, 2, 3) [arbitrary], face_coef solved
  ViscousStencil stencil;
  stencil.g_coef = {1.0, 2.0, 3.0};
  stencil.face_coef = {f_gas[0] / sigma_g[0],
                       f_gas[1] / (2.0 * sigma_g[1] - 1.0 * sigma_g[0]),
                       f_gas[2] / (3.0 * sigma_g[2] - 2.0 * sigma_g[1])};
  PrescribedStokes stokes(kSt);
  DustTransport transport(layout, grid, disk, gas, &stencil, stokes, {}, 1.0, 1.0);
  layout.freeze();
  std::vector<double> y(layout.size(), 0.0);
  for (int i = 0; i < 3; ++i) {
    y[layout.index(i, gas.slot)] = sigma_g[i];
    y[layout.index(i, transport.sigma_slot())] = 0.01 * sigma_g[i];
  }
  const auto v = transport.face_velocity(y);
  ASSERT_EQ(v.size(), 4u);
  const double want[] = {-1622.5698305324917, -1750.7984855003208, -4402.9630298333532};
  for (int f = 0; f < 3; ++f) EXPECT_NEAR(v[f] / want[f], 1.0, 1e-12) << "face " << f;
  EXPECT_EQ(v[3], 0.0);  // closed outer face
}

}  // namespace
}  // namespace panoptic
