// The key tables of the dust and its transport: [dust], [transport], [snowline].
#include "src/scene/key_builders.hpp"
#include "src/scene/key_tables.hpp"

namespace panoptic::scene_detail {

// [dust] initial condition, spec §6.4
std::vector<KeySpec> dust_keys() {
  return {
      when({dust_init("dust_to_gas")},
           real("dust.dust_to_gas", "0.01", "",
                "initial Sigma_d / Sigma_g outside the snow line (§1.7 Z_out; inside it "
                "(1 - snowline.f_ice) times this)",
                0.0, true, 1.0, false)),
      choice(
          "dust.init", "dust_to_gas", {"dust_to_gas", "gaussian_ring"},
          "initial Sigma_d: dust_to_gas = dust_to_gas * Sigma_g; gaussian_ring = a thin "
          "ring diffused to Gaussian width ring_width_au (the exact diffusing-ring "
          "profile, ~Gaussian for width << radius) on a floor of sigma_floor_rel * "
          "Sigma_g"),
      when({dust_init("gaussian_ring")},
           positive("dust.ring_r_au", "30.0", "au", "gaussian_ring: ring centre")),
      when({dust_init("gaussian_ring")},
           positive("dust.ring_width_au", "2.0", "au",
                    "gaussian_ring: Gaussian width (standard deviation)")),
      when({dust_init("gaussian_ring")},
           positive("dust.ring_sigma", "1.0", "g cm^-2", "gaussian_ring: peak Sigma_d")),
      when({dust_init("gaussian_ring")}, real("dust.sigma_floor_rel", "1e-30", "",
                                              "gaussian_ring: Sigma_d / Sigma_g outside "
                                              "the ring (§6.4; not a floor during "
                                              "the run: m and phi of a nearly empty cell "
                                              "are decoded through a floor set by "
                                              "solver.atol_sigma)",
                                              0.0, false, 1e-3, false)),
  };
}

// [transport] spec §6.1, §6.3
std::vector<KeySpec> transport_keys() {
  return {
      flag("transport.drift", "true", "radial drift (advection by v_r, §6.1)"),
      flag("transport.diffusion", "true",
           "turbulent diffusion of Sigma_d/Sigma_g (§6.1)"),
      when({is("growth.enabled", {"false"})},
           positive(
               "transport.St", "0.03", "",
               "prescribed Stokes number at 1 au with growth off (growth.enabled = true "
               "ignores it)")),
      when({is("growth.enabled", {"false"})},
           real("transport.St_slope", "0.0", "",
                "prescribed St ∝ r^St_slope (growth off)", -5.0, false, 5.0, false)),
      when(
          {is("transport.drift", {"true"})},
          choice(
              "transport.advection", "upwind", {"upwind", "van_leer"},
              "advection scheme of the drift: first-order upwind, or second-order upwind "
              "with a van Leer-limited reconstruction of r Sigma (MUSCL; widens the "
              "Jacobian stencil to 4 cells per face)")),
      when({is("transport.drift", {"true"}), single_size()},
           choice(
               "transport.face_stokes", "mean", {"mean", "upwind"},
               "Stokes number of the drift on a face: \"mean\", the geometric mean of "
               "its two cells' (exact for power laws on the log grid); \"upwind\", each "
               "cell's dust leaves at its own St (flux-vector splitting), so a zone of "
               "St >> 1 does not slow its neighbour's outflow "
               "(tests/bench/results/porous_mmsn.md); first-order advection only")),
  };
}

// [snowline] spec §1.7, §6.3
std::vector<KeySpec> snowline_keys() {
  return {
      flag("snowline.enabled", "true",
           "ice outside r_snow, silicate inside; drifting ice loses f_ice of its mass "
           "there"),
      real("snowline.f_ice", "0.5", "", "ice mass fraction of the icy solids (§1.7)", 0.0,
           false, 1.0, true),
  };
}

}  // namespace panoptic::scene_detail
