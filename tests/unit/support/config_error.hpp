#pragma once
//! Test helper: the message of the ConfigError that `action` throws, for the tests of
//! bad input. Anything else it throws, or no error at all, is a test failure (and "");
//! `what` names the input in that failure.
#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "src/core/error.hpp"

namespace panoptic {

template <class Action>
std::string config_error_message(Action&& action, const std::string& what) {
  try {
    action();
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": not a ConfigError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no error for " << what;
  return "";
}

}  // namespace panoptic
