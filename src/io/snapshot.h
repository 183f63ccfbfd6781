/* Snapshots: one HDF5 file per output in the layout planetary SPH users read
 * (SWIFT's /Header, /Units, /PartType0/...), an XDMF file beside it for
 * ParaView, both written to a temporary name and renamed.
 *
 * The same writer makes initial conditions (meta.ic = 1: only the fields an
 * IC holds), so the HDF5 code exists once. */
#ifndef BOLIDE_SNAPSHOT_H
#define BOLIDE_SNAPSHOT_H

#include "src/part.h"
#include "src/io/units.h"

/** What a snapshot records besides the particles. */
struct snapshot_meta {
  double time;             /**< simulation time (internal units) */
  double box_size[3];      /**< box side lengths (internal units) */
  int periodic;            /**< 1 for a periodic box (/RuntimePars/PeriodicBoundariesOn) */
  int compression;         /**< gzip level 0-9 of the datasets (Snapshots:compression) */
  int ic;                  /**< 1: write only the initial-condition fields (PART_IC_*) */
  const char *run_name;    /**< MetaData:run_name (NULL: "bolide") */
  const char *params;      /**< used parameters as YAML text (params_to_string); may be NULL */
  const char *command;     /**< command line that made the file (may be NULL) */
  int hydro, self_gravity; /**< physics switches recorded in /Policy */
};

/** Write the particles to path (an .hdf5 file) and path with its extension
 *  replaced by .xmf.  Values are written in the internal unit system `us`,
 *  which /Units describes; doubles stay doubles (bit-exact).  Fields flagged
 *  PART_SNAP are written, plus PART_SNAP_ACC when write_acc is non-zero (or
 *  PART_IC_REQ|PART_IC_OPT when meta->ic).  The files are written under
 *  temporary names, flushed to disk and renamed; any failure removes the
 *  temporary file and stops with one line naming the file and the dataset. */
void snapshot_write(const char *path, const struct snapshot_meta *meta, const struct parts *p,
                    const struct unit_system *us, int write_acc);

/** 1 if this build writes one file from several MPI ranks (parallel HDF5). */
int snapshot_parallel(void);

/** snapshot_write by every MPI rank at once (collective): p holds this
 *  rank's particles, which take rows rank after rank (rank 0's first) in
 *  one file, written with parallel HDF5 (MPI-IO, collective transfers);
 *  rank 0 creates, renames and flushes the file and writes the XDMF file.
 *  Only where snapshot_parallel(). */
void snapshot_write_ranks(const char *path, const struct snapshot_meta *meta, const struct parts *p,
                          const struct unit_system *us, int write_acc);

/** Name of the XDMF file that goes with an HDF5 file (".hdf5"/".h5" replaced
 *  by ".xmf", otherwise ".xmf" appended); buf of length len. */
void snapshot_xdmf_name(const char *path, char *buf, size_t len);

/** Write DIR/BASENAME.xmf, the XDMF time series of a run: a temporal
 *  collection of the grids of the snapshots BASENAME_0000 .. BASENAME_(count
 *  - 1) (copied from their own .xmf files), so that ParaView opens the whole
 *  run as one file.  Written to a temporary name and renamed. */
void snapshot_write_series(const char *dir, const char *basename, int count);

/** 1 if field f is written by snapshot_write with these settings. */
int snapshot_field_written(const struct part_field *f, int ic, int write_acc);

#endif
