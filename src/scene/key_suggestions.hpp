#pragma once
//! "Did you mean ...?": the schema key or table nearest to what the user wrote, for the
//! messages of the loader. Internal to the scene layer.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace panoptic::scene_detail {

//! Levenshtein distance, case-insensitive (disk.t_1au is a typo of disk.T_1au).
std::size_t edit_distance(std::string_view a, std::string_view b);
//! The candidate nearest to `word`, if it is near enough to be a plausible typo.
std::optional<std::string> nearest(std::string_view word,
                                   const std::vector<std::string>& candidates);
//! A key as a message shows it: whole up to a plausible length, else its start and
//! length.
std::string shown_key(const std::string& key);
//! The schema key the user probably meant by `key` ("table.key", or a bare key written
//! outside any table): the same leaf in another table first, then the nearest spelling.
std::optional<std::string> suggest_key(std::string_view key);
//! The fix of an unknown key: the key meant, else the keys of its table, else the tables.
std::string unknown_key_fix(const std::string& key);
//! The fix of an unknown table: the table or key meant, then the tables.
std::string unknown_table_fix(const std::string& name);

}  // namespace panoptic::scene_detail
