// The scene loader: TOML (parsed through src/scene/toml_guard.hpp, so arbitrary bytes
// give a ConfigError) validated against the schema of src/scene/scene_keys.cpp, defaults
// filled in,
// --set overrides applied last. Every message has the form
//   "<where>: <key> = <value as written>: <what is wrong>; <fix>"
// because the user has to find the line, see what was read and know what to write.
#include "src/scene/config.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>

#include "src/scene/toml_guard.hpp"
#include "src/scene/toml_literal.hpp"

namespace panoptic {
std::string trim_blanks(std::string_view s) {
  const size_t b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return "";
  const size_t e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

namespace {

// A scene is a page of text; anything this large is the wrong file, and refusing it
// early keeps a mistyped path from eating memory.
constexpr size_t kMaxSceneBytes = 16u << 20;
// Errors reported at once; the rest are counted.
constexpr size_t kMaxErrors = 20;

// ---------------------------------------------------------------------------------------
// The schema

const KeySpec* find_spec(std::string_view key) {
  for (const KeySpec& spec : scene_keys()) {
    if (spec.key == key) return &spec;
  }
  return nullptr;
}

std::string_view table_of(std::string_view key) { return key.substr(0, key.find('.')); }

std::string_view leaf_of(std::string_view key) {
  const size_t dot = key.find('.');
  return dot == std::string_view::npos ? key : key.substr(dot + 1);
}

// The tables, in schema order.
std::vector<std::string> schema_tables() {
  std::vector<std::string> tables;
  for (const KeySpec& spec : scene_keys()) {
    const std::string t(table_of(spec.key));
    if (std::find(tables.begin(), tables.end(), t) == tables.end()) tables.push_back(t);
  }
  return tables;
}

bool is_table(std::string_view name) {
  for (const KeySpec& spec : scene_keys()) {
    if (table_of(spec.key) == name) return true;
  }
  return false;
}

std::string join(const std::vector<std::string>& items, std::string_view sep) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) {
    if (i) out += sep;
    out += items[i];
  }
  return out;
}

std::string keys_of_table(std::string_view table) {
  std::vector<std::string> leaves;
  for (const KeySpec& spec : scene_keys()) {
    if (table_of(spec.key) == table) leaves.emplace_back(leaf_of(spec.key));
  }
  return join(leaves, ", ");
}

// Levenshtein distance, case-insensitive (disk.t_1au is a typo of disk.T_1au).
size_t edit_distance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) {
    return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  };
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      const size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + cost});
      diag = up;
    }
  }
  return row[b.size()];
}

