/* Test driver: the N points of one stretched equal-area shell
 * (ic_sea_shell) of unit radius.
 *
 *   sea_shell_dump [-b] [-a A] N SEED
 *
 * prints one "x y z" line per point, or with -b writes the 3 N doubles
 * x0 y0 z0 x1 ... in binary (native byte order) to stdout; -a A uses
 * ic_sea_shell_a with stretching parameter A (b = 10 A) instead of
 * ic_sea_shell's own choice. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "ic_planet.h"

int main(int argc, char **argv) {
  error_init(argv[0]);
  int binary = 0, arg = 1;
  double a = -1;
  while (arg < argc && argv[arg][0] == '-') {
    if (!strcmp(argv[arg], "-b")) {
      binary = 1, arg++;
    } else if (!strcmp(argv[arg], "-a") && arg + 1 < argc) {
      char *end;
      a = strtod(argv[arg + 1], &end);
      if (*end || !(a >= 0)) error_exit("bad stretching parameter -a %s", argv[arg + 1]);
      arg += 2;
    } else {
      error_exit("unknown option %s", argv[arg]);
    }
  }
  if (argc - arg != 2) error_exit("usage: sea_shell_dump [-b] [-a A] N SEED");
  char *end;
  const long N = strtol(argv[arg], &end, 10);
  if (*end || N < 1 || N > 10000000) error_exit("N out of range: %s", argv[arg]);
  uint64_t rng = (uint64_t)strtoull(argv[arg + 1], &end, 10);
  if (*end) error_exit("bad seed %s", argv[arg + 1]);
  double *x = error_malloc(3 * (size_t)N * sizeof(double), "shell");
  if (a >= 0)
    ic_sea_shell_a((int)N, a, x, x + N, x + 2 * N, &rng);
  else
    ic_sea_shell((int)N, x, x + N, x + 2 * N, &rng);
  if (binary) {
    double *buf = error_malloc(3 * (size_t)N * sizeof(double), "shell");
    for (long i = 0; i < N; i++) buf[3 * i] = x[i], buf[3 * i + 1] = x[N + i], buf[3 * i + 2] = x[2 * N + i];
    if (fwrite(buf, sizeof(double), 3 * (size_t)N, stdout) != 3 * (size_t)N) error_exit("write failed");
    free(buf);
  } else {
    for (long i = 0; i < N; i++) printf("%.17g %.17g %.17g\n", x[i], x[N + i], x[2 * N + i]);
  }
  free(x);
  return 0;
}
