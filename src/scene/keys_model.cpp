// The key table of the model kind: [model] (spec §15).
#include "src/scene/key_builders.hpp"
#include "src/scene/key_tables.hpp"

namespace panoptic::scene_detail {

// [model] spec §15: one particle per cell, or the whole size distribution
std::vector<KeySpec> model_keys() {
  return {
      choice("model.kind", "single_size", {"single_size", "distribution"},
             "single_size = the mass-dominating particle of each cell (spec §2-§7); "
             "distribution = the size distribution of each cell on a log-spaced mass "
             "grid, coagulated by the Smoluchowski equation and every bin transported "
             "with its own St (spec §15; compact or porous, with the snow line, "
             "planetesimals per bin and Krijt et al. 2015 erosion on unequal pairs; no "
             "bouncing: params/README.md)"),
      // > 1/log10(2) = 3.32: the two-bin split of a sticking pair needs a bin ratio
      // below 2 (physics/coagulation/mass_grid.hpp)
      when({distribution()},
           real("model.bins_per_decade", "7.0", "",
                "distribution: mass bins per decade (DustPy's default 7, spec §15.1)",
                3.33, false, 100.0, false)),
      when({distribution()},
           real("model.m_min_g", "0.0", "g",
                "distribution: mass of the first bin; 0 = the smallest monomer mass of "
                "the species on the grid (material.a0_um and their rho0)",
                0.0, false)),
      when({distribution()},
           positive("model.m_max_g", "1e5", "g",
                    "distribution: the grid reaches the first bin at or above this "
                    "(DustPy's default 1e5 g); products beyond it do not stick")),
      when({distribution()},
           choice("model.init", "mrn", {"mrn", "monomers"},
                  "distribution: the initial Sigma_d of each cell spread as MRN, n(a) ∝ "
                  "a^-3.5 from the bin of its monomers (the first bin when model.m_min_g "
                  "lies above them) up to model.a_max_init_um (as DustPy), or all in "
                  "that bin (spec §15.4)")),
      when({distribution(), one_of("model.init", {"mrn"})},
           positive("model.a_max_init_um", "1.0", "um",
                    "distribution, mrn: largest initial radius (DustPy's default 1 um)")),
  };
}

}  // namespace panoptic::scene_detail