// The candidate nearest to `word`, if it is near enough to be a plausible typo.
std::optional<std::string> nearest(std::string_view word,
                                   const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  size_t best_d = std::numeric_limits<size_t>::max();
  for (const std::string& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  const size_t limit = std::max<size_t>(2, word.size() / 3);
  if (best && best_d <= limit) return best;
  return std::nullopt;
}

// No scene key is longer than ~40 characters: a name longer than this is no typo of one
// (comparing it with every key cost O(length) each: 39 s for a 10 MB key), and a message
// shows only its start.
constexpr std::size_t kLongestPlausibleKey = 200;

// A key as a message shows it: whole up to kLongestPlausibleKey characters, else its
// start and length.
std::string shown_key(const std::string& key) {
  if (key.size() <= kLongestPlausibleKey) return key;
  return key.substr(0, 80) + "... (a name of " + std::to_string(key.size()) +
         " characters)";
}

// The schema key the user probably meant by `key` ("table.key", or a bare key written
// outside any table): the same leaf in another table first, then the nearest spelling.
std::optional<std::string> suggest_key(std::string_view key) {
  if (key.size() > kLongestPlausibleKey) return std::nullopt;
  const std::string_view leaf = leaf_of(key);
  for (const KeySpec& spec : scene_keys()) {
    if (leaf_of(spec.key) == leaf) return spec.key;
  }
  std::vector<std::string> all;
  for (const KeySpec& spec : scene_keys()) all.push_back(spec.key);
  if (auto best = nearest(key, all)) return best;
  // A bare key: compare with the leaves.
  if (key.find('.') == std::string_view::npos) {
    std::optional<std::string> best;
    size_t best_d = std::numeric_limits<size_t>::max();
    for (const KeySpec& spec : scene_keys()) {
      const size_t d = edit_distance(key, leaf_of(spec.key));
      if (d < best_d) {
        best_d = d;
        best = spec.key;
      }
    }
    if (best_d <= std::max<size_t>(2, key.size() / 3)) return best;
  }
  return std::nullopt;
}

// A comment must stay on its line: control characters would end it or break the file.
std::string comment_safe(std::string_view s) {
  std::string out;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    out += (c < 0x20 || c == 0x7F) ? '?' : ch;
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Describing a key's constraint

std::string bound_text(const KeySpec& spec, double x) {
  if (spec.type == KeyType::kInt && std::abs(x) < 1e18) {
    return std::to_string(static_cast<long long>(x));
  }
  return shortest(x);
}

// "> 0", ">= 4 and <= 1000000"; empty when the key has no bounds.
std::string range_text(const KeySpec& spec) {
  std::string out;
  if (spec.min) out += (spec.min_exclusive ? "> " : ">= ") + bound_text(spec, *spec.min);
  if (spec.max) {
    if (!out.empty()) out += " and ";
    out += (spec.max_exclusive ? "< " : "<= ") + bound_text(spec, *spec.max);
  }
  return out;
}

std::string unit_suffix(const KeySpec& spec) {
  return spec.unit.empty() ? "" : " [" + spec.unit + "]";
}

std::string type_text(KeyType type) {
  switch (type) {
    case KeyType::kReal:
      return "a real number";
    case KeyType::kInt:
      return "an integer";
    case KeyType::kBool:
      return "true or false";
    case KeyType::kString:
      return "a string";
    case KeyType::kRealList:
      return "a list of real numbers";
  }
  return "a value";
}

// "a real number > 0 (unit: au)", "one of: powerlaw, lbp".
std::string wanted_text(const KeySpec& spec) {
  if (!spec.choices.empty()) return "one of: " + join(spec.choices, ", ");
  std::string out = type_text(spec.type);
  const std::string range = range_text(spec);
  if (!range.empty()) out += (spec.type == KeyType::kRealList ? ", each " : " ") + range;
  if (!spec.unit.empty()) out += " (unit: " + spec.unit + ")";
  return out;
}

std::string example_value(const KeySpec& spec) {
  if (spec.type == KeyType::kRealList && spec.default_toml == "[]")
    return spec.unit == "au" ? "[3.0, 30.0]" : "[1e3, 1e4]";
  return spec.default_toml;
}

// The generic fix: what to write instead.
std::string fix_text(const KeySpec& spec) {
  return "set " + spec.key + " to " + wanted_text(spec) + ", e.g. " + spec.key + " = " +
         example_value(spec);
}

std::string node_type_text(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a real number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

// The reason `x` violates the bounds of `spec` ("must be > 0 [au]"), or "" when it does
// not.
std::string range_problem(const KeySpec& spec, double x) {
  const bool below =
      spec.min && (spec.min_exclusive ? !(x > *spec.min) : !(x >= *spec.min));
  const bool above =
      spec.max && (spec.max_exclusive ? !(x < *spec.max) : !(x <= *spec.max));
  if (!below && !above) return "";
  return "must be " + range_text(spec) + unit_suffix(spec);
}

// Converts a TOML node to the value of `spec`; on failure returns nullopt and sets
// `problem` to "<what is wrong>; <fix>".
std::optional<ConfigValue> convert(const KeySpec& spec, const toml::node& node,
                                   std::string& problem) {
  const auto type_problem = [&](std::string extra = "") {
    std::string what = node_type_text(node);
    // a --set value that reads as a number only beyond the range of a double or of a
    // 64-bit integer (1e999, 99999999999999999999) arrives as a string
    if (const auto* str = node.as_string()) {
      const std::string& t = str->get();
      char* end = nullptr;
      errno = 0;
      (void)std::strtod(t.c_str(), &end);
      const bool reads_as_number = !t.empty() && end == t.c_str() + t.size();
      const bool double_range = errno == ERANGE;
      errno = 0;
      (void)std::strtoll(t.c_str(), &end, 10);
      const bool int_text = !t.empty() && end == t.c_str() + t.size();
      const bool int_range = errno == ERANGE && int_text;
      if (reads_as_number && double_range)
        what = "a number beyond the range of a double";
      else if (reads_as_number && spec.type == KeyType::kInt && int_range)
        what = "a number beyond the range of a 64-bit integer";
      else if ((spec.type == KeyType::kInt && int_text) ||
               (spec.type == KeyType::kReal && reads_as_number))
        what = "a string (\"" + t + "\": write the number without quotes)";
    }
    problem = "must be " + type_text(spec.type) + unit_suffix(spec) + ", not " + what +
              "; " + (extra.empty() ? fix_text(spec) : extra);
    return std::nullopt;
  };
  const auto number = [](const toml::node& n) -> std::optional<double> {
    if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
    if (const auto* f = n.as_floating_point()) return f->get();
    return std::nullopt;
  };
  const auto finite_problem = [&](double x) {
    problem = std::string("must be a finite number, not ") +
              (std::isnan(x) ? "nan"
               : x < 0       ? "-inf"
                             : "inf") +
              "; " + fix_text(spec);
  };

  switch (spec.type) {
    case KeyType::kReal: {
      const auto x = number(node);
      if (!x) return type_problem();
      if (!std::isfinite(*x)) {
        finite_problem(*x);
        return std::nullopt;
      }
      if (std::string p = range_problem(spec, *x); !p.empty()) {
        problem = p + "; " + fix_text(spec);
        return std::nullopt;
      }
      return ConfigValue(*x);
    }
    case KeyType::kInt: {
      const auto* i = node.as_integer();
      if (!i) {
        if (const auto* f = node.as_floating_point(); f && std::isfinite(f->get()) &&
                                                      std::trunc(f->get()) == f->get() &&
                                                      std::abs(f->get()) < 1e18) {
          return type_problem(
              "write it without a decimal point or exponent: " + spec.key + " = " +
              std::to_string(static_cast<long long>(f->get())));
        }
        return type_problem();
      }
      const auto x = static_cast<long>(i->get());
      if (std::string p = range_problem(spec, static_cast<double>(x)); !p.empty()) {
        problem = p + "; " + fix_text(spec);
        return std::nullopt;
      }
      return ConfigValue(x);
    }
    case KeyType::kBool: {
      const auto* b = node.as_boolean();
      if (!b) {
        if (const auto* s = node.as_string();
            s && (s->get() == "true" || s->get() == "false")) {
          return type_problem("write " + s->get() + " without quotes");
        }
        return type_problem();
      }
      return ConfigValue(b->get());
    }
    case KeyType::kString: {
      const auto* s = node.as_string();
      if (!s) return type_problem();
      if (!spec.choices.empty() && std::find(spec.choices.begin(), spec.choices.end(),
                                             s->get()) == spec.choices.end()) {
        problem = "unknown choice; choose one of: " + join(spec.choices, ", ");
        if (auto best = nearest(s->get(), spec.choices))
          problem += " (did you mean " + *best + "?)";
        return std::nullopt;
      }
      return ConfigValue(s->get());
    }
    case KeyType::kRealList: {
      const auto* array = node.as_array();
      if (!array) {
        if (const auto x = number(node)) {
          return type_problem("write a list, even of one value: " + spec.key + " = [" +
                              toml_real(*x) + "]");
        }
        return type_problem();
      }
      std::vector<double> xs;
      for (size_t k = 0; k < array->size(); ++k) {
        const toml::node& element = *array->get(k);
        const auto x = number(element);
        const std::string which = "element " + std::to_string(k + 1);
        if (!x) {
          problem = which + " is " + node_type_text(element) +
                    ": every element must be a number" + unit_suffix(spec) + "; " +
                    fix_text(spec);
          return std::nullopt;
        }
        if (!std::isfinite(*x)) {
          problem = which + " must be a finite number; " + fix_text(spec);
          return std::nullopt;
        }
        if (std::string p = range_problem(spec, *x); !p.empty()) {
          problem = which + " (" + shortest(*x) + ") " + p + "; " + fix_text(spec);
          return std::nullopt;
        }
        xs.push_back(*x);
      }
      return ConfigValue(std::move(xs));
    }
  }
  return type_problem();
}

// ---------------------------------------------------------------------------------------
// Reading the parsed file

// The text of a node as the user wrote it, sliced from the input by its source region
// (columns count code points, like toml++), whitespace runs collapsed, long text cut.
class SourceText {
 public:
  explicit SourceText(std::string_view text) : text_(text) {
    line_starts_.push_back(0);
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') line_starts_.push_back(i + 1);
    }
  }

  std::string slice(const toml::source_region& region) const {
    const auto begin = offset(region.begin);
    const auto end = offset(region.end);
    if (!begin || !end || *end <= *begin) return "";
    return tidy(text_.substr(*begin, *end - *begin));
  }

  static std::string tidy(std::string_view s) {
    constexpr size_t kMaxCodePoints = 60;
    std::string out;
    size_t code_points = 0;
    bool space = false;
    for (size_t i = 0; i < s.size(); ++i) {
      const char c = s[i];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
        space = !out.empty();
        continue;
      }
      if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
        if (code_points + (space ? 1 : 0) >= kMaxCodePoints) return out + " ...";
        ++code_points;
      }
      if (space) out += ' ', ++code_points;
      space = false;
      out += c;
    }
    return out;
  }

 private:
  std::optional<size_t> offset(const toml::source_position& p) const {
    if (p.line < 1 || p.line > line_starts_.size() || p.column < 1) return std::nullopt;
    size_t i = line_starts_[p.line - 1];
    for (size_t col = 1; col < p.column; ++col) {
      if (i >= text_.size()) return std::nullopt;
      ++i;
      while (i < text_.size() && (static_cast<unsigned char>(text_[i]) & 0xC0) == 0x80)
        ++i;
    }
    return i;
  }

  std::string_view text_;
  std::vector<size_t> line_starts_;
};

