#pragma once
//! `panoptic reference --outputs`: every entry of a run's output file (root attributes,
//! /grid, /disk, /pebbles, /snapshots, /timeseries, /summary, /solver), each from the
//! declaration next to the code that writes it, for a scene with every process on.
//! src/io/README.md holds a copy (OutputReference.ReadmeCopyIsUpToDate checks it).
#include <string>

namespace panoptic {

//! The Markdown table (src/model/output_table.hpp).
std::string output_reference_markdown();

}  // namespace panoptic
