// `panoptic scan` (src/scan/scan.hpp): manifest, scheduling of the runs as child
// processes over local worker slots and, when built with MPI and launched by mpirun, over
// MPI ranks; the summary table at the end.
//
// MPI protocol (dynamic distribution, so runs of uneven cost balance): rank 0 expands and
// validates the scan, writes the manifest and sends every worker rank GO (or the error
// code). A worker rank asks for one run at a time (kRequest) whenever it has a free slot;
// rank 0 answers with a task (kTask: the run's command line and file names) or, when none
// is left, kStop. A worker executes the run as a child process, writes its status record
// and reports (kResult). Rank 0 runs tasks in its own slots meanwhile, and ends when
// every task dispatched has reported and every worker has been stopped. All waiting is
// polling with short sleeps, so idle ranks do not spin a core.
#include "src/scan/scan.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "src/core/error.hpp"
#include "src/core/exit_codes.hpp"
#include "src/core/signals.hpp"
#include "src/core/wall_clock.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/durable_file.hpp"
#include "src/run/max_wall.hpp"
#include "src/scan/scan_exec.hpp"
#include "src/scan/scan_manifest.hpp"
#include "src/scan/scan_summary.hpp"
#include "src/scene/toml_literal.hpp"

#ifdef PANOPTIC_HAVE_MPI
// the C API only: OpenMPI and MPICH would pull in their deprecated C++ bindings
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace panoptic {
namespace fs = std::filesystem;
namespace {

constexpr int kExitFailed = exit_codes::kFailed;
constexpr int kExitStopped = exit_codes::kStopped;

void nap() { std::this_thread::sleep_for(std::chrono::milliseconds(5)); }

//! The number of processes mpirun started, from the environment of the launchers
//! (OpenMPI, MPICH/PMI); 1 when not under mpirun.
int launcher_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 1;
}

struct Prepared {
  Manifest m;
  std::vector<ResolvedRun> resolved;
  fs::path dir;
  std::vector<ScanTask> tasks;  //!< one per entry
  std::deque<long> todo;        //!< ids of the runs to execute
};

std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ga = static_cast<bool>(std::getline(sa, la));
    const bool gb = static_cast<bool>(std::getline(sb, lb));
    if (!ga && !gb) return "";
    if (!ga) la = "(end)";
    if (!gb) lb = "(end)";
    if (la != lb)
      return "manifest line " + std::to_string(line) + ": was `" + la + "`, now `" + lb +
             "`";
  }
}

//! Expands and validates the scan; writes (or checks) DIR/manifest.toml; finds the runs
//! that are not complete. Throws ConfigError before anything is written when the scan
//! or any run's scene is bad.
Prepared prepare(const ScanOptions& o) {
  if (!o.progress.empty()) parse_duration(o.progress, "--progress");  // before any run
  Prepared p;
  p.m = load_scan(o.scan_file);
  p.resolved = validate_manifest(p.m);
  const std::string header =
      "# panoptic scan manifest of " + o.scan_file +
      ": every run of the scan, written before any run starts.\n"
      "# A rerun of the scan must expand to the same manifest (panoptic scan --force "
      "replaces it).\n";
  const std::string text = p.m.to_toml(header);
  if (o.dry_run) return p;
  p.dir = fs::absolute(o.dir);
  std::error_code ec;
  fs::create_directories(p.dir / "runs", ec);
  if (ec)
    throw IoError((p.dir / "runs").string() + ": cannot create directory (" +
                  ec.message() + ")");
  const fs::path manifest = p.dir / "manifest.toml";
  if (fs::exists(manifest)) {
    std::ifstream in(manifest);
    std::stringstream old;
    old << in.rdbuf();
    const std::string a = manifest_body(old.str()), b = manifest_body(text);
    if (a != b && !o.force)
      throw ConfigError(
          manifest.string() + ": the scan " + o.scan_file +
          " now expands to another manifest than the one of the scan in " +
          p.dir.string() + " (" + first_difference(a, b) +
          "); to resume that scan, restore its scan file and base scene; to start "
          "another "
          "scan, choose another -o DIR; to replace the manifest and keep every run that "
          "still matches it, pass --force");
    if (a != b)
      std::printf("scan: --force: replacing %s (%s)\n", manifest.c_str(),
                  first_difference(a, b).c_str());
    if (a != b) write_atomically(manifest, text);
  } else {
    write_atomically(manifest, text);
  }
  const std::string exe = o.run_exe.empty() ? self_executable() : o.run_exe;
  for (std::size_t i = 0; i < p.m.entries.size(); ++i) {
    const ManifestEntry& e = p.m.entries[i];
    ScanTask t;
    t.id = e.id;
    t.name = e.name;
    t.h5 = run_file(p.dir, e.name, "h5").string();
    t.log = run_file(p.dir, e.name, "log").string();
    t.err = run_file(p.dir, e.name, "err").string();
    t.status = run_file(p.dir, e.name, "status").string();
    t.config_toml = p.resolved[i].config_toml;
    t.argv = {exe, "run", p.m.scene.string()};
    for (const std::string& s : p.m.overrides(i))
      t.argv.insert(t.argv.end(), {"--set", s});
    if (!o.progress.empty()) t.argv.insert(t.argv.end(), {"--progress", o.progress});
    if (o.threads > 1)
      t.argv.insert(t.argv.end(), {"--threads", std::to_string(o.threads)});
    t.argv.insert(t.argv.end(), {"-o", t.h5, "--overwrite"});  // last: Pool::launch
    p.tasks.push_back(std::move(t));
  }
  return p;
}

