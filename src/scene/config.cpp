// The resolved scene: typed access to its values, where each came from, and the error
// of a cross-key check made after loading.
#include "src/scene/config.hpp"

#include "src/scene/toml_literal.hpp"

namespace panoptic {

std::string trim_blanks(std::string_view s) {
  const size_t b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return "";
  const size_t e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

namespace {

template <class T>
const T& get(const Config& config, std::string_view key, const char* accessor) {
  const auto it = config.values_.find(key);
  if (it == config.values_.end()) {
    throw Error(std::string("internal error: Config::") + accessor + "(\"" +
                std::string(key) +
                "\"): no such key in the scene (is it in src/scene/scene_keys.cpp?)");
  }
  if (const T* v = std::get_if<T>(&it->second)) return *v;
  throw Error(std::string("internal error: Config::") + accessor + "(\"" +
              std::string(key) + "\"): the key holds another type");
}

}  // namespace

double Config::real(std::string_view key) const {
  return get<double>(*this, key, "real");
}

long Config::integer(std::string_view key) const {
  return get<long>(*this, key, "integer");
}

bool Config::flag(std::string_view key) const { return get<bool>(*this, key, "flag"); }

const std::string& Config::str(std::string_view key) const {
  return get<std::string>(*this, key, "str");
}

const std::vector<double>& Config::reals(std::string_view key) const {
  return get<std::vector<double>>(*this, key, "reals");
}

bool Config::user_set(std::string_view key) const {
  const auto it = origins_.find(key);
  return it != origins_.end() && it->second.user_set;
}

const std::string& Config::where(std::string_view key) const {
  static const std::string kDefault = "default";
  const auto it = origins_.find(key);
  return it == origins_.end() ? kDefault : it->second.where;
}

void Config::fail(std::string_view key, std::string_view message) const {
  std::string text = where(key) + ": " + std::string(key);
  if (const auto it = values_.find(key); it != values_.end()) {
    text += " = " + toml_value(it->second);
  }
  throw ConfigError(text + ": " + std::string(message));
}

}  // namespace panoptic
