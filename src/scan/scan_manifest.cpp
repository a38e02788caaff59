// Scan files and their expansion into a manifest (src/scan/scan_manifest.hpp). The scan
// file is untrusted input like a scene: it is parsed through the guarded TOML parser, and
// every error names file:line:col, the key, the value and the fix.
#include "src/scan/scan_manifest.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "src/core/digest.hpp"
#include "src/model/scene_validation.hpp"
#include "src/scene/toml_guard.hpp"
#include "src/scene/toml_literal.hpp"

namespace panoptic {
namespace fs = std::filesystem;
namespace {

const KeySpec* find_key(std::string_view key) {
  for (const KeySpec& spec : scene_keys())
    if (spec.key == key) return &spec;
  return nullptr;
}

// Scan-file errors: "<file>:<line>:<col>: <message>".
class Where {
 public:
  explicit Where(std::string name) : name_(std::move(name)) {}
  [[noreturn]] void fail(const toml::node& node, const std::string& message) const {
    fail(node.source().begin, message);
  }
  [[noreturn]] void fail(const toml::source_position& at,
                         const std::string& message) const {
    throw ConfigError(name_ + ":" + std::to_string(at.line) + ":" +
                      std::to_string(at.column) + ": " + message);
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw ConfigError(name_ + ": " + message);
  }

 private:
  std::string name_;
};

const char* kFormat =
    "see params/README.md, Scans: [scan] scene = \"...\", set = [...], sampling = "
    "\"grid\" or "
    "\"lhs\", samples, seed; [[axis]] key = \"table.key\" with values = [...], or "
    "lin/log = [lo, hi] (and num for grid sampling), zip = \"group\"";

std::optional<double> number(const toml::node& n) {
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  return std::nullopt;
}

// A value of a scan file as the TOML literal of a --set override of a key of `type`.
std::string literal(const toml::node& n, KeyType type, const Where& where,
                    const std::string& key) {
  if (const auto* s = n.as_string()) return toml_string(s->get());
  if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* i = n.as_integer())
    return type == KeyType::kInt ? std::to_string(i->get())
                                 : toml_real(static_cast<double>(i->get()));
  if (const auto* f = n.as_floating_point()) return toml_real(f->get());
  if (const auto* a = n.as_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < a->size(); ++k) {
      const auto x = number(*a->get(k));
      if (!x) where.fail(*a->get(k), "axis " + key + ": a list value holds a non-number");
      out += (k ? ", " : "") + toml_real(*x);
    }
    return out + "]";
  }
  where.fail(n, "axis " + key + ": a value must be a number, string, boolean or list");
}

// Unknown scene key: the scene loader's own message, with its suggestion.
[[noreturn]] void unknown_key(const Where& where, const toml::node& node,
                              const std::string& key) {
  std::string why = "unknown scene key";
  try {
    const std::string item = key + "=0";
    load_scene_text("", "scan", std::span<const std::string>(&item, 1));
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    const auto at = msg.find("unknown key; ");
    if (at != std::string::npos) why += "; " + msg.substr(at + 13);
  }
  where.fail(node, "axis key = " + toml_string(key) + ": " + why);
}

struct Rng {
  // mt19937_64 is specified bit for bit by the standard; the distributions are not, so
  // uniforms and permutations are made here: the manifest of a seed is the same with
  // every compiler and library.
  std::mt19937_64 gen;
  double uniform() { return static_cast<double>(gen() >> 11) * 0x1.0p-53; }  // [0, 1)
  std::vector<long> permutation(long n) {
    std::vector<long> p(static_cast<std::size_t>(n));
    for (long k = 0; k < n; ++k) p[k] = k;
    for (long k = n - 1; k > 0; --k)  // Fisher-Yates
      std::swap(p[k], p[gen() % static_cast<std::uint64_t>(k + 1)]);
    return p;
  }
};

