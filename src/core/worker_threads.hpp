#pragma once
//! The worker threads of one run (`panoptic run --threads N`, default 1). The cell-local
//! work of the size distribution (its coagulation coefficients, the engine's right-hand
//! side and Jacobian per cell, the preconditioner's cell blocks) is shared among them
//! cell by cell with parallel_for. Each cell's arithmetic is the same whichever thread
//! does it, in the same order, and each writes only its own cell's entries: the results
//! are identical to the bit for every thread count (regression.test_worker_threads,
//! `WorkerThreads.*`). Default 1: a scan runs its runs as separate jobs, each on one
//! core.
#include <cstddef>
#include <exception>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace panoptic {

//! Sets the number of worker threads (>= 1; callers validate user input).
void set_worker_threads(int n);
//! The number of worker threads (1 unless set).
int worker_threads();

//! Calls body(i, worker) for i = 0 .. n - 1, worker in [0, worker_threads()): the
//! worker's index, for its own scratch space. The calls run on worker_threads() threads
//! (one thread: in order, on the caller's). An exception a call throws is rethrown here
//! once every call has returned (the first to be caught, when several throw). Not to be
//! nested: a body that called parallel_for would hand out worker indices its caller's
//! workers hold.
template <class Body>
void parallel_for(int n, Body&& body) {
  const int threads = worker_threads();
  if (threads <= 1 || n <= 1) {
    for (int i = 0; i < n; ++i) body(i, 0);
    return;
  }
  std::exception_ptr error;
  // dynamic: cells differ in cost (empty bins, compact pairs); the result does not
  // depend on which thread takes which cell
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (int i = 0; i < n; ++i) {
    try {
#ifdef _OPENMP
      body(i, omp_get_thread_num());
#else
      body(i, 0);
#endif
    } catch (...) {
#pragma omp critical(panoptic_parallel_for_error)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

//! Calls body(lo, hi) for worker_threads() consecutive bands [lo, hi) covering [0, n),
//! each on a worker of its own: for element-wise work (copies, scalings) and for sums
//! kept in the same order by bands of rows.
template <class Body>
void parallel_bands(std::size_t n, Body&& body) {
  const auto bands = static_cast<std::size_t>(worker_threads());
  parallel_for(static_cast<int>(bands), [&](int b, int) {
    const auto band = static_cast<std::size_t>(b);
    body(n * band / bands, n * (band + 1) / bands);
  });
}

}  // namespace panoptic
