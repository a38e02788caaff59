// The summary table of a scan (src/scan/scan_summary.hpp), rebuilt from the run files.
#include "src/scan/scan_summary.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "src/core/error.hpp"
#include "src/io/durable_file.hpp"
#include "src/io/h5.hpp"
#include "src/scan/scan_exec.hpp"

namespace panoptic {
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

//! Removes a temporary file when the summary is left by an exception (a failed write:
//! disk full, quota), so that none is left behind; `armed = false` once it is renamed.
struct RemoveOnExit {
  const fs::path& tmp;
  bool armed = true;
  ~RemoveOnExit() {
    std::error_code ec;
    if (armed) fs::remove(tmp, ec);
  }
};

struct Row {
  std::string status, error, worker;
  std::optional<long> exit_code;  //!< none without a record (the run never ended)
  double wall_s = kNaN, steps = kNaN;
  std::map<std::string, double> outcome;
};

// A fixed-length string dataset (h5py reads it as bytes).
void write_strings(hid_t parent, const std::string& name,
                   const std::vector<std::string>& xs, const std::string& description) {
  std::size_t width = 1;
  for (const std::string& s : xs) width = std::max(width, s.size());
  std::string buf(width * xs.size(), '\0');
  for (std::size_t k = 0; k < xs.size(); ++k) buf.replace(k * width, xs[k].size(), xs[k]);
  h5::Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), width);
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  const hsize_t dims[1] = {xs.size()};
  h5::Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
  h5::Handle ds(H5Dcreate2(parent, name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                           H5P_DEFAULT, H5P_DEFAULT),
                H5Dclose);
  if (!ds.valid() || (!xs.empty() && H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL,
                                              H5P_DEFAULT, buf.data()) < 0))
    throw IoError("HDF5: writing the string column " + name + " failed");
  h5::set_attr(ds.get(), "description", description);
}

bool numeric_key(const std::string& key) {
  for (const KeySpec& s : scene_keys())
    if (s.key == key)
      return s.type == KeyType::kReal || s.type == KeyType::kInt ||
             s.type == KeyType::kBool;
  return false;
}

