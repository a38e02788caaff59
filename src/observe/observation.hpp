#pragma once
//! One observation of `panoptic observe`, as its steps made it: what the output file
//! holds and the printed report reads, and the checks it must pass before it is written.
#include <string>

#include "src/observe/emission.hpp"
#include "src/observe/materials.hpp"
#include "src/observe/observe.hpp"
#include "src/observe/particles.hpp"
#include "src/observe/run_snapshot.hpp"
#include "src/observe/sky_images.hpp"
#include "src/observe/spectral_index.hpp"

namespace panoptic {

//! Largest relative difference between the image-summed flux and the flux over the
//! annuli: the projection makes them equal to round-off (DiskProjector), so a larger
//! one is a bug, reported as an internal error before anything is written.
inline constexpr double kFluxRoundOff = 1e-9;

struct Observation {
  const ObserveArgs& args;
  const RunSnapshot& snapshot;
  std::string scene_toml;  //!< the resolved scene (with --set observe.* overrides)
  const OpticalMaterials& materials;
  const CellParticles& particles;
  const CellEmission& emission;
  const SkyImages& images;
  const SpectralIndex& alpha;
};

//! Throws ConfigError when a number an option can make non-finite is (a beam or a
//! particle far outside the disk's scales), std::logic_error when an image's flux
//! differs from the annuli's beyond kFluxRoundOff.
void check_observation(const Observation& o);

}  // namespace panoptic
