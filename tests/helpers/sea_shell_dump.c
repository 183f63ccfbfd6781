/* Test driver: the N points of one stretched equal-area shell
 * (ic_sea_shell) of unit radius.
 *
 *   sea_shell_dump [-b | -s] [-a A] N SEED
 *
 * prints one "x y z" line per point, or with -b writes the 3 N doubles
 * x0 y0 z0 x1 ... in binary (native byte order) to stdout, or with -s
 * prints "N largest |rho_SPH / median - 1| kernel" of the shell (unit
 * masses, the compiled-in kernel and its default resolution_eta,
 * KERNEL_ETA_DEFAULT, Bolide's C estimator ic_sph_density); -a A uses
 * ic_sea_shell_a with stretching parameter A (b = 10 A) instead of
 * ic_sea_shell's own choice. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "src/error.h"
#include "tools/ic/ic_planet.h"
#include "tasks/hydro/kernel.h"

static int cmp_double(const void *p, const void *q) {
  const double a = *(const double *)p, b = *(const double *)q;
  return (a > b) - (a < b);
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  int binary = 0, spread = 0, arg = 1;
  double a = -1;
  while (arg < argc && argv[arg][0] == '-') {
    if (!strcmp(argv[arg], "-b")) {
      binary = 1, arg++;
    } else if (!strcmp(argv[arg], "-s")) {
      spread = 1, arg++;
    } else if (!strcmp(argv[arg], "-a") && arg + 1 < argc) {
      char *end;
      a = strtod(argv[arg + 1], &end);
      if (*end || !(a >= 0)) error_exit("bad stretching parameter -a %s", argv[arg + 1]);
      arg += 2;
    } else {
      error_exit("unknown option %s", argv[arg]);
    }
  }
  if (argc - arg != 2) error_exit("usage: sea_shell_dump [-b | -s] [-a A] N SEED");
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
  if (spread) {
    double *w = error_malloc(3 * (size_t)N * sizeof(double), "shell");
    double *m = w, *h = w + N, *rho = w + 2 * N;
    for (long i = 0; i < N; i++) m[i] = 1, h[i] = KERNEL_ETA_DEFAULT * sqrt(4 * M_PI / (double)N);
    ic_sph_density((size_t)N, x, x + N, x + 2 * N, m, KERNEL_ETA_DEFAULT, h, rho);
    memcpy(h, rho, (size_t)N * sizeof(double));
    qsort(h, (size_t)N, sizeof(double), cmp_double);
    const double med = N % 2 ? h[N / 2] : 0.5 * (h[N / 2 - 1] + h[N / 2]);
    double d = 0;
    for (long i = 0; i < N; i++) d = fmax(d, fabs(rho[i] / med - 1));
    printf("%ld %.9f %s\n", N, d, BOLIDE_KERNEL_NAME);
    free(w);
  } else if (binary) {
    double *buf = error_malloc(3 * (size_t)N * sizeof(double), "shell");
    for (long i = 0; i < N; i++)
      buf[3 * i] = x[i], buf[3 * i + 1] = x[N + i], buf[3 * i + 2] = x[2 * N + i];
    if (fwrite(buf, sizeof(double), 3 * (size_t)N, stdout) != 3 * (size_t)N)
      error_exit("write failed");
    free(buf);
  } else {
    for (long i = 0; i < N; i++) printf("%.17g %.17g %.17g\n", x[i], x[N + i], x[2 * N + i]);
  }
  free(x);
  return 0;
}
