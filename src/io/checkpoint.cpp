#include "src/io/checkpoint.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "build_info.hpp"  // PANOPTIC_GIT_SHA (generated at build time)
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/durable_file.hpp"
#include "src/io/h5.hpp"
#include "src/scene/toml_literal.hpp"

namespace fs = std::filesystem;

namespace panoptic {
namespace {

// Written into every checkpoint and checked on load: a file of another format (a later
// version of this one, or an output file passed by mistake) is refused by name.
constexpr const char* kFormat = "panoptic checkpoint 1";

// FNV-1a over a canonical serialisation of the fields: lengths before strings and
// vectors, so that moving bytes between two fields changes the hash too.
class Hasher {
 public:
  void bytes(std::span<const std::byte> b) { hash_ = fnv1a64(b, hash_); }
  void real(double x) { bytes(std::as_bytes(std::span<const double>(&x, 1))); }
  void integer(long x) {
    const std::int64_t v = x;
    bytes(std::as_bytes(std::span<const std::int64_t>(&v, 1)));
  }
  void text(std::string_view s) {
    integer(static_cast<long>(s.size()));
    bytes(std::as_bytes(std::span<const char>(s.data(), s.size())));
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

std::string hex(std::uint64_t x) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(x));
  return buf;
}

void set_stats(hid_t group, const SolverStats& s) {
  h5::set_attr(group, "nst", s.nst);
  h5::set_attr(group, "nfe", s.nfe);
  h5::set_attr(group, "nje", s.nje);
  h5::set_attr(group, "nsetups", s.nsetups);
  h5::set_attr(group, "netf", s.netf);
  h5::set_attr(group, "nni", s.nni);
  h5::set_attr(group, "nncf", s.nncf);
  h5::set_attr(group, "nreinit", s.nreinit);
  h5::set_attr(group, "h_last", s.h_last);
}

SolverStats get_stats(hid_t group) {
  SolverStats s;
  s.nst = h5::get_attr_long(group, "nst");
  s.nfe = h5::get_attr_long(group, "nfe");
  s.nje = h5::get_attr_long(group, "nje");
  s.nsetups = h5::get_attr_long(group, "nsetups");
  s.netf = h5::get_attr_long(group, "netf");
  s.nni = h5::get_attr_long(group, "nni");
  s.nncf = h5::get_attr_long(group, "nncf");
  s.nreinit = h5::get_attr_long(group, "nreinit");
  s.h_last = h5::get_attr_double(group, "h_last");
  return s;
}

void flush(hid_t file, const fs::path& path) {
  if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
    throw IoError(path.string() + ": writing the checkpoint failed" +
                  write_failure_hint(path, errno));
}

// Everything but the completeness flag, then the flag, each followed by a flush: a file
// cut anywhere before the end has no flag.
void write_file(const fs::path& path, const Checkpoint& chk) {
  h5::Handle f = h5::create_file(path.string());
  h5::set_attr(f.get(), "format", std::string(kFormat));
  h5::write_vector(f.get(), "y", chk.y, "cgs",
                   "raw CVODE state at t, in the order of layout_signature");
  h5::set_attr(f.get(), "t", chk.t);
  h5::set_attr(f.get(), "snapshot_index", chk.snapshot_index);
  h5::set_attr(f.get(), "n_cells", chk.n_cells);
  h5::set_attr(f.get(), "layout_signature", chk.layout_signature);
  h5::set_attr(f.get(), "config_toml", chk.config_toml);
  h5::set_attr(f.get(), "wall_s", chk.wall_s);
  h5::set_attr(f.get(), "output_file", chk.output_file);
  h5::set_attr(f.get(), "run_id", chk.run_id);
  h5::set_attr(f.get(), "git_sha", chk.git_sha);
  h5::set_attr(f.get(), "version", chk.version);
  {
    h5::Handle g = h5::create_group(f.get(), "solver");
    set_stats(g.get(), chk.stats);
  }
  if (!chk.row_digests.empty()) {
    // one dataset per output dataset, "snapshots/St" named "snapshots:St"
    h5::Handle g = h5::create_group(f.get(), "row_digests");
    for (const auto& [key, digests] : chk.row_digests) {
      std::string name = key;
      std::replace(name.begin(), name.end(), '/', ':');
      h5::write_u64s(g.get(), name, digests);
    }
  }
  h5::set_attr(f.get(), "checksum", "fnv1a64:" + hex(checkpoint_checksum(chk)));
  flush(f.get(), path);
  h5::set_attr(f.get(), "complete", 1L);
  flush(f.get(), path);
  h5::close_file(f, path.string());
}

Checkpoint read_fields(hid_t f) {
  Checkpoint chk;
  chk.y = h5::read_doubles(f, "y");
  chk.t = h5::get_attr_double(f, "t");
  chk.snapshot_index = h5::get_attr_long(f, "snapshot_index");
  chk.n_cells = h5::get_attr_long(f, "n_cells");
  chk.layout_signature = h5::get_attr_string(f, "layout_signature");
  chk.config_toml = h5::get_attr_string(f, "config_toml");
  chk.wall_s = h5::get_attr_double(f, "wall_s");
  chk.output_file = h5::get_attr_string(f, "output_file");
  chk.run_id = h5::get_attr_string(f, "run_id");
  chk.git_sha = h5::get_attr_string(f, "git_sha");
  chk.version = h5::get_attr_string(f, "version");
  h5::Handle g = h5::open_group(f, "solver");
  chk.stats = get_stats(g.get());
  if (h5::exists(f, "row_digests")) {
    h5::Handle d = h5::open_group(f, "row_digests");
    for (const std::string& name : h5::dataset_names(d.get())) {
      std::string key = name;
      std::replace(key.begin(), key.end(), ':', '/');
      chk.row_digests[key] = h5::read_u64s(d.get(), name);
    }
  }
  return chk;
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

}  // namespace

std::uint64_t checkpoint_checksum(const Checkpoint& chk) {
  Hasher h;
  h.real(chk.t);
  h.integer(static_cast<long>(chk.y.size()));
  h.bytes(std::as_bytes(std::span<const double>(chk.y)));
  h.integer(chk.n_cells);
  h.integer(chk.snapshot_index);
  h.text(chk.layout_signature);
  h.text(chk.config_toml);
  const SolverStats& s = chk.stats;
  for (const long x : {s.nst, s.nfe, s.nje, s.nsetups, s.netf, s.nni, s.nncf, s.nreinit})
    h.integer(x);
  h.real(s.h_last);
  h.real(chk.wall_s);
  h.text(chk.output_file);
  h.text(chk.run_id);
  // (nothing when there are none: checkpoints written before they were kept verify)
  for (const auto& [key, digests] : chk.row_digests) {
    h.text(key);
    h.integer(static_cast<long>(digests.size()));
    h.bytes(std::as_bytes(std::span<const std::uint64_t>(digests)));
  }
  return h.value();
}

fs::path checkpoint_path(const fs::path& output) {
  fs::path p = output;
  return p.replace_extension(".chk.h5");
}

fs::path previous_checkpoint_path(const fs::path& checkpoint) {
  const std::string s = checkpoint.string();
  if (ends_with(s, ".prev.h5")) return checkpoint;
  if (ends_with(s, ".h5")) return s.substr(0, s.size() - 3) + ".prev.h5";
  return s + ".prev.h5";
}

void write_checkpoint(const fs::path& path, const Checkpoint& chk) {
  h5::quiet_errors();
  const fs::path tmp = path.string() + ".tmp";
  const fs::path prev = previous_checkpoint_path(path);
  const fs::path prev_tmp = prev.string() + ".tmp";
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  try {
    write_file(tmp, chk);
    fsync_path(tmp, false);
    read_checkpoint(tmp);  // whole and verified, or it does not replace the last one
    // The current checkpoint becomes the fallback only if it is whole: promoting a
    // damaged one would throw away the good fallback we have.
    bool keep = false;
    if (fs::exists(path, ec)) {
      try {
        read_checkpoint(path);
        keep = true;
      } catch (const IoError&) {
      }
    }
    if (keep) {
      // A hard link renamed over .prev: both names exist at every moment. Where links
      // are not supported, a plain rename leaves a moment without .chk.h5, and a
      // restart then falls back to .prev by itself.
      fs::remove(prev_tmp, ec);
      if (::link(path.c_str(), prev_tmp.c_str()) == 0) {
        rename_or_throw(prev_tmp, prev);
      } else {
        rename_or_throw(path, prev);
      }
    }
    rename_or_throw(tmp, path);
    fsync_path(dir, true);
  } catch (const IoError& e) {
    fs::remove(tmp, ec);
    fs::remove(prev_tmp, ec);
    throw IoError(path.string() + ": cannot write the checkpoint: " + e.what());
  }
}

Checkpoint read_checkpoint(const fs::path& path) {
  h5::quiet_errors();
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError(name + ": checkpoint not found");
  // The wrong file given to --restart (a directory, the scene, the run's output) is bad
  // input, exit 2, with the file to give instead; it was called a truncated or damaged
  // checkpoint, with the advice to start the run again without --restart.
  const std::string give =
      "; --restart takes the checkpoint written next to the run's output, "
      "<output>.chk.h5";
  if (fs::is_directory(path, ec))
    throw ConfigError(name + ": is a directory, not a checkpoint" + give);
  h5::Handle f;
  try {
    f = h5::open_file(name, false);
  } catch (const IoError&) {
    if (!has_hdf5_signature(path) && !ends_with(name, ".chk.h5") &&
        !ends_with(name, ".chk.prev.h5"))
      throw ConfigError(name + ": not an HDF5 file, so not a checkpoint" + give);
    throw IoError(name +
                  ": not a readable HDF5 file: the checkpoint is truncated or "
                  "damaged");
  }
  if (!h5::has_attr(f.get(), "format") && h5::exists(f.get(), "snapshots")) {
    const fs::path chk = checkpoint_path(path);
    throw ConfigError(name + ": the output of a run, not its checkpoint; restart from " +
                      chk.string() +
                      (fs::exists(chk, ec) ? "" : " (not there: the run wrote none)"));
  }
  Checkpoint chk;
  std::string stored;
  try {
    if (!h5::has_attr(f.get(), "format") ||
        h5::get_attr_string(f.get(), "format") != kFormat)
      throw IoError(name + ": not a panoptic checkpoint (no attribute format = \"" +
                    kFormat + "\"); give the .chk.h5 file written next to the output");
    if (!h5::has_attr(f.get(), "complete") || h5::get_attr_long(f.get(), "complete") != 1)
      throw IoError(name +
                    ": incomplete checkpoint: writing it was interrupted (no "
                    "completeness flag)");
    chk = read_fields(f.get());
    stored = h5::get_attr_string(f.get(), "checksum");
  } catch (const IoError& e) {
    if (std::string_view(e.what()).starts_with(name)) throw;
    throw IoError(name + ": damaged checkpoint (" + e.what() + ")");
  }
  const std::string computed = "fnv1a64:" + hex(checkpoint_checksum(chk));
  if (stored != computed)
    throw IoError(name + ": checksum mismatch (stored " + stored + ", computed " +
                  computed + "): the checkpoint is corrupt");
  return chk;
}

bool is_checkpoint_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  if (fs::file_size(path, ec) == 0 && !ec) return true;  // nothing in it to lose
  if (!has_hdf5_signature(path)) return false;
  h5::quiet_errors();
  try {
    const h5::Handle f = h5::open_file(path.string(), false);
    // any version of the format ("panoptic checkpoint N"), so that a later version
    // still replaces the checkpoints of an earlier one
    return h5::has_attr(f.get(), "format") &&
           h5::get_attr_string(f.get(), "format").starts_with("panoptic checkpoint");
  } catch (const IoError&) {
    // an HDF5 file at a checkpoint path that HDF5 cannot open: a damaged checkpoint
    // (truncated, torn by a crash of the disk), which a restart refuses too
    return true;
  }
}

RestartPoint load_restart_point(const fs::path& path) {
  try {
    return {read_checkpoint(path), path, ""};
  } catch (const IoError& first) {
    const fs::path prev = previous_checkpoint_path(path);
    std::error_code ec;
    if (prev == path || !fs::exists(prev, ec))
      throw IoError(std::string(first.what()) + "; there is no previous checkpoint " +
                    prev.string() +
                    " to fall back on: start the run again without --restart");
    try {
      return {read_checkpoint(prev), prev, first.what()};
    } catch (const IoError& second) {
      throw IoError(std::string(first.what()) +
                    "\n  and the previous checkpoint: " + second.what() +
                    "\n  neither can be used: start the run again without --restart");
    }
  }
}

bool may_change_on_restart(std::string_view key) {
  // Listed one by one (not solver.* or output.*): a key added later must be judged
  // before a restart may change it, so the safe answer for an unknown key is no.
  static const std::vector<std::string_view> kKeys = {
      "output.t_end_yr",    "output.t_first_yr",
      "output.n_snapshots", "output.times_yr",
      "output.file",        "solver.rtol",
      "solver.atol_sigma",  "solver.max_steps",
      "solver.max_dt_yr",   "solver.reinit_at_snapshots",
      "solver.newton_coef", "solver.steps_per_jacobian"};
  if (key.starts_with("checkpoint.") || key.starts_with("meta.") ||
      key.starts_with("observe."))  // read by `panoptic observe` only
    return true;
  return std::find(kKeys.begin(), kKeys.end(), key) != kKeys.end();
}

std::vector<std::string> changed_keys(const Config& before, const Config& now) {
  std::vector<std::string> out;
  for (const KeySpec& spec : scene_keys()) {
    const auto a = before.values_.find(spec.key);
    const auto b = now.values_.find(spec.key);
    const bool in_a = a != before.values_.end(), in_b = b != now.values_.end();
    if (in_a != in_b || (in_a && a->second != b->second)) out.push_back(spec.key);
  }
  return out;
}

std::vector<std::string> check_compatible(const Checkpoint& chk, const fs::path& chk_path,
                                          const Config& cfg, const StateLayout& layout) {
  const std::string layout_signature = layout.signature();
  const std::string chk_name = chk_path.string();
  Config before;
  try {
    before = load_scene_text(chk.config_toml, chk_name + " (its stored scene)");
  } catch (const ConfigError& e) {
    throw ConfigError(chk_name +
                      ": the scene stored in the checkpoint does not load in this "
                      "version of panoptic (" PANOPTIC_VERSION ", " PANOPTIC_GIT_SHA
                      "):\n" +
                      e.what() + "\nrestart with the version that wrote it, panoptic " +
                      chk.version + " (" + chk.git_sha + ")");
  }
  std::string differing;
  std::string example;
  std::vector<std::string> allowed;
  for (const std::string& key : changed_keys(before, cfg)) {
    if (may_change_on_restart(key)) {
      const auto text_of = [&](const Config& c) {
        const auto it = c.values_.find(key);
        return it == c.values_.end() ? std::string("unset") : toml_value(it->second);
      };
      allowed.push_back(key + " = " + text_of(cfg) + " (was " + text_of(before) + ")");
      continue;
    }
    const std::string was = toml_value(before.values_.at(key));
    differing += "\n  " + key + " = " + toml_value(cfg.values_.at(key)) + " (" +
                 cfg.where(key) + "), the checkpoint has " + was;
    if (example.empty()) example = " (e.g. --set " + key + "=" + was + ")";
  }
  if (!differing.empty())
    throw ConfigError(
        cfg.file().string() + ": cannot restart from " + chk_name +
        ": the scene differs from the checkpoint's in keys that define the state being "
        "continued:" +
        differing +
        "\nA restart may change only the output times (output.t_end_yr, t_first_yr, "
        "n_snapshots, times_yr), output.file, the solver.* settings, checkpoint.*, "
        "observe.* and meta.*. "
        "Set these keys back to the checkpoint's values" +
        example + ", or start a new run without --restart.");
  if (chk.layout_signature != layout_signature)
    throw ConfigError(cfg.file().string() + ": cannot restart from " + chk_name +
                      ": the state layout differs (checkpoint: " + chk.layout_signature +
                      "; this scene: " + layout_signature +
                      "): the program that wrote the checkpoint registers other "
                      "variables; restart with panoptic " +
                      chk.version + " (" + chk.git_sha +
                      "), or start a new run without --restart");
  if (static_cast<long>(chk.y.size()) != layout.size() || chk.n_cells != layout.n_cells())
    throw IoError(chk_name + ": the state holds " + std::to_string(chk.y.size()) +
                  " values for " + std::to_string(chk.n_cells) +
                  " cells, but its layout needs " + std::to_string(layout.size()) +
                  "; the checkpoint is damaged: use " +
                  previous_checkpoint_path(chk_path).string());
  return allowed;
}

RunOutput continue_output(const RestartPoint& restart, const fs::path& output,
                          const Config& cfg, const std::vector<std::string>& changed) {
  const Checkpoint& chk = restart.chk;
  const std::string chk_name = restart.path.string();
  fs::path path = output;
  std::error_code ec;
  if (path.empty()) {
    // The output is written next to its checkpoints: prefer the file there, so that a
    // run directory copied or moved as a whole continues its own output; the recorded
    // path serves a checkpoint moved alone.
    const fs::path sibling =
        restart.path.parent_path() / fs::path(chk.output_file).filename();
    path = fs::exists(sibling, ec) ? sibling : fs::path(chk.output_file);
    if (!fs::exists(path, ec))
      throw IoError(chk_name + ": the run's output file " + chk.output_file +
                    " does not exist" +
                    (fs::weakly_canonical(sibling, ec) ==
                             fs::weakly_canonical(fs::path(chk.output_file), ec)
                         ? std::string()
                         : " (nor " + sibling.string() + ")") +
                    "; pass it with -o, or start a new run without --restart");
  } else if (!fs::exists(path, ec)) {
    // was "cannot read the run's output file ...: it is damaged"
    throw ConfigError("-o " + path.string() +
                      ": no such file; with --restart, -o names the existing output to "
                      "continue (the checkpoint's run wrote " +
                      chk.output_file + "); leave -o out to continue that one");
  }
  const auto n_keep = static_cast<std::size_t>(chk.snapshot_index) + 1;
  // Read-only first: a wrong file must be refused before a row of it is cut.
  {
    h5::quiet_errors();
    h5::Handle f;
    std::vector<double> t_yr;
    std::string run_id;
    try {
      f = h5::open_file(path.string(), false);
      if (h5::has_attr(f.get(), "run_id"))
        run_id = h5::get_attr_string(f.get(), "run_id");
      h5::Handle g = h5::open_group(f.get(), "snapshots");
      t_yr = h5::read_doubles(g.get(), "time");
    } catch (const IoError& e) {
      throw IoError(path.string() + ": cannot read the run's output file (" + e.what() +
                    "): it is damaged (truncated or overwritten) or not a panoptic "
                    "output, and cannot be continued; restore it, pass the run's output "
                    "with -o, or start the run again without --restart");
    }
    if (run_id != chk.run_id)
      throw IoError(path.string() + ": not the output of the run of checkpoint " +
                    chk_name + " (run_id " + run_id + ", the checkpoint's " + chk.run_id +
                    "); pass that run's output file with -o");
    if (t_yr.size() < n_keep || t_yr[n_keep - 1] != chk.t / units::kYr)
      throw IoError(path.string() + ": does not hold snapshot " +
                    std::to_string(chk.snapshot_index) + " at t = " +
                    std::to_string(chk.t / units::kYr) + " yr of checkpoint " + chk_name +
                    " (it has " + std::to_string(t_yr.size()) +
                    " snapshots); pass that run's output file with -o");
    if (t_yr.size() > n_keep)  // said aloud: a copied or older checkpoint cuts a run
      std::fprintf(
          stderr,
          "panoptic: warning: %s: its %zu snapshot%s after the checkpoint's (t = "
          "%.6g yr, snapshot %ld) up to t = %.6g yr %s cut and computed again\n",
          path.c_str(), t_yr.size() - n_keep, t_yr.size() - n_keep == 1 ? "" : "s",
          chk.t / units::kYr, chk.snapshot_index, t_yr.back(),
          t_yr.size() - n_keep == 1 ? "is" : "are");
  }
  RunOutput out(path, ContinueRun{n_keep, chk.row_digests});
  char line[160];
  std::snprintf(line, sizeof line, "t = %.17g yr (snapshot %ld): restarted from ",
                chk.t / units::kYr, chk.snapshot_index);
  std::string note =
      line + chk_name + " by panoptic " PANOPTIC_VERSION " (" PANOPTIC_GIT_SHA ")";
  if (!changed.empty()) {
    note += "; changed:";
    for (std::size_t k = 0; k < changed.size(); ++k)
      note += (k ? ", " : " ") + changed[k];
  }
  const std::string before = out.root_attr("restarts");
  out.set_root_attr("restarts", before.empty() ? note : before + "\n" + note);
  out.set_root_attr("config_toml", cfg.resolved_toml());
  return out;
}

std::vector<double> times_after_restart(std::span<const double> output_times,
                                        double t_restart) {
  std::vector<double> t{t_restart};
  for (const double x : output_times)
    if (x > t_restart) t.push_back(x);
  if (t.size() == 1) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "output.t_end_yr = %.6g: the checkpoint is at t = %.6g yr, at or "
                  "after the end of this run; raise output.t_end_yr (e.g. --set "
                  "output.t_end_yr=%.3g) to continue the run",
                  output_times.empty() ? 0.0 : output_times.back() / units::kYr,
                  t_restart / units::kYr, 10.0 * t_restart / units::kYr);
    throw ConfigError(buf);
  }
  return t;
}

