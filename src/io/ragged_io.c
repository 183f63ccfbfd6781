/* Per-particle arrays of variable length in HDF5 files: see ragged_io.h. */
#include "src/io/ragged_io.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"

/** Write a 1-D dataset `name` of n values (replacing one of that name). */
static int ragged_io_dataset(hid_t grp, const char *name, hid_t ftype, hid_t mtype, size_t n,
                             const void *data, int compression, const char *description) {
  if (H5Lexists(grp, name, H5P_DEFAULT) > 0 && H5Ldelete(grp, name, H5P_DEFAULT) < 0) return -1;
  hsize_t dim = n;
  hid_t space = H5Screate_simple(1, &dim, NULL);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (space < 0 || dcpl < 0) return -1;
  if (compression > 0 && n > 0) {
    hsize_t chunk = n < 262144 ? n : 262144;
    if (H5Pset_chunk(dcpl, 1, &chunk) < 0 || H5Pset_shuffle(dcpl) < 0 ||
        H5Pset_deflate(dcpl, (unsigned)compression) < 0)
      return -1;
  }
  hid_t d = H5Dcreate2(grp, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (d < 0) return -1;
  int rc = 0;
  if (n > 0 && H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) rc = -1;
  /* a description, as swiftsimio shows it */
  hid_t st = H5Tcopy(H5T_C_S1);
  hid_t as = H5Screate(H5S_SCALAR);
  if (st >= 0 && as >= 0 && H5Tset_size(st, strlen(description) + 1) >= 0) {
    hid_t a = H5Acreate2(d, "Description", st, as, H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0 || H5Awrite(a, st, description) < 0) rc = -1;
    if (a >= 0) H5Aclose(a);
  }
  if (st >= 0) H5Tclose(st);
  if (as >= 0) H5Sclose(as);
  H5Dclose(d);
  H5Pclose(dcpl);
  H5Sclose(space);
  return rc;
}

int ragged_io_check_offsets(const char *offsets_name, size_t n, const int64_t *offset,
                            size_t nvalues, char *msg, size_t len) {
  if (offset[0] != 0) {
    snprintf(msg, len, "%s[0] is %lld (must be 0)", offsets_name, (long long)offset[0]);
    return -1;
  }
  for (size_t i = 0; i < n; i++) {
    const int64_t a = offset[i], b = offset[i + 1];
    if (b < a || b - a > INT32_MAX) {
      snprintf(msg, len, "particle %zu: %s decrease or jump (%lld to %lld)", i, offsets_name,
               (long long)a, (long long)b);
      return -1;
    }
  }
  if (offset[n] != (int64_t)nvalues) {
    snprintf(msg, len, "%s ends at %lld but there are %zu values", offsets_name,
             (long long)offset[n], nvalues);
    return -1;
  }
  return 0;
}

int ragged_io_write_group(hid_t grp, const struct ragged_io_desc *desc, size_t n,
                          const double *values, const int64_t *first, const int32_t *count,
                          int compression) {
  int64_t *off = error_malloc((n + 1) * sizeof *off, desc->offsets_name);
  off[0] = 0;
  for (size_t i = 0; i < n; i++) off[i + 1] = off[i] + (count ? count[i] : first[i + 1] - first[i]);
  const size_t total = (size_t)off[n];
  double *buf = error_malloc((total ? total : 1) * sizeof *buf, desc->values_name);
  for (size_t i = 0; i < n; i++)
    if (off[i + 1] > off[i])
      memcpy(buf + off[i], values + first[i], (size_t)(off[i + 1] - off[i]) * sizeof *buf);
  int rc = ragged_io_dataset(grp, desc->values_name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, total, buf,
                             compression, desc->values_description);
  if (rc == 0)
    rc = ragged_io_dataset(grp, desc->offsets_name, H5T_STD_I64LE, H5T_NATIVE_INT64, n + 1, off,
                           compression, desc->offsets_description);
  free(buf);
  free(off);
  return rc;
}

void ragged_io_write_file(const char *path, const struct ragged_io_desc *desc, size_t n,
                          const int64_t *offset, const double *values) {
  H5Eset_auto(H5E_DEFAULT, NULL, NULL);
  hid_t file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  if (file < 0) error_exit("%s: cannot open HDF5 file for writing %s", path, desc->values_name);
  hid_t grp = H5Gopen2(file, "PartType0", H5P_DEFAULT);
  if (grp < 0) {
    H5Fclose(file);
    error_exit("%s: no group /PartType0", path);
  }
  const int rc = ragged_io_write_group(grp, desc, n, values, offset, NULL, 0);
  H5Gclose(grp);
  if (H5Fclose(file) < 0 || rc < 0)
    error_exit("%s: cannot write /PartType0/%s and %s (disk full?)", path, desc->values_name,
               desc->offsets_name);
}

/** Length of the rank-1 dataset `name`; stops if it is not rank 1. */
static size_t ragged_io_length(const char *path, hid_t d, const char *name) {
  hid_t space = H5Dget_space(d);
  hsize_t dim = 0;
  if (space < 0 || H5Sget_simple_extent_ndims(space) != 1 ||
      H5Sget_simple_extent_dims(space, &dim, NULL) < 0)
    error_exit("%s: dataset /PartType0/%s must be one-dimensional", path, name);
  H5Sclose(space);
  return (size_t)dim;
}

int ragged_io_read(const char *path, const struct ragged_io_desc *desc, size_t n, int64_t **offset,
                   double **values) {
  *offset = NULL;
  *values = NULL;
  const char *vn = desc->values_name, *on = desc->offsets_name;
  H5Eset_auto(H5E_DEFAULT, NULL, NULL);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) error_exit("%s: cannot open as HDF5", path);
  hid_t grp = H5Gopen2(file, "PartType0", H5P_DEFAULT);
  if (grp < 0) error_exit("%s: no group /PartType0", path);
  const int has_t = H5Lexists(grp, vn, H5P_DEFAULT) > 0;
  const int has_o = H5Lexists(grp, on, H5P_DEFAULT) > 0;
  if (!has_t && !has_o) {
    H5Gclose(grp);
    H5Fclose(file);
    return 0;
  }
  if (!has_t || !has_o)
    error_exit("%s: /PartType0 has %s but not %s (both or neither)", path, has_t ? vn : on,
               has_t ? on : vn);
  hid_t dt = H5Dopen2(grp, vn, H5P_DEFAULT);
  hid_t dof = H5Dopen2(grp, on, H5P_DEFAULT);
  if (dt < 0 || dof < 0) error_exit("%s: cannot open /PartType0/%s and %s", path, vn, on);
  const size_t nt = ragged_io_length(path, dt, vn);
  const size_t no = ragged_io_length(path, dof, on);
  if (no != n + 1)
    error_exit("%s: /PartType0/%s has %zu entries (expected N + 1 = %zu)", path, on, no, n + 1);
  int64_t *off = error_malloc((n + 1) * sizeof *off, on);
  double *val = error_malloc((nt ? nt : 1) * sizeof *val, vn);
  if (H5Dread(dof, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, off) < 0 ||
      (nt > 0 && H5Dread(dt, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, val) < 0))
    error_exit("%s: cannot read /PartType0/%s and %s", path, vn, on);
  H5Dclose(dt);
  H5Dclose(dof);
  H5Gclose(grp);
  H5Fclose(file);
  char msg[256];
  if (ragged_io_check_offsets(on, n, off, nt, msg, sizeof msg) != 0 ||
      (desc->check && desc->check(n, off, val, msg, sizeof msg) != 0))
    error_exit("%s: %s", path, msg);
  *offset = off;
  *values = val;
  return 1;
}
