#pragma once
//! The exit codes of panoptic, one list for every command (run, scan, observe, ...).
//! The error classes of error.hpp carry theirs; 75 is EX_TEMPFAIL of sysexits.h ("try
//! again"): a run or scan stopped so that it can be continued.

namespace panoptic::exit_codes {

inline constexpr int kOk = 0;
inline constexpr int kInternal = 1;  //!< a bug: an exception that is not a panoptic Error
inline constexpr int kBadInput =
    2;                             //!< ConfigError: scene, --set, command line, scan file
inline constexpr int kFailed = 3;  //!< SolverError; for a scan: some of its runs failed
inline constexpr int kIoError = 4;  //!< IoError: a file could not be read or written
//! Stopped by SIGINT, SIGTERM or --max-wall with a checkpoint: restart, or rerun the
//! scan.
inline constexpr int kStopped = 75;

}  // namespace panoptic::exit_codes
