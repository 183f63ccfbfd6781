/* HDF5 round trip: a snapshot of random particles, read back with ic_read
 * (initial-condition fields) and with raw HDF5 calls (every other field),
 * must be bit-identical; a file in cgs read into SI must carry the SI values;
 * the header must come back. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "src/error.h"
#include "src/io/ic.h"
#include "src/io/snapshot.h"

static int failures = 0;

#define CHECK(cond, ...)                                   \
  do {                                                     \
    if (!(cond)) {                                         \
      fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__); \
      fprintf(stderr, __VA_ARGS__);                        \
      fprintf(stderr, "\n");                               \
      failures++;                                          \
    }                                                      \
  } while (0)

/** xorshift64*: a small reproducible generator. */
static uint64_t rng_state = 0x9e3779b97f4a7c15ULL;
static uint64_t rng_next(void) {
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return rng_state * 2685821657736338717ULL;
}
/** A double with random mantissa and a wide exponent range, sign chosen. */
static double rng_double(int positive) {
  const double mant = (double)(rng_next() >> 11) / 9007199254740992.0 + 0.5;
  const int ex = (int)(rng_next() % 61) - 30;
  const double v = ldexp(mant, ex);
  return (positive || (rng_next() & 1)) ? v : -v;
}

/** Fill every field with random values (positive mass and h, valid ids and
 *  the ranges ic_read checks). */
static void fill_random(struct parts *p, size_t n) {
  parts_alloc(p, n);
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *f = &part_fields[k];
    void *a = part_field_array(p, f);
    for (size_t i = 0; i < n; i++) {
      if (f->type == PART_DOUBLE) ((double *)a)[i] = rng_double(0);
      if (f->type == PART_INT32) ((int32_t *)a)[i] = (int32_t)(rng_next() % 4);
    }
  }
  for (size_t i = 0; i < n; i++) {
    p->m[i] = rng_double(1);
    p->h[i] = rng_double(1);
    /* the fields ic_read range-checks: energies and densities >= 0, damage in [0, 1] */
    p->u[i] = rng_double(1);
    p->rho[i] = rng_double(1);
    p->eps_p[i] = rng_double(1);
    p->dmg[i] = (double)(rng_next() >> 11) / 9007199254740992.0;
    p->dcbrt[i] = (double)(rng_next() >> 11) / 9007199254740992.0;
    p->dmg_shear[i] = (double)(rng_next() >> 11) / 9007199254740992.0;
    p->id[i] = (int64_t)(rng_next() >> 2) + (int64_t)i; /* unique with overwhelming odds */
  }
  p->id[0] = INT64_C(1) << 40; /* needs 64 bits */
}

/** Read dataset name as raw bytes of the field's type; compare with the
 *  components gathered from p. */
static void compare_raw(const char *path, const struct parts *p, int k) {
  const struct part_field *f = &part_fields[k];
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  char name[256];
  snprintf(name, sizeof name, "/PartType0/%s", f->h5name);
  hid_t d = H5Dopen2(file, name, H5P_DEFAULT);
  CHECK(d >= 0, "%s: no dataset %s", path, name);
  if (d < 0) {
    H5Fclose(file);
    return;
  }
  const size_t n = p->count, nc = (size_t)f->ncomp;
  char *buf = malloc(n * nc * f->size + 1);
  hid_t mt = f->type == PART_DOUBLE  ? H5T_NATIVE_DOUBLE
             : f->type == PART_INT64 ? H5T_NATIVE_INT64
                                     : H5T_NATIVE_INT32;
  CHECK(H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0, "read %s", name);
  hid_t ft = H5Dget_type(d);
  CHECK(H5Tget_size(ft) == f->size, "%s stored with %zu bytes, expected %zu", name, H5Tget_size(ft),
        f->size);
  H5Tclose(ft);
  for (size_t c = 0; c < nc; c++) {
    const char *a = part_field_array(p, &part_fields[k + (int)c]);
    for (size_t i = 0; i < n; i++)
      if (memcmp(buf + (i * nc + c) * f->size, a + i * f->size, f->size) != 0) {
        CHECK(0, "%s: %s[%zu][%zu] differs", path, f->h5name, i, c);
        i = n;
        c = nc;
      }
  }
  free(buf);
  H5Dclose(d);
  H5Fclose(file);
}

