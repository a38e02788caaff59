// The key table of `panoptic observe`: [observe].
#include "src/scene/key_builders.hpp"
#include "src/scene/key_tables.hpp"

namespace panoptic::scene_detail {

// [observe] `panoptic observe` (src/observe/README.md): optical
// constants m = n + i k per species, tabulated against wavelength (n linear, k
// log-linear in ln lambda between the rows; no extrapolation).
std::vector<KeySpec> observe_keys() {
  return {
      choice("observe.outer_species", "mix", {"mix", "ice", "sil"},
             "solids outside the snow line (inside: sil): mix = water ice + silicate "
             "with the ice mass fraction snowline.f_ice, ice = pure water ice"),
      when(
          {one_of("observe.outer_species", {"mix"})},
          choice("observe.mix_rule", "bruggeman", {"bruggeman", "maxwell_garnett"},
                 "effective-medium rule of the mix (maxwell_garnett: silicate inclusions "
                 "in an ice matrix)")),
      when({one_of("observe.outer_species", {"mix", "ice"})},
           positive("observe.water_ice_rho", "0.92", "g cm^-3",
                    "density of water ice, for the volume fractions of the mix (with "
                    "material.sil_rho0)")),
      real_table("observe.ice_lambda_mm",
                 "[0.3, 0.5, 1.3, 5.0, 19.0, 39.0, 61.0, 86.0, 110.0]", "mm",
                 "water ice: wavelengths of the table (Warren & Brandt 2008, JGR 113, "
                 "D14220: rows of their table, at 266 K)",
                 0.0),
      real_table(
          "observe.ice_n",
          "[1.7989, 1.7908, 1.7868, 1.7861, 1.7861, 1.7861, 1.7861, 1.7861, 1.7861]", "",
          "water ice: real part n", 0.0),
      real_table("observe.ice_k",
                 "[2.549e-2, 1.405e-2, 5.173e-3, 1.337e-3, 3.574e-4, 1.839e-4, 1.294e-4, "
                 "1.058e-4, 9.675e-5]",
                 "", "water ice: imaginary part k", 0.0),
      real_table("observe.sil_lambda_mm",
                 "[0.29999, 0.49994, 0.70008, 0.99987, 1.2398, 1.4999, 2.0001, 2.4797, "
                 "2.9999, 3.9995, 4.9994, 6.1992, 7.0008, 8.9974, 9.9987, 12.398, "
                 "14.999, 20.001, 29.999, 49.994, 99.987]",
                 "mm",
                 "silicate: wavelengths of the table (Draine 2003, ApJ 598, 1026, "
                 "astrosilicate; rows of his callindex.out_silD03)",
                 0.0),
      real_table("observe.sil_n",
                 "[3.416, 3.405, 3.403, 3.406, 3.409, 3.412, 3.416, 3.418, 3.421, 3.424, "
                 "3.426, 3.428, 3.429, 3.431, 3.432, 3.433, 3.434, 3.434, 3.435, 3.435, "
                 "3.435]",
                 "", "silicate: real part n", 0.0),
      real_table("observe.sil_k",
                 "[0.1551, 0.08922, 0.06918, 0.05573, 0.04893, 0.04361, 0.03665, "
                 "0.03219, 0.02870, 0.02413, 0.02109, 0.01853, 0.01722, 0.01480, "
                 "0.01384, 0.01120, 0.009254, 0.006939, 0.004626, 0.002775, 0.001388]",
                 "", "silicate: imaginary part k", 0.0),
  };
}

}  // namespace panoptic::scene_detail
