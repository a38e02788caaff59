#pragma once
//! A TOML parse that survives arbitrary bytes. toml++ 3.3.0 (the Debian build) can abort
//! or crash on some malformed input (upstream tomlplusplus issues #294, #295), and a
//! scene file or a --set value is untrusted input: a typo must give a ConfigError, never
//! a core dump. So the bytes are first parsed in a fork()ed child process; the parent
//! parses them itself only after the child reported success.
#include <toml++/toml.h>

#include <string>
#include <string_view>

#include "src/core/error.hpp"

namespace panoptic {

//! Throws ConfigError "<name>:<line>:<col>: ..." when `text` holds a NUL byte or is not
//! valid UTF-8 (overlong forms, surrogates and code points above U+10FFFF included).
void check_text(std::string_view text, const std::string& name);

//! Knobs of parse_toml_guarded(); the defaults are what the loader uses.
struct GuardOptions {
  //! Wall-clock limit of the child's parse, seconds (alarm()). A parse of a scene takes
  //! microseconds, so hitting this means the parser hangs.
  unsigned timeout_s = 5;
  //! Test hook: run this in the child instead of toml::parse (to simulate a parser that
  //! crashes or hangs). It must throw toml::parse_error for a syntax error.
  void (*child_parse)(std::string_view text) = nullptr;
};

//! check_text(), then parses `text` as TOML; `name` is the file name used in messages.
//! Throws ConfigError "<name>:<line>:<col>: TOML syntax error: <description>" for a
//! syntax error and "<name>...: not a valid TOML file (the TOML parser crashed on it:
//! ...)" when the parser crashed or hung in the child.
toml::table parse_toml_guarded(std::string_view text, const std::string& name,
                               const GuardOptions& options = {});

}  // namespace panoptic
