#include "src/io/checkpoint.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "src/core/error.hpp"
#include "src/io/durable_file.hpp"
#include "src/io/h5.hpp"

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
  for (const SolverCounter& c : kSolverCounters) h5::set_attr(group, c.name, s.*c.value);
  h5::set_attr(group, "h_last", s.h_last);
}

SolverStats get_stats(hid_t group) {
  SolverStats s;
  for (const SolverCounter& c : kSolverCounters)
    s.*c.value = h5::get_attr_long(group, c.name);
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
  for (const SolverCounter& c : kSolverCounters) h.integer(s.*c.value);
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

}  // namespace panoptic