struct Problem {
  long line;  // sort key: problems of the file in file order, --set ones after
  long col;
  std::string message;
};

// Collects every problem of a scene, so that one run reports them all.
class Loader {
 public:
  Loader(std::string_view text, std::string name)
      : source_(text), name_(std::move(name)) {}

  void read_file(const toml::table& root) {
    for (auto&& [k, node] : root) {
      const std::string name(k.str());
      if (const toml::table* table = node.as_table()) {
        if (is_table(name)) {
          read_table(name, *table);
        } else {
          unknown_table(name, node.source().begin);
        }
      } else if (const toml::array* array = node.as_array();
                 array && array->is_array_of_tables()) {
        if (is_table(name)) {
          const std::string header = "[[" + name + "]]";
          add(node.source().begin, header +
                                       ": a scene table is not an array of tables; " +
                                       "write [" + name + "] with single brackets");
        } else {
          unknown_table(name, node.source().begin);
        }
      } else {
        // A key before the first [table] header.
        std::string fix = "scene keys belong to a table (table.key)";
        if (is_table(name)) {
          fix = name + " is a table: write [" + name + "] and its keys (" +
                keys_of_table(name) + ") below it";
        } else if (auto best = suggest_key(name)) {
          fix += "; did you mean " + *best + "? write it under [" +
                 std::string(table_of(*best)) + "]";
        } else {
          fix += "; the tables are: " + join(schema_tables(), ", ");
        }
        add(k.source().begin,
            name + " = " + written(node) + ": key outside any table; " + fix);
      }
    }
  }

