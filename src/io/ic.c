/* Initial conditions from HDF5: see ic.h.
 *
 * Accepted layout: /Header (BoxSize scalar or 3-vector, NumPart_Total with
 * NumPart_Total_HighWord, Time, Dimension), /Units (SWIFT's names), and in
 * /PartType0 one dataset per field of BOLIDE_PART_FIELDS flagged PART_IC_REQ
 * or PART_IC_OPT, under Bolide's (SWIFT's snapshot) name or the singular
 * GADGET-style aliases that woma and SEAGen also write.  A periodic flag is
 * taken from /RuntimePars/PeriodicBoundariesOn (SWIFT, woma) or
 * /Header/Periodic. */
#include "src/io/ic.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"

/** Other names of a dataset found in files made by other tools. */
static const char *const ic_aliases[][3] = {
    {"SmoothingLengths", "SmoothingLength", NULL},
    {"InternalEnergies", "InternalEnergy", NULL},
    {"Densities", "Density", NULL},
    {"MaterialIDs", "MaterialID", NULL},
    {"Masses", "Mass", NULL},
};

/** State of the file being read. */
struct ic_reader {
  const char *path; /**< file name for messages */
  hid_t file;       /**< HDF5 file */
};

/** Does link `name` exist under loc?  (H5Lexists fails on a missing parent.) */
static int ic_exists(hid_t loc, const char *name) {
  return H5Lexists(loc, name, H5P_DEFAULT) > 0;
}

/** Read attribute `name` of object `obj` as up to maxn doubles; returns the
 *  number of values (0 if absent).  Stops if it holds more than maxn. */
static int ic_attr_doubles(struct ic_reader *r, hid_t obj, const char *objname, const char *name,
                           double *out, int maxn) {
  if (H5Aexists(obj, name) <= 0) return 0;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  if (a < 0) error_exit("%s: cannot open attribute %s/%s", r->path, objname, name);
  hid_t space = H5Aget_space(a);
  hssize_t n = H5Sget_simple_extent_npoints(space);
  hid_t type = H5Aget_type(a);
  H5T_class_t cls = H5Tget_class(type);
  if (cls != H5T_INTEGER && cls != H5T_FLOAT)
    error_exit("%s: attribute %s/%s is not numeric", r->path, objname, name);
  if (n < 1 || n > maxn)
    error_exit("%s: attribute %s/%s has %lld values (expected 1 to %d)", r->path, objname, name,
               (long long)n, maxn);
  if (H5Aread(a, H5T_NATIVE_DOUBLE, out) < 0)
    error_exit("%s: cannot read attribute %s/%s", r->path, objname, name);
  H5Tclose(type);
  H5Sclose(space);
  H5Aclose(a);
  return (int)n;
}

/** Same for integers (NumPart_Total and friends, up to 2^63). */
static int ic_attr_llongs(struct ic_reader *r, hid_t obj, const char *objname, const char *name,
                          long long *out, int maxn) {
  if (H5Aexists(obj, name) <= 0) return 0;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  if (a < 0) error_exit("%s: cannot open attribute %s/%s", r->path, objname, name);
  hid_t space = H5Aget_space(a);
  hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n < 1 || n > maxn)
    error_exit("%s: attribute %s/%s has %lld values (expected 1 to %d)", r->path, objname, name,
               (long long)n, maxn);
  if (H5Aread(a, H5T_NATIVE_LLONG, out) < 0)
    error_exit("%s: cannot read attribute %s/%s as integers", r->path, objname, name);
  H5Sclose(space);
  H5Aclose(a);
  return (int)n;
}