// The value at fraction u in [0, 1] of an axis's range (or list).
std::string value_at(const ScanAxis& a, double u) {
  if (a.kind == ScanAxis::Kind::kList) {
    const auto n = static_cast<long>(a.list.size());
    return a.list[std::min(static_cast<long>(u * n), n - 1)];
  }
  double x =
      a.kind == ScanAxis::Kind::kLin
          ? a.lo + u * (a.hi - a.lo)
          : std::pow(10.0, std::log10(a.lo) + u * (std::log10(a.hi) - std::log10(a.lo)));
  return a.type == KeyType::kInt ? std::to_string(std::llround(x)) : toml_real(x);
}

std::vector<std::string> axis_values(const ScanAxis& a) {
  if (a.kind == ScanAxis::Kind::kList) return a.list;
  const std::vector<double> xs = a.kind == ScanAxis::Kind::kLin
                                     ? lin_points(a.lo, a.hi, a.num)
                                     : log_points(a.lo, a.hi, a.num);
  std::vector<std::string> out;
  for (double x : xs)
    out.push_back(a.type == KeyType::kInt ? std::to_string(std::llround(x))
                                          : toml_real(x));
  return out;
}

ScanAxis read_axis(const toml::table& t, const toml::node& self, bool lhs,
                   const Where& where) {
  ScanAxis a;
  for (auto&& [k, node] : t) {
    const std::string leaf(k.str());
    if (leaf != "key" && leaf != "values" && leaf != "lin" && leaf != "log" &&
        leaf != "num" && leaf != "zip")
      where.fail(k.source().begin,
                 "[[axis]] " + leaf +
                     ": unknown key; an axis has key, values, lin, log, num, zip");
  }
  const auto* key = t.get("key");
  if (!key || !key->as_string())
    where.fail(self,
               "[[axis]] needs key = \"table.key\" (a scene key, e.g. "
               "\"star.mass_msun\")");
  a.key = key->as_string()->get();
  const KeySpec* spec = find_key(a.key);
  if (!spec) unknown_key(where, *key, a.key);
  if (a.key == "output.file")
    where.fail(*key,
               "axis key = \"output.file\": every run writes its own file in "
               "DIR/runs/; scan another key");
  a.type = spec->type;
  const int n_kinds =
      (t.get("values") ? 1 : 0) + (t.get("lin") ? 1 : 0) + (t.get("log") ? 1 : 0);
  if (n_kinds != 1)
    where.fail(self, "axis " + a.key +
                         ": give exactly one of values = [...], lin = [lo, hi], log = "
                         "[lo, hi]");
  if (const auto* v = t.get("values")) {
    const auto* arr = v->as_array();
    if (!arr || arr->empty())
      where.fail(*v, "axis " + a.key +
                         ": values must be a non-empty list, e.g. values = " + "[" +
                         spec->default_toml + "]");
    for (std::size_t k = 0; k < arr->size(); ++k)
      a.list.push_back(literal(*arr->get(k), a.type, where, a.key));
    if (t.get("num"))
      where.fail(*t.get("num"),
                 "axis " + a.key + ": num goes with lin or log, not values");
  } else {
    const bool log = t.get("log") != nullptr;
    const toml::node& r = *t.get(log ? "log" : "lin");
    a.kind = log ? ScanAxis::Kind::kLog : ScanAxis::Kind::kLin;
    const std::string what = std::string(log ? "log" : "lin");
    const auto* arr = r.as_array();
    if (a.type != KeyType::kReal && a.type != KeyType::kInt)
      where.fail(r,
                 "axis " + a.key + ": " + what +
                     " ranges need a numeric key; list the values with values = [...]");
    std::optional<double> lo, hi;
    if (arr && arr->size() == 2) lo = number(*arr->get(0)), hi = number(*arr->get(1));
    if (!lo || !hi || !std::isfinite(*lo) || !std::isfinite(*hi))
      where.fail(r,
                 "axis " + a.key + ": " + what + " must be [lo, hi], two finite numbers");
    if (log && !(*lo > 0.0 && *hi > 0.0))
      where.fail(r, "axis " + a.key + ": log = [" + toml_real(*lo) + ", " +
                        toml_real(*hi) +
                        "]: both ends must be > 0; use lin for ranges through 0");
    a.lo = *lo;
    a.hi = *hi;
    if (const auto* num = t.get("num")) {
      if (lhs)
        where.fail(*num, "axis " + a.key +
                             ": num does not apply to sampling = \"lhs\" (the number of "
                             "runs is [scan] samples); remove it");
      const auto* i = num->as_integer();
      if (!i || i->get() < 2 || i->get() > 1000000)
        where.fail(*num, "axis " + a.key +
                             ": num must be an integer >= 2 (a range includes both "
                             "ends) and <= 1000000, e.g. num = 5; for one value give "
                             "values = [x]");
      a.num = static_cast<long>(i->get());
      // points that coincide (an integer key rounds them, or lo = hi) would run the
      // same scene more than once
      const std::vector<std::string> xs = axis_values(a);
      std::string shown;
      bool repeated = false;
      for (std::size_t k = 0; k < xs.size(); ++k) {
        repeated = repeated || (k > 0 && xs[k] == xs[k - 1]);
        if (k < 8) shown += (k ? ", " : "") + xs[k];
      }
      if (repeated)
        where.fail(*num, "axis " + a.key + ": " + what + " = [" + toml_real(a.lo) + ", " +
                             toml_real(a.hi) + "] with num = " + std::to_string(a.num) +
                             " gives repeated values (" + shown +
                             (xs.size() > 8 ? ", ..." : "") + ")" +
                             (a.type == KeyType::kInt ? ", rounded to integers" : "") +
                             ": the same scene would run more than once; lower num or "
                             "list the values with values = [...]");
    } else if (!lhs) {
      where.fail(r, "axis " + a.key + ": a " + what +
                        " range needs num = <number of points> with sampling = \"grid\"");
    }
  }
  if (const auto* z = t.get("zip")) {
    if (!z->as_string() || z->as_string()->get().empty())
      where.fail(*z, "axis " + a.key + ": zip must be a non-empty group name");
    if (lhs)
      where.fail(*z, "axis " + a.key + ": zip does not apply to sampling = \"lhs\"");
    a.zip = z->as_string()->get();
  }
  return a;
}

