/* The scheduling policy Scheduler:gpu (src/io/param_list.h): off, all, auto
 * or a list of task families.  Read and checked in every build, also
 * without CUDA, so that a bad value stops every run the same way; the GPU
 * runner (gpu_engine.c) turns it into a mode. */
#ifndef BOLIDE_GPU_POLICY_H
#define BOLIDE_GPU_POLICY_H

#include "params.h"

/** The task families Scheduler:gpu can name (bits of gpu_policy.families). */
enum gpu_family {
  GPU_FAMILY_DRIFT,
  GPU_FAMILY_DENSITY,
  GPU_FAMILY_GHOST,
  GPU_FAMILY_GRADIENT,
  GPU_FAMILY_FORCE,
  GPU_FAMILY_DAMAGE,
  GPU_FAMILY_KICK,
  GPU_FAMILY_GRAVITY,
  GPU_FAMILY_COUNT
};

/** Their names, as written in the list. */
extern const char *const gpu_family_names[GPU_FAMILY_COUNT];

/** The hydrodynamic families: one phase on the GPU, named together (ghost,
 *  the h iteration of density's loop, may be named or not). */
#define GPU_FAMILIES_HYDRO                                                              \
  ((1u << GPU_FAMILY_DRIFT) | (1u << GPU_FAMILY_DENSITY) | (1u << GPU_FAMILY_GRADIENT) | \
   (1u << GPU_FAMILY_FORCE) | (1u << GPU_FAMILY_DAMAGE) | (1u << GPU_FAMILY_KICK))

/** Kinds of value. */
enum gpu_policy_kind { GPU_POLICY_AUTO, GPU_POLICY_OFF, GPU_POLICY_ALL, GPU_POLICY_LIST };

/** A checked Scheduler:gpu. */
struct gpu_policy {
  enum gpu_policy_kind kind; /**< auto, off, all or a list */
  unsigned families;         /**< a list: bit (1u << gpu_family) of each family named */
  char text[256];            /**< the value as given (for the log) */
};

/** Read Scheduler:gpu.  Stops with one line naming the file and the key
 *  for an unknown family (listing the known ones) and for a list that
 *  names some hydrodynamic families but not all (naming the missing
 *  ones); a list naming gravity alone lacks all of them.  An empty list
 *  is off. */
struct gpu_policy gpu_policy_read(const struct params *p);

#endif
