/* Internal interface between the GPU runner (src/gpu/gpu.cu) and the
 * kernels of the task families (tasks/<name>/<name>_gpu.cu).  CUDA C++ only. */
#ifndef BOLIDE_GPU_KERNELS_H
#define BOLIDE_GPU_KERNELS_H

#include <cuda_runtime.h>

#include "gpu.h"
#include "gpu_check.h"
#include "hydro_props.h"
#include "part.h"

struct material_table;

/** Most threads per block.  The leaf kernels run one block per leaf cell,
 *  its threads over the leaf's particles (32, 64 or 128 of them, from the
 *  mean leaf size, struct gpu_leaves_dev.block); every thread of a warp
 *  reads the same neighbour j at a time (a broadcast load). */
#define GPU_BLOCK 128

/** The leaves and their neighbour lists in device memory (struct gpu_leaves). */
struct gpu_leaves_dev {
  int n;                    /**< number of leaves */
  int block;                /**< threads per block of the leaf kernels (<= GPU_BLOCK) */
  const size_t *offset;     /**< first particle of each leaf */
  const int *count;         /**< particles of each leaf */
  const double *h_cap;      /**< the top-level cells' cap on h */
  const double *h_list_cap; /**< largest h the lists cover */
  const int *ngb_start;     /**< n + 1 */
  const int *ngb_leaf;      /**< neighbouring leaf of each entry */
  const double *ngb_shift;  /**< 3 per entry */
};

/** The P2P ranges of the near-field gravity in device memory (struct gpu_p2p). */
struct gpu_p2p_dev {
  int n;                  /**< target ranges */
  int block;              /**< threads per block (<= GPU_BLOCK) */
  const size_t *t_offset; /**< first particle of each target range */
  const int *t_count;     /**< its particles */
  const int *src_start;   /**< n + 1: target T's sources are [src_start[T], src_start[T+1]) */
  const size_t *s_offset; /**< first particle of each source range */
  const int *s_count;     /**< its particles */
};

/** Counters of the h iteration in device memory. */
enum gpu_counter { GPU_LEFT = 0, GPU_CAPPED = 1, GPU_OVERFLOW = 2, GPU_NR_COUNTERS = 4 };

/** Density sums of every particle (or of those without PART_H_CONVERGED),
 *  gathered from the leaves' neighbour lists (tasks/density/density_gpu.cu). */
void density_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                        int only_unconverged);
/** First step of the h iteration for every particle (tasks/ghost/ghost_gpu.cu). */
void ghost_gpu_start_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                            struct hydro_props hp, int *counters);
/** Next step for the particles still iterating. */
void ghost_gpu_step_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                           struct hydro_props hp, int *counters);
/** Grad-h factor, EOS, Balsara switch, force sums zeroed. */
void ghost_gpu_finish_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                             struct hydro_props hp, const struct material_table *mats);
/** Gradient sums (solids), gather form with r < H_i (tasks/gradient/gradient_gpu.cu). */
void gradient_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv);
/** Extra ghost of every particle: corrected velocity gradient, plasticity,
 *  dS/dt, artificial stress (tasks/gradient/gradient_gpu.cu). */
void extra_ghost_gpu_launch(cudaStream_t s, struct parts p, struct hydro_props hp,
                            const struct material_table *mats);
/** Damage update of every particle over the step dt, flaw thresholds eps
 *  (tasks/damage/damage_gpu.cu). */
void damage_gpu_launch(cudaStream_t s, struct parts p, const struct material_table *mats,
                       const double *eps, double dt);
/** Near-field gravity: P2P of every target range from its source ranges,
 *  added to pot and ga (tasks/gravity/gravity_gpu.cu). */
void gravity_p2p_gpu_launch(cudaStream_t s, struct parts p, struct gpu_p2p_dev l, double G,
                            double eps, int softening);
/** Forces, gather form with r < max(H_i, H_j) (tasks/force/force_gpu.cu). */
void force_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                      struct hydro_props hp);
/** First half kick and drift of every particle (tasks/drift/drift_gpu.cu). */
void drift_gpu_launch(cudaStream_t s, struct parts p, double dt_kick, double dt, double xsph);
/** Second half kick and time step; leaf_dt[L] the smallest of leaf L; with
 *  damage_max_change > 0 the damage limit joins, with grav.enabled the
 *  gravitational acceleration and its limit (tasks/kick/kick_gpu.cu). */
void kick2_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                      struct hydro_props hp, const struct material_table *mats, double dt_kick,
                      double damage_max_change, struct gpu_gravity grav, double *leaf_dt);

#endif
