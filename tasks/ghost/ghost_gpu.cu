/* The ghost on the GPU: the smoothing-length iteration and the equation of
 * state for every particle, with the per-particle functions of ghost_part.h
 * that the CPU ghost calls.  The family's step of the FORCE phase
 * (ghost_gpu_phase) alternates ghost_gpu_step with density_gpu (unconverged
 * particles only) until no particle is left, reading the counters in
 * between. */
extern "C" {
#include "src/error.h"
}
#include "tasks/ghost/ghost_part.h"
#include "src/gpu/gpu_kernels.h"

/** One step for particle i of leaf L; counts what the runner must know. */
__device__ static void ghost_gpu_one(struct parts *p, size_t i, int L,
                                     const struct gpu_leaves_dev *lv, const struct hydro_props *hp,
                                     int *counters) {
  ghost_part_add_self(p, i);
  if (ghost_part_step(p, i, hp, lv->h_cap[L])) atomicOr(&counters[GPU_CAPPED], 1);
  if (!(p->flags[i] & PART_H_CONVERGED)) atomicAdd(&counters[GPU_LEFT], 1);
  /* the neighbour lists reach only so far: outgrowing them means new lists */
  if (p->h[i] > lv->h_list_cap[L]) atomicOr(&counters[GPU_OVERFLOW], 1);
}

/** See ghost_gpu_start_launch. */
__global__ void ghost_gpu_start_kernel(struct parts p, struct gpu_leaves_dev lv,
                                       struct hydro_props hp, int *counters) {
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  for (int t = threadIdx.x; t < lv.count[L]; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    if (PART_IS_INACTIVE(&p, i)) { /* (time bins: it keeps its h and sums) */
      p.flags[i] |= PART_H_CONVERGED;
      continue;
    }
    ghost_part_start(&p, i);
    if (ghost_part_keeps_h(&p, i)) { /* (a foreign copy: its owner's h, src/mpi/halo.c) */
      ghost_part_add_self(&p, i);
      continue;
    }
    ghost_gpu_one(&p, i, L, &lv, &hp, counters);
  }
}

/** See ghost_gpu_step_launch. */
__global__ void ghost_gpu_step_kernel(struct parts p, struct gpu_leaves_dev lv,
                                      struct hydro_props hp, int *counters) {
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  for (int t = threadIdx.x; t < lv.count[L]; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    if (p.flags[i] & PART_H_CONVERGED) continue;
    ghost_gpu_one(&p, i, L, &lv, &hp, counters);
  }
}

/** See ghost_gpu_finish_launch. */
__global__ void ghost_gpu_finish_kernel(struct parts p, struct gpu_leaves_dev lv,
                                        struct hydro_props hp, const struct material_table *mats) {
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  for (int t = threadIdx.x; t < lv.count[L]; t += blockDim.x)
    if (!PART_IS_INACTIVE(&p, beg + (size_t)t)) ghost_part_finish(&p, beg + (size_t)t, &hp, mats);
}

void ghost_gpu_start_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                            struct hydro_props hp, int *counters) {
  if (lv.n == 0) return;
  ghost_gpu_start_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, hp, counters);
  gpu_check_launch(ghost_gpu_start_kernel);
}

void ghost_gpu_step_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                           struct hydro_props hp, int *counters) {
  if (lv.n == 0) return;
  ghost_gpu_step_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, hp, counters);
  gpu_check_launch(ghost_gpu_step_kernel);
}

void ghost_gpu_finish_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                             struct hydro_props hp, const struct material_table *mats) {
  if (lv.n == 0) return;
  ghost_gpu_finish_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, hp, mats);
  gpu_check_launch(ghost_gpu_finish_kernel);
}

/** The ghost family's step of the FORCE phase (tasks/task_families.h): the
 *  h iteration, density again for the particles still iterating until none
 *  is left (ghost_cpu.c's loop), then the grad-h factor and the EOS.  Ends
 *  the phase (returns 1, out->overflow) when some h outgrew the lists. */
int ghost_gpu_phase(struct gpu_phase *ph) {
  const struct hydro_props *hp = &ph->hp;
  ghost_gpu_start_launch(ph->s, ph->dev, ph->lv, *hp, ph->counters);
  gpu_phase_read_counters(ph);
  int iter = 1;
  ph->out->resummed = 0;
  while (ph->counters_host[GPU_LEFT] > 0 && !ph->counters_host[GPU_OVERFLOW]) {
    if (iter > hp->max_iterations)
      error_exit(
          "the smoothing lengths of %d particles did not converge in %d iterations on the GPU; "
          "raise "
          "SPH:max_ghost_iterations or check the initial conditions",
          ph->counters_host[GPU_LEFT], hp->max_iterations);
    ph->out->resummed += ph->counters_host[GPU_LEFT];
    gpu_check(cudaMemsetAsync(ph->counters + GPU_LEFT, 0, sizeof(int), ph->s));
    density_gpu_launch(ph->s, ph->dev, ph->lv, 1);
    ghost_gpu_step_launch(ph->s, ph->dev, ph->lv, *hp, ph->counters);
    gpu_phase_read_counters(ph);
    iter++;
  }
  ph->out->iterations = iter;
  ph->out->capped = ph->counters_host[GPU_CAPPED];
  if (ph->counters_host[GPU_OVERFLOW]) {
    /* the lists were too short for the new h: the runner hands h back */
    ph->out->overflow = 1;
    return 1;
  }
  ghost_gpu_finish_launch(ph->s, ph->dev, ph->lv, *hp, ph->mats);
  return 0;
}
