#pragma once
//! The Output table of the documentation, generated from the fields the modules and the
//! model declare (OutputField), so that it is never kept by hand: `panoptic reference
//! --outputs`.
#include <span>
#include <string>
#include <vector>

#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/physics_module.hpp"

namespace panoptic {

//! A small scene that turns every process on (evolving gas, growth with porosity and
//! erosion, both planetesimal channels): its model declares every snapshot field there
//! is.
Config every_process_scene();

//! A Markdown table with one row per field, the static ones first: `<group>/<name>`,
//! units ("-" for a pure number), description.
std::string output_table_markdown(std::span<const StaticField> static_fields,
                                  std::span<const OutputField> fields);

}  // namespace panoptic