  void apply_override(const std::string& item) {
    const std::string where = "--set";
    try {
      check_text(item, where);
    } catch (const ConfigError& e) {
      add_override(e.what());
      return;
    }
    const size_t eq = item.find('=');
    if (eq == std::string::npos) {
      add_override("--set " + toml_string(item) +
                   ": missing '='; write --set table.key=value, e.g. --set " +
                   "grid.n_cells=500");
      return;
    }
    const std::string key = trim_blanks(item.substr(0, eq));
    const std::string raw = trim_blanks(item.substr(eq + 1));
    const std::string shown = SourceText::tidy(raw);  // long values are cut
    if (key.empty()) {
      add_override("--set " + toml_string(item) +
                   ": missing key before '='; write --set table.key=value");
      return;
    }
    const KeySpec* spec = find_spec(key);
    if (spec && raw.empty() && spec->type != KeyType::kString) {
      add_override(where + ": " + key + " = : no value after '='; " + fix_text(*spec));
      return;
    }
    if (!spec) {
      add_override(where + ": " + shown_key(key) + " = " + shown + ": unknown key; " +
                   unknown_key_fix(key));
      return;
    }
    std::string problem;
    std::optional<ConfigValue> value;
    if (const auto literal = parse_literal(*spec, raw, trusted_)) {
      value = convert(*spec, literal->node(), problem);
    } else {
      value = convert(*spec, toml::value<std::string>(raw), problem);
    }
    if (!value) {
      add_override(where + ": " + key + " = " + shown + ": " + problem);
      return;
    }
    values_[spec->key] = std::move(*value);
    origins_[spec->key] = ValueOrigin{where, true};
  }