//! Finds the runs to execute: those whose output is not complete (checked).
void find_todo(Prepared& p, std::optional<long> only) {
  long complete = 0;
  for (std::size_t i = 0; i < p.tasks.size(); ++i) {
    if (only && static_cast<long>(i) != *only) continue;
    const RunInspection in =
        inspect_run(p.tasks[i].h5, p.resolved[i].config_toml, p.resolved[i].t_end_yr);
    if (in.complete)
      ++complete;
    else
      p.todo.push_back(static_cast<long>(i));
  }
  std::printf("scan: %zu runs in %s: %ld complete (checked), %zu to run\n",
              only ? std::size_t{1} : p.tasks.size(), p.dir.c_str(), complete,
              p.todo.size());
  std::fflush(stdout);
}

//! Up to `slots` runs at once as child processes of this process.
class Pool {
 public:
  Pool(int slots, std::string label) : slots_(slots), label_(std::move(label)) {}
  bool has_free() const { return static_cast<int>(running_.size()) < slots_; }
  bool idle() const { return running_.empty(); }
  //! Starts a run: continued from its checkpoint when an earlier attempt left its output
  //! and a checkpoint of the run's scene (a run stopped by SIGTERM/SIGINT, or one killed
  //! after its last periodic checkpoint), else from the start.
  void start(const ScanTask& t) {
    // the lowest free slot (at most as many as run, not -j of them: -j may be huge)
    std::set<int> used;
    for (const auto& [pid, r] : running_) used.insert(r.slot);
    int slot = 0;
    while (used.count(slot)) ++slot;
    launch(t, slot, can_continue(t));
  }
  //! A run that ended since the last call, with its record written.
  std::optional<RunRecord> poll() {
    for (auto it = running_.begin(); it != running_.end(); ++it) {
      int status = 0;
      const pid_t r = waitpid(it->first, &status, WNOHANG);
      if (r == 0 || (r < 0 && errno == EINTR)) continue;
      if (r < 0) status = W_EXITCODE(127, 0);  // lost: count it as failed
      const Running run = it->second;
      running_.erase(it);
      // A checkpoint that panoptic run refuses (bad input 2: incompatible scene; I/O 4:
      // damaged checkpoint or output): run it from the start instead.
      if (run.restart && WIFEXITED(status) &&
          (WEXITSTATUS(status) == 2 || WEXITSTATUS(status) == 4)) {
        std::printf(
            "scan: %s: its checkpoint was refused (exit %d); running it from the "
            "start\n",
            run.task.name.c_str(), WEXITSTATUS(status));
        launch(run.task, run.slot, false);
        return poll();
      }
      return finish_task(run.task, status, seconds_since(run.start),
                         label_ + "/" + std::to_string(run.slot));
    }
    return std::nullopt;
  }
  void signal_all(int sig) {
    for (const auto& [pid, r] : running_) kill(pid, sig);
  }

 private:
  struct Running {
    ScanTask task;
    int slot = 0;
    WallClock::time_point start;
    bool restart = false;
  };
  void launch(const ScanTask& t, int slot, bool restart) {
    ScanTask run = t;
    if (restart) {  // "--overwrite" (last) becomes "--restart CHK"
      run.argv.back() = "--restart";
      run.argv.push_back(checkpoint_path(t.h5).string());
    }
    const pid_t pid = start_task(run);
    running_[pid] = Running{t, slot, WallClock::now(), restart};
  }
  int slots_;
  std::string label_;
  std::map<pid_t, Running> running_;
};

