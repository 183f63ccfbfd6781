/* libFuzzer harness of the initial-conditions reader (ic_read).  The input
 * bytes describe an HDF5 file, which the harness writes with the HDF5
 * library before reading it: which /Header and /Units attributes exist and
 * their values, and for every field the reader knows (part_fields[]) whether
 * its dataset exists, under which name, with which HDF5 type, shape and
 * length, and its values (special ones such as NaN, 1e300, -1, 2^40 or raw
 * bits).  This reaches every check of the reader; corrupt bytes inside an
 * HDF5 file would test the HDF5 library instead.  Every input must be read
 * or refused through error_exit. */
#include <math.h>

#include "tests/fuzz/fuzz_common.h"
#include "src/io/ic.h"
#include "src/part.h"
#include "src/io/units.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/** The input, consumed from the front (zeros once it runs out). */
struct fuzz_in {
  const uint8_t *d;
  size_t n, i;
};

static unsigned fz_u8(struct fuzz_in *in) {
  return in->i < in->n ? in->d[in->i++] : 0;
}

/** A value: mostly one of the interesting ones, else raw bits. */
static double fz_value(struct fuzz_in *in, double typical) {
  static const double special[] = {1.0,    0.0,     -1.0,  0.5,   1e300, -1e300,
                                   1e200,  1e-310,  101.0, 102.0, 2.5,   1099511627776.0,
                                   9.3e18, -9.3e18, 1.5,   3.0};
  const unsigned c = fz_u8(in);
  if (c < 128) return typical * (1.0 + (double)c / 128.0);
  if (c < 128 + 16) return special[c - 128];
  if (c == 200) return NAN;
  if (c == 201) return INFINITY;
  if (c == 202) return -INFINITY;
  if (c >= 240) {
    uint64_t bits = 0;
    for (int k = 0; k < 8; k++) bits = bits << 8 | fz_u8(in);
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
  }
  return (double)(int)(c - 160); /* small integers, ids and material numbers */
}

static const hid_t *fz_types(void) {
  static hid_t t[8];
  t[0] = H5T_NATIVE_DOUBLE, t[1] = H5T_NATIVE_FLOAT, t[2] = H5T_NATIVE_INT32,
  t[3] = H5T_NATIVE_INT64, t[4] = H5T_NATIVE_UINT64, t[5] = H5T_NATIVE_INT8,
  t[6] = H5T_NATIVE_UINT32, t[7] = H5T_C_S1;
  return t;
}

/** An attribute of n doubles (type chosen by the input) on loc. */
static void fz_attr(struct fuzz_in *in, hid_t loc, const char *name, int n, double typical) {
  const unsigned mode = fz_u8(in);
  if (mode % 8 == 7) return; /* absent */
  if (mode % 8 == 6) n = (int)(fz_u8(in) % 20);
  double v[20];
  for (int k = 0; k < n && k < 20; k++) v[k] = fz_value(in, typical);
  hsize_t dims[1] = {(hsize_t)(n > 0 ? n : 1)};
  const hid_t s = n > 0 ? H5Screate_simple(1, dims, NULL) : H5Screate(H5S_NULL);
  hid_t ftype = fz_types()[(mode >> 3) % 7];
  const hid_t a = H5Acreate2(loc, name, ftype, s, H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0 && n > 0) H5Awrite(a, H5T_NATIVE_DOUBLE, v);
  if (a >= 0) H5Aclose(a);
  H5Sclose(s);
}