double parse_duration(std::string_view text) {
  const auto bad = [&] {
    return ConfigError("--max-wall " + std::string(text) +
                       ": not a duration; write e.g. 90m, 2h, 3600s or 1h30m (units d, "
                       "h, m, s, each once and from the largest down; a plain number is "
                       "seconds), greater than 0");
  };
  double total = 0.0;
  std::size_t i = 0;
  bool any = false, bare = false;
  double previous_unit = 1e300;  // "90m30m" or "30m1h": a typo, not a sum to guess at
  while (i < text.size()) {
    double x = 0.0;
    const auto r = std::from_chars(text.data() + i, text.data() + text.size(), x);
    if (r.ec != std::errc() || !std::isfinite(x) || x < 0.0) throw bad();
    i = static_cast<std::size_t>(r.ptr - text.data());
    double unit = 1.0;
    if (i == text.size()) {
      if (any) throw bad();  // "1h30": is 30 minutes or seconds? say it
      bare = true;
    } else {
      switch (text[i]) {
        case 'd':
          unit = 86400.0;
          break;
        case 'h':
          unit = 3600.0;
          break;
        case 'm':
          unit = 60.0;
          break;
        case 's':
          unit = 1.0;
          break;
        default:
          throw bad();
      }
      ++i;
      if (!(unit < previous_unit)) throw bad();
      previous_unit = unit;
    }
    total += x * unit;
    any = true;
    if (bare) break;
  }
  if (!any || !(total > 0.0)) throw bad();
  return total;
}

bool CheckpointSchedule::due(long snapshot_index, double wall_now) const {
  if (every_snapshots_ > 0 && snapshot_index > 0 &&
      snapshot_index % every_snapshots_ == 0)
    return true;
  return every_wall_s_ > 0.0 && wall_now - last_wall_ >= every_wall_s_;
}

}  // namespace panoptic
