#include "src/io/run_output.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string_view>
#include <variant>

#include "src/core/error.hpp"
#include "src/io/durable_file.hpp"
#include "src/solver/solver_stats.hpp"

namespace panoptic {
namespace {

// 128 random bits as hex: tells this run's file from any other file of the same name,
// so a restart never continues a file with a checkpoint of another run.
std::string new_run_id() {
  std::random_device rd;
  std::string id;
  for (int i = 0; i < 4; ++i) {
    char buf[9];
    std::snprintf(buf, sizeof buf, "%08x", static_cast<unsigned>(rd()));
    id += buf;
  }
  return id;
}

// A restart continues a fresh copy of its output, not the file as the stopped run left
// it (src/run/README.md, Restart): a writer killed while HDF5 flushed the file can leave
// a chunk index inconsistent, and a run that appends to it can lose rows it writes itself
// (regression.test_restart_killed under load: a restart that completed had rows 51-55,
// the first it wrote, unallocated). h5::copy_file rebuilds every dataset with a new
// index; the copy is written beside the file, at `tmp`, and fsynced; the restart sets it
// up and RunOutput::start_appending renames it over the file, so that a restart killed
// before leaves the file as it was.
// HDF5 1.10 can crash on a file damaged badly enough (H5Ocopy did, with SIGSEGV, before
// copy_file copied dataset by dataset), so the copy runs in a child process: a crash
// there costs the rebuild, not the restart.
// Returns "" or, when the copy fails, why: the file is then continued in place.
std::string rebuild(const std::filesystem::path& path, const std::filesystem::path& tmp) {
  std::error_code ec;
  std::filesystem::remove(tmp, ec);  // left by a restart killed while copying
  std::fflush(nullptr);
  const pid_t child = ::fork();
  if (child == 0) {  // the copy, fsynced; the exit code says whether it is whole
    int code = 0;
    try {
      h5::copy_file(path.string(), tmp.string());
      fsync_path(tmp, false);
    } catch (...) {
      code = 1;
    }
    ::_exit(code);
  }
  int status = 0;
  pid_t waited = -1;
  if (child > 0) {
    // a stop signal (SIGTERM during the set-up) must not end the wait while the child
    // still writes the copy: it was taken for "no process", the file was continued in
    // place and the copy left behind (exit 4)
    do {
      waited = ::waitpid(child, &status, 0);
    } while (waited < 0 && errno == EINTR);
  }
  if (child < 0 || waited != child)
    return "could not rebuild it (no process for the copy); continued in place";
  std::string why;
  if (WIFSIGNALED(status))
    why = std::string("HDF5 crashed copying it (") + ::strsignal(WTERMSIG(status)) + ")";
  else if (WEXITSTATUS(status) != 0)
    why = "HDF5 could not copy it";
  if (why.empty()) return "";
  std::filesystem::remove(tmp, ec);
  return "could not rebuild it as a fresh copy (" + why +
         ": the file is damaged); continued in place";
}

}  // namespace

RunOutput::RunOutput(const std::filesystem::path& path, bool overwrite,
                     const RunMetadata& meta)
    : path_(path), staging_(path.string() + ".setup.tmp"), overwrite_(overwrite) {
  h5::quiet_errors();
  refuse_to_replace(path, overwrite);
  std::error_code ec;
  if (path.has_parent_path()) {
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec)
      throw IoError(path.parent_path().string() + ": cannot create directory (" +
                    ec.message() + ")");
  }
  // Set up under a name of its own and renamed to `path` by start_appending: a run
  // killed while HDF5 writes the set-up (not yet in SWMR mode) leaves no unreadable
  // stub at `path`, and the file that --overwrite replaces stays until then.
  std::filesystem::remove(staging_, ec);  // left by a run killed during its set-up
  try {
    file_ = h5::create_file(staging_.string());
    run_id_ = new_run_id();
    for (const OutputAttribute& a : root_attributes(meta, run_id_)) write_attribute(a);
    ensure_group("snapshots");
    h5::Handle g = h5::open_group(file_.get(), "snapshots");
    const OutputEntry time = snapshot_time();
    h5::create_stack(g.get(), "time", 0, time.units, time.description);
    flush();
  } catch (const IoError& e) {
    const int err = errno;  // of the failed write, if it was one
    const std::string hint = write_failure_hint(path, err);
    discard_staging();  // the stub holds no snapshot; the file at `path` was not touched
    if (std::string_view(e.what()).starts_with(path.string())) throw;
    throw IoError(path.string() + ": " + e.what() + hint);
  }
}

