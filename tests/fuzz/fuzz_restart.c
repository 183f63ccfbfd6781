/* libFuzzer harness of the restart reader: the input is the content of a
 * restart file (restart.bin in a private folder).  Every input must be
 * loaded or refused through error_exit: no crash, no out-of-bounds access,
 * no allocation sized by an unchecked count. */
#include <sys/stat.h>

#include "fuzz_common.h"
#include "restart.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char dir[256], file[300];

/** Remove the private folder at exit. */
static void fuzz_restart_cleanup(void) {
  unlink(file);
  rmdir(dir);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fuzz_quiet();
  if (!dir[0]) {
    snprintf(dir, sizeof dir, "%s", fuzz_path(".restart"));
    mkdir(dir, 0700);
    snprintf(file, sizeof file, "%s/restart.bin", dir);
    atexit(fuzz_restart_cleanup);
  }
  if (fuzz_write_file(file, data, size)) return 0;
  static struct parts p;
  memset(&p, 0, sizeof p);
  struct restart_state st;
  double *eps = NULL;
  int64_t nflaws = 0;
  if (setjmp(fuzz_env) == 0) {
    restart_read(dir, &st, &p, &eps, &nflaws);
    parts_free(&p);
    free(eps);
  }
  unlink(file);
  return 0;
}
