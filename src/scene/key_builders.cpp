#include "src/scene/key_builders.hpp"

#include <charconv>
#include <cmath>

#include "src/scene/toml_literal.hpp"

namespace panoptic::scene_detail {

std::string literal(double x) {
  if (x == 0.0 || std::abs(x) >= 0.01) return toml_real(x);
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::scientific);
  std::string s(buf, r.ptr);
  if (const size_t e = s.find("e-0"); e != std::string::npos) s.erase(e + 2, 1);  // e-03
  return s;
}

namespace {

// The fields every key has.
KeySpec spec(std::string key, KeyType type, std::string def, std::string doc) {
  KeySpec k;
  k.key = std::move(key);
  k.type = type;
  k.default_toml = std::move(def);
  k.doc = std::move(doc);
  return k;
}

}  // namespace

KeySpec real(std::string key, std::string def, std::string unit, std::string doc,
             std::optional<double> min, bool min_excl, std::optional<double> max,
             bool max_excl) {
  KeySpec k = spec(std::move(key), KeyType::kReal, std::move(def), std::move(doc));
  k.unit = std::move(unit);
  k.min = min;
  k.min_exclusive = min_excl;
  k.max = max;
  k.max_exclusive = max_excl;
  return k;
}

KeySpec positive(std::string key, std::string def, std::string unit, std::string doc) {
  return real(std::move(key), std::move(def), std::move(unit), std::move(doc), 0.0, true);
}

KeySpec integer(std::string key, std::string def, std::string doc, double min,
                double max) {
  KeySpec k = spec(std::move(key), KeyType::kInt, std::move(def), std::move(doc));
  k.min = min;
  k.max = max;
  return k;
}

KeySpec flag(std::string key, std::string def, std::string doc) {
  return spec(std::move(key), KeyType::kBool, std::move(def), std::move(doc));
}

KeySpec choice(std::string key, std::string def, std::vector<std::string> choices,
               std::string doc) {
  KeySpec k = spec(std::move(key), KeyType::kString, "\"" + def + "\"", std::move(doc));
  k.choices = std::move(choices);
  return k;
}

KeySpec text(std::string key, std::string doc) {
  return spec(std::move(key), KeyType::kString, "\"\"", std::move(doc));
}

KeySpec real_list(std::string key, std::string unit, std::string doc,
                  std::optional<double> min) {
  KeySpec k = spec(std::move(key), KeyType::kRealList, "[]", std::move(doc));
  k.unit = std::move(unit);
  k.min = min;
  return k;
}

KeySpec real_table(std::string key, std::string def, std::string unit, std::string doc,
                   double min) {
  KeySpec k = real_list(std::move(key), std::move(unit), std::move(doc), min);
  k.default_toml = std::move(def);
  k.min_exclusive = true;
  return k;
}

UsedWhen is(std::string key, std::vector<std::string> values) {
  return UsedWhen{std::move(key), std::move(values), {}};
}

UsedWhen one_of(std::string key, std::vector<std::string> names) {
  for (std::string& n : names) n = toml_string(n);  // as Config writes the value
  return is(std::move(key), std::move(names));
}

UsedWhen growth_on() { return is("growth.enabled", {"true"}); }
UsedWhen disk_model(const std::string& m) { return one_of("disk.model", {m}); }
UsedWhen dust_init(const std::string& i) { return one_of("dust.init", {i}); }
UsedWhen single_size() { return one_of("model.kind", {"single_size"}); }
UsedWhen distribution() { return one_of("model.kind", {"distribution"}); }
UsedWhen either(UsedWhen first, std::vector<UsedWhen> alternatives) {
  first.or_else = std::move(alternatives);
  return first;
}
UsedWhen erosion(std::vector<std::string> models) {
  return one_of("erosion.model", std::move(models));
}
UsedWhen si(std::vector<std::string> models) {
  return one_of("planetesimals.si", std::move(models));
}

KeySpec when(std::vector<UsedWhen> conditions, KeySpec k) {
  k.used_when = std::move(conditions);
  return k;
}

}  // namespace panoptic::scene_detail
