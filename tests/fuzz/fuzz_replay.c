/* Replays inputs through a libFuzzer harness without libFuzzer: links with
 * one tests/fuzz/fuzz_*.c (any compiler) and calls its
 * LLVMFuzzerTestOneInput on every file named on the command line.  The
 * corpus of tests/data/fuzz (every crash the fuzzers found) is replayed so
 * by tests/program/test_fuzz_corpus.sh in every build, the sanitizer builds too. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    FILE *f = fopen(argv[i], "rb");
    if (!f) {
      perror(argv[i]);
      return 1;
    }
    size_t cap = 1 << 16, n = 0, got;
    uint8_t *buf = malloc(cap);
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0)
      if ((n += got) == cap) buf = realloc(buf, cap *= 2);
    fclose(f);
    if (!buf) return 1;
    LLVMFuzzerTestOneInput(buf, n);
    free(buf);
    printf("replayed %s (%zu bytes)\n", argv[i], n);
  }
  return 0;
}