/** /Units (SWIFT's attribute names); internal units with a log line if absent. */
static void ic_read_units(struct ic_reader *r, const struct unit_system *internal,
                          struct ic_info *info) {
  info->file_units = *internal;
  info->has_units = ic_exists(r->file, "Units");
  if (!info->has_units) {
    error_log(0, "%s: no /Units group: values are taken to be in internal units", r->path);
    return;
  }
  hid_t g = H5Gopen2(r->file, "Units", H5P_DEFAULT);
  if (g < 0) error_exit("%s: cannot open group /Units", r->path);
  static const char *const names[5] = {"Unit mass in cgs (U_M)", "Unit length in cgs (U_L)",
                                       "Unit time in cgs (U_t)", "Unit current in cgs (U_I)",
                                       "Unit temperature in cgs (U_T)"};
  double *dst[5] = {&info->file_units.mass_cgs, &info->file_units.length_cgs,
                    &info->file_units.time_cgs, &info->file_units.current_cgs,
                    &info->file_units.temperature_cgs};
  for (int i = 0; i < 5; i++) {
    double v;
    if (ic_attr_doubles(r, g, "/Units", names[i], &v, 1) == 0) {
      if (i < 3) error_exit("%s: /Units has no attribute \"%s\"", r->path, names[i]);
      continue; /* current and temperature: keep the internal ones */
    }
    if (!(v > 0) || !isfinite(v))
      error_exit("%s: /Units \"%s\" is %g (must be positive)", r->path, names[i], v);
    *dst[i] = v;
  }
  H5Gclose(g);
}

/** /Header: box size, particle count, time, dimension; /RuntimePars. */
static long long ic_read_header(struct ic_reader *r, struct ic_info *info) {
  long long count = -1;
  info->periodic = -1;
  info->dimension = 3;
  if (ic_exists(r->file, "Header")) {
    hid_t g = H5Gopen2(r->file, "Header", H5P_DEFAULT);
    if (g < 0) error_exit("%s: cannot open group /Header", r->path);
    double box[3];
    int nb = ic_attr_doubles(r, g, "/Header", "BoxSize", box, 3);
    if (nb == 2) error_exit("%s: /Header/BoxSize has 2 values (expected 1 or 3)", r->path);
    for (int d = 0; d < nb; d++)
      if (!isfinite(box[d]) || box[d] < 0)
        error_exit("%s: /Header/BoxSize is %g (must be finite and >= 0)", r->path, box[d]);
    if (nb > 0) {
      info->has_box_size = 1;
      for (int d = 0; d < 3; d++) info->box_size[d] = box[nb == 3 ? d : 0];
    }
    double t;
    if (ic_attr_doubles(r, g, "/Header", "Time", &t, 1)) {
      if (!isfinite(t)) error_exit("%s: /Header/Time is %g (must be finite)", r->path, t);
      info->has_time = 1;
      info->time = t;
    }
    long long dim;
    if (ic_attr_llongs(r, g, "/Header", "Dimension", &dim, 1)) {
      if (dim != 3) error_exit("%s: /Header/Dimension is %lld (Bolide is 3-D)", r->path, dim);
      info->dimension = (int)dim;
    }
    /* 6 particle types in GADGET files, 7 in current SWIFT ones: accept up to 16 */
    long long tot[16] = {0}, high[16] = {0};
    const int ntypes = ic_attr_llongs(r, g, "/Header", "NumPart_Total", tot, 16);
    if (ntypes) {
      ic_attr_llongs(r, g, "/Header", "NumPart_Total_HighWord", high, 16);
      if (tot[0] < 0 || tot[0] > UINT32_MAX || high[0] < 0 || high[0] > INT32_MAX)
        error_exit("%s: /Header/NumPart_Total%s[0] is %lld (must be in [0, 2^32))", r->path,
                   tot[0] < 0 || tot[0] > UINT32_MAX ? "" : "_HighWord",
                   tot[0] < 0 || tot[0] > UINT32_MAX ? tot[0] : high[0]);
      /* SWIFT's convention: N = HighWord * 2^32 + Total */
      count = (long long)((unsigned long long)high[0] << 32) + tot[0];
      for (int t2 = 1; t2 < ntypes; t2++)
        if (tot[t2] != 0 || high[t2] != 0)
          error_log(0, "%s: particles of type %d are ignored (only PartType0 is read)", r->path,
                    t2);
    }
    long long per;
    if (ic_attr_llongs(r, g, "/Header", "Periodic", &per, 1)) info->periodic = per != 0;
    H5Gclose(g);
  }
  if (ic_exists(r->file, "RuntimePars")) {
    hid_t g = H5Gopen2(r->file, "RuntimePars", H5P_DEFAULT);
    long long per;
    if (g >= 0 && ic_attr_llongs(r, g, "/RuntimePars", "PeriodicBoundariesOn", &per, 1))
      info->periodic = per != 0;
    if (g >= 0) H5Gclose(g);
  }
  return count;
}