  // Throws the collected problems, if any, in file order.
  void throw_if_failed() {
    if (problems_.empty()) return;
    std::stable_sort(problems_.begin(), problems_.end(),
                     [](const Problem& a, const Problem& b) {
                       return a.line != b.line ? a.line < b.line : a.col < b.col;
                     });
    std::string message;
    for (size_t i = 0; i < problems_.size() && i < kMaxErrors; ++i) {
      if (i) message += "\n";
      message += problems_[i].message;
    }
    if (problems_.size() > kMaxErrors) {
      message +=
          "\n(and " + std::to_string(problems_.size() - kMaxErrors) + " more errors)";
    }
    throw ConfigError(message);
  }

  std::map<std::string, ConfigValue, std::less<>> values_;
  std::map<std::string, ValueOrigin, std::less<>> origins_;
  //! Parse --set literals in this process (text the program wrote itself).
  bool trusted_ = false;

 private:
  // A one-line TOML document holding the --set value, so that 2, 1e-3, true, "x" and
  // [1, 2] mean what they mean in a file; nullopt when the value is not a TOML literal
  // (then it is a bare string).
  struct Literal {
    toml::table doc;
    std::string table, leaf;
    const toml::node& node() const { return *doc[table][leaf].node(); }
  };
  static std::optional<Literal> parse_literal(const KeySpec& spec, const std::string& raw,
                                              bool trusted) {
    if (raw.empty() || raw.find_first_of("\r\n") != std::string::npos)
      return std::nullopt;
    Literal lit;
    lit.table = table_of(spec.key);
    lit.leaf = leaf_of(spec.key);
    const std::string doc = "[" + lit.table + "]\n" + lit.leaf + " = " + raw + "\n";
    try {
      if (trusted) {
        lit.doc = toml::parse(doc, std::string_view("--set"));
      } else {
        lit.doc = parse_toml_guarded(doc, "--set");
      }
    } catch (const toml::parse_error&) {
      return std::nullopt;
    } catch (const ConfigError&) {
      return std::nullopt;
    }
    const toml::table* t = lit.doc[lit.table].as_table();
    if (lit.doc.size() != 1 || !t || t->size() != 1 || !t->get(lit.leaf))
      return std::nullopt;
    return lit;
  }

  static std::string unknown_key_fix(const std::string& key) {
    if (auto best = suggest_key(key)) {
      return "did you mean " + *best + "? (params/reference.toml lists every key)";
    }
    const std::string table(table_of(key));
    if (key.find('.') != std::string::npos && is_table(table)) {
      return "the keys of [" + table + "] are: " + keys_of_table(table);
    }
    return "params/reference.toml lists every key; the tables are: " +
           join(schema_tables(), ", ");
  }

