#pragma once
//! The radial tables a scene's disk reads (disk.table_file: Sigma_g and T;
//! disk.alpha_file: alpha): the file named by the key, relative to the scene file that
//! sets it (or the current directory from --set), read and checked
//! (disk/radial_table.hpp) and required to cover the grid; every problem is a ConfigError
//! naming the key, its value, what is wrong and the fix.
#include <memory>
#include <string>
#include <vector>

#include "disk/radial_table.hpp"
#include "src/scene/config.hpp"

namespace panoptic {

//! The path of the file named by `key`: as written when absolute, else relative to the
//! directory of the scene file that set the key (Config::where), or to the current
//! directory when a --set gave it (a path on the command line).
std::filesystem::path scene_relative_path(const Config& cfg, const std::string& key);

//! The tables of the CSV file named by `key`: its first column r_au (`columns[0]`), one
//! RadialTable per further column, in cgs (r in cm; each value times `to_cgs[k]`, one per
//! further column). Fails (ConfigError) for a missing or malformed file, radii not
//! increasing, values not > 0, or a table that does not cover the grid
//! [grid.r_in_au, grid.r_out_au].
std::vector<std::shared_ptr<const RadialTable>> read_disk_table(
    const Config& cfg, const std::string& key, const std::vector<std::string>& columns,
    const std::vector<double>& to_cgs);

}  // namespace panoptic