/** Find the dataset of field f under its name or an alias; NULL if absent. */
static const char *ic_find_dataset(hid_t grp, const struct part_field *f) {
  for (size_t a = 0; a < sizeof ic_aliases / sizeof ic_aliases[0]; a++)
    if (strcmp(ic_aliases[a][0], f->h5name) == 0) {
      for (int j = 0; j < 3 && ic_aliases[a][j]; j++)
        if (ic_exists(grp, ic_aliases[a][j])) return ic_aliases[a][j];
      return NULL;
    }
  return ic_exists(grp, f->h5name) ? f->h5name : NULL;
}

/** Read dataset `name` into the fields k .. k+ncomp-1 of p, converting its
 *  type (HDF5 converts on read) and multiplying floating-point values by the
 *  unit factor. */
static void ic_read_dataset(struct ic_reader *r, hid_t grp, const char *name, int k,
                            struct parts *p, double factor) {
  const struct part_field *f = &part_fields[k];
  const size_t n = p->count, nc = (size_t)f->ncomp;
  hid_t d = H5Dopen2(grp, name, H5P_DEFAULT);
  if (d < 0) error_exit("%s: cannot open dataset /PartType0/%s", r->path, name);
  hid_t type = H5Dget_type(d);
  const H5T_class_t cls = H5Tget_class(type);
  if (cls != H5T_INTEGER && cls != H5T_FLOAT)
    error_exit("%s: dataset /PartType0/%s is not numeric", r->path, name);
  /* integer fields from a floating-point dataset: read as double, check
   * integral; integer datasets are read as 64-bit (unsigned 64-bit ones as
   * such) and range-checked, since HDF5 clips out-of-range values silently */
  const int as_double = f->type == PART_DOUBLE || cls == H5T_FLOAT;
  const int as_u64 = !as_double && H5Tget_sign(type) == H5T_SGN_NONE && H5Tget_size(type) >= 8;
  H5Tclose(type);

  void *buf = error_malloc((n ? n : 1) * nc * 8, name); /* 8 bytes per value in every case */
  const hid_t mtype = as_double ? H5T_NATIVE_DOUBLE : as_u64 ? H5T_NATIVE_UINT64 : H5T_NATIVE_INT64;
  if (n > 0 && H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
    free(buf);
    error_exit("%s: cannot read dataset /PartType0/%s", r->path, name);
  }
  H5Dclose(d);

  char why[1400];
  const double *dbuf = buf;
  const int64_t *ibuf = buf;
  const uint64_t *ubuf = buf;
  const int64_t imax = f->type == PART_INT64 ? INT64_MAX : INT32_MAX;
  const int64_t imin = f->type == PART_INT64 ? INT64_MIN : INT32_MIN;
  for (size_t c = 0; c < nc; c++) {
    const struct part_field *fc = &part_fields[k + (int)c];
    char *dst = part_field_array(p, fc);
    if (f->type == PART_DOUBLE) {
      double *a = (double *)dst;
      if (factor == 1.0)
        for (size_t i = 0; i < n; i++) a[i] = dbuf[i * nc + c];
      else
        for (size_t i = 0; i < n; i++) a[i] = dbuf[i * nc + c] * factor;
      continue;
    }
    for (size_t i = 0; i < n; i++) {
      int64_t v;
      const size_t j = i * nc + c;
      if (as_double) {
        const double x = dbuf[j];
        if (!(x == floor(x)) || !(x >= (double)imin && x < -(double)imin)) {
          snprintf(why, sizeof why, "%s: particle %zu: %s is %g (must be an integer)", r->path, i,
                   name, x);
          goto bad;
        }
        v = (int64_t)x;
      } else if (as_u64) {
        if (ubuf[j] > (uint64_t)imax) {
          snprintf(why, sizeof why, "%s: particle %zu: %s is %llu (too large)", r->path, i, name,
                   (unsigned long long)ubuf[j]);
          goto bad;
        }
        v = (int64_t)ubuf[j];
      } else {
        v = ibuf[j];
      }
      if (v < imin || v > imax) {
        snprintf(why, sizeof why, "%s: particle %zu: %s is %lld (out of range)", r->path, i, name,
                 (long long)v);
        goto bad;
      }
      if (f->type == PART_INT64)
        ((int64_t *)dst)[i] = v;
      else
        ((int32_t *)dst)[i] = (int32_t)v;
    }
  }
  free(buf);
  return;
bad: /* (the buffer freed before the exit: no leak for the sanitizers to report) */
  free(buf);
  error_exit("%s", why);
}

