/* Initial conditions: read an HDF5 file in the SWIFT/GADGET layout that
 * planetary tools (woma, SEAGen, SWIFT's own scripts) write, convert it into
 * the internal unit system and check every particle. */
#ifndef BOLIDE_IC_H
#define BOLIDE_IC_H

#include <stdint.h>

#include "src/part.h"
#include "src/io/units.h"

/** Largest number of particle fields the ICs reader tracks (part_fields). */
#define IC_MAX_FIELDS 256

/** What the file said besides the particles. */
struct ic_info {
  double box_size[3];            /**< /Header/BoxSize (internal units; 0 if absent) */
  int has_box_size;              /**< 1 if /Header/BoxSize was present */
  int periodic;                  /**< 1 if the file says periodic, 0 if not, -1 if silent */
  double time;                   /**< /Header/Time (internal units; 0 if absent) */
  int has_time;                  /**< 1 if /Header/Time was present */
  int dimension;                 /**< /Header/Dimension (3 if absent) */
  int has_units;                 /**< 1 if /Units was present */
  struct unit_system file_units; /**< the file's units (= internal if absent) */
  uint64_t fields_read[IC_MAX_FIELDS / 64]; /**< bit k set: part_fields[k] came from the file */
};

/** Read initial conditions from `path` into p (allocated here with
 *  parts_alloc; fields absent from the file are zero).  Every numeric HDF5
 *  type is accepted and converted; values are converted from the file's
 *  /Units into `internal`.  valid_mat: the n_valid_mat known material ids
 *  (NULL: any id >= 0).  Any problem (HDF5 failure, missing or mismatched
 *  dataset, non-finite value, non-positive mass or smoothing length, unknown
 *  material, duplicate id) stops with one line naming the file and the first
 *  offending particle or dataset.  info may be NULL. */
void ic_read(const char *path, const struct unit_system *internal, const int32_t *valid_mat,
             int n_valid_mat, struct parts *p, struct ic_info *info);
/** ic_read, where the fields marked in unused (part_nr_fields flags; the
 *  fields a run never uses) are not allocated (absent, parts_drop) unless
 *  the file has a dataset of one of them: then every field is. */
void ic_read_unused(const char *path, const struct unit_system *internal, const int32_t *valid_mat,
                    int n_valid_mat, struct parts *p, struct ic_info *info,
                    const unsigned char *unused);

/** 1 if part_fields[k] was read according to info. */
static inline int ic_field_read(const struct ic_info *info, int k) {
  return k >= 0 && k < IC_MAX_FIELDS && ((info->fields_read[k / 64] >> (k % 64)) & 1);
}

#endif