double literal_number(const std::string& v) {
  if (v == "true") return 1.0;
  if (v == "false") return 0.0;
  return std::strtod(v.c_str(), nullptr);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_number(double x) {
  if (std::isnan(x)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string unquote(const std::string& v) {
  return v.size() >= 2 && v.front() == '"' ? v.substr(1, v.size() - 2) : v;
}

}  // namespace

fs::path run_file(const fs::path& dir, const std::string& name, const std::string& ext) {
  return dir / "runs" / (name + "." + ext);
}

ScanCounts write_scan_summary(const fs::path& dir, const Manifest& m,
                              const std::vector<ResolvedRun>& resolved) {
  ScanCounts counts;
  std::vector<Row> rows(m.entries.size());
  std::set<std::string> outcome_names;
  std::map<std::string, std::string> outcome_units;  // from the first run that has each
  for (std::size_t i = 0; i < m.entries.size(); ++i) {
    const std::string& name = m.entries[i].name;
    Row& row = rows[i];
    const RunInspection in = inspect_run(run_file(dir, name, "h5"),
                                         resolved[i].config_toml, resolved[i].t_end_yr);
    const std::optional<RunRecord> rec = read_record(run_file(dir, name, "status"));
    // wall time: the run's own (/solver wall_s, summed over the segments of a run
    // continued from its checkpoints), else its last process's
    row.wall_s = in.wall_s >= 0 ? in.wall_s : rec ? rec->wall_s : kNaN;
    if (rec) {
      row.worker = rec->worker;
      row.exit_code = rec->exit_code;
    }
    if (in.steps >= 0) row.steps = static_cast<double>(in.steps);
    if (in.complete) {
      row.status = "completed";
      row.outcome = in.summary;
      for (const auto& [k, v] : in.summary) outcome_names.insert(k);
      for (const auto& [k, u] : in.units) outcome_units.emplace(k, u);
      ++counts.completed;
      continue;
    }
    if (rec && rec->outcome == "failed") {
      row.status = "failed";
      row.error = rec->error;
      ++counts.failed;
    } else if (rec && rec->outcome == "completed") {
      row.status = "failed";
      row.error = "exited 0 but its output is not complete: " + in.why;
      ++counts.failed;
    } else {
      row.status =
          rec ? rec->outcome : (in.why == "no output file" ? "not run" : "incomplete");
      row.error = in.why;
      ++counts.other;
    }
  }

  // --- CSV, written to its temporary file first (renamed with the HDF5 file, below)
  std::string csv = "id,name";
  for (const ScanAxis& a : m.axes) csv.append(",").append(csv_field(a.key));
  csv += ",status,exit_code,wall_s,steps,worker";
  for (const std::string& o : outcome_names) csv.append(",").append(o);
  csv += ",error\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    csv += std::to_string(m.entries[i].id) + "," + m.entries[i].name;
    std::vector<std::string> fields;
    for (const auto& [k, v] : m.entries[i].values)
      fields.push_back(csv_field(unquote(v)));
    fields.insert(fields.end(),
                  {r.status, r.exit_code ? std::to_string(*r.exit_code) : "",
                   csv_number(r.wall_s), csv_number(r.steps), csv_field(r.worker)});
    for (const std::string& o : outcome_names) {
      const auto it = r.outcome.find(o);
      fields.push_back(csv_number(it == r.outcome.end() ? kNaN : it->second));
    }
    fields.push_back(csv_field(r.error));
    for (const std::string& f : fields) csv.append(",").append(f);
    csv += "\n";
  }
  const fs::path csv_tmp = write_temporary(dir / "summary.csv", csv);
  RemoveOnExit remove_csv_temporary{csv_tmp};

  // --- HDF5, built in memory, written to a temporary file and renamed
  const fs::path h5path = dir / "summary.h5";
  // host and PID: processes of one scan on different nodes of a shared file system may
  // have the same PID (HDF5 writes the file itself, so mkstemp's name cannot be used)
  const fs::path tmp =
      dir / ("summary.h5.tmp." + hostname() + "." + std::to_string(getpid()));
  // a failed write (disk full, quota) leaves the old summary and no temporary file
  // (after the rename there is none to remove)
  RemoveOnExit remove_temporary{tmp};
  h5::quiet_errors();
  {
    h5::Handle f = h5::create_file_in_memory(tmp.string());
    h5::set_attr(f.get(), "scene", m.scene.string());
    h5::set_attr(f.get(), "sampling", m.sampling);
    std::string axes;
    for (const ScanAxis& a : m.axes) axes += (axes.empty() ? "" : ",") + a.key;
    h5::set_attr(f.get(), "axes", axes);
    h5::set_attr(f.get(), "manifest", m.to_toml());
    h5::set_attr(f.get(), "n_runs", static_cast<long>(m.entries.size()));
    h5::set_attr(f.get(), "n_completed", counts.completed);
    h5::set_attr(f.get(), "n_failed", counts.failed);
    h5::Handle runs = h5::create_group(f.get(), "runs");
    const std::size_t n = rows.size();
    std::vector<std::string> names(n), status(n), error(n), worker(n);
    std::vector<double> id(n), code(n), wall(n), steps(n);
    for (std::size_t i = 0; i < n; ++i) {
      names[i] = m.entries[i].name;
      status[i] = rows[i].status;
      error[i] = rows[i].error;
      worker[i] = rows[i].worker;
      id[i] = static_cast<double>(m.entries[i].id);
      code[i] = rows[i].exit_code ? static_cast<double>(*rows[i].exit_code) : kNaN;
      wall[i] = rows[i].wall_s;
      steps[i] = rows[i].steps;
    }
    h5::write_vector(runs.get(), "id", id, "", "manifest entry id");
    write_strings(runs.get(), "name", names, "run name: DIR/runs/<name>.h5");
    write_strings(runs.get(), "status", status,
                  "completed, failed, interrupted, incomplete or not run");
    write_strings(runs.get(), "error", error, "why the run failed or is not complete");
    write_strings(runs.get(), "worker", worker, "worker that ran it (local/k, rankR/k)");
    h5::write_vector(runs.get(), "exit_code", code, "",
                     "exit code of panoptic run (-N: killed by signal N; NaN: "
                     "no record, the run has not ended)");
    h5::write_vector(runs.get(), "wall_s", wall, "s",
                     "wall time of the run (/solver wall_s: all its segments), else of "
                     "its last process");
    h5::write_vector(runs.get(), "steps", steps, "", "CVODE steps (/solver nst)");
    h5::Handle axes_g = h5::create_group(f.get(), "axes");
    for (std::size_t j = 0; j < m.axes.size(); ++j) {
      const ScanAxis& a = m.axes[j];
      const std::string spacing = a.kind == ScanAxis::Kind::kLog   ? "log"
                                  : a.kind == ScanAxis::Kind::kLin ? "lin"
                                                                   : "list";
      if (numeric_key(a.key)) {
        std::vector<double> v(n);
        for (std::size_t i = 0; i < n; ++i)
          v[i] = literal_number(m.entries[i].values[j].second);
        h5::write_vector(axes_g.get(), a.key, v, "", "scan axis (units: the key's)");
      } else {
        std::vector<std::string> v(n);
        for (std::size_t i = 0; i < n; ++i) v[i] = unquote(m.entries[i].values[j].second);
        write_strings(axes_g.get(), a.key, v, "scan axis");
      }
      h5::Handle ds(H5Dopen2(axes_g.get(), a.key.c_str(), H5P_DEFAULT), H5Dclose);
      h5::set_attr(ds.get(), "spacing", spacing);
    }
    h5::Handle out_g = h5::create_group(f.get(), "outcome");
    h5::set_attr(out_g.get(), "description",
                 std::string("each run's /summary scalars, with their units "
                             "attribute; t_first_pl_min = min over cells of t_first_pl; "
                             "NaN where the run is not complete"));
    for (const std::string& o : outcome_names) {
      std::vector<double> v(n, kNaN);
      for (std::size_t i = 0; i < n; ++i)
        if (const auto it = rows[i].outcome.find(o); it != rows[i].outcome.end())
          v[i] = it->second;
      const auto u = outcome_units.find(o);
      h5::write_vector(out_g.get(), o, v, u == outcome_units.end() ? "" : u->second,
                       "/summary/" + o + " of each run");
    }
    if (H5Fflush(f.get(), H5F_SCOPE_GLOBAL) < 0)
      throw IoError(tmp.string() + ": flushing failed");
  }
  // The two files are renamed back to back, so that a scan killed while it writes its
  // summary leaves both old or both new (but for the moment between the renames), not
  // the new HDF5 beside the old CSV while the CSV's temporary is written and fsynced.
  if (std::rename(tmp.c_str(), h5path.c_str()) != 0)
    throw IoError(h5path.string() + ": cannot rename the new summary over it");
  remove_temporary.armed = false;
  commit_temporary(csv_tmp, dir / "summary.csv");
  remove_csv_temporary.armed = false;

  return counts;
}

}  // namespace panoptic
