// Child processes of a scan and the files that record them (src/scan/scan_exec.hpp).
#include "src/scan/scan_exec.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "src/core/error.hpp"
#include "src/core/exit_codes.hpp"
#include "src/core/signals.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/durable_file.hpp"
#include "src/io/h5.hpp"
#include "src/run/restart.hpp"
#include "src/scene/config.hpp"

namespace panoptic {
namespace fs = std::filesystem;
namespace {

// key=value lines; backslash and newline escaped, so any stderr text fits on one line.
std::string escape(std::string_view s) {
  std::string out;
  for (const char c : s) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '\n')
      out += "\\n";
    else if (c == '\0')
      out += "\\0";
    else
      out += c;
  }
  return out;
}

std::string unescape(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 1 < s.size()) {
      ++i;
      out += s[i] == 'n' ? '\n' : s[i] == '0' ? '\0' : s[i];
    } else {
      out += s[i];
    }
  }
  return out;
}

// The last `lines` non-empty lines of a file, at most `max_bytes` of them.
std::string tail(const fs::path& file, int lines, std::size_t max_bytes) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const auto size = static_cast<long long>(in.tellg());
  const long long start = std::max(0LL, size - 16384);
  in.seekg(start);
  std::string text((std::istreambuf_iterator<char>(in)),
                   std::istreambuf_iterator<char>());
  std::vector<std::string> all;
  std::istringstream s(text);
  for (std::string line; std::getline(s, line);)
    if (!line.empty() && line.find_first_not_of(" \t\r") != std::string::npos)
      all.push_back(line);
  std::string out;
  for (std::size_t k = all.size() > std::size_t(lines) ? all.size() - lines : 0;
       k < all.size(); ++k)
    out += (out.empty() ? "" : "\n") + all[k];
  if (out.size() > max_bytes) out = "..." + out.substr(out.size() - max_bytes);
  // keep the text printable for the CSV and HDF5 table
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 && c != '\n') c = '?';
  return out;
}

// The last "panoptic: error: ..." line of a run's stderr.
std::optional<std::string> error_line(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::optional<std::string> found;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("panoptic: error: ", 0) == 0) found = line.substr(17, 600);
  if (found)
    for (char& c : *found)
      if (static_cast<unsigned char>(c) < 0x20) c = '?';
  return found;
}

}  // namespace

std::string hostname() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

std::string ScanTask::serialize() const {
  // NUL-separated fields: id, name, h5, log, err, status, config_toml, then argv
  std::string out = std::to_string(id);
  for (const std::string* s : {&name, &h5, &log, &err, &status, &config_toml})
    out += '\0' + *s;
  for (const std::string& a : argv) out += '\0' + a;
  return out;
}

ScanTask ScanTask::deserialize(std::string_view bytes) {
  std::vector<std::string> f;
  std::size_t a = 0;
  for (;;) {
    const std::size_t b = bytes.find('\0', a);
    f.emplace_back(
        bytes.substr(a, b == std::string_view::npos ? bytes.size() - a : b - a));
    if (b == std::string_view::npos) break;
    a = b + 1;
  }
  if (f.size() < 8) throw Error("internal error: malformed scan task message");
  ScanTask t;
  t.id = std::stol(f[0]);
  t.name = f[1];
  t.h5 = f[2];
  t.log = f[3];
  t.err = f[4];
  t.status = f[5];
  t.config_toml = f[6];
  t.argv.assign(f.begin() + 7, f.end());
  return t;
}

std::string self_executable() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw IoError("cannot find the panoptic executable (/proc/self/exe)");
  return p.string();
}