/** Write the file the input describes; 0 on success. */
static int fz_write_ic(struct fuzz_in *in, const char *path) {
  const hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) return -1;
  const unsigned groups = fz_u8(in);
  const size_t n = fz_u8(in) % 12;
  if (!(groups & 1)) {
    const hid_t g = H5Gcreate2(f, "Header", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    fz_attr(in, g, "BoxSize", 3, 4.0);
    fz_attr(in, g, "NumPart_Total", 6, (double)n);
    fz_attr(in, g, "NumPart_Total_HighWord", 6, 0.0);
    fz_attr(in, g, "Time", 1, 0.0);
    fz_attr(in, g, "Dimension", 1, 3.0);
    fz_attr(in, g, "Periodic", 1, 1.0);
    H5Gclose(g);
  }
  if (!(groups & 2)) {
    const hid_t g = H5Gcreate2(f, "Units", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    fz_attr(in, g, "Unit mass in cgs (U_M)", 1, 1000.0);
    fz_attr(in, g, "Unit length in cgs (U_L)", 1, 100.0);
    fz_attr(in, g, "Unit time in cgs (U_t)", 1, 1.0);
    fz_attr(in, g, "Unit current in cgs (U_I)", 1, 1.0);
    fz_attr(in, g, "Unit temperature in cgs (U_T)", 1, 1.0);
    H5Gclose(g);
  }
  if (groups & 4) {
    const hid_t g = H5Gcreate2(f, "RuntimePars", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    fz_attr(in, g, "PeriodicBoundariesOn", 1, 1.0);
    H5Gclose(g);
  }
  if (!(groups & 8)) {
    const hid_t g = H5Gcreate2(f, "PartType0", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    for (int k = 0; k < part_nr_fields; k++) {
      const struct part_field *pf = &part_fields[k];
      if (!pf->h5name || pf->comp != 0 || !(pf->flags & (PART_IC_REQ | PART_IC_OPT))) continue;
      const unsigned mode = fz_u8(in);
      if (mode % 8 == 7) continue; /* absent */
      const char *name = pf->h5name;
      if (mode % 8 == 6 && strlen(name) > 1 && name[strlen(name) - 1] == 's') {
        static char alias[64]; /* the singular alias (Masses -> Masse is no alias: refused) */
        snprintf(alias, sizeof alias, "%.*s", (int)strlen(name) - 1, name);
        name = alias;
      }
      size_t len = n;
      if (mode % 8 == 5) len = fz_u8(in) % 12;
      int ncomp = pf->ncomp;
      int rank = ncomp > 1 ? 2 : 1;
      const unsigned shape = fz_u8(in);
      if (shape % 16 == 15) ncomp = (int)(shape >> 4) % 5, rank = 2;
      if (shape % 16 == 14) rank = 3;
      const hsize_t dims[3] = {len, (hsize_t)(ncomp > 0 ? ncomp : 0), 1};
      const hid_t s = H5Screate_simple(rank, dims, NULL);
      const hid_t ftype = fz_types()[(mode >> 3) % 8];
      const hid_t d = H5Dcreate2(g, name, ftype, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      const size_t nv = len * (size_t)(ncomp > 0 ? ncomp : 0);
      if (d >= 0 && nv > 0 && ftype != H5T_C_S1) {
        double *v = malloc(nv * sizeof *v);
        double typical = strcmp(pf->name, "mat") == 0 ? 101.0 : 1.0;
        for (size_t j = 0; j < nv; j++)
          v[j] = strcmp(pf->name, "id") == 0 && fz_u8(in) < 200 ? (double)(j + 1)
                                                                : fz_value(in, typical);
        H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
        free(v);
      }
      if (d >= 0) H5Dclose(d);
      H5Sclose(s);
    }
    H5Gclose(g);
  }
  return H5Fclose(f) < 0 ? -1 : 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fuzz_quiet();
  H5Eset_auto(H5E_DEFAULT, NULL, NULL);
  struct fuzz_in in = {data, size, 0};
  const char *path = fuzz_path(".hdf5");
  if (fz_write_ic(&in, path)) {
    fuzz_close_hdf5();
    unlink(path);
    return 0;
  }
  struct unit_system us;
  units_init_si(&us);
  static const int32_t mats[2] = {101, 102};
  const int with_mats = fz_u8(&in) & 1;
  static struct parts p;
  memset(&p, 0, sizeof p);
  struct ic_info info;
  if (setjmp(fuzz_env) == 0) {
    ic_read(path, &us, with_mats ? mats : NULL, with_mats ? 2 : 0, &p, &info);
    parts_free(&p);
  } else {
    fuzz_close_hdf5(); /* what the reader had allocated is leaked */
  }
  unlink(path);
  return 0;
}
