// presets.hpp — accuracy presets of `panoptic run --fast` / `--accurate` (issue 7): fixed
// sets of scene overrides, chosen on the work-precision front measured by
// tests/bench/work_precision.py (tests/bench/README.md, "Work-precision"). A preset is
// applied before the --set options, so an explicit --set of the same key still wins.
#pragma once

#include <string>
#include <vector>

namespace panoptic {

//! The overrides ("table.key=value") of a preset: "fast", "accurate"; "" = none.
//! Throws std::invalid_argument for another name.
std::vector<std::string> preset_overrides(const std::string& preset);

//! The preset's overrides followed by `sets`: what load_scene() applies in order.
std::vector<std::string> with_preset(const std::string& preset,
                                     const std::vector<std::string>& sets);

}  // namespace panoptic
