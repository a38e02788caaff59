#pragma once
//! Values written back as TOML literals that read back exactly: the resolved scene stored
//! in every run file (src/scene/resolved_toml.cpp) and the manifest of a scan
//! (src/scan/scan_manifest.cpp), and scene values in messages (src/io/checkpoint.cpp).
#include <string>
#include <string_view>

#include "src/scene/config_value.hpp"

namespace panoptic {

//! Shortest text that reads back as exactly `x` (std::to_chars, locale-independent).
std::string shortest(double x);
//! A TOML float literal: "1" would read back as an integer, so it becomes "1.0";
//! nan and +-inf as TOML spells them.
std::string toml_real(double x);
//! A TOML basic string, quoted, with every character TOML requires escaped.
std::string toml_string(std::string_view s);
//! A scene value as the TOML literal that reads back as it: toml_real, an integer,
//! true/false, toml_string, or a list of toml_real.
std::string toml_value(const ConfigValue& v);
//! `s` with every control character replaced by '?': a comment must stay on its line.
std::string comment_safe(std::string_view s);

}  // namespace panoptic
