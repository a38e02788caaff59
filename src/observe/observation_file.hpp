#pragma once
//! The writer of `panoptic observe`: an observation as an HDF5 file (layout:
//! src/observe/README.md, Synthetic observations).
#include <filesystem>

#include "src/observe/observation.hpp"

namespace panoptic {

//! Writes `o` to `path`, whole or not at all: to <path>.tmp, then fsynced and renamed
//! into place (commit_temporary). Throws IoError when it cannot.
void write_observation_file(const std::filesystem::path& path, const Observation& o);

}  // namespace panoptic