  void read_table(const std::string& table_name, const toml::table& table) {
    for (auto&& [k, node] : table) {
      const std::string key = table_name + "." + std::string(k.str());
      const toml::source_position at = k.source().begin;
      const KeySpec* spec = find_spec(key);
      if (!spec) {
        if (node.is_table()) {
          const std::string what =
              "unknown table; a scene has two levels, [table] and key = value";
          add(node.source().begin,
              "[" + shown_key(key) + "]: " + what + "; " + unknown_key_fix(key));
        } else {
          add(at, shown_key(key) + " = " + written(node) + ": unknown key; " +
                      unknown_key_fix(key));
        }
        continue;
      }
      std::string problem;
      if (auto value = convert(*spec, node, problem)) {
        values_[key] = std::move(*value);
        origins_[key] = ValueOrigin{here(at), true};
      } else {
        add(at, key + " = " + written(node) + ": " + problem);
      }
    }
  }

  void unknown_table(const std::string& name, const toml::source_position& at) {
    const std::vector<std::string> tables = schema_tables();
    std::string fix;
    if (auto best = nearest(name, tables)) {
      fix = "did you mean [" + *best + "]? ";
    } else if (const KeySpec* spec = find_spec(suggest_key(name).value_or(""))) {
      fix = "did you mean " + spec->key + "? ";
    }
    add(at, "[" + name + "]: unknown table; " + fix +
                "the tables are: " + join(tables, ", "));
  }

  std::string written(const toml::node& node) const {
    std::string s = source_.slice(node.source());
    if (!s.empty()) return s;
    std::ostringstream out;
    node.visit([&](auto&& n) { out << n; });
    return SourceText::tidy(out.str());
  }

  std::string here(const toml::source_position& at) const {
    return name_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.column);
  }

  void add(const toml::source_position& at, const std::string& message) {
    problems_.push_back(Problem{static_cast<long>(at.line), static_cast<long>(at.column),
                                here(at) + ": " + message});
  }

  void add_override(const std::string& message) {
    problems_.push_back(Problem{std::numeric_limits<long>::max(), 0, message});
  }

  SourceText source_;
  std::string name_;
  std::vector<Problem> problems_;
};

// The schema defaults as values, parsed once. A default that is not valid for its own
// key is a bug in src/scene/scene_keys.cpp, reported as such.
const std::map<std::string, ConfigValue, std::less<>>& default_values() {
  static const auto values = [] {
    std::map<std::string, ConfigValue, std::less<>> out;
    for (const KeySpec& spec : scene_keys()) {
      std::string problem;
      std::optional<ConfigValue> value;
      try {
        // Trusted text from the source code: parsed in-process, without the guard.
        const toml::table doc =
            toml::parse("v = " + spec.default_toml, std::string_view("schema"));
        if (const toml::node* node = doc.get("v")) value = convert(spec, *node, problem);
      } catch (const toml::parse_error& e) {
        problem = std::string(e.description());
      }
      if (!value) {
        throw Error("internal error in src/scene/scene_keys.cpp: the default of " +
                    spec.key + " (" + spec.default_toml + ") is invalid: " + problem);
      }
      out.emplace(spec.key, std::move(*value));
    }
    return out;
  }();
  return values;
}

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

double default_real(std::string_view key) {
  const auto it = default_values().find(key);
  if (it == default_values().end() || !std::holds_alternative<double>(it->second))
    throw Error("internal error: " + std::string(key) +
                " is not a real key of the schema");
  return std::get<double>(it->second);
}

// ---------------------------------------------------------------------------------------
// Config

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

