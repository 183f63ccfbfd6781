/* Internal interface between the GPU runner (src/gpu/gpu.cu) and the
 * kernels of the task families (tasks/<name>/<name>_gpu.cu).  CUDA C++ only. */
#ifndef BOLIDE_GPU_KERNELS_H
#define BOLIDE_GPU_KERNELS_H

#include <cuda_runtime.h>

#include "src/gpu/gpu.h"
#include "src/gpu/gpu_check.h"
#include "tasks/hydro/hydro_props.h"
#include "src/part.h"
#include "tasks/task_families.h"

struct material_table;

/** Most threads per block.  The leaf kernels run one block per leaf cell,
 *  its threads over the leaf's particles (32, 64 or 128 of them, from the
 *  mean leaf size, struct gpu_leaves_dev.block), a small leaf's with
 *  several threads per particle (tasks/iact_loop_gpu.h). */
#define GPU_BLOCK 128

/** The lanes of a leaf of cnt particles in a block (tasks/iact_loop_gpu.h):
 *  g per particle, the largest power of two up to a warp with g cnt <= the
 *  block's threads (so a group never spans two warps); this thread's lane
 *  sub of its group, which takes the group's particle threadIdx.x / g (then
 *  every blockDim.x / g); mask, the group's lanes (for __shfl_xor_sync). */
struct gpu_lanes {
  int g, sub;
  unsigned mask;
};

__device__ static inline struct gpu_lanes gpu_lanes_of(int cnt) {
  struct gpu_lanes r;
  r.g = 1;
  while (r.g < 32 && 2 * r.g * cnt <= (int)blockDim.x) r.g *= 2;
  r.sub = (int)threadIdx.x & (r.g - 1);
  const unsigned lane = threadIdx.x & 31u;
  r.mask = r.g == 32 ? 0xffffffffu : ((1u << r.g) - 1u) << (lane & ~(unsigned)(r.g - 1));
  return r;
}

/** v[0..n) += the same values of lane ^ o (mask: the lanes taking part,
 *  o below their number).  Both lanes end with the same sums: IEEE
 *  addition commutes. */
__device__ static inline void gpu_lanes_add(double *v, int n, unsigned mask, int o) {
  for (int k = 0; k < n; k++) v[k] += __shfl_xor_sync(mask, v[k], o);
}

/** *v = max(*v, lane ^ o's *v), as gpu_lanes_add. */
__device__ static inline void gpu_lanes_max(double *v, unsigned mask, int o) {
  const double w = __shfl_xor_sync(mask, *v, o);
  if (w > *v) *v = w;
}

/** The leaves and their neighbour lists in device memory (struct gpu_leaves). */
struct gpu_leaves_dev {
  int n;                         /**< number of leaves */
  int block;                     /**< threads per block of the leaf kernels (<= GPU_BLOCK) */
  const size_t *offset;          /**< first particle of each leaf */
  const int *count;              /**< particles of each leaf */
  const double *h_cap;           /**< the top-level cells' cap on h */
  const double *h_list_cap;      /**< largest h the lists cover */
  const int *ngb_start;          /**< n + 1 */
  const int *ngb_leaf;           /**< neighbouring leaf of each entry */
  const unsigned char *ngb_code; /**< its periodic shift, gpu_shift_code of a box of sides dim */
  double dim[3];                 /**< the box's sides (gpu_shift_of) */
};

/** Counters of the h iteration in device memory. */
enum gpu_counter { GPU_LEFT = 0, GPU_CAPPED = 1, GPU_OVERFLOW = 2, GPU_NR_COUNTERS = 4 };

/** What the steps of one GPU FORCE phase share (src/gpu/gpu.cu fills it).
 *  The step of each task family (column gpu of tasks/task_families.h, in
 *  tasks/<family>/<family>_gpu.cu) queues its kernels on stream s and
 *  returns 0, or 1 to end the phase at once (the ghost's, when the h
 *  iteration outgrew the neighbour lists: out->overflow). */
struct gpu_phase {
  cudaStream_t s;                    /**< stream 0: fields and kernels */
  struct parts dev;                  /**< the device particle arrays */
  struct gpu_leaves_dev lv;          /**< the leaves and their lists */
  struct hydro_props hp;             /**< SPH settings */
  const struct material_table *mats; /**< the material table on the device */
  const double *flaws;               /**< Weibull flaw thresholds on the device */
  int damage;                        /**< the damage step runs in this phase */
  double dmg_dt;                     /**< step over which damage grows */
  double dmg_max_change;             /**< Damage:max_change (0 without damage) */
  struct gpu_gravity grav;           /**< gravity in the kick */
  double dt_kick;                    /**< second half kick */
  struct gpu_bins bins;              /**< individual time steps (bins.on = 0: none) */
  double *leaf_dt;                   /**< smallest new time step of each leaf (device; with
                                          bins 3 per leaf, gpu_force_phase) */
  int *counters;                     /**< counters of the h iteration (device) */
  int *counters_host;                /**< their pinned copy (gpu_phase_read_counters) */
  void (*wait)(void *);              /**< gpu_set_kick_wait's hook (NULL: none) */
  void *wait_ctx;                    /**< its argument */
  struct gpu_force_out *out;         /**< what the phase reports */
};