static void roundtrip(const char *path, int compression) {
  const size_t n = 1000;
  struct parts p, q;
  fill_random(&p, n);
  struct unit_system si;
  units_init_si(&si);
  struct snapshot_meta meta = {
      .time = 0.125,
      .box_size = {1.5, 2.5, 3.5},
      .periodic = 1,
      .compression = compression,
      .run_name = "roundtrip",
      .params = "MetaData:\n  run_name: roundtrip\nSPH:\n  resolution_eta: 1.2348\n"};
  snapshot_write(path, &meta, &p, &si, 1);

  struct ic_info info;
  ic_read(path, &si, NULL, 0, &q, &info);
  CHECK(q.count == n, "count %zu != %zu", q.count, n);
  CHECK(info.time == 0.125 && info.has_time, "time %g", info.time);
  CHECK(info.box_size[0] == 1.5 && info.box_size[1] == 2.5 && info.box_size[2] == 3.5, "box size");
  CHECK(info.periodic == 1, "periodic flag %d", info.periodic);
  int nread = 0;
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *f = &part_fields[k];
    const int ic_field = f->h5name && (f->flags & (PART_IC_REQ | PART_IC_OPT));
    CHECK(ic_field_read(&info, k) == ic_field, "field %s read=%d", f->name,
          ic_field_read(&info, k));
    if (ic_field && q.count == n) {
      nread++;
      CHECK(memcmp(part_field_array(&p, f), part_field_array(&q, f), n * f->size) == 0,
            "field %s differs after the round trip (compression %d)", f->name, compression);
    }
    if (snapshot_field_written(f, 0, 1) && f->comp == 0) compare_raw(path, &p, k);
  }
  CHECK(nread >= 10, "only %d fields compared", nread);
  parts_free(&p);
  parts_free(&q);
}

/** A file written in cgs, read into SI: every value scaled by the physical
 *  factor (written out here, independent of the unit module). */
static void cgs_to_si(const char *path) {
  const size_t n = 50;
  struct parts p, q;
  fill_random(&p, n);
  struct unit_system cgs, si;
  units_init_cgs(&cgs);
  units_init_si(&si);
  struct snapshot_meta meta = {.time = 2.0, .box_size = {100, 200, 300}};
  snapshot_write(path, &meta, &p, &cgs, 0);
  ic_read(path, &si, NULL, 0, &q, NULL);
  struct {
    const double *a, *b, factor;
    const char *what;
  } cases[] = {
      {p.x, q.x, 1e-2, "position cm -> m"},
      {p.vy, q.vy, 1e-2, "velocity cm/s -> m/s"},
      {p.m, q.m, 1e-3, "mass g -> kg"},
      {p.h, q.h, 1e-2, "smoothing length cm -> m"},
      {p.rho, q.rho, 1e3, "density g/cm^3 -> kg/m^3"},
      {p.u, q.u, 1e-4, "specific energy erg/g -> J/kg"},
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
    for (size_t i = 0; i < n; i++) {
      const double want = cases[c].a[i] * cases[c].factor;
      if (fabs(cases[c].b[i] - want) > 4e-16 * fabs(want)) {
        CHECK(0, "%s: particle %zu: %.17g, expected %.17g", cases[c].what, i, cases[c].b[i], want);
        break;
      }
    }
  CHECK(memcmp(p.id, q.id, n * sizeof *p.id) == 0, "ids changed by unit conversion");
  parts_free(&p);
  parts_free(&q);
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  char dir[] = "/tmp/bolide-io-XXXXXX";
  if (!mkdtemp(dir)) return 1;
  char a[256], b[256], c[256], x[256];
  snprintf(a, sizeof a, "%s/plain.hdf5", dir);
  snprintf(b, sizeof b, "%s/gzip.hdf5", dir);
  snprintf(c, sizeof c, "%s/cgs.hdf5", dir);
  roundtrip(a, 0);
  roundtrip(b, 6);
  cgs_to_si(c);
  /* no temporary files left, the XDMF files exist */
  snprintf(x, sizeof x, "%s/plain.hdf5.tmp", dir);
  CHECK(access(x, F_OK) != 0, "temporary file %s left behind", x);
  snprintf(x, sizeof x, "%s/plain.xmf", dir);
  CHECK(access(x, F_OK) == 0, "no XDMF file %s", x);
  char cmd[512];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) return 1;
  if (failures) fprintf(stderr, "%d failures\n", failures);
  printf("%s\n", failures ? "FAIL" : "PASS");
  return failures ? 1 : 0;
}
