#pragma once
//! A TOML value checked against its KeySpec and converted to a ConfigValue: the type,
//! the range, finiteness, the choices. Internal to the scene layer.
#include <toml++/toml.h>

#include <optional>
#include <string>

#include "src/scene/config_value.hpp"
#include "src/scene/scene_keys.hpp"

namespace panoptic::scene_detail {

//! Converts a TOML node to the value of `spec`; on failure returns nullopt and sets
//! `problem` to "<what is wrong>; <fix>".
std::optional<ConfigValue> convert(const KeySpec& spec, const toml::node& node,
                                   std::string& problem);

}  // namespace panoptic::scene_detail
