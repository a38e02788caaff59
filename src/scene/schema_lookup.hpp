#pragma once
//! Lookups in the scene schema (scene_keys()) shared by the loader, the suggestions and
//! the writers of src/scene. Internal to the scene layer.
#include <string>
#include <string_view>
#include <vector>

#include "src/scene/scene_keys.hpp"

namespace panoptic::scene_detail {

//! The KeySpec of `key` ("grid.r_in_au"), or nullptr when the schema has no such key.
const KeySpec* find_spec(std::string_view key);
//! "grid" of "grid.r_in_au" (all of `key` when it has no dot).
std::string_view table_of(std::string_view key);
//! "r_in_au" of "grid.r_in_au" (all of `key` when it has no dot).
std::string_view leaf_of(std::string_view key);
//! The tables, in schema order.
std::vector<std::string> schema_tables();
//! True when the schema has a table `name`.
bool is_table(std::string_view name);
//! The leaves of `table`, in schema order, joined by ", ".
std::string keys_of_table(std::string_view table);
//! `items` joined by `sep`.
std::string join(const std::vector<std::string>& items, std::string_view sep);

}  // namespace panoptic::scene_detail