pid_t start_task(const ScanTask& task) {
  std::error_code ec;
  fs::remove(task.status, ec);
  // Everything the child needs is prepared before fork(): after it, only
  // async-signal-safe calls (open, dup2, prctl, execv, _exit).
  std::vector<char*> argv;
  for (const std::string& a : task.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string cannot = "panoptic scan: cannot execute " + task.argv.at(0) + ": ";
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw IoError(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    // Die with the scan process: a killed scan must not leave runs writing files that its
    // rerun writes too.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    // SIGTERM/SIGINT stay blocked (pending) until `panoptic run` has installed its
    // handlers and unblocks them: a stop that arrives while the run is starting is then
    // a checkpointed stop (exit 75), not a death by the default action.
    block_stop_signals(true);
    const int out =
        open(task.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    const int err =
        open(task.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    const int in = open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (out < 0 || err < 0 || in < 0) _exit(126);
    dup2(in, 0);
    dup2(out, 1);
    dup2(err, 2);
    execv(argv[0], argv.data());
    const char* why = strerror(errno);  // glibc: a table lookup, safe in the child
    [[maybe_unused]] auto n = write(2, cannot.data(), cannot.size());
    n = write(2, why, std::strlen(why));
    n = write(2, "\n", 1);
    _exit(127);
  }
  return pid;
}

RunRecord finish_task(const ScanTask& task, int wait_status, double wall_s,
                      const std::string& worker) {
  RunRecord r;
  r.id = task.id;
  r.wall_s = wall_s;
  r.worker = worker;
  r.host = hostname();
  // panoptic's own error line says what went wrong; otherwise (a crash) the last lines
  const std::string err_tail = error_line(task.err).value_or(tail(task.err, 3, 600));
  if (WIFEXITED(wait_status)) {
    r.exit_code = WEXITSTATUS(wait_status);
    r.outcome = r.exit_code == 0                      ? "completed"
                : r.exit_code == exit_codes::kStopped ? "interrupted"
                                                      : "failed";
    if (r.exit_code != 0) r.error = "exit code " + std::to_string(r.exit_code);
  } else if (WIFSIGNALED(wait_status)) {
    const int sig = WTERMSIG(wait_status);
    r.exit_code = -sig;
    // SIGTERM/SIGINT come from outside (the scan or the batch system stopping it, before
    // the run installed its handler): the run was interrupted, it did not fail
    r.outcome = sig == SIGTERM || sig == SIGINT ? "interrupted" : "failed";
    r.error = "killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
  } else {
    r.exit_code = -1;
    r.outcome = "failed";
    r.error = "ended abnormally";
  }
  if (r.exit_code != 0 && !err_tail.empty()) r.error += ": " + err_tail;
  std::ostringstream s;
  s.precision(17);
  s << "id=" << r.id << "\noutcome=" << r.outcome << "\nexit_code=" << r.exit_code
    << "\nwall_s=" << r.wall_s << "\nworker=" << escape(r.worker)
    << "\nhost=" << escape(r.host) << "\nerror=" << escape(r.error) << "\n";
  write_atomically(task.status, s.str());
  return r;
}

namespace {

// Two resolved scenes of the same values: the same text, or (a run written by another
// version of panoptic, whose resolved scene is commented otherwise) the same values.
bool same_scene(const std::string& stored, const std::string& expected) {
  if (stored == expected) return true;
  try {
    return load_scene_text(stored, "config_toml").values_ ==
           load_scene_text(expected, "manifest").values_;
  } catch (const ConfigError&) {
    return false;
  }
}

}  // namespace

bool can_continue(const ScanTask& task) {
  std::error_code ec;
  if (!fs::exists(task.h5, ec)) return false;
  h5::quiet_errors();
  try {
    // the checkpoint `panoptic run --restart` would continue (the previous one when the
    // last is missing, damaged or incomplete), read as it reads it
    return same_scene(load_restart_point(checkpoint_path(task.h5)).chk.config_toml,
                      task.config_toml);
  } catch (const Error&) {
    return false;  // neither can be used
  }
}

std::optional<RunRecord> read_record(const fs::path& status) {
  std::ifstream in(status);
  if (!in) return std::nullopt;
  RunRecord r;
  bool have_outcome = false;
  try {
    for (std::string line; std::getline(in, line);) {
      const auto eq = line.find('=');
      if (eq == std::string::npos) continue;
      const std::string k = line.substr(0, eq), v = unescape(line.substr(eq + 1));
      if (k == "id") r.id = std::stol(v);
      if (k == "outcome") r.outcome = v, have_outcome = true;
      if (k == "exit_code") r.exit_code = std::stoi(v);
      if (k == "wall_s") r.wall_s = std::stod(v);
      if (k == "worker") r.worker = v;
      if (k == "host") r.host = v;
      if (k == "error") r.error = v;
    }
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (!have_outcome) return std::nullopt;
  return r;
}

RunInspection inspect_run(const fs::path& h5path, const std::string& config_toml,
                          double t_end_yr) {
  RunInspection r;
  std::error_code ec;
  if (!fs::exists(h5path, ec)) {
    r.why = "no output file";
    return r;
  }
  h5::quiet_errors();
  try {
    h5::Handle f = h5::open_file(h5path.string(), false);
    if (!h5::has_attr(f.get(), "config_toml") ||
        !same_scene(h5::get_attr_string(f.get(), "config_toml"), config_toml)) {
      r.why =
          "the file is of another scene (config_toml differs from the manifest's run)";
      return r;
    }
    if (h5::exists(f.get(), "solver")) {
      h5::Handle g = h5::open_group(f.get(), "solver");
      if (h5::has_attr(g.get(), "nst")) r.steps = h5::get_attr_long(g.get(), "nst");
      if (h5::has_attr(g.get(), "wall_s"))
        r.wall_s = h5::get_attr_double(g.get(), "wall_s");
      const std::string status =
          h5::has_attr(g.get(), "status") ? h5::get_attr_string(g.get(), "status") : "";
      if (status != "completed") {
        r.why = "solver status is \"" + status + "\", not \"completed\"";
        return r;
      }
    } else {
      r.why = "no /solver: the run did not end";
      return r;
    }
    {
      h5::Handle g = h5::open_group(f.get(), "snapshots");
      const std::vector<double> t = h5::read_doubles(g.get(), "time");
      if (t.empty() || !(std::abs(t.back() - t_end_yr) <= 1e-9 * t_end_yr)) {
        r.why = "the last snapshot is not at t_end_yr";
        return r;
      }
    }
    if (!h5::exists(f.get(), "summary")) {
      r.why = "no /summary";
      return r;
    }
    h5::Handle g = h5::open_group(f.get(), "summary");
    for (const std::string& name : h5::dataset_names(g.get())) {
      const std::vector<double> v = h5::read_doubles(g.get(), name);
      std::string units;
      {
        h5::Handle ds(H5Dopen2(g.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
        if (ds.valid() && h5::has_attr(ds.get(), "units"))
          units = h5::get_attr_string(ds.get(), "units");
      }
      if (v.size() == 1) {
        r.summary[name] = v[0];
        r.units[name] = units;
      } else if (name == "t_first_pl") {
        double lo = std::numeric_limits<double>::quiet_NaN();
        for (double x : v)
          if (!std::isnan(x) && !(x >= lo)) lo = x;
        r.summary["t_first_pl_min"] = lo;
        r.units["t_first_pl_min"] = units;
      }
    }
    if (!r.summary.count("m_dust_final")) {
      r.why = "/summary lacks m_dust_final";
      return r;
    }
    r.complete = true;
  } catch (const Error& e) {
    r.complete = false;
    r.why = std::string("unreadable: ") + e.what();
  }
  return r;
}

}  // namespace panoptic
