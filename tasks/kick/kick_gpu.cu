/* Second half kick and new time step on the GPU, with kick2_part (kick.h)
 * and, with brittle materials, damage_part_timestep (damage_part.h), with
 * self-gravity the gravitational acceleration added first and
 * gravity_timestep (gravity_iact.h), as the CPU task (kick2_task) does; each block reduces the
 * smallest time step of its leaf. */
#include "damage/damage_part.h"
#include "gravity/gravity_iact.h"
#include "gpu_kernels.h"
#include "kick.h"
#include "kick_porous.h"

/** See kick2_gpu_launch. */
__global__ void kick2_gpu_kernel(struct parts p, struct gpu_leaves_dev lv, struct hydro_props hp,
                                 const struct material_table *mats, double dt_kick,
                                 double damage_max_change, struct gpu_gravity grav,
                                 double *leaf_dt) {
  __shared__ double dt_min[GPU_BLOCK];
  const int L = blockIdx.x;
  const size_t beg = lv.offset[L];
  double dt = 1e300;
  for (int t = threadIdx.x; t < lv.count[L]; t += blockDim.x) {
    const size_t i = beg + (size_t)t;
    if (grav.enabled) {
      p.ax[i] += p.gax[i];
      p.ay[i] += p.gay[i];
      p.az[i] += p.gaz[i];
    }
    /* porous materials (kick_porous.h; no-ops for the others); dt_kick is
     * 0 exactly after the first force computation, which has no return */
    kick2_porous_rate(&p, i, mats);
    const double d = kick2_part(&p, i, dt_kick, &hp, mats);
    if (dt_kick > 0.0) kick2_porous_return(&p, i, mats, hp.continuity);
    if (d < dt) dt = d;
    if (damage_max_change > 0.0) {
      const double dtd = damage_part_timestep(&p, i, damage_max_change);
      if (dtd < dt) dt = dtd;
    }
    if (grav.enabled && grav.eps > 0.0) {
      const double ga[3] = {p.gax[i], p.gay[i], p.gaz[i]};
      const double dtg = gravity_timestep(ga, grav.eps, grav.eta);
      if (dtg < dt) dt = dtg;
    }
  }
  dt_min[threadIdx.x] = dt;
  __syncthreads();
  for (int w = blockDim.x / 2; w > 0; w /= 2) {
    if ((int)threadIdx.x < w && dt_min[threadIdx.x + w] < dt_min[threadIdx.x])
      dt_min[threadIdx.x] = dt_min[threadIdx.x + w];
    __syncthreads();
  }
  if (threadIdx.x == 0) leaf_dt[L] = dt_min[0];
}

void kick2_gpu_launch(cudaStream_t s, struct parts p, struct gpu_leaves_dev lv,
                      struct hydro_props hp, const struct material_table *mats, double dt_kick,
                      double damage_max_change, struct gpu_gravity grav, double *leaf_dt) {
  if (lv.n == 0) return;
  kick2_gpu_kernel<<<lv.n, lv.block, 0, s>>>(p, lv, hp, mats, dt_kick, damage_max_change, grav,
                                             leaf_dt);
  gpu_check_launch(kick2_gpu_kernel);
}

/** The kick family's step of the FORCE phase (tasks/task_families.h): the
 *  second half kick and the new time steps, the smallest of each leaf in
 *  leaf_dt. */
int kick_gpu_phase(struct gpu_phase *ph) {
  kick2_gpu_launch(ph->s, ph->dev, ph->lv, ph->hp, ph->mats, ph->dt_kick, ph->dmg_max_change,
                   ph->grav, ph->leaf_dt);
  return 0;
}
