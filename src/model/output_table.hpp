#pragma once
//! The Output table of the documentation, generated from the entries the modules, the
//! model and the writers declare (OutputField, StaticField, OutputAttribute), so that it
//! is never kept by hand: `panoptic reference --outputs` (src/run/output_reference.hpp
//! puts the groups together).
#include <span>
#include <string>
#include <vector>

#include "src/io/output_entry.hpp"
#include "src/model/simulation.hpp"
#include "src/scene/config.hpp"
#include "src/solver/physics_module.hpp"

namespace panoptic {

//! A small scene that turns every process on (evolving gas, growth with porosity and
//! erosion, both planetesimal channels): its model declares every snapshot field there
//! is.
Config every_process_scene();

//! A small scene of the size-distribution model (model.kind = "distribution", evolving
//! gas, growth): its model declares the fields the single-size one has not (sigma(r, m),
//! the mass grid) and describes some shared ones otherwise.
Config distribution_scene();

//! Merges the rows of another model into `rows`: a path not listed yet goes after the
//! last row of its group (at the end if none), its description led by "(<model>)"; a
//! listed path the other model describes otherwise gets "; <model>: <its description>"
//! (a field of both models keeps one row, as a file has one dataset of that name).
void merge_entries(std::vector<OutputEntry>& rows, std::span<const OutputEntry> more,
                   const std::string& model);

//! The rows of datasets /<group>/<name> declared as OutputField.
std::vector<OutputEntry> output_entries(const std::string& group,
                                        std::span<const OutputField> fields);
//! The rows of the static datasets (/grid, /disk, /pebbles).
std::vector<OutputEntry> output_entries(std::span<const StaticField> fields);
//! The rows of attributes: "<group>@<name>", "@<name>" at the root.
std::vector<OutputEntry> output_entries(std::span<const OutputAttribute> attributes);

//! A Markdown table with one row per entry, in the given order: path, units ("-" for a
//! pure number or a text), description.
std::string output_table_markdown(std::span<const OutputEntry> entries);

}  // namespace panoptic
