/* A full disk for tests (LD_PRELOAD=tests/helpers/faultfs.so): write, pwrite and
 * pwrite64 on regular files fail with ENOSPC once FAULTFS_BYTES bytes have
 * been written through them by the process.  HDF5 writes through pwrite, so
 * a snapshot fails inside the HDF5 library as on a real full disk; stdio
 * (restart files, statistics) writes through glibc's internal calls and is
 * not limited.  Used by tests/program/test_hostile_inputs.sh (issue 18 item 5). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

/** Bytes allowed (FAULTFS_BYTES), and written so far. */
static long long faultfs_budget = -1, faultfs_used = 0;

/** 1 if n more bytes to fd do not fit on the "disk" (counted if they do). */
static int faultfs_full(int fd, size_t n) {
  if (faultfs_budget < 0) {
    const char *s = getenv("FAULTFS_BYTES");
    faultfs_budget = s ? atoll(s) : LLONG_MAX;
  }
  struct stat st;
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return 0;
  if (faultfs_used + (long long)n > faultfs_budget) return 1;
  faultfs_used += (long long)n;
  return 0;
}

ssize_t write(int fd, const void *buf, size_t n) {
  static ssize_t (*real)(int, const void *, size_t);
  if (!real) real = (ssize_t(*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
  if (faultfs_full(fd, n)) return errno = ENOSPC, -1;
  return real(fd, buf, n);
}

ssize_t pwrite(int fd, const void *buf, size_t n, off_t off) {
  static ssize_t (*real)(int, const void *, size_t, off_t);
  if (!real) real = (ssize_t(*)(int, const void *, size_t, off_t))dlsym(RTLD_NEXT, "pwrite");
  if (faultfs_full(fd, n)) return errno = ENOSPC, -1;
  return real(fd, buf, n, off);
}

ssize_t pwrite64(int fd, const void *buf, size_t n, off64_t off) {
  static ssize_t (*real)(int, const void *, size_t, off64_t);
  if (!real) real = (ssize_t(*)(int, const void *, size_t, off64_t))dlsym(RTLD_NEXT, "pwrite64");
  if (faultfs_full(fd, n)) return errno = ENOSPC, -1;
  return real(fd, buf, n, off);
}
