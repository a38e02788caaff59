#include "src/observe/observe_args.hpp"

#include <cmath>
#include <cstddef>
#include <string>

#include "src/core/error.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/durable_file.hpp"

namespace fs = std::filesystem;

namespace panoptic {

void check_arguments(const ObserveArgs& a) {
  if (a.lambda_mm.empty())
    throw ConfigError("--lambda-mm: no wavelength given; e.g. --lambda-mm 0.87,1.3,3.0");
  for (const double l : a.lambda_mm)
    if (!(l > 0.0) || !std::isfinite(l))
      throw ConfigError("--lambda-mm " + num(l) + ": wavelengths must be > 0 [mm]");
  for (std::size_t i = 0; i < a.lambda_mm.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (a.lambda_mm[i] == a.lambda_mm[j])
        throw ConfigError("--lambda-mm: " + num(a.lambda_mm[i]) +
                          " mm given twice; give each wavelength once");
  if (!(a.distance_pc > 0.0) || !std::isfinite(a.distance_pc))
    throw ConfigError("--distance-pc " + num(a.distance_pc) + ": must be > 0 [pc]");
  if (!(a.incl_deg >= 0.0 && a.incl_deg < 90.0))
    throw ConfigError("--incl-deg " + num(a.incl_deg) +
                      ": must be in [0, 90) [deg] (a thin disk seen edge-on has no "
                      "projected area); 0 = face-on");
  if (!std::isfinite(a.pa_deg))
    throw ConfigError("--pa-deg " + num(a.pa_deg) + ": must be a finite angle [deg]");
  if (!(a.bmin_arcsec > 0.0) || !(a.bmaj_arcsec >= a.bmin_arcsec) ||
      !std::isfinite(a.bmaj_arcsec) || !std::isfinite(a.bpa_deg))
    throw ConfigError("--beam-arcsec " + num(a.bmaj_arcsec) + "," + num(a.bmin_arcsec) +
                      "," + num(a.bpa_deg) +
                      ": needs bmaj >= bmin > 0 [arcsec] and a finite PA [deg]");
  // 1 nm to 100 km: below, the Rayleigh-limit opacity overflows (1e-308 gave NaN)
  if (a.a_cm_given && !(a.a_cm >= 1e-7 && a.a_cm <= 1e7))
    throw ConfigError("--a-cm " + num(a.a_cm) +
                      ": must be >= 1e-7 and <= 1e7 [cm] (1 nm to 100 km)");
  for (const std::string& o : a.overrides)
    if (o.rfind("observe.", 0) != 0)
      throw ConfigError("--set " + o +
                        ": observe may change only observe.* keys (the run is done); "
                        "rerun the scene to change anything else");
}

fs::path output_path(const ObserveArgs& a) {
  const fs::path out =
      a.output.empty()
          ? fs::path(fs::path(a.run_file).replace_extension("").string() + "_obs.h5")
          : fs::path(a.output);
  refuse_output_is_input(out, a.run_file, "the run file observe reads");
  const fs::path chk = checkpoint_path(a.run_file);  // nor the run's checkpoints
  for (const fs::path& c : {chk, previous_checkpoint_path(chk)})
    refuse_output_is_input(out, c, "a checkpoint of the run");
  refuse_to_replace(out, a.overwrite);
  return out;
}

}  // namespace panoptic
