/* Shared by the libFuzzer harnesses (tests/fuzz/fuzz_*.c, built and run by
 * tools/fuzz.sh, `make fuzz`): the readers stop on bad input through
 * error_exit, which here jumps back to the harness instead of exiting, so
 * that one process tries millions of inputs.  What the reader had allocated
 * before the jump is leaked (run with -detect_leaks=0; tools/fuzz.sh runs
 * the harnesses in fork mode, whose jobs are restarted every few minutes),
 * and open HDF5 objects are closed by fuzz_close_hdf5. */
#ifndef BOLIDE_FUZZ_COMMON_H
#define BOLIDE_FUZZ_COMMON_H

#include <hdf5.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "src/error.h"

static jmp_buf fuzz_env;

static inline void fuzz_jump(void) {
  longjmp(fuzz_env, 1);
}

/** A file name private to this process under /dev/shm (or /tmp). */
static inline const char *fuzz_path(const char *suffix) {
  static char path[256];
  const char *dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
  snprintf(path, sizeof path, "%s/bolide-fuzz-%d%s", dir, (int)getpid(), suffix);
  return path;
}

/** Write size bytes to path; 0 on success. */
static inline int fuzz_write_file(const char *path, const uint8_t *data, size_t size) {
  FILE *f = fopen(path, "wb");
  if (!f) return -1;
  const int ok = fwrite(data, 1, size, f) == size;
  return fclose(f) == 0 && ok ? 0 : -1;
}

/** Close every HDF5 object still open (a reader that stopped half-way). */
static inline void fuzz_close_hdf5(void) {
  const ssize_t n = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
  if (n <= 0) return;
  hid_t *ids = malloc((size_t)n * sizeof *ids);
  const ssize_t m = H5Fget_obj_ids(H5F_OBJ_ALL, H5F_OBJ_ALL, (size_t)n, ids);
  for (int pass = 0; pass < 2; pass++) /* objects first, then the files */
    for (ssize_t i = 0; i < m; i++) {
      const H5I_type_t t = H5Iget_type(ids[i]);
      if (pass == 0 && t == H5I_ATTR) H5Aclose(ids[i]);
      if (pass == 0 && t == H5I_DATASET) H5Dclose(ids[i]);
      if (pass == 0 && t == H5I_GROUP) H5Gclose(ids[i]);
      if (pass == 0 && t == H5I_DATATYPE) H5Tclose(ids[i]);
      if (pass == 1 && t == H5I_FILE) H5Fclose(ids[i]);
    }
  free(ids);
}

/** Route error_exit to fuzz_jump (once).  The error lines of refused
 *  inputs are hidden by running with -close_fd_mask=3 (tools/fuzz.sh). */
static inline void fuzz_quiet(void) {
  error_exit_hook = fuzz_jump;
}

#endif