/** Shape check: N (rank 1, or N x 1) for scalars, N x ncomp for vectors. */
static size_t ic_dataset_length(struct ic_reader *r, hid_t grp, const char *name, int ncomp) {
  hid_t d = H5Dopen2(grp, name, H5P_DEFAULT);
  if (d < 0) error_exit("%s: cannot open dataset /PartType0/%s", r->path, name);
  hid_t space = H5Dget_space(d);
  const int rank = H5Sget_simple_extent_ndims(space);
  hsize_t dims[2] = {0, 1};
  if (rank < 1 || rank > 2 || H5Sget_simple_extent_dims(space, dims, NULL) < 0 ||
      (rank == 2 ? (int)dims[1] : 1) != ncomp)
    error_exit("%s: dataset /PartType0/%s has the wrong shape (expected %s%d)", r->path, name,
               ncomp > 1 ? "N x " : "N, rank ", ncomp > 1 ? ncomp : 1);
  H5Sclose(space);
  H5Dclose(d);
  return (size_t)dims[0];
}

/** Sort the pairs (key[i], val[i]) by key, stably: least significant
 *  digit first, 11 bits a pass (6 passes; a pass whose digit every key
 *  shares is skipped).  tk, tv: room for n each.  Linear in n, where the
 *  qsort of the two checks below was most of the read of a large file. */
static void ic_sort_keys(uint64_t *key, size_t *val, uint64_t *tk, size_t *tv, size_t n) {
  enum { BITS = 11, BUCKETS = 1 << BITS };
  size_t *cnt = error_malloc(BUCKETS * sizeof *cnt, "initial conditions: key sort");
  uint64_t *k0 = key, *k1 = tk;
  size_t *v0 = val, *v1 = tv;
  for (int shift = 0; shift < 64; shift += BITS) {
    memset(cnt, 0, BUCKETS * sizeof *cnt);
    for (size_t i = 0; i < n; i++) cnt[k0[i] >> shift & (BUCKETS - 1)]++;
    if (cnt[k0[0] >> shift & (BUCKETS - 1)] == n) continue; /* one digit: in order */
    size_t sum = 0;
    for (int d = 0; d < BUCKETS; d++) {
      const size_t c = cnt[d];
      cnt[d] = sum;
      sum += c;
    }
    for (size_t i = 0; i < n; i++) {
      const size_t b = cnt[k0[i] >> shift & (BUCKETS - 1)]++;
      k1[b] = k0[i];
      v1[b] = v0[i];
    }
    uint64_t *tkk = k0;
    k0 = k1, k1 = tkk;
    size_t *tvv = v0;
    v0 = v1, v1 = tvv;
  }
  if (k0 != key) {
    memcpy(key, k0, n * sizeof *key);
    memcpy(val, v0, n * sizeof *val);
  }
  free(cnt);
}

/** Pairs (key, particle index) for ic_sort_keys: 2n of each, the second
 *  halves the sort's work room. */
struct ic_keys {
  uint64_t *key;
  size_t *idx;
};

static struct ic_keys ic_keys_new(size_t n) {
  struct ic_keys k = {error_malloc(2 * n * sizeof *k.key, "initial conditions: sorted keys"),
                      error_malloc(2 * n * sizeof *k.idx, "initial conditions: sorted keys")};
  for (size_t i = 0; i < n; i++) k.idx[i] = i;
  return k;
}

static void ic_keys_sort(struct ic_keys *k, size_t n) {
  ic_sort_keys(k->key, k->idx, k->key + n, k->idx + n, n);
}

static void ic_keys_free(struct ic_keys *k) {
  free(k->key);
  free(k->idx);
}

/** Particle ids must be unique: sort them, report the smallest duplicate
 *  with the first two particles (in file order) holding it. */
