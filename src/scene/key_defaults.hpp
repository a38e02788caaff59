#pragma once
//! The schema defaults (KeySpec::default_toml) as values. Internal to the scene layer.
#include <functional>
#include <map>
#include <string>

#include "src/scene/config_value.hpp"

namespace panoptic::scene_detail {

//! Every key's default, parsed once. A default that is not valid for its own key is a
//! bug in src/scene/scene_keys.cpp, thrown as such.
const std::map<std::string, ConfigValue, std::less<>>& default_values();

}  // namespace panoptic::scene_detail
