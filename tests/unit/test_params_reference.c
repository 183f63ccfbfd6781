/* The reference parameter file examples/parameters.yml is what
 * params_write_reference() writes (byte for byte), and it is a valid
 * parameter file (params_read accepts it, placeholders included).
 *
 *   test_params_reference             check (make check)
 *   test_params_reference --write F   regenerate F (examples/parameters.yml) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "src/error.h"
#include "tasks/hydro/kernel.h"
#include "src/io/params.h"

/** Whole content of a file (malloc'd), or NULL; *len gets its size. */
static char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  char *s = NULL;
  size_t n = 0, cap = 0, r;
  do {
    if (n + 4096 > cap) s = error_realloc(s, cap = 2 * (n + 4096), "file");
    r = fread(s + n, 1, cap - n, f);
    n += r;
  } while (r > 0);
  fclose(f);
  *len = n;
  return s;
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  if (argc == 3 && strcmp(argv[1], "--write") == 0) {
    FILE *f = fopen(argv[2], "w");
    if (!f) error_exit("%s: cannot write", argv[2]);
    params_write_reference(f);
    if (fclose(f) != 0) error_exit("%s: cannot write", argv[2]);
    return 0;
  }
  /* the file is that of the default build: SPH:resolution_eta's default
   * depends on the kernel (KERNEL_ETA_DEFAULT, tasks/hydro/kernel.h) */
  if (KERNEL_TYPE != KERNEL_TYPE_WENDLAND_C2) {
    printf(
        "SKIP: examples/parameters.yml is written for the default kernel (wendland-C2), "
        "this build has %s\n",
        kernel_name);
    return 77;
  }
  const char *src = getenv("BOLIDE_SRCDIR");
  if (!src) src = BOLIDE_SRCDIR;
  char ref[4096], tmp[] = "/tmp/test_params_reference_XXXXXX";
  snprintf(ref, sizeof ref, "%s/examples/parameters.yml", src);
  int fd = mkstemp(tmp);
  if (fd < 0) error_exit("cannot make a temporary file");
  FILE *f = fdopen(fd, "w");
  params_write_reference(f);
  fclose(f);
  size_t n_new, n_old;
  char *fresh = slurp(tmp, &n_new), *old = slurp(ref, &n_old);
  int ok = old && n_new == n_old && memcmp(fresh, old, n_new) == 0;
  if (!ok)
    fprintf(stderr,
            "test_params_reference: %s differs from params_write_reference(); regenerate "
            "it with: tests/unit/test_params_reference --write %s\n",
            ref, ref);
  /* the generated text must read back (both the fresh one and the file) */
  struct params *p = params_read(tmp, 0, NULL);
  int keys_ok = params_get_real(p, "TimeIntegration:time_end") > 0 &&
                strcmp(params_get_string(p, "InitialConditions:file_name"), "ics.hdf5") == 0;
  if (!keys_ok) fprintf(stderr, "test_params_reference: placeholders not read back\n");
  params_free(p);
  if (old) params_free(params_read(ref, 0, NULL));
  unlink(tmp);
  free(fresh);
  free(old);
  return ok && keys_ok ? 0 : 1;
}
