/* The scheduling policy Scheduler:gpu (src/io/param_list.h): off, all, auto
 * or a list of task families.  Read and checked in every build, also
 * without CUDA, so that a bad value stops every run the same way; the GPU
 * runner (gpu_engine.c) turns it into a mode. */
#ifndef BOLIDE_GPU_POLICY_H
#define BOLIDE_GPU_POLICY_H

#include "src/io/params.h"
#include "src/task.h"

/* The task families Scheduler:gpu can name are those of the registry
 * (tasks/task_families.h), by their names (task_family_names); bit
 * (1u << task_family_x) of gpu_policy.families.  The families of column
 * policy HYDRO run on the GPU as one phase and are named together
 * (TASK_FAMILIES_HYDRO: ghost, the h iteration of density's loop, may be
 * named or not). */

/** Kinds of value. */
enum gpu_policy_kind { GPU_POLICY_AUTO, GPU_POLICY_OFF, GPU_POLICY_ALL, GPU_POLICY_LIST };

/** A checked Scheduler:gpu. */
struct gpu_policy {
  enum gpu_policy_kind kind; /**< auto, off, all or a list */
  unsigned families;         /**< a list: bit (1u << task_family) of each family named */
  char text[256];            /**< the value as given (for the log) */
};

/** Read Scheduler:gpu.  Stops with one line naming the file and the key
 *  for an unknown family (listing the known ones) and for a list that
 *  names some hydrodynamic families but not all (naming the missing
 *  ones); a list naming gravity alone lacks all of them.  An empty list
 *  is off. */
struct gpu_policy gpu_policy_read(const struct params *p);

#endif
