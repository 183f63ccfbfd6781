/* Weibull flaws in HDF5 files: /PartType0/FlawThresholds (all thresholds,
 * one flat double array, dimensionless strains) and /PartType0/FlawOffsets
 * (N + 1 int64: particle i owns FlawThresholds[off[i] .. off[i+1]-1],
 * ascending), in the particle order of the file (flaws.h).
 *
 * Separate from snapshot.c so that the engine can call it next to
 * snapshot_write and ic_read:
 *   - initial conditions: flaws_io_read(path, n, &f) after ic_read();
 *   - snapshots and restarts: flaws_io_write_group(grp, ...) while
 *     /PartType0 is open in snapshot_write (a one-line hook), or
 *     flaws_io_write_file() on a finished file. */
#ifndef BOLIDE_FLAWS_IO_H
#define BOLIDE_FLAWS_IO_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>

#include "damage/flaws.h"

/** Write FlawThresholds and FlawOffsets into the open group grp for n
 *  particles whose flaws are the slices eps[first[i] .. first[i]+count[i]-1]
 *  (the engine's layout after reordering; first/count may be f->offset
 *  and NULL for the file layout, see flaws_io_write).  compression: gzip
 *  level 0-9.  Existing datasets of those names are replaced.  Returns 0, or
 *  -1 on an HDF5 failure (the caller names the file and stops). */
int flaws_io_write_group(hid_t grp, size_t n, const double *eps, const int64_t *first,
                         const int32_t *count, int compression);

/** The same for flaws in the file layout (struct flaws). */
int flaws_io_write(hid_t grp, const struct flaws *f, int compression);

/** Add (or replace) the flaws in the existing HDF5 file `path` (its
 *  /PartType0 must exist).  Stops with one line naming the file on failure. */
void flaws_io_write_file(const char *path, const struct flaws *f);

/** Read the flaws of the n particles of `path`.  Returns 1 and fills f when
 *  the file has them, 0 (f zeroed) when it has neither dataset.  A file with
 *  only one of them, a length other than n + 1 offsets, or a layout that
 *  fails flaws_check stops with one line naming the file. */
int flaws_io_read(const char *path, size_t n, struct flaws *f);

#endif
