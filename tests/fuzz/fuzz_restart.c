/* libFuzzer harness of the restart reader: the input is the content of a
 * restart file, parsed and validated by restart_read_buffer (the reader of
 * --restart reads the file into memory and calls it).  Every input must be
 * loaded or refused with one line: no crash, no out-of-bounds access, no
 * allocation sized by an unchecked count.
 *
 * A mutated file almost never keeps its checksum, so that the fuzzer would
 * only test the checksum: inputs of even length are first repaired (the
 * header's payload length, the parameter hash and the final checksum made
 * to match the bytes), so that the validation of every field behind them is
 * reached; inputs of odd length are read as they are. */
#include "tests/fuzz/fuzz_common.h"
#include "src/part.h"
#include "src/io/restart.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/** Make the header's payload length, the parameter hash and the checksum of
 *  the file in buf (len bytes) match its content, where they can be found. */
static void fuzz_restart_repair(unsigned char *buf, size_t len) {
  if (len < RESTART_HEADER_BYTES + 8) return;
  const uint64_t payload = len - RESTART_HEADER_BYTES - 8;
  memcpy(buf + 88, &payload, 8);
  const size_t ppos =
      RESTART_HEADER_BYTES + 4 + (size_t)part_nr_fields * 36 + sizeof(struct restart_state);
  uint64_t plen;
  if (ppos + 8 <= len - 8) {
    memcpy(&plen, buf + ppos, 8);
    if (plen <= len - 8 - ppos - 8) {
      const uint64_t phash = restart_checksum(buf + ppos + 8, (size_t)plen, RESTART_HASH_INIT);
      memcpy(buf + 80, &phash, 8);
    }
  }
  const uint64_t sum = restart_checksum(buf, len - 8, RESTART_HASH_INIT);
  memcpy(buf + len - 8, &sum, 8);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fuzz_quiet();
  unsigned char *buf = malloc(size ? size : 1);
  memcpy(buf, data, size);
  if (size % 2 == 0) fuzz_restart_repair(buf, size);
  struct restart_data d;
  char err[1024];
  if (setjmp(fuzz_env) == 0) {
    if (restart_read_buffer(buf, size, "fuzz.bin", NULL, &d, err, sizeof err) == 0)
      restart_data_free(&d);
  }
  free(buf);
  return 0;
}
