#pragma once
//! The --max-wall option of `panoptic run`: the wall time after which the run stops with
//! a checkpoint (exit code 75), so that a batch job ends before its limit.
#include <string_view>

namespace panoptic {

//! A wall-clock duration for --max-wall (or `option`: --progress): "90m", "2h", "3600s",
//! "1h30m", "1.5h", or a plain number of seconds. Throws ConfigError naming `option` and
//! saying what is accepted.
double parse_duration(std::string_view text, std::string_view option = "--max-wall");

}  // namespace panoptic