std::string run_name(long id, long n) {
  const int width = n > 100000 ? static_cast<int>(std::to_string(n - 1).size()) : 5;
  char buf[32];
  std::snprintf(buf, sizeof buf, "run_%0*ld", width, id);
  return buf;
}

std::string hex64(std::uint64_t x) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(x));
  return buf;
}

std::string read_file(const fs::path& file, const std::string& what) {
  std::ifstream in(file, std::ios::binary);
  if (!in || fs::is_directory(file))
    throw ConfigError(file.string() + ": cannot read " + what);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::vector<double> lin_points(double lo, double hi, long num) {
  std::vector<double> x(static_cast<std::size_t>(num));
  for (long k = 0; k < num; ++k)
    x[k] = num == 1 ? lo : lo + (hi - lo) * static_cast<double>(k) / (num - 1);
  if (num > 1) x.back() = hi;  // both ends exact
  return x;
}

std::vector<double> log_points(double lo, double hi, long num) {
  // Equal steps in log10, so a range over decades hits the powers of ten exactly
  // (pow(10, integer) is exact in glibc); both ends are the values given.
  std::vector<double> x(static_cast<std::size_t>(num));
  const double l0 = std::log10(lo), l1 = std::log10(hi);
  for (long k = 0; k < num; ++k)
    x[k] = num == 1 ? lo
                    : std::pow(10.0, l0 + (l1 - l0) * static_cast<double>(k) / (num - 1));
  x.front() = lo;
  if (num > 1) x.back() = hi;
  return x;
}

std::vector<std::string> ManifestEntry::overrides() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : values) out.push_back(k + "=" + v);
  return out;
}

std::vector<std::string> Manifest::overrides(std::size_t i) const {
  std::vector<std::string> out = fixed;
  for (const std::string& s : entries.at(i).overrides()) out.push_back(s);
  return out;
}