/** The steps of the registry (one per family with column gpu STEP). */
#define GPU_STEP_DECL_STEP(fn) int fn(struct gpu_phase *ph);
#define GPU_STEP_DECL_NOSTEP
#define GPU_STEP_DECL_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  GPU_STEP_DECL_##gpu
TASK_FAMILIES(GPU_STEP_DECL_)
#undef GPU_STEP_DECL_

/** Copy the counters of the h iteration to counters_host (waits for stream s). */
void gpu_phase_read_counters(struct gpu_phase *ph);

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
/** Damage update of every particle over the step dt (with bins.on, of each
 *  particle that ends its step, over its own step), flaw thresholds eps
 *  (tasks/damage/damage_gpu.cu). */
void damage_gpu_launch(cudaStream_t s, struct parts p, const struct material_table *mats,
                       const double *eps, double dt, struct gpu_bins bins);
/** Internal services of the runner (src/gpu/gpu.cu) for the other runner
 *  files: stream k (0: fields and kernels), the device particle arrays
 *  grown to count particles (contents kept only if no growth was needed),
 *  copies of the fields named names[0..n) of particles [0, p->count),
 *  allocation with the out-of-memory report, and the bus counters. */
cudaStream_t gpu_stream(struct gpu *g, int k);
struct parts gpu_device_parts(struct gpu *g, size_t count);
void gpu_copy_named(struct gpu *g, struct parts *p, const char *const *names, int n, int to_device);
void *gpu_alloc(size_t bytes, const char *what);
/** Free what gpu_alloc gave (NULL: nothing). */
void gpu_dfree(void *ptr);
void gpu_bytes_add(struct gpu *g, double h2d, double d2h);

/** Forces, gather form with r < max(H_i, H_j) (tasks/force/force_gpu.cu). */
void force_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                      struct hydro_props hp);
/** First half kick and drift of every particle (tasks/drift/drift_gpu.cu). */
void drift_gpu_launch(cudaStream_t s, struct parts p, double dt_kick, double dt, double xsph,
                      double h_max, int h_continuity);
/** A stage of TimeIntegration:scheme rk2 or pc (drift_rk_stage; st's arrays
 *  on the device); the largest error estimate into *err (as the bits of a
 *  non-negative double, atomicMax; zero it first). */
struct drift_stage;
void drift_stage_gpu_launch(cudaStream_t s, struct parts p, const struct drift_stage *st,
                            struct hydro_props hp, unsigned long long *err);
/** The state y0 and the evaluation r1 back into the particles (drift_rk_restore). */
void drift_restore_gpu_launch(cudaStream_t s, struct parts p, const double *y0, const double *r1);
/** The same with time bins, from bins.ti_old to bins.ti_new (drift_part_bins,
 *  with the device's material table mats). */
void drift_bins_gpu_launch(cudaStream_t s, struct parts p, const struct gpu_bins *bins,
                           struct hydro_props hp, const struct material_table *mats);
/** Second half kick and time step; leaf_dt[L] the smallest of leaf L; with
 *  damage_max_change > 0 the damage limit joins, with grav.enabled the
 *  gravitational acceleration and its limit; with bins.on the kick of time
 *  bins (kick2_part_bins), leaf_dt 3 per leaf (gpu_force_phase)
 *  (tasks/kick/kick_gpu.cu). */
void kick2_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                      struct hydro_props hp, const struct material_table *mats, double dt_kick,
                      double damage_max_change, struct gpu_gravity grav, struct gpu_bins bins,
                      double *leaf_dt);

/** In place, by one block of at most 1024 threads: c[0..n) become their
 *  exclusive prefix sums, c[n] the total (T: int or unsigned long long).  Each thread sums a chunk,
 * thread 0 scans the chunks' sums, each thread then writes its chunk.  (The list builds of
 * tasks/gravity/gpu_gravity.cu and gpu_lists.cu.) */
template <typename T>
static __device__ __forceinline__ void gpu_block_exclusive_scan(T *c, int n) {
  __shared__ T part[1024];
  const int t = threadIdx.x, nt = blockDim.x;
  const int chunk = (n + nt - 1) / nt;
  const int b = min(t * chunk, n), e = min(b + chunk, n);
  T sum = 0;
  for (int i = b; i < e; i++) sum += c[i];
  part[t] = sum;
  __syncthreads();
  if (t == 0) {
    T run = 0;
    for (int k = 0; k < nt; k++) {
      const T v = part[k];
      part[k] = run;
      run += v;
    }
    c[n] = run;
  }
  __syncthreads();
  T run = part[t];
  for (int i = b; i < e; i++) {
    const T v = c[i];
    c[i] = run;
    run += v;
  }
}

#endif