static void ic_check_unique_ids(const char *path, const struct parts *p) {
  const size_t n = p->count;
  if (n < 2) return;
  struct ic_keys k = ic_keys_new(n);
  /* (the sign bit flipped: the order of the signed ids) */
  for (size_t i = 0; i < n; i++) k.key[i] = (uint64_t)p->id[i] ^ (UINT64_C(1) << 63);
  ic_keys_sort(&k, n);
  for (size_t i = 1; i < n; i++)
    if (k.key[i] == k.key[i - 1]) {
      /* (stable: the first two in file order) */
      const size_t a = k.idx[i - 1], b = k.idx[i];
      const long long dup = (long long)p->id[a];
      ic_keys_free(&k);
      error_exit("%s: particles %zu and %zu have the same id %lld (ids must be unique)", path, a, b,
                 dup);
    }
  ic_keys_free(&k);
}

/** The bits of x, -0 as +0 (equal positions, equal bits). */
static uint64_t ic_bits(double x) {
  x += 0.0;
  uint64_t b;
  memcpy(&b, &x, sizeof b);
  return b;
}

/** A 64-bit mix (the finaliser of splitmix64, Steele et al. 2014). */
static uint64_t ic_mix(uint64_t z) {
  z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
  return z ^ (z >> 31);
}

static int ic_same_pos(const struct parts *p, size_t i, size_t j) {
  return p->x[i] == p->x[j] && p->y[i] == p->y[j] && p->z[i] == p->z[j];
}

/** No two particles at the same position: their pair has no direction, and
 *  a file with all particles at one point would cost minutes of smoothing
 *  length iterations before failing.  Sorts a hash of each position (equal
 *  positions, equal hashes) and compares the positions of equal hashes;
 *  reports the first two particles in file order of the first such run. */
static void ic_check_distinct_positions(const char *path, const struct parts *p) {
  const size_t n = p->count;
  if (n < 2) return;
  struct ic_keys k = ic_keys_new(n);
  /* (33 bits of the hash: 3 passes of the sort; a particle shares its
   * hash with another of 1.1e8 at random once in 80) */
  for (size_t i = 0; i < n; i++)
    k.key[i] = ic_mix(ic_bits(p->x[i]) ^ ic_mix(ic_bits(p->y[i]) ^ ic_mix(ic_bits(p->z[i])))) >> 31;
  ic_keys_sort(&k, n);
  for (size_t r0 = 0, r1; r0 < n; r0 = r1) {
    for (r1 = r0 + 1; r1 < n && k.key[r1] == k.key[r0];) r1++;
    /* a run of one hash: distinct positions that share it are rare (the
     * pairs are compared); equal ones show at the run's first pair */
    for (size_t u = r0; u < r1; u++)
      for (size_t v = u + 1; v < r1; v++)
        if (ic_same_pos(p, k.idx[u], k.idx[v])) {
          const size_t a = k.idx[u], b = k.idx[v]; /* (stable: a < b) */
          ic_keys_free(&k);
          error_exit(
              "%s: particles %zu (id %lld) and %zu (id %lld) are at the same position (%g, %g, "
              "%g)",
              path, a, (long long)p->id[a], b, (long long)p->id[b], p->x[a], p->y[a], p->z[a]);
        }
  }
  ic_keys_free(&k);
}

/** Allowed ranges of the fields read (inclusive); NaN and infinities are
 *  refused for every field.  Negative internal energies and densities have no
 *  meaning in initial conditions (the run's floors would hide them). */
static const struct {
  const char *field;
  double min, max;
} ic_ranges[] = {
    {"u", 0.0, INFINITY}, {"rho", 0.0, INFINITY},  {"dmg", 0.0, 1.0},
    {"dcbrt", 0.0, 1.0},  {"dmg_shear", 0.0, 1.0}, {"eps_p", 0.0, INFINITY},
};

