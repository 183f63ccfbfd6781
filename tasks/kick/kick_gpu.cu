/* Second half kick and new time step on the GPU with kick2_part (kick.h),
 * the function of the CPU task (kick2_task): the gravitational acceleration,
 * the porous rates and return, and every time-step criterion
 * (timestep_part: hydrodynamic, damage and gravitational, the softening
 * tied to h included); each block reduces the smallest time step of its
 * leaf.  With time bins (gpu_set_bins) kick2_part_bins, the CPU task's
 * function, and each block also the earliest end of a step and the number
 * of particles kicked. */
#include <limits.h>

#include "src/gpu/gpu_kernels.h"
#include "tasks/kick/kick.h"

/** See kick2_gpu_launch. */
__global__ void kick2_gpu_kernel(struct parts p, struct gpu_leaves_dev lv, struct hydro_props hp,
                                 const struct material_table *mats, double dt_kick,
                                 double damage_max_change, struct gpu_gravity grav,
                                 struct gpu_bins bins, double *leaf_dt) {
  __shared__ double dt_min[GPU_BLOCK];
  __shared__ long long ti_min[GPU_BLOCK], kicked[GPU_BLOCK];
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  /* the GPU runs only with hydrodynamics on (gpu_engine.c); porous rates
   * are no-ops for the other materials */
  struct timestep_props tp;
  tp.hydro = 1;
  tp.porous = 1;
  tp.damage_max_change = damage_max_change;
  tp.gravity = grav.enabled;
  tp.grav_eps = grav.eps;
  tp.grav_h_factor = grav.h_factor;
  tp.grav_eta = grav.eta;
  double dt = 1e300;
  long long ti = LLONG_MAX, n = 0;
  for (int t = threadIdx.x; t < lv.count[L]; t += blockDim.x) {
    /* (no kick: a foreign copy of several MPI ranks, as kick2_cell_cpu) */
    if (PART_IS_NOT_OWNED(&p, beg + (size_t)t)) continue;
    double d;
    if (bins.on) {
      integertime_t ti_end;
      n += kick2_part_bins(&p, beg + (size_t)t, &hp, mats, &tp, &bins.tl, bins.ti_new, bins.first,
                           &ti_end, &d);
      if (ti_end < ti) ti = ti_end;
    } else {
      d = kick2_part(&p, beg + (size_t)t, dt_kick, &hp, mats, &tp);
    }
    if (d < dt) dt = d;
  }
  dt_min[threadIdx.x] = dt;
  ti_min[threadIdx.x] = ti;
  kicked[threadIdx.x] = n;
  __syncthreads();
  for (int w = blockDim.x / 2; w > 0; w /= 2) {
    if ((int)threadIdx.x < w) {
      if (dt_min[threadIdx.x + w] < dt_min[threadIdx.x])
        dt_min[threadIdx.x] = dt_min[threadIdx.x + w];
      if (ti_min[threadIdx.x + w] < ti_min[threadIdx.x])
        ti_min[threadIdx.x] = ti_min[threadIdx.x + w];
      kicked[threadIdx.x] += kicked[threadIdx.x + w];
    }
    __syncthreads();
  }
  if (threadIdx.x == 0) {
    leaf_dt[L] = dt_min[0];
    if (bins.on) {
      leaf_dt[lv.n + L] = __longlong_as_double(ti_min[0]);
      leaf_dt[2 * lv.n + L] = __longlong_as_double(kicked[0]);
    }
  }
}

void kick2_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                      struct hydro_props hp, const struct material_table *mats, double dt_kick,
                      double damage_max_change, struct gpu_gravity grav, struct gpu_bins bins,
                      double *leaf_dt) {
  if (lv.n == 0) return;
  kick2_gpu_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, hp, mats, dt_kick, damage_max_change, grav,
                                             bins, leaf_dt);
  gpu_check_launch(kick2_gpu_kernel);
}

/** The kick family's step of the FORCE phase (tasks/task_families.h): the
 *  second half kick and the new time steps, the smallest of each leaf in
 *  leaf_dt. */
int kick_gpu_phase(struct gpu_phase *ph) {
  kick2_gpu_launch(ph->s, ph->dev, ph->lv, ph->hp, ph->mats, ph->dt_kick, ph->dmg_max_change,
                   ph->grav, ph->bins, ph->leaf_dt);
  return 0;
}
