// The drift speed on the faces with static gas whose profile is not a power law (as the
// LBP disk of params/compact_fragmentation.toml, whose Sigma_g is held fixed): eta must
// come from the pressure gradient between the two centres either side of each face (spec
// §1.4, §6.1), the inner face taking that of the first interior face. On a power-law
// disk dlnP/dlnr is the same everywhere, so only such a profile tells the faces apart.
// Also: the van Leer flux by hand, and transport.face_stokes = "upwind" (each cell's dust
// at its own St's speed) by hand and refused with van Leer.
//
// Set-up (as tests/unit/physics/test_transport_flux.cpp): 3 log-spaced cells from 3 to 9
// au (faces 3, 4.3267, 6.2403, 9 au), MMSN temperature T = 280 (r/au)^-1/2 K, mu = 2.34,
// M = 1 M_sun, St = (0.05, 0.2, 0.8) per cell (faces: 0.05, 0.1, 0.4), static gas
// Sigma_g = 1700 (r_c/au)^-1.5 x (1, 1.3, 0.7) g cm^-2, drift only.
// Worked out by hand (constants of spec §1.1):
//   P = Sigma_g c_s Omega/sqrt(2 pi) with c_s Omega ∝ r^-1/4 r^-3/2, so between centres a
//   and b, ln(r_c,b/r_c,a) = ln(3)/3 = 0.3662041:
//     dlnP/dlnr = -1.5 - 1.75 + ln(x_b/x_a)/0.3662041,
//     cells 0-1: ln 1.3 = 0.2623643 -> -3.25 + 0.7164385 = -2.5335615 (faces 0 and 1)
//     cells 1-2: ln(0.7/1.3) = -0.6190392 -> -3.25 - 1.6904200 = -4.9404200 (face 2)
//   eta v_K = -1/2 (H/r)^2 v_K dlnP/dlnr, (H/r)^2 v_K = c_s^2/v_K = k T/(mu m_H) /
//   sqrt(G M/r), the same on every face here (both ∝ r^-1/2): at 3 au T = 161.658 K,
//   c_s^2 = 5.69975e9 cm^2 s^-2, v_K = 1.719824e6 cm/s, c_s^2/v_K = 3314.14 cm/s, so
//     eta v_K = 4198.28 cm/s (faces 0, 1) and 8186.63 cm/s (face 2)
//   (the same numbers as the mpmath values of FaceVelocityWithMovingGas, whose gas has
//   this profile), and v = -2 St eta v_K/(1 + St^2):
//     face 0: -2 (0.05) 4198.28/1.0025 = -418.781 cm/s
//     face 1: -2 (0.1)  4198.28/1.01   = -831.343 cm/s
//     face 2: -2 (0.4)  8186.63/1.16   = -5645.95 cm/s
// The test computes these from the same formulas in double precision (tolerance 1e-10)
// and checks them against the rounded hand values to 1e-5.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "disk/gas_column.hpp"
#include "disk/gas_disk.hpp"
#include "physics/modules/dust_transport.hpp"
#include "physics/stokes_model.hpp"
#include "src/core/units.hpp"
#include "src/model/scene_validation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/grid.hpp"
#include "src/solver/state_layout.hpp"
#include "tests/unit/support/config_error.hpp"

