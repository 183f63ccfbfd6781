/* Weibull flaws in HDF5 files: see flaws_io.h. */
#include "flaws_io.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"

/** Dataset names (one place). */
#define FLAWS_IO_THRESHOLDS "FlawThresholds"
#define FLAWS_IO_OFFSETS "FlawOffsets"

/** Write a 1-D dataset `name` of n values (replacing one of that name). */
static int flaws_io_dataset(hid_t grp, const char *name, hid_t ftype, hid_t mtype, size_t n,
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

int flaws_io_write_group(hid_t grp, size_t n, const double *eps, const int64_t *first,
                         const int32_t *count, int compression) {
  int64_t *off = error_malloc((n + 1) * sizeof *off, "flaw offsets");
  off[0] = 0;
  for (size_t i = 0; i < n; i++) off[i + 1] = off[i] + (count ? count[i] : first[i + 1] - first[i]);
  const size_t total = (size_t)off[n];
  double *buf = error_malloc((total ? total : 1) * sizeof *buf, "flaw thresholds");
  for (size_t i = 0; i < n; i++)
    if (off[i + 1] > off[i])
      memcpy(buf + off[i], eps + first[i], (size_t)(off[i + 1] - off[i]) * sizeof *buf);
  int rc = flaws_io_dataset(grp, FLAWS_IO_THRESHOLDS, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, total, buf,
                            compression,
                            "Weibull flaw activation strains of all particles, ascending per "
                            "particle (slices given by FlawOffsets)");
  if (rc == 0)
    rc = flaws_io_dataset(grp, FLAWS_IO_OFFSETS, H5T_STD_I64LE, H5T_NATIVE_INT64, n + 1, off,
                          compression,
                          "N+1 offsets: particle i owns FlawThresholds[off[i]:off[i+1]]");
  free(buf);
  free(off);
  return rc;
}

int flaws_io_write(hid_t grp, const struct flaws *f, int compression) {
  return flaws_io_write_group(grp, f->n_parts, f->eps, f->offset, NULL, compression);
}

void flaws_io_write_file(const char *path, const struct flaws *f) {
  H5Eset_auto(H5E_DEFAULT, NULL, NULL);
  hid_t file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  if (file < 0) error_exit("%s: cannot open HDF5 file for writing flaws", path);
  hid_t grp = H5Gopen2(file, "PartType0", H5P_DEFAULT);
  if (grp < 0) {
    H5Fclose(file);
    error_exit("%s: no group /PartType0", path);
  }
  const int rc = flaws_io_write(grp, f, 0);
  H5Gclose(grp);
  if (H5Fclose(file) < 0 || rc < 0)
    error_exit("%s: cannot write /PartType0/%s and %s (disk full?)", path, FLAWS_IO_THRESHOLDS,
               FLAWS_IO_OFFSETS);
}

/** Length of the rank-1 dataset `name`; stops if it is not rank 1. */
static size_t flaws_io_length(const char *path, hid_t d, const char *name) {
  hid_t space = H5Dget_space(d);
  hsize_t dim = 0;
  if (space < 0 || H5Sget_simple_extent_ndims(space) != 1 ||
      H5Sget_simple_extent_dims(space, &dim, NULL) < 0)
    error_exit("%s: dataset /PartType0/%s must be one-dimensional", path, name);
  H5Sclose(space);
  return (size_t)dim;
}

int flaws_io_read(const char *path, size_t n, struct flaws *f) {
  memset(f, 0, sizeof *f);
  H5Eset_auto(H5E_DEFAULT, NULL, NULL);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) error_exit("%s: cannot open as HDF5", path);
  hid_t grp = H5Gopen2(file, "PartType0", H5P_DEFAULT);
  if (grp < 0) error_exit("%s: no group /PartType0", path);
  const int has_t = H5Lexists(grp, FLAWS_IO_THRESHOLDS, H5P_DEFAULT) > 0;
  const int has_o = H5Lexists(grp, FLAWS_IO_OFFSETS, H5P_DEFAULT) > 0;
  if (!has_t && !has_o) {
    H5Gclose(grp);
    H5Fclose(file);
    return 0;
  }
  if (!has_t || !has_o)
    error_exit("%s: /PartType0 has %s but not %s (both or neither)", path,
               has_t ? FLAWS_IO_THRESHOLDS : FLAWS_IO_OFFSETS,
               has_t ? FLAWS_IO_OFFSETS : FLAWS_IO_THRESHOLDS);
  hid_t dt = H5Dopen2(grp, FLAWS_IO_THRESHOLDS, H5P_DEFAULT);
  hid_t dof = H5Dopen2(grp, FLAWS_IO_OFFSETS, H5P_DEFAULT);
  if (dt < 0 || dof < 0) error_exit("%s: cannot open the flaw datasets", path);
  const size_t nt = flaws_io_length(path, dt, FLAWS_IO_THRESHOLDS);
  const size_t no = flaws_io_length(path, dof, FLAWS_IO_OFFSETS);
  if (no != n + 1)
    error_exit("%s: /PartType0/%s has %zu entries (expected N + 1 = %zu)", path, FLAWS_IO_OFFSETS,
               no, n + 1);
  f->n_parts = n;
  f->offset = error_malloc((n + 1) * sizeof *f->offset, "flaw offsets");
  f->eps = error_malloc((nt ? nt : 1) * sizeof *f->eps, "flaw thresholds");
  if (H5Dread(dof, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, f->offset) < 0 ||
      (nt > 0 && H5Dread(dt, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, f->eps) < 0))
    error_exit("%s: cannot read the flaw datasets", path);
  H5Dclose(dt);
  H5Dclose(dof);
  H5Gclose(grp);
  H5Fclose(file);
  if (f->offset[n] != (int64_t)nt)
    error_exit("%s: /PartType0/%s ends at %lld but %s has %zu values", path, FLAWS_IO_OFFSETS,
               (long long)f->offset[n], FLAWS_IO_THRESHOLDS, nt);
  char msg[256];
  if (flaws_check(f, msg, sizeof msg) != 0) error_exit("%s: %s", path, msg);
  return 1;
}