std::string Manifest::to_toml(const std::string& header) const {
  std::string out = header;
  const auto list = [](const std::vector<std::string>& xs) {
    std::string s = "[";
    for (std::size_t k = 0; k < xs.size(); ++k) s += (k ? ", " : "") + toml_string(xs[k]);
    return s + "]";
  };
  std::vector<std::string> keys;
  for (const ScanAxis& a : axes) keys.push_back(a.key);
  out += "scene = " + toml_string(scene.string()) + "\n";
  out += "scene_fnv1a64 = " + toml_string(scene_hash) + "\n";
  out += "set = " + list(fixed) + "\n";
  out += "sampling = " + toml_string(sampling) + "\n";
  if (sampling == "lhs")
    out += "samples = " + std::to_string(samples) + "\nseed = " + std::to_string(seed) +
           "\n";
  out += "axes = " + list(keys) + "\n";
  out += "n_runs = " + std::to_string(entries.size()) + "\n";
  for (const ManifestEntry& e : entries)
    out += "\n[[run]]\nid = " + std::to_string(e.id) + "\nname = " + toml_string(e.name) +
           "\nset = " + list(e.overrides()) + "\n";
  return out;
}

std::string manifest_body(std::string_view text) {
  std::string out;
  std::size_t a = 0;
  while (a < text.size()) {
    std::size_t b = text.find('\n', a);
    if (b == std::string_view::npos) b = text.size();
    const std::string_view line = text.substr(a, b - a);
    if (line.empty() || line[0] != '#') out.append(line).append("\n");
    a = b + 1;
  }
  return out;
}

