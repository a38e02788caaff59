#pragma once
//! A parameter scan: a scan file (TOML) names a base scene, fixed overrides and axes over
//! scene keys, and expands into a manifest, the list of runs with the --set overrides of
//! each. The manifest is written to the scan directory before any run starts and a rerun
//! must expand to the same one (params/README.md, Scans).
//!
//! Axes: an explicit list (`values`), a linear or logarithmic range (`lin`/`log` with
//! `num` points, both ends included). With `sampling = "grid"` the runs are the product
//! of the axes, where axes sharing a `zip` name advance together as one dimension; with
//! `sampling = "lhs"` they are `samples` points of a Latin hypercube drawn with `seed`
//! (McKay, Beckman & Conover 1979): each axis's range is cut into `samples` equal strata
//! (in log for `log`), every stratum holds exactly one run, the pairing of strata across
//! axes is random.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "src/scene/config.hpp"

namespace panoptic {

//! One axis of a scan file.
struct ScanAxis {
  enum class Kind { kList, kLin, kLog };
  std::string key;
  KeyType type = KeyType::kReal;  //!< of the scene key
  Kind kind = Kind::kList;
  std::vector<std::string> list;  //!< kList: each value as a TOML literal
  double lo = 0.0, hi = 0.0;      //!< kLin, kLog: the range ends
  long num = 0;                   //!< grid sampling: number of points of a range
  std::string zip;  //!< grid sampling: axes of one zip group advance together
};

//! One run of a scan.
struct ManifestEntry {
  long id = 0;
  std::string name;  //!< "run_00017": the stem of its files in DIR/runs/
  //! (key, value as a TOML literal), one per axis, in axis order.
  std::vector<std::pair<std::string, std::string>> values;
  //! "key=value" strings for --set.
  std::vector<std::string> overrides() const;
};

struct Manifest {
  std::filesystem::path scene;  //!< base scene, absolute
  std::string scene_hash;       //!< FNV-1a of the bytes of the scene and its bases (hex)
  std::vector<std::string> fixed;  //!< --set overrides applied to every run (before axes)
  std::string sampling = "grid";   //!< "grid" or "lhs"
  long samples = 0;                //!< lhs
  std::uint64_t seed = 0;          //!< lhs
  std::vector<ScanAxis> axes;
  std::vector<ManifestEntry> entries;

  //! The manifest as TOML. Two expansions of the same scan (and base scene) give the same
  //! text; `header` adds comment lines (the scan file's name) that comparisons ignore.
  std::string to_toml(const std::string& header = "") const;
  //! Every --set override of entry `i`: the fixed ones, then the axis values.
  std::vector<std::string> overrides(std::size_t i) const;
};

//! Parses a scan file's text (`name` in messages, relative scene paths resolved against
//! `base_dir`) and expands it. Throws ConfigError naming file:line, the key and the fix
//! for a malformed file, an unknown scene key (with the nearest key), a value of the
//! wrong type, a zip group of unequal lengths, and so on. The scene values themselves are
//! checked by validate_manifest().
Manifest expand_scan_text(std::string_view text, const std::string& name,
                          const std::filesystem::path& base_dir);
//! Same, from a file.
Manifest load_scan(const std::filesystem::path& file);

//! The resolved scene of every run: loads the base scene with each entry's overrides
//! through the scene schema and its cross-key checks, so a bad axis value is refused
//! before any run starts. Throws ConfigError "run_00017 (key=value, ...): <scene
//! error>". Returns, per entry, the resolved scene text (what the run's output records
//! as config_toml) and its end time [yr].
struct ResolvedRun {
  std::string config_toml;
  double t_end_yr = 0.0;
};
std::vector<ResolvedRun> validate_manifest(const Manifest& m);

//! A manifest's text without its comment lines, for comparing a rerun's with the one on
//! disk.
std::string manifest_body(std::string_view text);

//! Values of the sampled coordinates for tests: lin and log ranges of `num` points.
std::vector<double> lin_points(double lo, double hi, long num);
std::vector<double> log_points(double lo, double hi, long num);

}  // namespace panoptic
