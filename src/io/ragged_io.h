/* Per-particle arrays of variable length in HDF5 files
 * (theory/architecture.md, "Data layout"): one flat double array of values and N + 1 int64 offsets,
 * particle i owning values[off[i] .. off[i+1]-1], in the particle order of
 * the file.  The io layer knows no task family: a family describes its array
 * by a struct ragged_io_desc (dataset names, descriptions, its own check of
 * the values), e.g. the Weibull flaws of the damage model (flaws_ragged,
 * tasks/damage/flaws.h: /PartType0/FlawThresholds and FlawOffsets).
 *
 *   - initial conditions: ragged_io_read(path, desc, n, ...) after ic_read();
 *   - snapshots and restarts: ragged_io_write_group(grp, desc, ...) while
 *     /PartType0 is open, or ragged_io_write_file() on a finished file. */
#ifndef BOLIDE_RAGGED_IO_H
#define BOLIDE_RAGGED_IO_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>

/** A family's check of a layout read from a file: n particles, offset[n + 1]
 *  (already checked to start at 0, never decrease and end at the number of
 *  values), values.  Returns 0, or -1 with the first problem in msg. */
typedef int (*ragged_io_check_fn)(size_t n, const int64_t *offset, const double *values, char *msg,
                                  size_t len);

/** How a family stores one per-particle array of variable length. */
struct ragged_io_desc {
  const char *values_name;         /**< dataset of the flat values (double), in /PartType0 */
  const char *offsets_name;        /**< dataset of the N + 1 offsets (int64), in /PartType0 */
  const char *values_description;  /**< Description attribute of the values */
  const char *offsets_description; /**< Description attribute of the offsets */
  ragged_io_check_fn check;        /**< the family's check of the values (NULL: none) */
};

/** Check the offsets of n particles against nvalues values: offset[0] = 0,
 *  never decreasing, at most INT32_MAX values per particle, ending at
 *  nvalues.  Returns 0, or -1 with the first problem in msg (named after
 *  offsets_name). */
int ragged_io_check_offsets(const char *offsets_name, size_t n, const int64_t *offset,
                            size_t nvalues, char *msg, size_t len);

/** Write the array of desc into the open group grp for n particles whose
 *  values are the slices values[first[i] .. first[i]+count[i]-1] (the
 *  engine's layout after reordering; first/count may be the file layout's
 *  offsets and NULL).  compression: gzip level 0-9.  Existing datasets of
 *  those names are replaced.  Returns 0, or -1 on an HDF5 failure (the
 *  caller names the file and stops). */
int ragged_io_write_group(hid_t grp, const struct ragged_io_desc *desc, size_t n,
                          const double *values, const int64_t *first, const int32_t *count,
                          int compression);

/** Add (or replace) the array of desc, n particles in the file layout
 *  (offset[n + 1], values), in the existing HDF5 file `path` (its /PartType0
 *  must exist).  Stops with one line naming the file on failure. */
void ragged_io_write_file(const char *path, const struct ragged_io_desc *desc, size_t n,
                          const int64_t *offset, const double *values);

/** Read the array of desc for the n particles of `path`.  Returns 1 and sets
 *  *offset (n + 1) and *values (allocated here; free both) when the file has
 *  it, 0 (both NULL) when it has neither dataset.  A file with only one of
 *  them, a length other than n + 1 offsets, offsets that fail
 *  ragged_io_check_offsets or values that fail desc->check stops with one
 *  line naming the file. */
int ragged_io_read(const char *path, const struct ragged_io_desc *desc, size_t n, int64_t **offset,
                   double **values);

#endif