/** Check every particle; stop at the first offender. */
static void ic_validate(const char *path, const struct parts *p, const struct ic_info *info,
                        const int32_t *valid_mat, int n_valid_mat) {
  int kh = -1, kmat = -1;
  for (int k = 0; k < part_nr_fields; k++) {
    if (strcmp(part_fields[k].name, "h") == 0) kh = k;
    if (strcmp(part_fields[k].name, "mat") == 0) kmat = k;
  }
  const int check_h = kh >= 0 && ic_field_read(info, kh);
  int krange[sizeof ic_ranges / sizeof ic_ranges[0]];
  for (size_t r = 0; r < sizeof ic_ranges / sizeof ic_ranges[0]; r++) {
    krange[r] = -1;
    for (int k = 0; k < part_nr_fields; k++)
      if (strcmp(part_fields[k].name, ic_ranges[r].field) == 0 && ic_field_read(info, k))
        krange[r] = k;
  }
  const int check_mat = kmat >= 0 && ic_field_read(info, kmat);
  /* the checks a field at a time first (tight loops: the loop below, every
   * field of a particle, then the next, took most of the read); then that
   * loop from the first particle that fails one, for the message of the
   * first of its checks */
  size_t first = p->count;
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *f = &part_fields[k];
    if (!ic_field_read(info, k) || f->type != PART_DOUBLE) continue;
    const double *a = part_field_array(p, f);
    for (size_t i = 0; i < first; i++)
      if (!isfinite(a[i])) first = i;
  }
  for (size_t r = 0; r < sizeof ic_ranges / sizeof ic_ranges[0]; r++) {
    if (krange[r] < 0) continue;
    const double *a = part_field_array(p, &part_fields[krange[r]]);
    for (size_t i = 0; i < first; i++)
      if (a[i] < ic_ranges[r].min || a[i] > ic_ranges[r].max) first = i;
  }
  for (size_t i = 0; i < first; i++)
    if (!(p->m[i] > 0) || (check_h && !(p->h[i] > 0))) first = i;
  for (size_t i = 0; check_mat && i < first; i++) {
    int ok = p->mat[i] >= 0;
    if (valid_mat) {
      ok = 0;
      for (int j = 0; j < n_valid_mat; j++) ok |= valid_mat[j] == p->mat[i];
    }
    if (!ok) first = i;
  }
  for (size_t i = first; i < p->count; i++) {
    for (int k = 0; k < part_nr_fields; k++) {
      const struct part_field *f = &part_fields[k];
      if (!ic_field_read(info, k) || f->type != PART_DOUBLE) continue;
      const double v = ((const double *)part_field_array(p, f))[i];
      if (!isfinite(v))
        error_exit("%s: particle %zu (id %lld): %s is %g (must be finite)", path, i,
                   (long long)p->id[i], f->description, v);
    }
    for (size_t r = 0; r < sizeof ic_ranges / sizeof ic_ranges[0]; r++) {
      if (krange[r] < 0) continue;
      const struct part_field *f = &part_fields[krange[r]];
      const double v = ((const double *)part_field_array(p, f))[i];
      if (v < ic_ranges[r].min || v > ic_ranges[r].max) {
        char range[64];
        if (isinf(ic_ranges[r].max))
          snprintf(range, sizeof range, ">= %g", ic_ranges[r].min);
        else
          snprintf(range, sizeof range, "in [%g, %g]", ic_ranges[r].min, ic_ranges[r].max);
        error_exit("%s: particle %zu (id %lld): %s is %g (must be %s)", path, i,
                   (long long)p->id[i], f->h5name, v, range);
      }
    }
    if (!(p->m[i] > 0))
      error_exit("%s: particle %zu (id %lld): mass is %g (must be positive)", path, i,
                 (long long)p->id[i], p->m[i]);
    if (check_h && !(p->h[i] > 0))
      error_exit("%s: particle %zu (id %lld): smoothing length is %g (must be positive)", path, i,
                 (long long)p->id[i], p->h[i]);
    if (check_mat) {
      const int32_t m = p->mat[i];
      int ok = m >= 0;
      if (valid_mat) {
        ok = 0;
        for (int j = 0; j < n_valid_mat; j++) ok |= valid_mat[j] == m;
      }
      if (!ok)
        error_exit("%s: particle %zu (id %lld): material id %d is not a known material", path, i,
                   (long long)p->id[i], (int)m);
    }
  }
  ic_check_unique_ids(path, p);
  ic_check_distinct_positions(path, p);
}

void ic_read(const char *path, const struct unit_system *internal, const int32_t *valid_mat,
             int n_valid_mat, struct parts *p, struct ic_info *info_out) {
  ic_read_unused(path, internal, valid_mat, n_valid_mat, p, info_out, NULL);
}

