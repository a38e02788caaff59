// LD_PRELOAD shim for regression.test_kill_during_flush: the process kills itself with
// SIGKILL just before its (N+1)-th write to a file whose path begins with
// $PANOPTIC_KILL_PATH, N = $PANOPTIC_KILL_AFTER_WRITES (the output, and the name it is
// set up under). A write that returns is in the page cache: the file is then exactly as
// a SIGKILL at that moment leaves it, so N = 0, 1, 2, ... goes through every state.
// Only the process started counts: a child it forks (the copy a restart makes of the
// output) writes unhindered, as it does when its parent is killed.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

static long writes = 0;
static pid_t owner = 0;

__attribute__((constructor)) static void remember_owner(void) { owner = getpid(); }

static void count_or_kill(int fd) {
  const char* prefix = getenv("PANOPTIC_KILL_PATH");
  const char* limit = getenv("PANOPTIC_KILL_AFTER_WRITES");
  if (!prefix || !limit || getpid() != owner) return;
  char link[64], path[PATH_MAX];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, path, sizeof path - 1);
  if (n < 0) return;
  path[n] = '\0';
  if (strncmp(path, prefix, strlen(prefix)) != 0) return;
  if (writes >= atol(limit)) raise(SIGKILL);
  ++writes;
}

ssize_t pwrite(int fd, const void* buf, size_t n, off_t off) {
  static ssize_t (*real)(int, const void*, size_t, off_t);
  if (!real) *(void**)(&real) = dlsym(RTLD_NEXT, "pwrite");  // POSIX dlsym idiom
  count_or_kill(fd);
  return real(fd, buf, n, off);
}

ssize_t pwrite64(int fd, const void* buf, size_t n, off_t off) {
  static ssize_t (*real)(int, const void*, size_t, off_t);
  if (!real) *(void**)(&real) = dlsym(RTLD_NEXT, "pwrite64");  // POSIX dlsym idiom
  count_or_kill(fd);
  return real(fd, buf, n, off);
}

ssize_t write(int fd, const void* buf, size_t n) {
  static ssize_t (*real)(int, const void*, size_t);
  if (!real) *(void**)(&real) = dlsym(RTLD_NEXT, "write");  // POSIX dlsym idiom
  count_or_kill(fd);
  return real(fd, buf, n);
}
