#pragma once
//! The arguments of `panoptic observe`, checked before the run is read (a bad argument
//! costs nothing), and the output path they give.
#include <filesystem>

#include "src/observe/observe.hpp"

namespace panoptic {

//! Throws ConfigError naming the argument: the wavelengths, distance, inclination, the
//! angles, the beam, --a-cm, and a --set of a key outside [observe].
void check_arguments(const ObserveArgs& a);

//! -o, or <run stem>_obs.h5 beside the run. Throws ConfigError when it is the run file
//! or one of the run's checkpoints, IoError when it may not be replaced
//! (refuse_to_replace).
std::filesystem::path output_path(const ObserveArgs& a);

}  // namespace panoptic
