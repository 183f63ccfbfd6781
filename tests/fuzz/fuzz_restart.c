/* libFuzzer harness of the restart reader: the input is the content of a
 * restart file, parsed and validated by restart_read_buffer (the reader of
 * --restart reads the file into memory and calls it).  Every input must be
 * loaded or refused with one line: no crash, no out-of-bounds access, no
 * allocation sized by an unchecked count. */
#include "fuzz_common.h"
#include "restart.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fuzz_quiet();
  struct restart_data d;
  char err[1024];
  if (setjmp(fuzz_env) == 0) {
    if (restart_read_buffer(data, size, "fuzz.bin", NULL, &d, err, sizeof err) == 0) restart_data_free(&d);
  }
  return 0;
}