void ic_read_unused(const char *path, const struct unit_system *internal, const int32_t *valid_mat,
                    int n_valid_mat, struct parts *p, struct ic_info *info_out,
                    const unsigned char *unused) {
  struct ic_info info_local;
  struct ic_info *info = info_out ? info_out : &info_local;
  memset(info, 0, sizeof *info);
  if (part_nr_fields > IC_MAX_FIELDS)
    error_bug("ic_info.fields_read holds at most %d fields", IC_MAX_FIELDS);
  H5Eset_auto(H5E_DEFAULT, NULL, NULL);

  FILE *probe = fopen(path, "rb");
  if (!probe) error_exit("%s: cannot open initial conditions: %s", path, strerror(errno));
  fclose(probe);
  if (H5Fis_hdf5(path) <= 0) error_exit("%s: not an HDF5 file", path);
  struct ic_reader r = {.path = path};
  r.file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (r.file < 0) error_exit("%s: cannot open as HDF5 (damaged file?)", path);

  ic_read_units(&r, internal, info);
  const long long header_count = ic_read_header(&r, info);
  const double lfac = units_conversion_factor(&info->file_units, internal, 0, 1, 0);
  const double tfac = units_conversion_factor(&info->file_units, internal, 0, 0, 1);
  for (int d = 0; d < 3; d++) info->box_size[d] *= lfac;
  info->time *= tfac;

  if (!ic_exists(r.file, "PartType0")) error_exit("%s: no group /PartType0", path);
  hid_t grp = H5Gopen2(r.file, "PartType0", H5P_DEFAULT);
  if (grp < 0) error_exit("%s: cannot open group /PartType0", path);

  /* pass 1: find the datasets, check presence and lengths */
  const char *found[IC_MAX_FIELDS] = {NULL};
  const char *first = NULL;
  size_t n = 0;
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *f = &part_fields[k];
    if (!f->h5name || f->comp != 0 || !(f->flags & (PART_IC_REQ | PART_IC_OPT))) continue;
    found[k] = ic_find_dataset(grp, f);
    if (!found[k]) {
      if (f->flags & PART_IC_REQ)
        error_exit("%s: missing required dataset /PartType0/%s", path, f->h5name);
      continue;
    }
    const size_t len = ic_dataset_length(&r, grp, found[k], f->ncomp);
    if (!first) {
      first = found[k];
      n = len;
    } else if (len != n) {
      error_exit("%s: dataset /PartType0/%s has %zu particles but /PartType0/%s has %zu", path,
                 found[k], len, first, n);
    }
  }
  if (n == 0) error_exit("%s: no particles in /PartType0", path);
  if (header_count >= 0 && (size_t)header_count != n)
    error_exit("%s: /Header/NumPart_Total says %lld particles but /PartType0/%s has %zu", path,
               header_count, first, n);

  /* pass 2: read and convert (the unused fields not allocated, unless the
   * file has one of them: the groups that the shared functions test by one
   * array's pointer are then all held) */
  struct parts like = {0};
  for (int k = 0; k < part_nr_fields && unused; k++) like.absent[k] = unused[k];
  for (int k = 0; k < part_nr_fields; k++)
    for (int c = 0; found[k] && c < part_fields[k].ncomp; c++)
      if (like.absent[k + c]) memset(like.absent, 0, sizeof like.absent);
  parts_alloc_like(p, n, &like);
  for (int k = 0; k < part_nr_fields; k++) {
    if (!found[k]) continue;
    const struct part_field *f = &part_fields[k];
    const double factor =
        f->type == PART_DOUBLE
            ? units_conversion_factor(&info->file_units, internal, f->uM, f->uL, f->uT)
            : 1.0;
    ic_read_dataset(&r, grp, found[k], k, p, factor);
    for (int c = 0; c < f->ncomp; c++) info->fields_read[(k + c) / 64] |= 1ULL << ((k + c) % 64);
  }
  H5Gclose(grp);
  H5Fclose(r.file);

  ic_validate(path, p, info, valid_mat, n_valid_mat);
  error_log(1, "%s: %zu particles read", path, n);
}
