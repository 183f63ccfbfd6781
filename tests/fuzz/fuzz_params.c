/* libFuzzer harness of the parameter reader: the input is a parameter file,
 * optionally followed by a NUL byte and -P overrides, one per line.  Every
 * input must either be read (and then its units and materials set up as
 * bolide does) or be refused through error_exit: no crash, no hang, no
 * sanitizer report. */
#include "tests/fuzz/fuzz_common.h"
#include "src/materials/material.h"
#include "src/io/params.h"
#include "src/io/units.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/** Read the file with its overrides and set up units and materials; a
 *  refused input returns through fuzz_jump (what it allocated is leaked, see
 *  fuzz_common.h). */
static void fuzz_params_read(const char *path, int nover, char **over) {
  if (setjmp(fuzz_env)) return;
  struct params *p = params_read(path, nover, over);
  struct unit_system us;
  units_init_from_params(&us, p);
  struct material_table *mats = calloc(1, sizeof *mats);
  material_table_init(mats);
  material_table_from_params(mats, p);
  FILE *f = fopen("/dev/null", "w");
  if (f) {
    params_write_yaml(p, f);
    fclose(f);
  }
  free(params_to_string(p));
  material_table_free(mats);
  free(mats);
  params_free(p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fuzz_quiet();
  const uint8_t *nul = memchr(data, 0, size);
  const size_t ylen = nul ? (size_t)(nul - data) : size;
  const char *path = fuzz_path(".yml");
  if (fuzz_write_file(path, data, ylen)) return 0;
  /* overrides: the lines after the NUL */
  char *text = NULL, *over[16];
  int nover = 0;
  if (nul) {
    const size_t olen = size - ylen - 1;
    text = malloc(olen + 1);
    memcpy(text, nul + 1, olen);
    text[olen] = '\0';
    for (char *line = strtok(text, "\n"); line && nover < 16; line = strtok(NULL, "\n"))
      over[nover++] = line;
  }
  fuzz_params_read(path, nover, over);
  free(text);
  unlink(path);
  return 0;
}
