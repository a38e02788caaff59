// The scene loader: TOML (parsed through src/scene/toml_guard.hpp, so arbitrary bytes
// give a ConfigError) validated against the schema of src/scene/scene_keys.cpp, defaults
// filled in, --set overrides applied last. Every message has the form
//   "<where>: <key> = <value as written>: <what is wrong>; <fix>"
// because the user has to find the line, see what was read and know what to write.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <sstream>

#include "src/scene/config.hpp"
#include "src/scene/key_defaults.hpp"
#include "src/scene/key_suggestions.hpp"
#include "src/scene/key_text.hpp"
#include "src/scene/key_use.hpp"
#include "src/scene/schema_lookup.hpp"
#include "src/scene/source_text.hpp"
#include "src/scene/toml_guard.hpp"
#include "src/scene/toml_literal.hpp"
#include "src/scene/value_conversion.hpp"

namespace fs = std::filesystem;

namespace panoptic {
using namespace scene_detail;
namespace {

// A scene is a page of text; anything this large is the wrong file, and refusing it
// early keeps a mistyped path from eating memory.
constexpr size_t kMaxSceneBytes = 16u << 20;
// Errors reported at once; the rest are counted.
constexpr size_t kMaxErrors = 20;
// The root key naming the scene a scene builds on.
constexpr std::string_view kBaseKey = "base";

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

  //! The next file of a scene's chain of bases (the deepest base first): its keys
  //! override those read before, and messages name it.
  void begin_file(std::string_view text, std::string name) {
    source_ = SourceText(text);
    name_ = std::move(name);
  }

  void read_file(const toml::table& root) {
    for (auto&& [k, node] : root) {
      const std::string name(k.str());
      if (name == kBaseKey) continue;  // read by read_with_bases
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
    origins_[spec->key] = ValueOrigin{where, true, "", false};
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

  void read_table(const std::string& table_name, const toml::table& table) {
    for (auto&& [k, node] : table) {
      const std::string key = table_name + "." + std::string(k.str());
      const toml::source_position at = k.source().begin;
      const KeySpec* spec = find_spec(key);
      if (!spec && k.str() == kBaseKey) {
        add(at, key + " = " + written(node) + ": unknown key; " + std::string(kBaseKey) +
                    " = \"other.toml\" goes at the top of the scene, before the first "
                    "[table]");
        continue;
      }
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
        const std::string_view comment = source_.rest_of_line(node.source().end);
        origins_[key] = ValueOrigin{here(at), true, name_,
                                    comment.find(kNotReadMark) != std::string_view::npos};
      } else {
        add(at, key + " = " + written(node) + ": " + problem);
      }
    }
  }

  void unknown_table(const std::string& name, const toml::source_position& at) {
    add(at, "[" + name + "]: unknown table; " + unknown_table_fix(name));
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

// The bytes of a scene file; ConfigError "<file>: ..." when it cannot be read, is a
// directory or is larger than kMaxSceneBytes.
std::string read_scene_bytes(const fs::path& file) {
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
      if (text.size() > kMaxSceneBytes) break;  // checked below
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
  return text;
}

void check_size(std::string_view text, const std::string& name) {
  if (text.size() > kMaxSceneBytes) {
    throw ConfigError(name + ": scene file too large (" + std::to_string(text.size()) +
                      " bytes, the limit is " + std::to_string(kMaxSceneBytes >> 20) +
                      " MiB); is this the right file?");
  }
}

// A file as the cycle check compares it: the same file under two spellings is one.
std::string identity(const fs::path& file) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(file, ec), ec);
  return ec ? fs::absolute(file).lexically_normal().string() : p.string();
}

// The scenes read so far, from the scene given down to the base being read.
struct Chain {
  std::vector<std::string> ids;  // identity() of each
  std::vector<fs::path> files;   // as the loader opened them
};

// Reads the scene `text` (file `name`) into `loader` (when given): its base scene first,
// recursively, so that the keys of each file override those of its bases. `chain`
// gets every file read. ConfigError for a base that is no string, cannot be read, or
// closes a cycle, naming the file and line of the base key, the path tried and the fix.
void read_with_bases(Loader* loader, std::string_view text, const std::string& name,
                     Chain& chain) {
  check_size(text, name);
  const toml::table root = parse_toml_guarded(text, name);
  chain.ids.push_back(identity(name));
  chain.files.emplace_back(name);
  if (const toml::node* base = root.get(kBaseKey)) {
    const toml::source_position at = base->source().begin;
    const std::string where = name + ":" + std::to_string(at.line) + ":" +
                              std::to_string(at.column) +
                              ": base = " + SourceText(text).slice(base->source());
    const auto* path_text = base->as_string();
    if (!path_text || path_text->get().empty())
      throw ConfigError(where +
                        ": must be the path of the scene this one builds on, as a "
                        "string relative to this file's folder, e.g. base = "
                        "\"fiducial.toml\"");
    fs::path path = path_text->get();
    if (path.is_relative()) path = fs::path(name).parent_path() / path;
    path = path.lexically_normal();
    const std::string id = identity(path);
    if (std::find(chain.ids.begin(), chain.ids.end(), id) != chain.ids.end()) {
      std::string cycle;
      const auto first = std::find(chain.ids.begin(), chain.ids.end(), id);
      for (auto it = first; it != chain.ids.end(); ++it)
        cycle +=
            chain.files[static_cast<size_t>(it - chain.ids.begin())].string() + " -> ";
      throw ConfigError(where + ": the scenes build on each other in a cycle, " + cycle +
                        path.string() +
                        "; a scene cannot be its own base: remove the base line of one "
                        "of them");
    }
    std::string base_text;
    try {
      base_text = read_scene_bytes(path);
    } catch (const ConfigError& e) {
      throw ConfigError(where + ": cannot read the base scene: " + e.what() +
                        "; the path is relative to the folder of " + name +
                        ": correct it, or remove the base line");
    }
    read_with_bases(loader, base_text, path.string(), chain);
    if (loader) loader->throw_if_failed();  // a base's own problems, at once
  }
  if (loader) {
    loader->begin_file(text, name);
    loader->read_file(root);
  }
}

}  // namespace

Config load_scene_text(std::string_view text, const std::string& name,
                       std::span<const std::string> overrides) {
  Loader loader(text, name);
  Chain chain;
  read_with_bases(&loader, text, name, chain);
  for (const std::string& item : overrides) loader.apply_override(item);
  loader.throw_if_failed();

  Config config;
  config.file_ = name;
  config.values_ = std::move(loader.values_);
  config.origins_ = std::move(loader.origins_);
  for (const auto& [key, value] : default_values()) {
    if (config.values_.emplace(key, value).second) {
      config.origins_[key] = ValueOrigin{"default", false, "", false};
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

Config load_scene(const fs::path& file, std::span<const std::string> overrides) {
  Config config = load_scene_text(read_scene_bytes(file), file.string(), overrides);
  config.file_ = file;
  return config;
}

std::vector<fs::path> scene_files(const fs::path& file) {
  Chain chain;
  read_with_bases(nullptr, read_scene_bytes(file), file.string(), chain);
  return chain.files;
}

}  // namespace panoptic