std::string Config::resolved_toml() const {
  std::string out = "# The resolved scene " + comment_safe(file_.string()) +
                    ": every key, defaults included.\n"
                    "# \"(default)\" marks a key the scene did not set.\n";
  std::string table;
  std::vector<std::pair<std::string, std::string>> lines;  // "key = value", comment
  const auto flush = [&] {
    constexpr size_t kMaxAlign = 40;  // long values do not push every comment right
    size_t width = 0;
    for (const auto& [text, comment] : lines) {
      if (text.size() <= kMaxAlign) width = std::max(width, text.size());
    }
    for (const auto& [text, comment] : lines) {
      out += text;
      if (!comment.empty()) {
        out += std::string(text.size() < width ? width - text.size() : 0, ' ') + "  #" +
               comment;
      }
      out += "\n";
    }
    lines.clear();
  };
  for (const KeySpec& spec : scene_keys()) {
    const auto it = values_.find(spec.key);
    if (it == values_.end()) continue;
    if (table != table_of(spec.key)) {
      flush();
      table = table_of(spec.key);
      out += "\n[" + table + "]\n";
    }
    std::string comment;
    if (!spec.unit.empty()) comment += " [" + spec.unit + "]";
    if (!user_set(spec.key)) comment += " (default)";
    lines.emplace_back(std::string(leaf_of(spec.key)) + " = " + toml_value(it->second),
                       comment);
  }
  flush();
  return out;
}

// ---------------------------------------------------------------------------------------
// Loading

Config load_scene_text(std::string_view text, const std::string& name,
                       std::span<const std::string> overrides) {
  if (text.size() > kMaxSceneBytes) {
    throw ConfigError(name + ": scene file too large (" + std::to_string(text.size()) +
                      " bytes, the limit is " + std::to_string(kMaxSceneBytes >> 20) +
                      " MiB); is this the right file?");
  }
  const toml::table root = parse_toml_guarded(text, name);

  Loader loader(text, name);
  loader.read_file(root);
  for (const std::string& item : overrides) loader.apply_override(item);
  loader.throw_if_failed();

  Config config;
  config.file_ = name;
  config.values_ = std::move(loader.values_);
  config.origins_ = std::move(loader.origins_);
  for (const auto& [key, value] : default_values()) {
    if (config.values_.emplace(key, value).second) {
      config.origins_[key] = ValueOrigin{"default", false};
    }
  }
  return config;
}

Config apply_trusted_overrides(const Config& base,
                               std::span<const std::string> overrides) {
  Loader loader("", base.file().string());
  loader.trusted_ = true;
  for (const std::string& item : overrides) loader.apply_override(item);
  loader.throw_if_failed();
  Config config = base;
  for (auto& [key, value] : loader.values_) {
    config.values_[key] = std::move(value);
    config.origins_[key] = loader.origins_[key];
  }
  return config;
}

Config load_scene(const std::filesystem::path& file,
                  std::span<const std::string> overrides) {
  const std::string name = file.string();
  const auto cannot_read = [&](int err) {
    return ConfigError(name + ": cannot read scene file (" + std::strerror(err) + ")");
  };
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw cannot_read(errno);
  std::string text;
  struct stat st {};
  int err = 0;
  if (::fstat(fd, &st) != 0) {
    err = errno;
  } else if (S_ISDIR(st.st_mode)) {
    ::close(fd);
    throw ConfigError(name +
                      ": is a directory, not a scene file; give the path of a "
                      ".toml file");
  } else {
    char buf[1 << 16];
    for (;;) {
      const ssize_t n = ::read(fd, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) err = errno;
      if (n <= 0) break;
      text.append(buf, static_cast<size_t>(n));
      if (text.size() > kMaxSceneBytes) break;  // load_scene_text says why
    }
  }
  ::close(fd);
  if (err) throw cannot_read(err);
  if (text.size() > kMaxSceneBytes) {  // the read stops past the limit: give the size
    const bool regular = S_ISREG(st.st_mode);
    throw ConfigError(name + ": scene file too large (" +
                      (regular
                           ? std::to_string(st.st_size) + " bytes"
                           : "more than " + std::to_string(kMaxSceneBytes) + " bytes") +
                      ", the limit is " + std::to_string(kMaxSceneBytes >> 20) +
                      " MiB); is this the right file?");
  }
  Config config = load_scene_text(text, name, overrides);
  config.file_ = file;
  return config;
}

// ---------------------------------------------------------------------------------------
// Keys set but not used (KeySpec::used_when)

