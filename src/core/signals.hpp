#pragma once
//! SIGINT and SIGTERM as a request to stop: the handler only records the signal, and the
//! run (or scan) stops at its next check with a checkpoint, exit code 75
//! (exit_codes::kStopped). A second signal of the same kind ends the process at once
//! (the checkpoint on disk stays whole: it is replaced by rename).

namespace panoptic {

//! How a repeated stop signal is told apart from the first.
enum class SecondStop {
  //! `panoptic scan`: the handler is reset by the first signal, so any second one of the
  //! same kind ends the scan at once.
  kEndsAtOnce,
  //! `panoptic run`: a signal its parent sent (a scan forwarding the stop) is not a
  //! second one: a batch system ending a job, or mpirun, signals every process of it,
  //! so the run may have had the same SIGTERM directly, just before or after.
  kUnlessFromParent,
};

//! Installs the handler for SIGINT and SIGTERM (SA_RESTART: slow calls such as waitpid
//! go on after it).
void install_stop_handlers(SecondStop second);

//! The stop signal received (SIGINT or SIGTERM), 0 while none.
int stop_signal();
//! "SIGINT" or "SIGTERM", for the messages of a stop.
const char* stop_signal_name(int sig);
//! Forgets the stop once it is acted upon (a scan that forwarded it to its run).
void clear_stop_signal();

//! Blocks (true) or unblocks SIGINT and SIGTERM; a stop that arrives while they are
//! blocked is delivered when they are unblocked. Async-signal-safe: a scan's child
//! blocks them between fork and exec, the run unblocks them once its handlers are in
//! place.
void block_stop_signals(bool block);

}  // namespace panoptic