class Progress {
 public:
  Progress(const Prepared& p, std::size_t total) : p_(p), total_(total) {}
  void report(const RunRecord& r) {
    ++done_;
    const std::string& name = p_.tasks.at(static_cast<std::size_t>(r.id)).name;
    std::string what = r.outcome;
    if (r.outcome != "completed") {
      std::string err = r.error;
      if (const auto nl = err.find('\n'); nl != std::string::npos)
        err = err.substr(0, nl) + " ...";
      what += " (" + err + ")";
    }
    std::printf("[%zu/%zu] %s %s in %.2f s on %s\n", done_, total_, name.c_str(),
                what.c_str(), r.wall_s, r.worker.c_str());
    std::fflush(stdout);
  }

 private:
  const Prepared& p_;
  std::size_t total_, done_ = 0;
};

#ifdef PANOPTIC_HAVE_MPI
enum Tag : int { kGo = 1, kRequest = 2, kTask = 3, kStop = 4, kResult = 5 };

struct MpiSession {
  MpiSession() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SINGLE, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
  }
  ~MpiSession() { MPI_Finalize(); }
  int rank = 0, size = 1;
};

//! Runs `body` on a rank once the ranks work together. An error there (an I/O error
//! writing a run's record or the summary, ...) must not just end this rank: the others
//! would wait for its messages forever, and the job would hang until its time limit. So
//! the error is printed and the whole job ended (MPI_Abort: mpirun stops every rank, and
//! the runs die with their ranks, PR_SET_PDEATHSIG); a rerun resumes the scan.
template <class Body>
int or_abort(Body&& body) {
  int code = 1;
  try {
    return body();
  } catch (const Error& e) {
    std::fprintf(stderr, "panoptic: error: %s\n", e.what());
    code = e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "panoptic: internal error: %s\n", e.what());
  }
  std::fflush(stdout);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
  return code;
}