Manifest expand_scan_text(std::string_view text, const std::string& name,
                          const fs::path& base_dir) {
  const Where where(name);
  const toml::table root = parse_toml_guarded(text, name);
  for (auto&& [k, node] : root) {
    const std::string key(k.str());
    if (key != "scan" && key != "axis")
      where.fail(k.source().begin, key +
                                       ": unknown; a scan file holds [scan] and [[axis]] "
                                       "tables; " +
                                       kFormat);
  }
  const toml::table* scan = root["scan"].as_table();
  if (!scan) where.fail("no [scan] table; " + std::string(kFormat));
  Manifest m;
  for (auto&& [k, node] : *scan) {
    const std::string leaf(k.str());
    if (leaf != "scene" && leaf != "set" && leaf != "sampling" && leaf != "samples" &&
        leaf != "seed")
      where.fail(k.source().begin, "scan." + leaf +
                                       ": unknown key; [scan] has scene, set, sampling, "
                                       "samples, seed");
  }
  // base scene, relative to the scan file
  const auto* scene = scan->get("scene");
  if (!scene || !scene->as_string() || scene->as_string()->get().empty())
    where.fail("[scan] needs scene = \"path/to/scene.toml\" (relative to the scan file)");
  fs::path scene_path = scene->as_string()->get();
  if (scene_path.is_relative()) scene_path = base_dir / scene_path;
  std::error_code ec;
  const fs::path canon = fs::weakly_canonical(scene_path, ec);
  m.scene = ec ? fs::absolute(scene_path) : canon;
  try {
    // the scene and the scenes it builds on (its `base` chain), as a run reads them
    std::string bytes = read_file(m.scene, "the base scene");
    const std::vector<fs::path> files = scene_files(m.scene);
    for (std::size_t k = 1; k < files.size(); ++k)
      bytes += read_file(files[k], "a base of the scan's scene");
    m.scene_hash = hex64(fnv1a64(std::as_bytes(std::span(bytes.data(), bytes.size()))));
  } catch (const ConfigError& e) {
    where.fail(*scene, "scan.scene = " + toml_string(scene->as_string()->get()) + ": " +
                           e.what() + "; the path is relative to the scan file");
  }
  if (const auto* set = scan->get("set")) {
    const auto* arr = set->as_array();
    if (!arr) where.fail(*set, "scan.set must be a list of \"table.key=value\" strings");
    for (std::size_t k = 0; k < arr->size(); ++k) {
      const auto* s = arr->get(k)->as_string();
      if (!s || s->get().find('=') == std::string::npos)
        where.fail(*arr->get(k),
                   "scan.set: every element must be a \"table.key=value\" "
                   "string, e.g. \"grid.n_cells=64\"");
      m.fixed.push_back(s->get());
    }
  }
  if (const auto* s = scan->get("sampling")) {
    if (!s->as_string() ||
        (s->as_string()->get() != "grid" && s->as_string()->get() != "lhs"))
      where.fail(*s,
                 "scan.sampling must be \"grid\" (product of the axes) or \"lhs\" "
                 "(Latin hypercube)");
    m.sampling = s->as_string()->get();
  }
  const bool lhs = m.sampling == "lhs";
  for (const char* k : {"samples", "seed"}) {
    const auto* n = scan->get(k);
    if (!n) {
      if (lhs)
        where.fail(std::string("sampling = \"lhs\" needs scan.") + k +
                   " (an integer: samples = number of runs, seed = random seed)");
      continue;
    }
    if (!lhs)
      where.fail(*n, std::string("scan.") + k + " applies to sampling = \"lhs\" only");
    const auto* i = n->as_integer();
    const long lo = std::string(k) == "samples" ? 1 : 0;
    if (!i || i->get() < lo || (std::string(k) == "samples" && i->get() > 10000000))
      where.fail(
          *n, std::string("scan.") + k + " must be an integer >= " + std::to_string(lo));
    if (std::string(k) == "samples")
      m.samples = static_cast<long>(i->get());
    else
      m.seed = static_cast<std::uint64_t>(i->get());
  }
  // axes
  const toml::node* axes = root.get("axis");
  if (axes) {
    const auto* arr = axes->as_array();
    if (!arr || !arr->is_array_of_tables())
      where.fail(*axes, "axis must be written as [[axis]] tables");
    for (std::size_t k = 0; k < arr->size(); ++k) {
      ScanAxis a = read_axis(*arr->get(k)->as_table(), *arr->get(k), lhs, where);
      for (const ScanAxis& b : m.axes)
        if (b.key == a.key)
          where.fail(*arr->get(k), "axis " + a.key + " appears twice; merge the two");
      for (const std::string& f : m.fixed)
        if (trim_blanks(f.substr(0, f.find('='))) == a.key)  // as --set reads the key
          where.fail(*arr->get(k),
                     "axis " + a.key + " is also fixed in scan.set; remove one of them");
      m.axes.push_back(std::move(a));
    }
  }
  if (m.axes.empty()) where.fail("no [[axis]]: a scan needs at least one axis");

  if (lhs) {
    Rng rng{std::mt19937_64(m.seed)};
    const long n = m.samples;
    std::vector<std::vector<std::string>> cols;
    for (const ScanAxis& a : m.axes) {
      const std::vector<long> perm = rng.permutation(n);
      std::vector<std::string> col;
      for (long i = 0; i < n; ++i)
        col.push_back(value_at(a, (static_cast<double>(perm[i]) + rng.uniform()) / n));
      cols.push_back(std::move(col));
    }
    for (long i = 0; i < n; ++i) {
      ManifestEntry e{i, run_name(i, n), {}};
      for (std::size_t j = 0; j < m.axes.size(); ++j)
        e.values.emplace_back(m.axes[j].key, cols[j][i]);
      m.entries.push_back(std::move(e));
    }
    return m;
  }
  // grid: one dimension per zip group (an axis without zip is its own group), in order of
  // first appearance; the last dimension varies fastest
  std::vector<std::vector<std::size_t>> dims;
  std::map<std::string, std::size_t> group_dim;
  for (std::size_t j = 0; j < m.axes.size(); ++j) {
    const std::string& z = m.axes[j].zip;
    if (!z.empty() && group_dim.count(z)) {
      dims[group_dim[z]].push_back(j);
      continue;
    }
    if (!z.empty()) group_dim[z] = dims.size();
    dims.push_back({j});
  }
  std::vector<std::vector<std::string>> values(m.axes.size());
  std::vector<std::size_t> len;
  for (const auto& d : dims) {
    for (std::size_t j : d) values[j] = axis_values(m.axes[j]);
    for (std::size_t j : d)
      if (values[j].size() != values[d[0]].size())
        where.fail("zip = \"" + m.axes[j].zip + "\": axes " + m.axes[d[0]].key + " (" +
                   std::to_string(values[d[0]].size()) + " values) and " + m.axes[j].key +
                   " (" + std::to_string(values[j].size()) +
                   " values) advance together and must have the same number of values");
    len.push_back(values[d[0]].size());
    // a value (or, for zipped axes, a tuple of values) listed twice would run the same
    // scene twice, as repeated range points would
    for (std::size_t k = 0; k < len.back(); ++k)
      for (std::size_t k2 = 0; k2 < k; ++k2) {
        bool same = true;
        for (std::size_t j : d) same = same && values[j][k] == values[j][k2];
        if (!same) continue;
        std::string shown;
        for (std::size_t j : d)
          shown += (shown.empty() ? "" : ", ") + m.axes[j].key + " = " + values[j][k];
        where.fail("axis values " + shown + " appear twice (entries " +
                   std::to_string(k2 + 1) + " and " + std::to_string(k + 1) +
                   "): the same scene would run twice; remove one");
      }
  }
  long total = 1;
  for (std::size_t l : len) {
    total *= static_cast<long>(l);
    if (total > 10000000)
      where.fail("the product of the axes has more than 1e7 runs; reduce it");
  }
  std::vector<std::size_t> idx(dims.size(), 0);
  for (long i = 0; i < total; ++i) {
    ManifestEntry e{i, run_name(i, total), {}};
    for (std::size_t j = 0; j < m.axes.size(); ++j)
      e.values.emplace_back(m.axes[j].key, "");
    for (std::size_t d = 0; d < dims.size(); ++d)
      for (std::size_t j : dims[d]) e.values[j].second = values[j][idx[d]];
    m.entries.push_back(std::move(e));
    for (std::size_t d = dims.size(); d-- > 0;) {  // odometer, last dimension fastest
      if (++idx[d] < len[d]) break;
      idx[d] = 0;
    }
  }
  return m;
}

