#include "src/core/signals.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace panoptic {
namespace {

std::atomic<int> g_signal{0};
SecondStop g_second = SecondStop::kEndsAtOnce;
volatile std::sig_atomic_t g_seen_int = 0, g_seen_term = 0, g_parent_stop = 0;

extern "C" void on_stop_signal(int sig, siginfo_t* info, void*) {
  if (g_second == SecondStop::kEndsAtOnce) {
    g_signal = sig;
    std::signal(sig, SIG_DFL);
    return;
  }
  const bool from_parent =
      info != nullptr && info->si_code == SI_USER && info->si_pid == getppid();
  volatile std::sig_atomic_t& seen = sig == SIGINT ? g_seen_int : g_seen_term;
  if (seen && !from_parent && !g_parent_stop) {
    std::signal(sig, SIG_DFL);
    raise(sig);
    return;
  }
  if (from_parent) g_parent_stop = 1;
  seen = 1;
  g_signal = sig;
}

}  // namespace

void install_stop_handlers(SecondStop second) {
  g_second = second;
  struct sigaction sa {};
  sa.sa_sigaction = on_stop_signal;
  sa.sa_flags = SA_SIGINFO | SA_RESTART;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int stop_signal() { return g_signal; }

const char* stop_signal_name(int sig) { return sig == SIGINT ? "SIGINT" : "SIGTERM"; }

void clear_stop_signal() { g_signal = 0; }

void block_stop_signals(bool block) {
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  sigprocmask(block ? SIG_BLOCK : SIG_UNBLOCK, &stop_signals, nullptr);
}

}  // namespace panoptic
