/* Test driver: print the N points of one stretched equal-area shell
 * (ic_sea_shell) of unit radius, one "x y z" line each. */
#include <stdio.h>
#include <stdlib.h>

#include "error.h"
#include "ic_planet.h"

int main(int argc, char **argv) {
  error_init(argv[0]);
  if (argc != 3) error_exit("usage: sea_shell_dump N SEED");
  const int N = atoi(argv[1]);
  if (N < 1 || N > 10000000) error_exit("N out of range: %s", argv[1]);
  uint64_t rng = (uint64_t)atol(argv[2]);
  double *x = error_malloc(3 * (size_t)N * sizeof(double), "shell");
  ic_sea_shell(N, x, x + N, x + 2 * N, &rng);
  for (int i = 0; i < N; i++) printf("%.17g %.17g %.17g\n", x[i], x[N + i], x[2 * N + i]);
  free(x);
  return 0;
}
