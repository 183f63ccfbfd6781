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

/** The fields a run never uses (parts_drop): not held, zeros in a snapshot
 *  (the layout unchanged), left absent by parts_reserve, parts_alloc_like,
 *  parts_permute and parts_copy_one; ic_read_unused leaves them out of a
 *  file without them and holds every field of a file with one of them. */
static void dropped(const char *path, const char *bare) {
  const size_t n = 200;
  struct parts p, q;
  fill_random(&p, n);
  for (size_t i = 0; i < n; i++) p.id[i] = (int64_t)i + 1;
  size_t dropped_bytes = 0;
  unsigned char unused[PART_NR_FIELDS] = {0};
  for (int g = 0; g < 2; g++) {
    const char *const *l = g ? part_damage_fields : part_solid_fields;
    const int nl = g ? part_nr_damage_fields : part_nr_solid_fields;
    for (int k = 0; k < part_nr_fields; k++)
      for (int j = 0; j < nl; j++)
        if (!strcmp(part_fields[k].name, l[j])) {
          unused[k] = 1;
          dropped_bytes += part_fields[k].size;
        }
  }
  CHECK(dropped_bytes == 384, "the solid and damage fields are %zu bytes, not 384", dropped_bytes);
  const double x1 = p.x[1], m1 = p.m[1];
  CHECK(parts_drop(&p, part_solid_fields, part_nr_solid_fields) +
                parts_drop(&p, part_damage_fields, part_nr_damage_fields) ==
            dropped_bytes,
        "parts_drop's bytes");
  CHECK(parts_drop(&p, part_solid_fields, part_nr_solid_fields) == 0, "dropped twice");
  CHECK(parts_bytes_held(&p) == parts_bytes_per_particle() - dropped_bytes,
        "held %zu bytes per particle", parts_bytes_held(&p));
  CHECK(p.Sxx == NULL && p.dmg == NULL && p.flaw_first == NULL && p.x != NULL,
        "the dropped arrays are not NULL");
  for (int k = 0; k < part_nr_fields; k++)
    CHECK(!unused[k] == (part_field_array(&p, &part_fields[k]) != NULL) && p.absent[k] == unused[k],
          "field %s held %d", part_fields[k].name, part_field_array(&p, &part_fields[k]) != NULL);
  parts_reserve(&p, 3 * n);
  CHECK(p.Sxx == NULL && p.dmg_rate == NULL && p.capacity == 3 * n, "parts_reserve");
  parts_copy_one(&p, 0, 1);
  size_t *perm = malloc(n * sizeof *perm);
  for (size_t i = 0; i < n; i++) perm[i] = n - 1 - i;
  parts_permute(&p, perm);
  free(perm);
  CHECK(p.x[n - 1] == x1 && p.m[n - 1] == m1, "parts_copy_one, parts_permute");
  for (size_t i = 0; i < n; i++)
    p.x[i] = (double)i, p.id[i] = (int64_t)i + 1; /* (distinct again) */
  struct parts c;
  parts_alloc_like(&c, 5, &p);
  CHECK(c.Sxx == NULL && c.Rzz == NULL && c.x != NULL && c.absent[0] == 0, "parts_alloc_like");
  parts_free(&c);

  /* the snapshot: every dataset there, the dropped ones zero */
  struct unit_system si;
  units_init_si(&si);
  struct snapshot_meta meta = {.time = 0.5, .box_size = {1, 1, 1}, .run_name = "dropped"};
  snapshot_write(path, &meta, &p, &si, 0);
  struct ic_info info;
  ic_read(path, &si, NULL, 0, &q, &info);
  CHECK(q.count == n && q.Sxx != NULL, "the snapshot read back");
  for (size_t i = 0; i < n && q.count == n; i++)
    if (q.Sxx[i] != 0.0 || q.Szz[i] != 0.0 || q.dmg[i] != 0.0 || q.eps_p[i] != 0.0 ||
        q.x[i] != p.x[i]) {
      CHECK(0, "particle %zu: S %g %g, d %g, eps_p %g, x %g (%g)", i, q.Sxx[i], q.Szz[i], q.dmg[i],
            q.eps_p[i], q.x[i], p.x[i]);
      break;
    }
  parts_free(&q);
  /* a file with one of them (the snapshot's zeros): every field held */
  ic_read_unused(path, &si, NULL, 0, &q, NULL, unused);
  CHECK(q.Sxx != NULL && q.dmg != NULL && parts_bytes_held(&q) == parts_bytes_per_particle(),
        "ic_read_unused: a file with DeviatoricStress: every field held");
  parts_free(&q);
  /* a file without them: left out */
  snapshot_write(bare, &meta, &p, &si, 0);
  hid_t file = H5Fopen(bare, H5F_ACC_RDWR, H5P_DEFAULT);
  for (int k = 0; k < part_nr_fields; k++)
    if (unused[k] && part_fields[k].h5name && part_fields[k].comp == 0) {
      char name[128];
      snprintf(name, sizeof name, "/PartType0/%s", part_fields[k].h5name);
      if (H5Lexists(file, name, H5P_DEFAULT) > 0) H5Ldelete(file, name, H5P_DEFAULT);
    }
  H5Fclose(file);
  ic_read_unused(bare, &si, NULL, 0, &q, NULL, unused);
  CHECK(q.count == n && q.Sxx == NULL && q.dmg == NULL && q.x != NULL &&
            parts_bytes_held(&q) == parts_bytes_per_particle() - dropped_bytes,
        "ic_read_unused: a file without them: %zu bytes per particle held", parts_bytes_held(&q));
  for (size_t i = 0; i < n && q.count == n; i++)
    if (q.x[i] != p.x[i] || q.m[i] != p.m[i]) {
      CHECK(0, "ic_read_unused: particle %zu differs", i);
      break;
    }
  parts_free(&q);
  parts_free(&p);
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
  char d[256], e[256];
  snprintf(d, sizeof d, "%s/dropped.hdf5", dir);
  snprintf(e, sizeof e, "%s/bare.hdf5", dir);
  dropped(d, e);
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
