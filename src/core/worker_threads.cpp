#include "src/core/worker_threads.hpp"

#include <algorithm>

namespace panoptic {
namespace {

int g_worker_threads = 1;

}  // namespace

void set_worker_threads(int n) { g_worker_threads = std::max(1, n); }

int worker_threads() { return g_worker_threads; }

}  // namespace panoptic
