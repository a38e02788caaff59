#include "src/scene/toml_guard.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "src/scene/number_text.hpp"

namespace panoptic {
namespace {

// 1-based line and column (in code points, like toml++) of byte `offset` in `text`.
struct TextPos {
  long line = 1;
  long col = 1;
};

TextPos position_of(std::string_view text, size_t offset) {
  TextPos p;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++p.line;
      p.col = 1;
    } else if ((c & 0xC0) != 0x80) {  // continuation bytes do not start a column
      ++p.col;
    }
  }
  return p;
}

std::string hex_byte(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", c);
  return buf;
}

// Length of the valid UTF-8 sequence at text[i], or 0 when it is not valid (RFC 3629:
// no overlong forms, no surrogates, nothing above U+10FFFF).
size_t utf8_sequence_length(std::string_view text, size_t i) {
  const auto at = [&](size_t k) -> unsigned {
    return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0x100;
  };
  const auto in = [](unsigned c, unsigned lo, unsigned hi) { return c >= lo && c <= hi; };
  const unsigned c0 = at(0);
  if (c0 < 0x80) return 1;
  if (in(c0, 0xC2, 0xDF)) return in(at(1), 0x80, 0xBF) ? 2 : 0;
  if (in(c0, 0xE0, 0xEF)) {
    const unsigned lo = c0 == 0xE0 ? 0xA0 : 0x80;
    const unsigned hi = c0 == 0xED ? 0x9F : 0xBF;
    return in(at(1), lo, hi) && in(at(2), 0x80, 0xBF) ? 3 : 0;
  }
  if (in(c0, 0xF0, 0xF4)) {
    const unsigned lo = c0 == 0xF0 ? 0x90 : 0x80;
    const unsigned hi = c0 == 0xF4 ? 0x8F : 0xBF;
    return in(at(1), lo, hi) && in(at(2), 0x80, 0xBF) && in(at(3), 0x80, 0xBF) ? 4 : 0;
  }
  return 0;
}

const char* signal_abbrev(int sig) {
  switch (sig) {
    case SIGSEGV:
      return "SIGSEGV";
    case SIGABRT:
      return "SIGABRT";
    case SIGBUS:
      return "SIGBUS";
    case SIGFPE:
      return "SIGFPE";
    case SIGILL:
      return "SIGILL";
    case SIGTRAP:
      return "SIGTRAP";
    case SIGKILL:
      return "SIGKILL";
    case SIGALRM:
      return "SIGALRM";
    case SIGPIPE:
      return "SIGPIPE";
    case SIGTERM:
      return "SIGTERM";
    default:
      return nullptr;
  }
}

std::string signal_name(int sig) {
  const char* abbrev = signal_abbrev(sig);
  std::string name = abbrev ? abbrev : "signal " + std::to_string(sig);
  if (const char* text = strsignal(sig)) name += std::string(" (") + text + ")";
  return name;
}

// What the child reported (or how it died).
enum class Verdict { kOk, kSyntaxError, kCrashed, kTimedOut, kFailed, kNoChild };

struct ChildResult {
  Verdict verdict = Verdict::kFailed;
  long line = 0;
  long col = 0;
  std::string text;  // syntax error description, exception text or errno text
  int signal = 0;
};