RunOutput::RunOutput(const std::filesystem::path& path, ContinueRun keep) : path_(path) {
  h5::quiet_errors();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw IoError(path.string() +
                  ": the output file of the checkpoint does not exist; pass the run's "
                  "output file with -o");
  const std::filesystem::path copy = path.string() + ".restart.tmp";
  rebuild_note_ = rebuild(path, copy);
  if (rebuild_note_.empty()) {  // the copy is set up, and put in place when started
    staging_ = copy;
    overwrite_ = true;
  }
  try {
    file_ = h5::open_file(staging_.empty() ? path.string() : staging_.string(), true);
  } catch (const IoError&) {
    discard_staging();
    throw IoError(path.string() +
                  ": cannot open the output file read-write (damaged, not HDF5, or "
                  "open in another program?)");
  }
  if (h5::has_attr(file_.get(), "run_id"))
    run_id_ = h5::get_attr_string(file_.get(), "run_id");
  try {
    h5::Handle g = h5::open_group(file_.get(), "snapshots");
    const auto have = static_cast<std::size_t>(h5::stack_rows(g.get(), "time"));
    if (have < keep.n_snapshots)
      throw IoError(path.string() + ": holds " + std::to_string(have) +
                    " snapshots, but the checkpoint was taken after " +
                    std::to_string(keep.n_snapshots) +
                    ": this is not the output of that checkpoint's run; pass the right "
                    "file with -o");
    for (const std::string& name : h5::dataset_names(g.get())) {
      if (h5::stack_rows(g.get(), name) < keep.n_snapshots)
        throw IoError(path.string() + ": /snapshots/" + name +
                      " has fewer rows than the " + std::to_string(keep.n_snapshots) +
                      " snapshots of the checkpoint");
      // Time first: a reader trusts only rows that have a time.
      if (name == "time") h5::truncate_stack(g.get(), name, keep.n_snapshots);
    }
    for (const std::string& name : h5::dataset_names(g.get())) {
      if (name == "time") continue;
      h5::truncate_stack(g.get(), name, keep.n_snapshots);
      h5::Handle ds(H5Dopen2(g.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
      h5::Handle space(H5Dget_space(ds.get()), H5Sclose);
      std::array<hsize_t, 2> dims{0, 0};
      const int rank = H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
      fields_[name] = rank == 2 ? dims[1] : 0;
    }
    n_snapshots_ = keep.n_snapshots;
    restart_digests_ = std::move(keep.digests);
    lost_ = keep_rows("snapshots", keep.n_snapshots);
    flush();
  } catch (const IoError& e) {
    discard_staging();  // the copy is not needed: the output stays as it was
    throw_if_damaged(e);
    throw;
  }
}

void RunOutput::throw_if_damaged(const IoError& e) const {
  // HDF5's own failures on a damaged file (ours name the file already)
  if (!std::string_view(e.what()).starts_with("HDF5:")) return;
  throw IoError(path_.string() +
                ": the output file is damaged and cannot be continued (" + e.what() +
                (rebuild_note_.empty() ? "" : "; " + rebuild_note_) +
                "); start the run again (--overwrite, or -o another file)");
}

std::string RunOutput::keep_rows(const std::string& group, hsize_t rows) {
  return mark_lost_rows(file_.get(), group, rows, restart_digests_, digests_);
}

std::string mark_lost_rows(hid_t file, const std::string& group, hsize_t rows,
                           const RowDigests& expected, RowDigests& kept) {
  h5::Handle g = h5::open_group(file, group);
  std::string lost;
  for (const std::string& name : h5::dataset_names(g.get())) {
    const std::string key = group + "/" + name;
    std::vector<char> bad(rows, 0);
    for (const auto& [first, last] : h5::unallocated_rows(g.get(), name, rows))
      std::fill(bad.begin() + static_cast<long>(first),
                bad.begin() + static_cast<long>(last), 1);
    const auto it = expected.find(key);
    const hsize_t width = h5::stack_width(g.get(), name);
    const std::vector<double> data = h5::read_rows(g.get(), name, 0, rows);
    std::vector<std::uint64_t> digests(rows);
    for (hsize_t i = 0; i < rows; ++i) {
      digests[i] = row_digest(std::span(data).subspan(i * width, width));
      if (it != expected.end() && i < it->second.size() && digests[i] != it->second[i])
        bad[i] = 1;
    }
    const std::uint64_t nan_digest =
        row_digest(std::vector<double>(width, std::numeric_limits<double>::quiet_NaN()));
    for (hsize_t first = 0; first < rows;) {
      if (!bad[first]) {
        ++first;
        continue;
      }
      hsize_t last = first;
      while (last < rows && bad[last]) ++last;
      h5::fill_rows_nan(g.get(), name, first, last);
      std::fill(digests.begin() + static_cast<long>(first),
                digests.begin() + static_cast<long>(last), nan_digest);
      lost += (lost.empty() ? "/" : "; /") + key +
              (last == first + 1
                   ? " row " + std::to_string(first)
                   : " rows " + std::to_string(first) + "-" + std::to_string(last - 1));
      first = last;
    }
    kept[key] = std::move(digests);
  }
  return lost;
}

std::vector<double> RunOutput::times_yr() const {
  h5::Handle g = h5::open_group(file_.get(), "snapshots");
  return h5::read_doubles(g.get(), "time");
}

void RunOutput::set_root_attr(const std::string& name, const std::string& value) {
  leave_swmr();
  h5::set_attr(file_.get(), name, value);
  flush();
}

std::string RunOutput::root_attr(const std::string& name) const {
  if (!h5::has_attr(file_.get(), name)) return "";
  return h5::get_attr_string(file_.get(), name);
}

RunOutput::~RunOutput() {
  if (!file_.valid()) return;
  if (!staging_.empty()) {  // set up but never started: a stub, not an output
    discard_staging();
    return;
  }
  std::error_code ec;
  try {
    close();
  } catch (const IoError& e) {  // the output keeps every row; its closing writes are lost
    std::fprintf(stderr, "panoptic: warning: %s\n", e.what());
    if (!finishing_.empty()) std::filesystem::remove(finishing_, ec);
  }
}

void RunOutput::discard_staging() {
  file_.reset();
  std::error_code ec;
  if (!staging_.empty()) std::filesystem::remove(staging_, ec);
  staging_.clear();
}

void RunOutput::ensure_group(const std::string& group) {
  leave_swmr();  // every caller creates an object or an attribute
  if (!h5::exists(file_.get(), group)) h5::create_group(file_.get(), group);
}

void RunOutput::write_static(const std::string& group, const std::string& name,
                             std::span<const double> data, const std::string& units,
                             const std::string& description) {
  ensure_group(group);
  h5::Handle g = h5::open_group(file_.get(), group);
  // replaced when it exists: a restarted run rewrites its /summary
  if (h5::exists(g.get(), name)) H5Ldelete(g.get(), name.c_str(), H5P_DEFAULT);
  h5::write_vector(g.get(), name, data, units, description);
}

void RunOutput::write_attribute(const OutputAttribute& a) {
  h5::Handle g;
  if (a.group.empty())
    leave_swmr();  // as ensure_group: an attribute is not created in SWMR mode
  else {
    ensure_group(a.group);
    g = h5::open_group(file_.get(), a.group);
  }
  const hid_t object = a.group.empty() ? file_.get() : g.get();
  std::visit([&](const auto& v) { h5::set_attr(object, a.name, v); }, a.value);
}

void RunOutput::add_series(const std::string& group, const std::string& name,
                           std::size_t width, const std::string& units,
                           const std::string& description) {
  ensure_group(group);
  h5::Handle g = h5::open_group(file_.get(), group);
  if (!h5::exists(g.get(), name))
    h5::create_stack(g.get(), name, width, units, description);
}

void RunOutput::append_series(const std::string& group, const std::string& name,
                              std::span<const double> row) {
  h5::Handle g = h5::open_group(file_.get(), group);
  h5::append_row(g.get(), name, row);
  digests_[group + "/" + name].push_back(row_digest(row));
}

void RunOutput::add_field(const std::string& name, std::size_t width,
                          const std::string& units, const std::string& description,
                          bool compressed) {
  leave_swmr();
  h5::Handle g = h5::open_group(file_.get(), "snapshots");
  if (n_snapshots_ > 0 && fields_.contains(name)) return;  // continued: in the file
  h5::create_stack(g.get(), name, width, units, description, compressed);
  fields_[name] = width;
  if (n_snapshots_ == 0) return;
  // A continued output without this field. If the checkpoint's run wrote it (the
  // checkpoint holds its row digests), the restart's copy could not read it (its header
  // torn by a kill): lost. If not, the checkpoint's run did not write it at all (an
  // earlier panoptic, without this field): new, not lost. Either way its kept rows are
  // NaN, and said (lost_rows, new_fields).
  const std::vector<double> nan(width == 0 ? 1 : width,
                                std::numeric_limits<double>::quiet_NaN());
  const std::string key = "snapshots/" + name;
  const bool was_written = restart_digests_.contains(key);
  auto& digests = digests_[key];
  for (std::size_t i = 0; i < n_snapshots_; ++i) {
    h5::append_row(g.get(), name, nan);
    digests.push_back(row_digest(nan));
  }
  const std::string rows = " rows 0-" + std::to_string(n_snapshots_ - 1);
  if (was_written)
    lost_ += (lost_.empty() ? "/" : "; /") + key + rows +
             " (the dataset was unreadable: recreated)";
  else
    new_fields_ += (new_fields_.empty() ? "/" : "; /") + key + rows;
}

void RunOutput::write_snapshot(double t_yr,
                               const std::map<std::string, std::vector<double>>& fields) {
  h5::Handle g = h5::open_group(file_.get(), "snapshots");
  // Every field first, time last: a reader trusts only rows that have a time.
  for (const auto& [name, width] : fields_) {
    const auto it = fields.find(name);
    if (it == fields.end() || it->second.size() != (width == 0 ? 1 : width))
      throw IoError("snapshot field '" + name + "' missing or of the wrong length");
    h5::append_row(g.get(), name, it->second);
    digests_["snapshots/" + name].push_back(row_digest(it->second));
  }
  const double t[1] = {t_yr};
  h5::append_row(g.get(), "time", t);
  digests_["snapshots/time"].push_back(row_digest(t));
  ++n_snapshots_;
  flush();
}

void RunOutput::write_solver(const SolverStats& s, double wall_s,
                             const std::string& status) {
  for (const OutputAttribute& a : solver_attributes(s, wall_s, status))
    write_attribute(a);
  flush();
}

std::vector<OutputAttribute> RunOutput::root_attributes(const RunMetadata& meta,
                                                        const std::string& run_id) {
  return {{"", "run_id", "", "random id of this output, which its checkpoints record",
           run_id},
          {"", "scene", "", "scene name (the scene file's stem)", meta.scene},
          {"", "config_toml", "", "the resolved scene, defaults included (TOML)",
           meta.config_toml},
          {"", "git_sha", "",
           "commit of the build (-dirty if it had uncommitted changes)", meta.git_sha},
          {"", "version", "", "panoptic version", meta.version}};
}

OutputEntry RunOutput::snapshot_time() {
  return {"snapshots/time", "yr", "simulated time of each snapshot"};
}

std::vector<OutputAttribute> RunOutput::solver_attributes(const SolverStats& s,
                                                          double wall_s,
                                                          const std::string& status) {
  std::vector<OutputAttribute> attributes;
  for (const SolverCounter& c : kSolverCounters)
    attributes.push_back({"solver", c.name, "", c.description, s.*c.value});
  attributes.push_back({"solver", "wall_s", "s", "wall-clock time of the run", wall_s});
  attributes.push_back(
      {"solver", "status", "",
       "how the run ended: completed, stopped by ... (with the restart command), failed",
       status});
  return attributes;
}

std::string RunOutput::start_appending() {
  flush();
  swmr_ = h5::start_swmr_write(file_.get());
  if (!staging_.empty()) {  // set up aside (a new output, a restart's copy): in place now
    flush();
    refuse_to_replace(path_, overwrite_);  // nothing has appeared there since
    rename_or_throw(staging_, path_);
    fsync_path(path_.has_parent_path() ? path_.parent_path() : ".", true);
    staging_.clear();
  }
  if (swmr_) return "";
  return "HDF5 cannot write " + path_.string() +
         " in SWMR mode (a file in the HDF5 1.8 format, from an older panoptic, that the "
         "restart could not rebuild, or a file system on which HDF5 cannot lock it): a "
         "kill in the middle of a flush can leave it unreadable";
}

// HDF5 1.10 does not support creating or deleting objects and attributes in SWMR mode
// (a run's closing /solver attributes made H5Fflush fail: "slist not empty"). The file
// is closed, which ends the mode and leaves it whole, and the last writes go to a copy
// of it that replaces it once closed (close): a plain read-write file is marked open
// by HDF5 until closed, and a kill would leave it unreadable (regression.
// test_kill_during_flush: 38 of 303 kill points, in a run's closing writes) and its
// metadata half written; killed now, the output is the closed file, every row in it.
void RunOutput::leave_swmr() {
  if (!swmr_) return;
  flush();
  h5::close_file(file_, path_.string());
  swmr_ = false;
  finishing_ = path_.string() + ".finish.tmp";
  std::error_code ec;
  std::filesystem::remove(finishing_, ec);  // left by a run killed in its closing writes
  // A copy of the bytes: the file is closed and whole (h5::copy_file, which rebuilds
  // every chunk index, took 47 s for a run of 3 000 snapshots of 4 cells).
  std::string why;
  if (!std::filesystem::copy_file(path_, finishing_, ec) || ec) {
    why = ec.message();
  } else {
    try {
      file_ = h5::open_file(finishing_.string(), true);
    } catch (const IoError& e) {
      why = e.what();
    }
  }
  if (!why.empty()) {
    const int err = ec ? ec.value() : errno;  // of the failed write, if it was one
    std::filesystem::remove(finishing_, ec);
    throw IoError(path_.string() + ": the copy that its closing writes go to (" +
                  finishing_.string() + ") could not be written (" + why + ")" +
                  write_failure_hint(finishing_, err) + "; " + path_.string() +
                  " holds every snapshot, without /summary and /solver");
  }
}

void RunOutput::close() {
  if (!file_.valid()) return;
  flush();
  h5::close_file(file_, finishing_.empty() ? path_.string() : finishing_.string());
  if (finishing_.empty()) return;
  fsync_path(finishing_, false);
  rename_or_throw(finishing_, path_);
  finishing_.clear();
}

void RunOutput::flush() {
  if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0)
    throw IoError(path_.string() + ": flushing the HDF5 file failed" +
                  write_failure_hint(path_, errno));
}

}  // namespace panoptic
