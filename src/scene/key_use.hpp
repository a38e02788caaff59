#pragma once
//! Whether a run of a scene reads a key (KeySpec::used_when), and how the resolved scene
//! marks a key that is not read, so that the scene re-runs without a warning about it.
//! Internal to the scene layer.
#include <string>
#include <string_view>
#include <vector>

#include "src/scene/config.hpp"

namespace panoptic::scene_detail {

//! A condition of KeySpec::used_when that a scene does not meet.
struct UnmetCondition {
  std::string now;     //!< the switch as the scene has it: "disk.model = \"powerlaw\""
  std::string wanted;  //!< what would make a run read the key: "disk.model = \"lbp\""
};

//! The conditions of `spec.used_when` that `config` does not meet (empty: a run reads the
//! key).
std::vector<UnmetCondition> unmet_conditions(const Config& config, const KeySpec& spec);

//! Starts the comment of a resolved scene's line for a key that the run does not read
//! ("(not read: disk.model = \"powerlaw\")"). The loader takes a key whose line's comment
//! holds it as set knowingly and warns about nothing, so that a resolved scene (`panoptic
//! check > x.toml`, an output's config_toml), which lists every key, re-runs silently.
inline constexpr std::string_view kNotReadMark = "(not read: ";

}  // namespace panoptic::scene_detail