void write_all(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

void default_child_parse(std::string_view text) {
  (void)toml::parse(text, std::string_view("child"));
}

// The child: parse, report through `fd`, _exit. Never returns, so no exception, atexit
// handler, static destructor or gtest code of the parent runs in it, and no stdio buffer
// inherited from the parent is flushed twice.
[[noreturn]] void run_child(int fd, std::string_view text, const GuardOptions& options) {
  // The parser must not write to the terminal; and a crash in here is expected now and
  // then, so it must not leave core files behind or run a crash handler of the parent.
  const int devnull = ::open("/dev/null", O_RDWR);
  if (devnull >= 0) {
    ::dup2(devnull, STDOUT_FILENO);
    ::dup2(devnull, STDERR_FILENO);
  }
  const struct rlimit no_core = {0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  for (int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGALRM})
    std::signal(sig, SIG_DFL);
  sigset_t unblock;
  sigemptyset(&unblock);
  sigaddset(&unblock, SIGALRM);
  sigprocmask(SIG_UNBLOCK, &unblock, nullptr);
  ::alarm(options.timeout_s);

  int status = 0;
  try {
    std::string report;
    try {
      (options.child_parse ? options.child_parse : default_child_parse)(text);
      report = "O";
    } catch (const toml::parse_error& e) {
      const auto& begin = e.source().begin;
      report = "E" + std::to_string(begin.line) + "\t" + std::to_string(begin.column) +
               "\t" + std::string(e.description());
    } catch (const std::exception& e) {
      report = std::string("X") + e.what();
    } catch (...) {
      report = "Xan exception that is not a std::exception";
    }
    write_all(fd, report);
  } catch (...) {
    status = 1;  // out of memory while reporting: the parent sees an empty report
  }
  ::_exit(status);
}

ChildResult run_in_child(std::string_view text, const GuardOptions& options) {
  ChildResult result;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    result.verdict = Verdict::kNoChild;
    result.text = std::strerror(errno);
    return result;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    result.verdict = Verdict::kNoChild;
    result.text = std::strerror(errno);
    ::close(fds[0]);
    ::close(fds[1]);
    return result;
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_child(fds[1], text, options);
  }
  ::close(fds[1]);

  // Read the whole report before waiting, so a long report cannot fill the pipe and
  // block the child forever.
  std::string report;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    report.append(buf, static_cast<size_t>(n));
  }
  ::close(fds[0]);

  int status = 0;
  pid_t waited;
  do {
    waited = ::waitpid(pid, &status, 0);
  } while (waited < 0 && errno == EINTR);
  // waited < 0 (ECHILD) happens when the program ignores SIGCHLD: children are reaped
  // by the kernel and the status is lost. The report then is all there is.
  const bool have_status = waited == pid;

  if (have_status && WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
    result.verdict = result.signal == SIGALRM ? Verdict::kTimedOut : Verdict::kCrashed;
    return result;
  }
  if (report.empty()) {
    result.verdict = Verdict::kFailed;
    result.text = "the parser process ended without a report";
    return result;
  }
  switch (report[0]) {
    case 'O':
      result.verdict = Verdict::kOk;
      break;
    case 'E': {
      result.verdict = Verdict::kSyntaxError;
      const size_t t1 = report.find('\t');
      const size_t t2 = t1 == std::string::npos ? t1 : report.find('\t', t1 + 1);
      if (t2 == std::string::npos) {
        result.text = report.substr(1);
      } else {
        result.line = std::atol(report.substr(1, t1 - 1).c_str());
        result.col = std::atol(report.substr(t1 + 1, t2 - t1 - 1).c_str());
        result.text = report.substr(t2 + 1);
      }
      break;
    }
    default:
      result.verdict = Verdict::kFailed;
      result.text = report.substr(1);
  }
  return result;
}

// The shortest prefix of `text` on which the parser crashes, found by bisection (each
// step is one more child). A parser crash usually happens soon after it reads the bad
// bytes, so the end of that prefix is the best place we can point the user to. Returns
// npos when the crash cannot be reproduced on a prefix.
size_t locate_crash(std::string_view text, const GuardOptions& options) {
  size_t good = 0;           // a prefix known not to crash
  size_t bad = text.size();  // a prefix known to crash
  for (int step = 0; step < 40 && bad - good > 1; ++step) {
    const size_t mid = good + (bad - good) / 2;
    const ChildResult r = run_in_child(text.substr(0, mid), options);
    if (r.verdict == Verdict::kNoChild) return std::string_view::npos;
    (r.verdict == Verdict::kCrashed ? bad : good) = mid;
  }
  return bad - good == 1 ? bad - 1 : std::string_view::npos;
}