//! A message from rank 0 if one is waiting: its tag and bytes.
std::optional<std::pair<int, std::string>> poll_master() {
  int flag = 0;
  MPI_Status st;
  MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
  if (!flag) return std::nullopt;
  int n = 0;
  MPI_Get_count(&st, MPI_CHAR, &n);
  std::string bytes(static_cast<std::size_t>(n), '\0');
  MPI_Recv(bytes.data(), n, MPI_CHAR, 0, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return std::make_pair(st.MPI_TAG, std::move(bytes));
}

//! Waits (polling, not spinning) for a message from rank 0; returns its tag and bytes.
std::pair<int, std::string> receive_from_master() {
  for (;;) {
    if (auto msg = poll_master()) return *std::move(msg);
    nap();
  }
}

//! A worker rank: asks rank 0 for runs while it has free slots, until told to stop.
int mpi_worker(const MpiSession& mpi, int jobs) {
  const auto [tag, go] = receive_from_master();
  if (tag != kGo || go != "0") return std::atoi(go.c_str());
  Pool pool(jobs, "rank" + std::to_string(mpi.rank));
  bool asked = false, stopped = false, stopping = false;
  for (;;) {
    bool busy = false;
    if (stop_signal() != 0 &&
        !stopping) {  // mpirun forwards SIGTERM: let the runs checkpoint
      stopping = true;
      pool.signal_all(SIGTERM);
    }
    if (!stopped && !asked && pool.has_free()) {
      MPI_Send(nullptr, 0, MPI_CHAR, 0, kRequest, MPI_COMM_WORLD);
      asked = true;
    }
    if (asked) {
      if (auto reply = poll_master()) {
        const auto& [reply_tag, bytes] = *reply;
        asked = false;
        busy = true;
        if (reply_tag == kTask && !stopping) {
          pool.start(ScanTask::deserialize(bytes));
        } else if (reply_tag == kTask) {  // stopping: record it as interrupted, unrun
          const ScanTask t = ScanTask::deserialize(bytes);
          const RunRecord r = finish_task(t, W_EXITCODE(kExitStopped, 0), 0.0,
                                          "rank" + std::to_string(mpi.rank));
          const double msg[3] = {static_cast<double>(r.id),
                                 static_cast<double>(kExitStopped), 0.0};
          MPI_Send(msg, 3, MPI_DOUBLE, 0, kResult, MPI_COMM_WORLD);
        } else {
          stopped = true;
        }
      }
    }
    while (const auto r = pool.poll()) {
      const double msg[3] = {static_cast<double>(r->id),
                             static_cast<double>(r->exit_code), r->wall_s};
      MPI_Send(msg, 3, MPI_DOUBLE, 0, kResult, MPI_COMM_WORLD);
      busy = true;
    }
    if (stopped && pool.idle()) return 0;
    if (!busy) nap();
  }
}
#endif

//! Executes p.todo over `jobs` local slots and, under MPI, the worker ranks. Returns
//! false when stopped by a signal.
bool execute(Prepared& p, int jobs, [[maybe_unused]] int mpi_size) {
  Progress progress(p, p.todo.size());
  Pool pool(jobs, mpi_size > 1 ? "rank0" : "local");
  bool stopping = false;
  [[maybe_unused]] long dispatched = 0, reported = 0;
  [[maybe_unused]] int stopped_workers = 0;
  for (;;) {
    bool busy = false;
    if (stop_signal() != 0 && !stopping) {
      stopping = true;
      std::printf(
          "scan: stopped by %s: the runs under way are stopped (they checkpoint); "
          "rerun the same command to continue\n",
          stop_signal_name(stop_signal()));
      std::fflush(stdout);
      p.todo.clear();
      pool.signal_all(SIGTERM);
    }
    while (pool.has_free() && !p.todo.empty()) {
      pool.start(p.tasks[static_cast<std::size_t>(p.todo.front())]);
      p.todo.pop_front();
      busy = true;
    }
#ifdef PANOPTIC_HAVE_MPI
    if (mpi_size > 1) {
      for (;;) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
        if (!flag) break;
        busy = true;
        if (st.MPI_TAG == kRequest) {
          MPI_Recv(nullptr, 0, MPI_CHAR, st.MPI_SOURCE, kRequest, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE);
          if (!p.todo.empty()) {
            const std::string bytes =
                p.tasks[static_cast<std::size_t>(p.todo.front())].serialize();
            p.todo.pop_front();
            MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_CHAR,
                     st.MPI_SOURCE, kTask, MPI_COMM_WORLD);
            ++dispatched;
          } else {
            MPI_Send(nullptr, 0, MPI_CHAR, st.MPI_SOURCE, kStop, MPI_COMM_WORLD);
            ++stopped_workers;
          }
        } else if (st.MPI_TAG == kResult) {
          double msg[3];
          MPI_Recv(msg, 3, MPI_DOUBLE, st.MPI_SOURCE, kResult, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE);
          ++reported;
          const auto rec =
              read_record(p.tasks.at(static_cast<std::size_t>(msg[0])).status);
          RunRecord r = rec.value_or(RunRecord{});
          r.id = static_cast<long>(msg[0]);
          if (!rec) {
            r.outcome = "failed";
            r.wall_s = msg[2];
            r.worker = "rank" + std::to_string(st.MPI_SOURCE);
            r.error = "no status record (shared file system?)";
          }
          progress.report(r);
        }
      }
    }
#endif
    while (const auto r = pool.poll()) {
      progress.report(*r);
      busy = true;
    }
    const bool remote_done =
        mpi_size <= 1 || (reported == dispatched && stopped_workers == mpi_size - 1);
    if (p.todo.empty() && pool.idle() && remote_done) break;
    if (!busy) nap();
  }
  return !stopping;
}

int finish(const Prepared& p, bool completed_loop) {
  const ScanCounts c = write_scan_summary(p.dir, p.m, p.resolved);
  std::printf(
      "scan: %ld of %zu runs complete, %ld failed, %ld not complete; summary in "
      "%s and %s\n",
      c.completed, p.m.entries.size(), c.failed, c.other, (p.dir / "summary.h5").c_str(),
      (p.dir / "summary.csv").c_str());
  if (!completed_loop) return kExitStopped;
  if (c.failed > 0) return kExitFailed;
  return c.other > 0 ? kExitStopped : 0;
}

//! --task I as given: the id of a manifest entry (checked against the manifest by
//! run_one_task). An empty value (an unset $SLURM_ARRAY_TASK_ID) is refused, not taken
//! as "every run": each task of the array would run the whole scan.
long parse_task(const std::string& text) {
  long i = -1;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, i);
  if (text.empty() || ec != std::errc() || ptr != end || i < 0)
    throw ConfigError("--task " + toml_string(text) +
                      ": must be the id of a manifest entry, an integer >= 0 (0 to "
                      "n_runs - 1 of DIR/manifest.toml); in a job array give --task "
                      "$SLURM_ARRAY_TASK_ID (or your batch system's array index) with "
                      "indices from 0");
  return i;
}

