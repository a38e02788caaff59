#include "src/observe/observe.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "src/observe/emission.hpp"
#include "src/observe/materials.hpp"
#include "src/observe/observation.hpp"
#include "src/observe/observation_file.hpp"
#include "src/observe/observe_args.hpp"
#include "src/observe/particles.hpp"
#include "src/observe/run_snapshot.hpp"
#include "src/observe/sky_images.hpp"
#include "src/observe/spectral_index.hpp"
#include "src/scene/config.hpp"

namespace panoptic {
namespace {

void print_report(const Observation& o, const std::filesystem::path& out) {
  const ObserveArgs& a = o.args;
  const SkyImages& im = o.images;
  const std::size_t n = o.emission.n_cells;
  std::printf("panoptic observe: %s, snapshot %ld at t = %.6g yr (asked %.6g yr)\n",
              a.run_file.c_str(), o.snapshot.index, o.snapshot.time_yr, a.time_yr);
  std::printf(
      "  d = %g pc, i = %g deg, PA = %g deg; beam %g x %g arcsec at %g deg; "
      "%d x %d pixels of %.4g arcsec (FFT %d^2)\n",
      a.distance_pc, a.incl_deg, a.pa_deg, a.bmaj_arcsec, a.bmin_arcsec, a.bpa_deg,
      im.grid.n, im.grid.n, im.grid.pixel, im.padded_size);
  const std::vector<double>& tau = o.emission.tau;
  for (std::size_t l = 0; l < a.lambda_mm.size(); ++l) {
    std::printf(
        "  %6.3g mm: flux %.6g Jy (after the beam %.6g Jy; over the annuli %.6g Jy), max "
        "tau %.3g\n",
        a.lambda_mm[l], im.flux_model[l], im.flux_convolved[l], im.flux_annuli[l],
        *std::max_element(tau.begin() + l * n, tau.begin() + (l + 1) * n));
  }
  for (std::size_t p = 0; p < o.alpha.n_pairs; ++p)
    std::printf("  alpha(%g-%g mm) of the total flux: %.4g\n", o.alpha.pairs_mm[2 * p],
                o.alpha.pairs_mm[2 * p + 1], o.alpha.total[p]);
  std::printf("  -> %s\n", out.c_str());
}

}  // namespace

int observe(const ObserveArgs& a) {
  check_arguments(a);  // before the file is read: a bad argument costs nothing
  const std::filesystem::path out = output_path(a);
  const RunSnapshot s = read_run_snapshot(a.run_file, a.time_yr);
  const Config cfg =
      load_scene_text(s.config_toml, a.run_file + ":config_toml", a.overrides);
  const OpticalMaterials mat = optical_materials(cfg);
  check_wavelengths_covered(mat, a.lambda_mm);
  check_observable(s, a.run_file, a.a_cm_given);
  const MonomerDensities rho0{cfg.real("material.ice_rho0"),
                              cfg.real("material.sil_rho0")};
  const CellParticles particles =
      cell_particles(s, mat, cfg.flag("snowline.enabled"), rho0, a);
  const CellEmission emission = cell_emission(a.lambda_mm, a.incl_deg, s, mat, particles);
  const SkyImages images = sky_images(a, s, emission);
  const SpectralIndex alpha = spectral_index(a.lambda_mm, emission, images);
  const Observation o{a, s, cfg.resolved_toml(), mat, particles, emission, images, alpha};
  check_observation(o);
  write_observation_file(out, o);
  print_report(o, out);
  return 0;
}

}  // namespace panoptic