std::string where(const std::string& name, TextPos p) {
  return name + ":" + std::to_string(p.line) + ":" + std::to_string(p.col);
}

}  // namespace

void check_text(std::string_view text, const std::string& name) {
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == 0) {
      throw ConfigError(where(name, position_of(text, i)) +
                        ": NUL byte (0x00) at byte offset " + std::to_string(i) +
                        "; a scene file is plain UTF-8 text: is this the right file?");
    }
    const size_t n = utf8_sequence_length(text, i);
    if (n == 0) {
      throw ConfigError(where(name, position_of(text, i)) + ": not valid UTF-8 (byte " +
                        hex_byte(c) + " at byte offset " + std::to_string(i) +
                        "); a scene file must be UTF-8 text: save it as UTF-8 or remove "
                        "the byte");
    }
    i += n;
  }
}

namespace {
// What the parser's message means for two common mistakes, to append to it: a number
// beyond the range of a double (toml++: "'1e400' could not be interpreted as a value"),
// and a basic string left open at the end of its line (toml++ reports the newline as a
// prohibited control character).
std::string syntax_hint(const std::string& description) {
  const std::string quoted = "' could not be interpreted as a value";
  if (const auto end = description.find(quoted); end != std::string::npos && end > 0) {
    const auto begin = description.rfind('\'', end - 1);
    if (begin != std::string::npos) {
      const std::string token = description.substr(begin + 1, end - begin - 1);
      if (read_number_text(token).beyond_double)
        return " (" + token +
               " is beyond the range of a double, |x| < 1.8e308: give a number in range)";
    }
  }
  if (description.find("Error while parsing string") != std::string::npos &&
      description.find("control characters") != std::string::npos)
    return " (a string not closed on its line? A \"...\" string ends with a quote on the "
           "line it starts; use '''...''' for text over several lines)";
  return "";
}
}  // namespace

toml::table parse_toml_guarded(std::string_view text, const std::string& name,
                               const GuardOptions& options) {
  check_text(text, name);
  const ChildResult r = run_in_child(text, options);
  switch (r.verdict) {
    case Verdict::kOk:
    case Verdict::kNoChild:
      // kNoChild: fork() failed (process or memory limit). Refusing every scene then
      // would be worse than the small risk of parsing in-process, so fall through.
      break;
    case Verdict::kSyntaxError:
      throw ConfigError(name + ":" + std::to_string(r.line) + ":" +
                        std::to_string(r.col) + ": TOML syntax error: " + r.text +
                        syntax_hint(r.text));
    case Verdict::kCrashed: {
      const size_t at = locate_crash(text, options);
      const std::string what = "not a valid TOML file (the TOML parser crashed on it: " +
                               signal_name(r.signal) + ")";
      if (at == std::string_view::npos) {
        throw ConfigError(name + ": " + what +
                          "; check the syntax of the file: brackets, quotes and '=' of "
                          "every line");
      }
      const TextPos p = position_of(text, at);
      throw ConfigError(where(name, p) + ": " + what + "; check the syntax near line " +
                        std::to_string(p.line) + ", column " + std::to_string(p.col) +
                        " (the parser crashes once it has read this far)");
    }
    case Verdict::kTimedOut:
      throw ConfigError(name +
                        ": not a valid TOML file (the TOML parser did not finish " +
                        "within " + std::to_string(options.timeout_s) +
                        " s); check the file for runaway brackets or quotes");
    case Verdict::kFailed:
      throw ConfigError(name + ": not a valid TOML file (the TOML parser failed on it: " +
                        r.text + "); check the syntax of the file");
  }
  try {
    return toml::parse(text, std::string(name));
  } catch (const toml::parse_error& e) {
    // Only reached when the child could not run: the same message it would have sent.
    throw ConfigError(name + ":" + std::to_string(e.source().begin.line) + ":" +
                      std::to_string(e.source().begin.column) +
                      ": TOML syntax error: " + std::string(e.description()) +
                      syntax_hint(std::string(e.description())));
  }
}

}  // namespace panoptic
