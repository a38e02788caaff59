#pragma once
//! The summary table of a scan: one row per manifest entry with its axis values, its
//! status (completed, failed, interrupted, incomplete, not run), exit code, error, wall
//! time, CVODE steps, the worker that ran it and the /summary scalars of its output. It
//! is rebuilt from the run files and their status records every time, so a killed scan
//! loses nothing: DIR/summary.h5 and DIR/summary.csv (params/README.md, Scans).
#include <filesystem>
#include <string>
#include <vector>

#include "src/scan/scan_manifest.hpp"

namespace panoptic {

struct ScanCounts {
  long completed = 0, failed = 0, other = 0;  //!< other: interrupted, incomplete, not run
};

//! Writes DIR/summary.h5 and DIR/summary.csv (each atomically) and returns the counts.
ScanCounts write_scan_summary(const std::filesystem::path& dir, const Manifest& m,
                              const std::vector<ResolvedRun>& resolved);

//! DIR/runs/<name>.<ext>
std::filesystem::path run_file(const std::filesystem::path& dir, const std::string& name,
                               const std::string& ext);

}  // namespace panoptic