namespace {

// "erosion.model = \"halt\" or \"balance\""
std::string condition_text(const UsedWhen& c) {
  std::string out = c.key + " = ";
  for (size_t i = 0; i < c.values.size(); ++i) out += (i ? " or " : "") + c.values[i];
  return out;
}

// A key that other keys' use depends on (disk.model, growth.enabled, ...).
bool is_switch(std::string_view key) {
  for (const KeySpec& spec : scene_keys()) {
    for (const UsedWhen& c : spec.used_when) {
      if (c.key == key) return true;
    }
  }
  return false;
}

}  // namespace

std::string empty_scene_warning(const Config& config) {
  // a scene file that sets no key (empty, only comments, or the wrong file): the run
  // would be every default, 1 Myr on 250 cells, without a word
  for (const KeySpec& spec : scene_keys())
    if (config.user_set(spec.key) && config.where(spec.key) != "--set") return "";
  return "panoptic: warning: " + config.file().string() +
         " sets no key: every key not given with --set takes its default "
         "(params/reference.toml); check the file";
}

std::vector<std::string> unused_key_warnings(const Config& config) {
  std::vector<std::string> out;
  for (const KeySpec& spec : scene_keys()) {
    if (spec.used_when.empty() || !config.user_set(spec.key)) continue;
    const auto it = config.values_.find(spec.key);
    if (it == config.values_.end()) continue;
    const std::string value = toml_value(it->second);
    std::vector<std::string> now, wanted;  // the conditions that fail
    for (const UsedWhen& c : spec.used_when) {
      const auto sw = config.values_.find(c.key);
      const std::string v = sw == config.values_.end() ? "" : toml_value(sw->second);
      if (std::find(c.values.begin(), c.values.end(), v) == c.values.end()) {
        now.push_back(c.key + " = " + v);
        wanted.push_back(condition_text(c));
      }
    }
    if (now.empty()) continue;
    // fragmentation.enabled = false with growth off: an explicit "off" turns nothing on
    if (is_switch(spec.key) && value == toml_value(default_values().at(spec.key)))
      continue;
    out.push_back("panoptic: warning: " + spec.key + " = " + value + " (" +
                  config.where(spec.key) + ") is not used: " + join(now, ", ") +
                  "; set " + join(wanted, " and ") + " to use it, or remove the key");
  }
  return out;
}

std::string reference_toml() {
  std::string out =
      "# panoptic scene reference: every scene key, with its default value and its "
      "unit.\n"
      "# Generated by `panoptic reference` from the schema in src/scene/scene_keys.cpp; "
      "do "
      "not\n"
      "# edit by hand (a unit test checks that params/reference.toml equals the "
      "output).\n"
      "# A scene sets only the keys it changes; every other key keeps the default "
      "below.\n"
      "# Comments: [unit] meaning (allowed values); \"read only with\" names the\n"
      "# switches a run needs to read the key (`panoptic check` and `run` warn about a\n"
      "# key set without them).\n";
  std::string table;
  std::vector<std::pair<std::string, std::string>> lines;
  const auto flush = [&] {
    size_t width = 0;
    for (const auto& [text, comment] : lines) width = std::max(width, text.size());
    for (const auto& [text, comment] : lines) {
      out += text + std::string(width - text.size(), ' ') + "   #" + comment + "\n";
    }
    lines.clear();
  };
  for (const KeySpec& spec : scene_keys()) {
    if (table != table_of(spec.key)) {
      flush();
      table = table_of(spec.key);
      out += "\n[" + table + "]\n";
    }
    std::string comment;
    if (!spec.unit.empty()) comment += " [" + spec.unit + "]";
    comment += " " + comment_safe(spec.doc);
    if (!spec.choices.empty()) {
      comment += " (one of: " + join(spec.choices, ", ") + ")";
    } else if (const std::string range = range_text(spec); !range.empty()) {
      comment +=
          spec.type == KeyType::kRealList ? " (each " + range + ")" : " (" + range + ")";
    }
    if (!spec.used_when.empty()) {
      std::vector<std::string> conditions;
      for (const UsedWhen& c : spec.used_when) conditions.push_back(condition_text(c));
      comment += "; read only with " + join(conditions, " and ");
    }
    lines.emplace_back(std::string(leaf_of(spec.key)) + " = " + spec.default_toml,
                       comment);
  }
  flush();
  return out;
}

}  // namespace panoptic