namespace panoptic {
namespace {

// spec §1.1 constants
constexpr double kAu = 1.496e13, kG = 6.674e-8, kMsunG = 1.989e33, kBoltz = 1.3807e-16,
                 kMassH = 1.6735e-24;
constexpr double kPi = 3.14159265358979323846;

//! The drift speed on a face at radius r [cm] by hand: v = -2 St eta v_K/(1 + St^2),
//! eta v_K = -1/2 (c_s^2/v_K) dlnP/dlnr, MMSN temperature T = 280 (r/au)^-1/2 K,
//! mu = 2.34, M = 1 M_sun [cm s^-1].
double drift_speed_by_hand(double r, double st, double dlnp_dlnr) {
  const double cs2 = kBoltz * 280.0 / std::sqrt(r / kAu) / (2.34 * kMassH);
  const double vk = std::sqrt(kG * kMsunG / r);
  const double eta_vk = -0.5 * cs2 / vk * dlnp_dlnr;
  return -2.0 * st * eta_vk / (1.0 + st * st);
}

TEST(DustTransportFlux, FaceVelocityWithStaticGasThatIsNotAPowerLaw) {
  const double au = kAu;
  ThermalParams th;  // T_1au = 280 K, q = 1/2, mu = 2.34, alpha = 1e-3 (spec §10.1)
  const PowerLawDisk disk({units::kMsun, units::kLsun}, th, 1700.0, 1.5);
  const Grid grid(3.0 * au, 9.0 * au, 3);
  const double x[] = {1.0, 1.3, 0.7};
  GasColumn gas;
  for (int i = 0; i < 3; ++i)
    gas.static_sigma.push_back(1700.0 * std::pow(grid.r_c(i) / au, -1.5) * x[i]);
  StateLayout layout(3);
  PrescribedStokes stokes({0.05, 0.2, 0.8});
  DustTransportOptions opt;
  opt.diffusion = false;
  DustTransport transport(layout, grid, disk, gas, nullptr, stokes, opt, 1.0, 1.0);
  layout.freeze();
  std::vector<double> y(layout.size(), 0.0);
  for (int i = 0; i < 3; ++i) y[layout.index(i, transport.sigma_slot())] = 1.0;
  const auto v = transport.face_velocity(y);
  ASSERT_EQ(v.size(), 4u);

  const double dlnr = std::log(3.0) / 3.0;
  const double dlnp01 = -3.25 + std::log(1.3) / dlnr;
  const double dlnp12 = -3.25 + std::log(0.7 / 1.3) / dlnr;
  const double st_face[] = {0.05, std::sqrt(0.05 * 0.2), std::sqrt(0.2 * 0.8)};
  const double dlnp_face[] = {dlnp01, dlnp01, dlnp12};
  const double hand[] = {-418.781, -831.343, -5645.95};
  for (int f = 0; f < 3; ++f) {
    const double want = drift_speed_by_hand(grid.r_f(f), st_face[f], dlnp_face[f]);
    EXPECT_NEAR(v[f] / want, 1.0, 1e-10) << "face " << f;
    EXPECT_NEAR(v[f] / hand[f], 1.0, 1e-5) << "face " << f;
  }
  EXPECT_EQ(v[3], 0.0);  // closed outer face
}

// The 5 log-spaced cells of 3-9 au of the flux tests below: MMSN gas times x = (1, 1, 3,
// 3, 1), a pressure bump whose face 2 drifts outward; dust Sigma_d = c/(r_c/au), so
// q = 2 pi r_c Sigma_d = 2 pi au c with c = (1, 1.5, 2.5, 4.5, 8.5).
struct BumpDisk {
  static constexpr int n = 5;
  ThermalParams th;
  PowerLawDisk disk{{units::kMsun, units::kLsun}, th, 1700.0, 1.5};
  Grid grid{3.0 * kAu, 9.0 * kAu, n};
  GasColumn gas;
  const double c[n] = {1.0, 1.5, 2.5, 4.5, 8.5};
  double dlnp[n];  //!< dln P/dln r on faces 0..n-1
  BumpDisk() {
    const double x[] = {1.0, 1.0, 3.0, 3.0, 1.0};
    for (int i = 0; i < n; ++i)
      gas.static_sigma.push_back(1700.0 * std::pow(grid.r_c(i) / kAu, -1.5) * x[i]);
    const double dlnr = std::log(3.0) / n, bump = std::log(3.0) / dlnr;
    const double faces[] = {-3.25, -3.25, -3.25 + bump, -3.25, -3.25 - bump};
    std::copy(faces, faces + n, dlnp);
  }
  //! The mass flow and the velocity on every face of one population with St per cell.
  std::pair<std::vector<double>, std::vector<double>> flows(
      const std::vector<double>& st, const DustTransportOptions& opt) const {
    StateLayout layout(n);
    PrescribedStokes stokes(st);
    DustTransport transport(layout, grid, disk, gas, nullptr, stokes, opt, 1.0, 1.0);
    layout.freeze();
    std::vector<double> y(layout.size(), 0.0);
    for (int i = 0; i < n; ++i)
      y[layout.index(i, transport.sigma_slot())] = c[i] / (grid.r_c(i) / kAu);
    return {transport.mass_flow(y), transport.face_velocity(y)};
  }
};

// The limited (van Leer) drift flux on every face, inward and outward, against the MUSCL
// formula worked out from the state (tests/bench/README.md, Work-precision:
// `transport.advection = "van_leer"`; van Leer 1977, LeVeque 2002 §6.9). 5 log-spaced
// cells from 3 to 9 au (d ln r = ln(3)/5 = 0.2197225), St = 0.1 everywhere, MMSN
// temperature, static gas Sigma_g = 1700 (r_c/au)^-1.5 x (1, 1, 3, 3, 1): dlnP/dlnr =
// -3.25 + ln(x_b/x_a)/0.2197225 between centres is -3.25 (faces 0, 1, 3: inward), +1.7802
// (face 2: outward, the pressure rising) and -8.2802 (face 4: inward). Sigma_d = c_i /
// (r_c/au) with c = (1, 1.5, 2.5, 4.5, 8.5), so q = 2 pi r_c Sigma_d = 2 pi au c rises
// with r and every limited face has a b > 0 with a != b. Upwind (u), far (w) and downwind
// (d) cells:
//   face 1 (inward):  u = 1, w = 2, d = 0: limited
//   face 2 (outward): u = 1, w = 0, d = 2: limited (the far cell is cell 0)
//   face 3 (inward):  u = 3, w = 4, d = 2: limited
//   face 4 (inward):  u = 4, w = 5 off the grid: first order
//   face 0 (r_in, inward, the slope of face 1): first order, 2 pi r_c(0) v Sigma_d,0
// flow = v (q_u + a b / (a + b)), a = q_u - q_w, b = q_d - q_u (half the van Leer slope
// 2ab/(a+b)). By hand in units of 2 pi au v: face 1: a = -1, b = -0.5: 1.5 + 0.5/(-1.5) =
// 1.16667; face 2: a = 0.5, b = 1: 1.5 + 0.5/1.5 = 1.83333; face 3: a = -4, b = -2: 4.5 +
// 8/(-6) = 3.16667.
TEST(DustTransportFlux, VanLeerFluxInwardAndOutward) {
  const BumpDisk d;
  DustTransportOptions opt;
  opt.diffusion = false;
  opt.limited = true;
  const auto [flow, v_face] = d.flows(std::vector<double>(BumpDisk::n, 0.1), opt);
  ASSERT_EQ(flow.size(), std::size_t(BumpDisk::n + 1));
  const double* q = d.c;  // q / (2 pi au)
  const auto muscl = [&](int u, int w, int dn) {
    const double a = q[u] - q[w], b = q[dn] - q[u];
    return q[u] + a * b / (a + b);
  };
  const double face_q[] = {q[0], muscl(1, 2, 0), muscl(1, 0, 2), muscl(3, 4, 2), q[4]};
  const double hand_q[] = {1.0, 1.1666667, 1.8333333, 3.1666667, 8.5};
  for (int f = 0; f < BumpDisk::n; ++f) {
    const double v = drift_speed_by_hand(d.grid.r_f(f), 0.1, d.dlnp[f]);
    EXPECT_EQ(v > 0.0, f == 2) << "face " << f;
    EXPECT_NEAR(face_q[f] / hand_q[f], 1.0, 1e-7) << "face " << f;
    EXPECT_NEAR(flow[f] / (2.0 * kPi * kAu * v * face_q[f]), 1.0, 1e-10) << "face " << f;
  }
  EXPECT_EQ(flow[BumpDisk::n], 0.0);  // closed outer face
}

// transport.face_stokes = "upwind" (flux-vector splitting): the dust crossing a face
// drifts at the speed of its own cell's St, not at the mean of the two cells'. The gas of
// the van Leer test above (face 2 drifts outward, the others inward); St 1e3 in cell 0
// beside St 1 in cell 1, whose dust the mean St (sqrt(1e3)) would move 15.8x too slowly
// through face 1.
TEST(DustTransportFlux, UpwindStokesMovesEachCellsDustAtItsOwnSpeed) {
  const BumpDisk d;
  const std::vector<double> st = {1e3, 1.0, 0.5, 0.5, 0.1};
  for (const bool upwind : {true, false}) {
    DustTransportOptions opt;
    opt.diffusion = false;
    opt.upwind_stokes = upwind;
    const auto [flow, v] = d.flows(st, opt);
    for (int f = 0; f < BumpDisk::n; ++f) {
      const int up = f == 2 ? 1 : f;  // face 2 outward: cell 1 upwind; face 0: cell 0
      const double st_face = upwind || f == 0 ? st[up] : std::sqrt(st[f - 1] * st[f]);
      const double want = drift_speed_by_hand(d.grid.r_f(f), st_face, d.dlnp[f]);
      EXPECT_NEAR(v[f] / want, 1.0, 1e-10) << "face " << f << (upwind ? " upwind" : "");
      EXPECT_NEAR(flow[f] / (2.0 * kPi * kAu * want * d.c[up]), 1.0, 1e-10)
          << "face " << f << (upwind ? " upwind" : " mean");
    }
    const double at_mean = drift_speed_by_hand(d.grid.r_f(1), std::sqrt(1e3), d.dlnp[1]);
    // St/(1 + St^2) at St 1 over that at sqrt(1e3): 15.8
    const double faster = 0.5 / (std::sqrt(1e3) / 1001.0);
    EXPECT_NEAR(v[1] / at_mean, upwind ? faster : 1.0, 1e-10 * faster);
  }
}

// The split flux has no limited (van Leer) form: the pair is refused by name, with the
// fix.
TEST(DustTransportFlux, UpwindStokesWithVanLeerIsRefused) {
  const std::string fiducial = std::string(PANOPTIC_SOURCE_DIR) + "/params/fiducial.toml";
  const std::vector<std::string> upwind{"transport.face_stokes=\"upwind\""},
      van_leer{"transport.advection=\"van_leer\""},
      both{"transport.face_stokes=\"upwind\"", "transport.advection=\"van_leer\""};
  const std::string msg =
      config_error_message([&] { validate_scene(load_scene(fiducial, both)); },
                           "face_stokes upwind with van Leer");
  EXPECT_NE(msg.find("transport.face_stokes"), std::string::npos) << msg;
  EXPECT_NE(msg.find("transport.advection = \"upwind\""), std::string::npos) << msg;
  // each alone is a valid scene
  validate_scene(load_scene(fiducial, upwind));
  validate_scene(load_scene(fiducial, van_leer));
}

}  // namespace
}  // namespace panoptic
