#pragma once
//! The error hierarchy of panoptic. main() maps each class to an exit code
//! (exit_codes.hpp): ConfigError -> 2 (bad input), SolverError -> 3, IoError -> 4.
#include <sstream>
#include <stdexcept>
#include <string>

#include "src/core/exit_codes.hpp"

namespace panoptic {

//! A number as a person writes it (%g: 6 significant digits), for error messages.
inline std::string num(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  virtual int exit_code() const { return exit_codes::kInternal; }
};

//! Bad input: scene file, --set override, command line. Exit code 2.
class ConfigError : public Error {
 public:
  using Error::Error;
  int exit_code() const override { return exit_codes::kBadInput; }
};

//! CVODE failed or the model produced an unrecoverable state. Exit code 3.
class SolverError : public Error {
 public:
  using Error::Error;
  int exit_code() const override { return exit_codes::kFailed; }
};

//! A file could not be read or written. Exit code 4.
class IoError : public Error {
 public:
  using Error::Error;
  int exit_code() const override { return exit_codes::kIoError; }
};

}  // namespace panoptic