int run_one_task(Prepared& p, long i) {
  if (i >= static_cast<long>(p.tasks.size()))
    throw ConfigError("--task " + std::to_string(i) + ": the manifest has runs 0 to " +
                      std::to_string(p.tasks.size() - 1) + "; choose one of them");
  find_todo(p, i);
  if (p.todo.empty()) return 0;
  Pool pool(1, "task");
  pool.start(p.tasks[static_cast<std::size_t>(i)]);
  for (;;) {
    if (stop_signal() != 0) pool.signal_all(SIGTERM), clear_stop_signal();
    if (const auto r = pool.poll()) {
      Progress(p, 1).report(*r);
      if (r->outcome == "completed") return 0;
      return r->exit_code > 0 ? r->exit_code : kExitFailed;
    }
    nap();
  }
}

}  // namespace

bool scan_has_mpi() {
#ifdef PANOPTIC_HAVE_MPI
  return true;
#else
  return false;
#endif
}

int run_scan(const ScanOptions& o) {
  if (o.jobs < 1)
    throw ConfigError("-j " + std::to_string(o.jobs) + ": must be >= 1 (runs at once)");
  if (o.threads < 1)
    throw ConfigError("--threads " + std::to_string(o.threads) +
                      ": must be >= 1 (the worker threads of each run); give --threads 1 "
                      "(the default) or the cores each run may use");
  const int world = launcher_world_size();
  if (world > 1 && (o.dry_run || o.task))
    throw ConfigError(
        "--dry-run and --task run in one process: do not start them with "
        "mpirun");
#ifndef PANOPTIC_HAVE_MPI
  if (world > 1)
    throw ConfigError("panoptic scan was started by mpirun with " +
                      std::to_string(world) +
                      " processes, but this panoptic is built without MPI (each process "
                      "would run the whole scan); install libopenmpi-dev and rebuild, or "
                      "run without mpirun, with -j N local workers");
#endif
  const long task = o.task ? parse_task(*o.task) : -1;
  if (!o.run_exe.empty()) {
    std::error_code ec;
    if (!fs::is_regular_file(o.run_exe, ec) || access(o.run_exe.c_str(), X_OK) != 0)
      throw ConfigError("--run-exe " + o.run_exe +
                        ": not an executable file (every run would fail to start); give "
                        "the path of panoptic or of a script taking the arguments of "
                        "panoptic run");
  }
  install_stop_handlers(SecondStop::kEndsAtOnce);
  if (o.dry_run) {
    const Prepared p = prepare(o);
    std::fputs(
        p.m.to_toml("# panoptic scan --dry-run " + o.scan_file + ": " +
                    std::to_string(p.m.entries.size()) + " runs (nothing written)\n")
            .c_str(),
        stdout);
    return 0;
  }
#ifdef PANOPTIC_HAVE_MPI
  if (world > 1) {
    MpiSession mpi;
    if (mpi.rank != 0) return or_abort([&] { return mpi_worker(mpi, o.jobs); });
    Prepared p;
    int code = 0;
    try {
      p = prepare(o);
    } catch (const Error& e) {
      code = e.exit_code();
      const std::string c = std::to_string(code);
      for (int r = 1; r < mpi.size; ++r)
        MPI_Send(c.data(), static_cast<int>(c.size()), MPI_CHAR, r, kGo, MPI_COMM_WORLD);
      throw;
    }
    for (int r = 1; r < mpi.size; ++r) MPI_Send("0", 1, MPI_CHAR, r, kGo, MPI_COMM_WORLD);
    return or_abort([&] {
      find_todo(p, std::nullopt);
      std::printf("scan: %d MPI ranks, %d run%s at once each\n", mpi.size, o.jobs,
                  o.jobs == 1 ? "" : "s");
      const bool done = execute(p, o.jobs, mpi.size);
      return finish(p, done);
    });
  }
#endif
  Prepared p = prepare(o);
  if (o.task) return run_one_task(p, task);
  find_todo(p, std::nullopt);
  const bool done = execute(p, o.jobs, 1);
  return finish(p, done);
}

}  // namespace panoptic
