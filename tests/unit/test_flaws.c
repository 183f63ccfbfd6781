/* Weibull flaws (tasks/damage/flaws.h, through src/io/ragged_io.h):
 *  - every brittle particle has at least one flaw, the others none;
 *  - the number of flaws per particle averaged over seeds matches the
 *    coupon-collector expectation H_N = ln N + 0.5772 + 1/(2N) within 4
 *    standard errors (sigma of one draw pi/sqrt(6) per particle);
 *  - the Weibull law holds exactly: the sorted thresholds are
 *    (j / (k V))^(1/m), so the count below eps is floor(k V eps^m);
 *  - slices ascending; reproducible from the seed; other materials' flaws
 *    kept; the bounded integer generator is uniform (chi-square);
 *  - HDF5 round trip (file layout and the engine's permuted layout) and the
 *    errors of bad files (one line, exit 1).
 * Exit 0 pass, 1 fail. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tasks/damage/flaws.h"
#include "src/error.h"
#include "src/io/ragged_io.h"
#include "src/materials/material.h"

static int failures = 0;

/** Report one check: measured error against its bound. */
static void check(const char *what, double err, double tol) {
  const int ok = err <= tol && err == err;
  printf("%-60s %10.3e  (tol %.0e)  %s\n", what, err, tol, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/** Compare doubles (qsort). */
static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/** Statistics of the Benz & Asphaug procedure. */
static void test_statistics(void) {
  enum { N = 30000, NB = 24000, SEEDS = 24 };
  static unsigned char brittle[N];
  for (size_t i = 0; i < N; i++) brittle[i] = (i % 5) != 2; /* 4 of 5 brittle */
  const double k = 5e34, m = 8, V = 1e-3;
  double mean_sum = 0;
  long bad_cover = 0, bad_other = 0, not_sorted = 0;
  for (int s = 0; s < SEEDS; s++) {
    struct flaws f;
    const int64_t drawn = flaws_generate(N, brittle, k, m, V, 1000 + s, NULL, &f);
    for (size_t i = 0; i < N; i++) {
      const int64_t c = f.offset[i + 1] - f.offset[i];
      if (brittle[i] && c < 1) bad_cover++;
      if (!brittle[i] && c != 0) bad_other++;
      for (int64_t j = f.offset[i] + 1; j < f.offset[i + 1]; j++)
        if (f.eps[j] < f.eps[j - 1]) not_sorted++;
    }
    if (f.offset[N] != drawn) bad_cover++;
    mean_sum += (double)drawn / NB;
    if (s == 0) {
      /* the Weibull law: sorted thresholds are (j/(kV))^(1/m) */
      double *all = malloc((size_t)drawn * sizeof *all);
      memcpy(all, f.eps, (size_t)drawn * sizeof *all);
      qsort(all, (size_t)drawn, sizeof *all, cmp_double);
      double worst = 0;
      for (int64_t j = 1; j <= drawn; j++)
        worst = fmax(worst, fabs(all[j - 1] / flaws_threshold(j, k, m, V) - 1));
      check("sorted thresholds = (j/(kV))^(1/m) (relative)", worst, 1e-13);
      /* count below eps = floor(k V eps^m) at eps between thresholds */
      long wrong = 0;
      for (int64_t j = 0; j < drawn; j += 97) {
        const double eps = pow((j + 0.5) / (k * V), 1 / m);
        int64_t below = 0;
        while (below < drawn && all[below] < eps) below++;
        if (below != (int64_t)floor(k * V * pow(eps, m))) wrong++;
      }
      check("#{eps_j < eps} = floor(k V eps^m) (mismatches)", wrong, 0);
      printf("N = %d brittle: %lld flaws, %.3f per particle (ln N = %.3f), %.1f bytes/particle\n",
             NB, (long long)drawn, (double)drawn / NB, log((double)NB),
             (double)flaws_bytes(&f) / N);
      free(all);
      /* reproducible: the same seed gives the same flaws, another differs */
      struct flaws g, h;
      flaws_generate(N, brittle, k, m, V, 1000, NULL, &g);
      flaws_generate(N, brittle, k, m, V, 1001, NULL, &h);
      check("same seed, same flaws (differences)",
            memcmp(f.offset, g.offset, (N + 1) * sizeof *f.offset) != 0 ||
                memcmp(f.eps, g.eps, (size_t)drawn * sizeof *f.eps) != 0,
            0);
      check("other seed, other flaws (1 if identical)",
            memcmp(f.offset, h.offset, (N + 1) * sizeof *f.offset) == 0, 0);
      /* a second material keeps the first's flaws */
      static unsigned char other[N];
      for (size_t i = 0; i < N; i++) other[i] = !brittle[i];
      struct flaws two;
      flaws_generate(N, other, 1e40, 9.1, 2e-4, 5, &f, &two);
      long changed = 0, uncovered = 0;
      for (size_t i = 0; i < N; i++) {
        const int64_t c = two.offset[i + 1] - two.offset[i];
        if (c < 1) uncovered++;
        if (brittle[i] &&
            (c != f.offset[i + 1] - f.offset[i] ||
             memcmp(two.eps + two.offset[i], f.eps + f.offset[i], (size_t)c * sizeof(double)) != 0))
          changed++;
      }
      check("second material: first material's flaws kept (changed)", changed, 0);
      check("second material: every particle has flaws (uncovered)", uncovered, 0);
      char msg[256];
      check("flaws_check accepts generated flaws", flaws_check(&two, msg, sizeof msg) != 0, 0);
      flaws_free(&two);
      flaws_free(&g);
      flaws_free(&h);
    }
    flaws_free(&f);
  }
  check("every brittle particle has a flaw (violations)", bad_cover, 0);
  check("non-brittle particles have none (violations)", bad_other, 0);
  check("slices ascending (violations)", not_sorted, 0);
  double H = 0;
  for (int i = 1; i <= NB; i++) H += 1.0 / i;
  const double mean = mean_sum / SEEDS, se = M_PI / sqrt(6.0) / sqrt((double)SEEDS);
  printf("flaws per particle: mean %.4f over %d seeds, H_N %.4f, ln N %.4f, standard error %.3f\n",
         mean, SEEDS, H, log((double)NB), se);
  check("mean flaws per particle - H_N (in standard errors)", fabs(mean - H) / se, 4);
}

/** Uniformity of flaws_rng_below by a chi-square test on 16 bins. */
static void test_rng(void) {
  struct flaws_rng r;
  flaws_rng_seed(&r, 0);
  enum { B = 16, DRAWS = 1600000 };
  long count[B] = {0};
  for (int i = 0; i < DRAWS; i++) count[flaws_rng_below(&r, B)]++;
  double chi2 = 0;
  for (int b = 0; b < B; b++) chi2 += pow(count[b] - DRAWS / B, 2) / (DRAWS / B);
  /* 15 degrees of freedom: P(chi2 > 37.7) = 0.001 */
  check("rng_below uniform: chi-square, 15 d.o.f.", chi2, 37.7);
  long out = 0;
  for (int i = 0; i < 100000; i++) out += flaws_rng_below(&r, 3) > 2;
  check("rng_below(3) in range (violations)", out, 0);
}

/** A minimal HDF5 file with an empty /PartType0. */
static void make_file(const char *path) {
  hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t g = H5Gcreate2(f, "PartType0", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Gclose(g);
  H5Fclose(f);
}

/** Overwrite /PartType0/NAME with n doubles or int64 values. */
static void put(const char *path, const char *name, const void *data, size_t n, int is_int) {
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t g = H5Gopen2(f, "PartType0", H5P_DEFAULT);
  if (H5Lexists(g, name, H5P_DEFAULT) > 0) H5Ldelete(g, name, H5P_DEFAULT);
  hsize_t dim = n;
  hid_t s = H5Screate_simple(1, &dim, NULL);
  hid_t d = H5Dcreate2(g, name, is_int ? H5T_STD_I64LE : H5T_IEEE_F64LE, s, H5P_DEFAULT,
                       H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, is_int ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  H5Dclose(d);
  H5Sclose(s);
  H5Gclose(g);
  H5Fclose(f);
}

/** Read path's flaws in a child process: its exit status (0 or 1) and the
 *  first line of its stderr in msg. */
static int read_in_child(const char *path, size_t n, char *msg, size_t len) {
  int fd[2];
  if (pipe(fd) != 0) return -1;
  fflush(NULL);
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fd[1], 2);
    close(fd[0]);
    struct flaws f;
    flaws_io_read(path, n, &f);
    _exit(0);
  }
  close(fd[1]);
  const ssize_t r = read(fd[0], msg, len - 1);
  msg[r > 0 ? r : 0] = 0;
  close(fd[0]);
  int status;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/** Round trip and bad files. */
static void test_io(void) {
  char path[] = "/tmp/test_flaws_XXXXXX";
  const int fd = mkstemp(path);
  close(fd);
  enum { N = 500 };
  static unsigned char brittle[N];
  for (int i = 0; i < N; i++) brittle[i] = i % 7 != 0;
  struct flaws f, g;
  flaws_generate(N, brittle, 1e30, 9, 1.0, 3, NULL, &f);
  make_file(path);
  struct flaws none;
  check("file without flaws: read returns 0", flaws_io_read(path, N, &none) != 0, 0);
  flaws_io_write_file(path, &f);
  const int got = flaws_io_read(path, N, &g);
  check("round trip: found", got != 1, 0);
  check("round trip: offsets and thresholds bit-exact",
        memcmp(f.offset, g.offset, (N + 1) * sizeof *f.offset) != 0 ||
            memcmp(f.eps, g.eps, (size_t)f.offset[N] * sizeof *f.eps) != 0,
        0);
  flaws_free(&g);

  /* the engine's layout: particles reversed, each pointing at its slice */
  int64_t first[N];
  int32_t count[N];
  for (int i = 0; i < N; i++) {
    first[i] = f.offset[N - 1 - i];
    count[i] = (int32_t)(f.offset[N - i] - f.offset[N - 1 - i]);
  }
  hid_t file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t grp = H5Gopen2(file, "PartType0", H5P_DEFAULT);
  const int rc = ragged_io_write_group(grp, &flaws_ragged, N, f.eps, first, count, 4);
  H5Gclose(grp);
  H5Fclose(file);
  flaws_io_read(path, N, &g);
  long wrong = rc != 0;
  for (int i = 0; i < N; i++) {
    const int64_t c = g.offset[i + 1] - g.offset[i];
    if (c != count[i] || memcmp(g.eps + g.offset[i], f.eps + first[i], (size_t)c * 8) != 0) wrong++;
  }
  check("engine layout (reversed particles, gzip) round trip (wrong)", wrong, 0);
  flaws_free(&g);

  /* bad files: one line naming the file, exit 1 */
  char msg[512];
  int st = read_in_child(path, N + 1, msg, sizeof msg);
  printf("  wrong N: %s", msg);
  check("wrong particle count: exit 1 with the file named",
        st == 1 && strstr(msg, path) && strstr(msg, "FlawOffsets") ? 0 : 1, 0);
  double eps_bad[3] = {2e-4, 1e-4, 3e-4};
  int64_t off_bad[N + 1];
  for (int i = 0; i <= N; i++) off_bad[i] = i < 1 ? 0 : 3;
  put(path, "FlawThresholds", eps_bad, 3, 0);
  put(path, "FlawOffsets", off_bad, N + 1, 1);
  st = read_in_child(path, N, msg, sizeof msg);
  printf("  descending: %s", msg);
  check("descending thresholds: exit 1", st == 1 && strstr(msg, "ascending") ? 0 : 1, 0);
  off_bad[N] = 7;
  put(path, "FlawOffsets", off_bad, N + 1, 1);
  st = read_in_child(path, N, msg, sizeof msg);
  printf("  inconsistent: %s", msg);
  check("offsets beyond the thresholds: exit 1", st == 1 && strstr(msg, "ends at") ? 0 : 1, 0);
  make_file(path);
  put(path, "FlawThresholds", eps_bad, 3, 0);
  st = read_in_child(path, N, msg, sizeof msg);
  printf("  half: %s", msg);
  check("thresholds without offsets: exit 1", st == 1 && strstr(msg, "both or neither") ? 0 : 1, 0);
  flaws_free(&f);
  unlink(path);
}

/** Start-up generation for a table of materials = one call per material. */
static void test_materials(void) {
  enum { N = 3000 };
  static int32_t mat[N];
  static double mass[N], rho[N];
  for (int i = 0; i < N; i++) {
    mat[i] = i % 3 == 0 ? 0 : i % 3 == 1 ? 4 : 9;
    mass[i] = 1e-3 * (1 + (i % 7));
    rho[i] = i % 11 == 0 ? 0.0 : 2000 + i % 5; /* some without density */
  }
  struct material_table t;
  material_table_init(&t);
  struct material m;
  char msg[256];
  const int32_t ids[3] = {0, 4, 9};
  const double wk[3] = {5e34, 0, 1e40}, wm[3] = {8, 0, 9.1};
  int ok = 1;
  for (int k = 0; k < 3; k++) {
    material_init(&m, ids[k], k == 0 ? "basalt" : k == 1 ? "water" : "ice", EOS_LIQUID);
    material_set(&m, "rho0", 2500, msg, sizeof msg);
    material_set(&m, "c0", 3000, msg, sizeof msg);
    if (wk[k] > 0) {
      material_set(&m, "weibull_k", wk[k], msg, sizeof msg);
      material_set(&m, "weibull_m", wm[k], msg, sizeof msg);
    }
    ok &= material_finalize(&m, msg, sizeof msg) == 0;
    if (!ok) printf("material: %s\n", msg);
    material_table_add(&t, &m);
  }
  struct flaws f, a, b;
  const int64_t total = flaws_generate_materials(N, mat, mass, rho, &t, 77, &f);
  /* the same by hand: material 0 then material 9 */
  static unsigned char s0[N], s9[N];
  double V0 = 0, V9 = 0;
  for (int i = 0; i < N; i++) {
    s0[i] = mat[i] == 0, s9[i] = mat[i] == 9;
    const double r = rho[i] > 0 ? rho[i] : 2500;
    if (s0[i]) V0 += mass[i] / r;
    if (s9[i]) V9 += mass[i] / r;
  }
  flaws_generate(N, s0, 5e34, 8, V0, 77 + 0, NULL, &a);
  flaws_generate(N, s9, 1e40, 9.1, V9, 77 + 9, &a, &b);
  long water = 0;
  for (int i = 0; i < N; i++) water += mat[i] == 4 && f.offset[i + 1] != f.offset[i];
  check("materials: = one flaws_generate per brittle material",
        ok && total == b.offset[N] && memcmp(f.offset, b.offset, (N + 1) * sizeof *f.offset) == 0 &&
                memcmp(f.eps, b.eps, (size_t)total * sizeof *f.eps) == 0
            ? 0
            : 1,
        0);
  check("materials: non-brittle material has no flaws (count)", water, 0);
  flaws_free(&f);
  flaws_free(&a);
  flaws_free(&b);
  material_table_free(&t);
}

int main(int argc, char **argv) {
  (void)argc;
  error_init(argv[0]);
  test_materials();
  test_rng();
  test_statistics();
  test_io();
  if (failures) printf("%d check(s) FAILED\n", failures);
  return failures ? 1 : 0;
}
