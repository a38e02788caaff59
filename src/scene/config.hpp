#pragma once
//! A scene: one TOML file plus command-line overrides, validated against the key schema
//! (src/scene/scene_keys.hpp) before anything is allocated. Values stay in the units of
//! their key names (au, yr, M_sun, ...); callers convert to cgs with src/core/units.hpp.
//!
//! Style: Athena++ GetOrAdd + dump of the resolved table; Cantera InputFileError messages
//! ("file:line:col: key = value: constraint; fix").
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "src/core/error.hpp"
#include "src/scene/config_value.hpp"
#include "src/scene/scene_keys.hpp"

namespace panoptic {

//! Where a value came from, for error messages: "params/x.toml:7:11", "--set", "default".
struct ValueOrigin {
  std::string where;
  bool user_set = false;  //!< false when the default was used
  //! the scene file that set it (the scene or one of its bases); "" for --set, default
  std::string file;
  //! its line says the run does not read it (a resolved scene's mark: no warning)
  bool marked_not_read = false;
};

class Config {
 public:
  double real(std::string_view key) const;
  long integer(std::string_view key) const;
  bool flag(std::string_view key) const;
  const std::string& str(std::string_view key) const;
  const std::vector<double>& reals(std::string_view key) const;

  //! True when the scene file or an override set the key (false: default in use).
  bool user_set(std::string_view key) const;
  //! "file:line:col", "--set", or "default".
  const std::string& where(std::string_view key) const;

  //! Throws ConfigError "<where>: <key> = <value>: <message>". For cross-key checks made
  //! after loading (e.g. r_in >= r_out); the message should say the constraint and the
  //! fix.
  [[noreturn]] void fail(std::string_view key, std::string_view message) const;

  //! The resolved scene as TOML, defaults included, each key commented with its unit and
  //! whether it is a default. Stored as the `config_toml` attribute of every output.
  std::string resolved_toml() const;

  const std::filesystem::path& file() const { return file_; }

  // Filled by load_scene(); public for tests that build a Config by hand.
  std::filesystem::path file_;
  std::map<std::string, ConfigValue, std::less<>> values_;
  std::map<std::string, ValueOrigin, std::less<>> origins_;
};

//! The scene file named in the first line of a resolved scene (Config::resolved_toml),
//! "" when `resolved` does not start with that line.
std::string resolved_scene_file(std::string_view resolved);

//! Reads and validates a scene. `overrides` are "table.key=value" strings (--set), where
//! value is a TOML literal, or a bare word taken as a string. Unknown keys, wrong types,
//! out-of-range values, unknown choices and malformed TOML (even arbitrary bytes) throw
//! ConfigError naming file:line:col, the key, the value, the constraint and the fix.
//! A scene may start with `base = "other.toml"` (relative to its folder): the keys of
//! that scene (and of its own base, to any depth) with this file's keys over them; a
//! base that cannot be read, or a cycle of bases, throws ConfigError naming the chain.
Config load_scene(const std::filesystem::path& file,
                  std::span<const std::string> overrides = {});

//! Same, from text in memory (`name` is used in messages, and a `base` is relative to its
//! folder). For tests, the fuzzer and the scenes stored in outputs and checkpoints.
Config load_scene_text(std::string_view text, const std::string& name,
                       std::span<const std::string> overrides = {});

//! `base` with further "table.key=value" overrides applied after its own, exactly as
//! load_scene() would apply them. Only for text the program wrote itself (the axis values
//! of panoptic scan, canonical TOML literals): the literals are parsed in this process,
//! without the crash guard of src/scene/toml_guard.hpp, which costs a fork() per value.
Config apply_trusted_overrides(const Config& base,
                               std::span<const std::string> overrides);

//! `s` without the spaces and tabs at either end: how a --set item's key and value are
//! read (panoptic scan compares its scan.set keys the same way).
std::string trim_blanks(std::string_view s);

//! The warning for a scene file that sets no key (empty or only comments: every key
//! would take its default), or "" when it sets one.
std::string empty_scene_warning(const Config& config);

//! One line per key the scene file or --set set that a run of this scene does not read
//! (its KeySpec::used_when fails: disk.r_c_au without disk.model = "lbp"), naming the
//! key, where it was set, the switches that leave it unused and the fix. A switch set to
//! its default (off) value is not reported: it turns nothing on. Warnings, not errors: a
//! scan's base scene may carry keys for an axis that switches the model.
std::vector<std::string> unused_key_warnings(const Config& config);

//! The scene files `file` reads, itself first, then its base, its base's base, ...
//! (paths as the loader opens them). Throws ConfigError as load_scene() does for a base
//! that cannot be read or a cycle. For panoptic scan, which keeps a digest of them.
std::vector<std::filesystem::path> scene_files(const std::filesystem::path& file);

//! params/reference.toml as generated from the schema: every key, commented, with units
//! and defaults. A unit test checks that the file in the repository equals this text.
std::string reference_toml();

}  // namespace panoptic
