#pragma once
//! The key tables, one per scene table ([disk], [growth], ...), defined in keys_*.cpp and
//! listed, in the order of params/reference.toml, by scene_keys() (scene_keys.cpp).
//! Internal to the scene layer.
#include <vector>

#include "src/scene/scene_keys.hpp"

namespace panoptic::scene_detail {

std::vector<KeySpec> meta_keys();
std::vector<KeySpec> model_keys();
std::vector<KeySpec> star_keys();
std::vector<KeySpec> disk_keys();
std::vector<KeySpec> gas_keys();
std::vector<KeySpec> dust_keys();
std::vector<KeySpec> transport_keys();
std::vector<KeySpec> growth_keys();
std::vector<KeySpec> porosity_keys();
std::vector<KeySpec> erosion_keys();
std::vector<KeySpec> fragmentation_keys();
std::vector<KeySpec> bouncing_keys();
std::vector<KeySpec> snowline_keys();
std::vector<KeySpec> material_keys();
std::vector<KeySpec> planetesimals_keys();
std::vector<KeySpec> pebbles_keys();
std::vector<KeySpec> grid_keys();
std::vector<KeySpec> solver_keys();
std::vector<KeySpec> checkpoint_keys();
std::vector<KeySpec> output_keys();
std::vector<KeySpec> observe_keys();

}  // namespace panoptic::scene_detail
