#pragma once
//! The value of one scene key, typed by its KeySpec::type: kReal, kInt, kBool, kString,
//! kRealList in this order.
#include <string>
#include <variant>
#include <vector>

namespace panoptic {

using ConfigValue = std::variant<double, long, bool, std::string, std::vector<double>>;

}  // namespace panoptic