Manifest load_scan(const fs::path& file) {
  const std::string text = read_file(file, "scan file");
  return expand_scan_text(text, file.string(), file.parent_path());
}

std::vector<ResolvedRun> validate_manifest(const Manifest& m) {
  // The base scene and the fixed overrides (user text: parsed through the guard) once;
  // then each run's axis values, which expand_scan_text wrote as canonical TOML literals,
  // through the same schema, and the cross-key checks of the whole scene.
  std::optional<Config> base;
  try {
    base = load_scene(m.scene, m.fixed);
  } catch (const ConfigError& e) {
    throw ConfigError(
        std::string(e.what()) +
        "\n(in the base scene of the scan or its scan.set; the scan refuses "
        "to start)");
  }
  std::vector<ResolvedRun> out;
  out.reserve(m.entries.size());
  for (const ManifestEntry& e : m.entries) {
    const std::vector<std::string> ov = e.overrides();
    try {
      const Config cfg = apply_trusted_overrides(*base, ov);
      validate_scene(cfg);
      out.push_back({cfg.resolved_toml(), cfg.real("output.t_end_yr")});
    } catch (const ConfigError& ex) {
      std::string what = ex.what();
      if (what.rfind("--set: ", 0) == 0) what = what.substr(7);  // not a --set here
      std::string vals;
      for (const std::string& s : ov) vals += (vals.empty() ? "" : ", ") + s;
      throw ConfigError(e.name + " (" + vals + "): " + what +
                        "\n(the scan refuses to start: fix this scan axis)");
    }
  }
  return out;
}

}  // namespace panoptic
