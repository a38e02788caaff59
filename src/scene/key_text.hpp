#pragma once
//! A key's constraint in words, for messages and for params/reference.toml: its type,
//! range, unit, a fix ("set grid.n_cells to an integer >= 4 ..., e.g. ...") and the
//! switches that make a run read it. Internal to the scene layer.
#include <string>

#include "src/scene/scene_keys.hpp"

namespace panoptic::scene_detail {

//! "> 0", ">= 4 and <= 1000000"; empty when the key has no bounds.
std::string range_text(const KeySpec& spec);
//! " [au]", or "" for a key without a unit.
std::string unit_suffix(const KeySpec& spec);
//! "a real number", "an integer", ...
std::string type_text(KeyType type);
//! The generic fix: what to write instead.
std::string fix_text(const KeySpec& spec);
//! "erosion.model = \"halt\" or \"balance\"", with alternatives (UsedWhen::or_else)
//! "(erosion.model = \"balance\" or model.kind = \"distribution\")"
std::string condition_text(const UsedWhen& c);

}  // namespace panoptic::scene_detail
