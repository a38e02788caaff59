#pragma once
//! The checks of a loaded scene that span several keys (the loader checks each key on
//! its own: type, range, choices).
#include "src/scene/config.hpp"

namespace panoptic {

//! Cross-key checks of a loaded scene (r_in < r_out, output times, ...): throws
//! ConfigError naming the key. Call before anything is allocated or written.
void validate_scene(const Config& cfg);

}  // namespace panoptic
