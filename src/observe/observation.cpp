#include "src/observe/observation.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

#include "src/core/error.hpp"

namespace panoptic {

void check_observation(const Observation& o) {
  const CellEmission& e = o.emission;
  const SkyImages& im = o.images;
  for (const auto& [name, v] : {std::pair{"kappa_abs", &e.kappa_abs},
                                {"tau", &e.tau},
                                {"intensity", &e.intensity},
                                {"model image", &im.model},
                                {"convolved image", &im.convolved},
                                {"model flux", &im.flux_model},
                                {"annuli flux", &im.flux_annuli},
                                {"convolved flux", &im.flux_convolved}})
    for (const double x : *v)
      if (!std::isfinite(x))
        throw ConfigError("the observation is not finite (" + std::string(name) + " = " +
                          num(x) +
                          "): the options are outside what the model can image; bring "
                          "--beam-arcsec, --a-cm and --distance-pc nearer to the disk's "
                          "scales");
  // The projection conserves each annulus's flux (DiskProjector): the image's flux is
  // the annuli's to round-off at any pixel size.
  for (std::size_t l = 0; l < im.flux_model.size(); ++l)
    if (!(std::abs(im.flux_model[l] - im.flux_annuli[l]) <=
          kFluxRoundOff * std::abs(im.flux_annuli[l])))
      throw std::logic_error("observe: at " + num(o.args.lambda_mm[l]) +
                             " mm the image's flux " + num(im.flux_model[l]) +
                             " Jy differs from the annuli's " + num(im.flux_annuli[l]) +
                             " Jy beyond round-off");
}

}  // namespace panoptic
