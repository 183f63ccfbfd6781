/* The GPU runner: one CUDA device holding the particle arrays and running
 * the FORCE phase of a step (density -> ghost -> force -> kick2/time step)
 * as batched kernels over every leaf cell (theory/architecture.md, "CPU and
 * GPU").
 *
 * The interface is C; the implementation (src/gpu/gpu.cu and the kernels
 * in tasks/<name>/<name>_gpu.cu) is CUDA C++ calling the same inline pair
 * functions and material models as the CPU loops.  Device memory is
 * allocated once and grown, never per step; every CUDA call is checked
 * (gpu_check.h).  Built only when configure finds nvcc (HAVE_CUDA). */
#ifndef BOLIDE_GPU_H
#define BOLIDE_GPU_H

#include <stddef.h>
#include <stdio.h>

#include "tasks/hydro/hydro_props.h"
#include "src/part.h"
#include "src/timeline.h"

#ifdef __cplusplus
extern "C" {
#endif

struct material_table;
struct gpu_lists;
/** A device with its streams, buffers and timers (opaque). */
struct gpu;

/** The batch of one FORCE phase, as host arrays: the leaf cells (each one
 *  contiguous particle range) and, for each leaf, the leaves (with periodic
 *  shifts) that its particles can interact with. */
struct gpu_leaves {
  int n;                    /**< number of leaves */
  const size_t *offset;     /**< first particle of each leaf */
  const int *count;         /**< particles of each leaf */
  const double *h_cap;      /**< largest h the top-level cells allow (capped: rebuild) */
  const double *h_list_cap; /**< largest h the neighbour lists below cover */
  const int
      *ngb_start;      /**< n + 1 entries: leaf L's neighbours are [ngb_start[L], ngb_start[L+1]) */
  const int *ngb_leaf; /**< neighbouring leaf of each entry (the leaf itself included) */
  const double *ngb_shift;       /**< 3 per entry: added to the neighbour's positions */
  int nr_ngb;                    /**< number of entries */
  const struct gpu_lists *lists; /**< non-NULL: the lists were built on the device
                                      (gpu_lists.h); ngb_start, ngb_leaf and ngb_shift
                                      above are then unused */
};

/** Damage in a FORCE phase (brittle materials, tasks/damage). */
struct gpu_damage {
  int enabled;       /**< run the damage task after the forces (flaws: gpu_set_flaws) */
  double dt;         /**< step over which damage grows (0 at the first force computation) */
  double max_change; /**< Damage:max_change, the time-step limit */
};

/** Self-gravity in a FORCE phase: the gravitational accelerations (gax,
 *  gay, gaz, complete on the device: gpu_grav_run) join the
 *  hydrodynamic ones in the kick, and their time-step criterion joins. */
struct gpu_gravity {
  int enabled;     /**< add ga in the kick */
  double eps;      /**< softening (time step criterion when > 0) */
  double eta;      /**< Gravity:eta */
  double h_factor; /**< Gravity:softening_h_factor (time step criterion with eps_i = h_factor h_i
                      when > 0) */
};

/** What a FORCE phase reports besides the particle fields. */
struct gpu_force_out {
  int capped;         /**< some h hit the top-level cells' cap: rebuild */
  int overflow;       /**< some h outgrew h_list_cap: rebuild the lists and call again
                           (h was copied back, everything else is unchanged) */
  int iterations;     /**< rounds of the h iteration */
  long long resummed; /**< particles whose density sums were redone, summed over the rounds */
};

/** Find the CUDA devices (cudaGetDeviceCount) and set up number device
 *  modulo their number (several MPI ranks of a node: each its own, from
 *  the node-local rank); NULL when there is none, with the reason in why. */
struct gpu *gpu_init(int device, char *why, size_t len);
/** The PCI bus ids ("0000:3b:00.0") of the CUDA devices 0 .. n-1 into
 *  ids[k] (len bytes each, at most max of them), without choosing one;
 *  returns n (0: none, or CUDA cannot be used). */
int gpu_bus_ids(char *ids, size_t len, int max);
/** "NVIDIA H100 80GB HBM3 (132 SMs, 79.1 GiB)" */
const char *gpu_name(const struct gpu *g);
/** Copy the flat array of Weibull flaw thresholds (n of them, indexed by the
 *  particles' flaw_first) to the device, where the damage kernel reads it;
 *  again whenever the array changes. */
void gpu_set_flaws(struct gpu *g, const double *eps, size_t n);
/** Run the FORCE phase on the particles p: density, h iteration (repeating
 *  the density sums of unconverged particles), equation of state, with
 *  solids (hp->solids) the gradient loop and the extra ghost (plasticity,
 *  dS/dt), forces, with dmg->enabled the damage update, second half kick by
 *  dt_kick (with grav->enabled adding the gravitational acceleration already
 *  on the device) and new time steps.  resident = 0: copy what
 *  the loops read to the device first and the results back after;
 *  resident = 1: the device arrays are current (gpu_upload_all), nothing
 *  but the leaf time steps comes back.  leaf_dt_min[L]: smallest new time
 *  step of leaf L; with time bins (gpu_set_bins) also, bit for bit in the
 *  doubles, the int64 earliest end of a step leaf_dt_min[n + L] and the
 *  int64 number of particles kicked leaf_dt_min[2 n + L] (n leaves).  A particle whose h does not
 * converge in hp->max_iterations stops the run with an error. */
void gpu_force_phase(struct gpu *g, struct parts *p, const struct gpu_leaves *lv,
                     const struct hydro_props *hp, const struct material_table *mats,
                     const struct gpu_damage *dmg, const struct gpu_gravity *grav, double dt_kick,
                     double *leaf_dt_min, int resident, struct gpu_force_out *out);
/** After a FORCE phase that ended in out->overflow (its grown h handed
 *  back to build wider lists): put back the h the phase started from, on
 *  the device (resident) or in p (not resident), so that the repeat
 *  iterates from there as the CPU's ghost does.  Synchronous. */
void gpu_restore_h(struct gpu *g, struct parts *p, int resident);
/** Have gpu_force_phase call fn(ctx) before its kick reads ga, and before
 *  it writes the host's h when the lists overflow (fn NULL: nothing).  The
 *  hybrid runner's hook: it waits there for the self-gravity computed
 *  beside the phase (CPU tasks), then completes ga on the device (the
 *  device part of gravity on stream 0, or gpu_upload_gravity). */
void gpu_set_kick_wait(struct gpu *g, void (*fn)(void *), void *ctx);
/** Several MPI ranks: fn(ctx, k) is called within gpu_force_phase after
 *  stage k of the phase (0: density and ghost; 1: gradient and extra
 *  ghost), the device idle, so that the foreign copies take their owners'
 *  results before the next stage reads them (src/mpi/halo.c; fn NULL:
 *  nothing). */
void gpu_set_stage_hook(struct gpu *g, void (*fn)(void *, int), void *ctx);
/** The records of several MPI ranks (src/mpi/halo.c) from and to the
 *  resident particles.  gpu_halo_pack: the fields of sel (NULL: every
 *  field) of particles idx[0 .. n), field after field as halo.c packs
 *  them (the absent fields left out), into the host buffer dst.  gpu_halo_unpack: a block of such
 * records into particles slot[0 .. n) of the device, each marked a foreign copy (PART_FOREIGN, msrc
 * = q0 + k) as the host marks them.  gpu_halo_ms: the milliseconds both took so far. */
void gpu_halo_pack(struct gpu *g, const struct parts *p, const size_t *idx, size_t n, char *dst,
                   const unsigned char *sel);
void gpu_halo_unpack(struct gpu *g, const size_t *slot, size_t n, const char *src,
                     const unsigned char *sel, int64_t q0);
double gpu_halo_ms(const struct gpu *g);

/** Individual time steps (TimeIntegration:global_step: false) in the GPU's
 *  drift and kick (drift_part_bins, kick2_part_bins: the CPU's functions). */
struct gpu_bins {
  int on;               /**< 0: the global step */
  int first;            /**< the first force computation: every particle takes a bin, no kick */
  integertime_t ti_old; /**< the drift's start on the time line */
  integertime_t ti_new; /**< the drift's end, the kick's time */
  struct timeline tl;   /**< the run's time line */
};

/** The time bins of the next FORCE phases' kicks (NULL or on = 0: the
 *  global step); with them the phase's leaf_dt_min holds 3 values per leaf
 *  (gpu_force_phase). */
void gpu_set_bins(struct gpu *g, const struct gpu_bins *bins);
/** Copy gax, gay, gaz and pot of the resident particles from the host to
 *  the device on stream 0 (self-gravity computed on the CPU). */
void gpu_upload_gravity(struct gpu *g, struct parts *p);
/** Let host threads waiting for the device sleep instead of spinning (the
 *  hybrid runner: the CPU workers need the cores).  Returns 0 when the
 *  driver refuses (the waits then keep spinning). */
int gpu_set_blocking_sync(struct gpu *g);
/** Mark the named particle fields (n of them) as absent from the device:
 *  the fields the host does not hold either (parts_drop), never allocated,
 *  copied, reordered or put in the MPI records there (the run never uses
 *  them; the shared functions test the array pointer, e.g. p->Sxx, before
 *  they touch a group that may be absent).  Before the first upload only.
 *  Returns the bytes per particle saved. */
int gpu_set_absent(struct gpu *g, const char *const *names, int n);
/** Copy every particle field to the device (after a rebuild or a restart). */
void gpu_upload_all(struct gpu *g, const struct parts *p);
/** Copy every particle field back to the host (outputs, rebuilds). */
void gpu_download_all(struct gpu *g, struct parts *p);
/** Copy the named fields (n of them) to the device (to_device 1) or back. */
void gpu_copy_some(struct gpu *g, struct parts *p, const char *const *names, int n, int to_device);
/** A rebuild of resident particles: element i of every device field
 *  becomes the old element perm[i] (n = the resident count; space_order's
 *  permutation), and x0 = x. */
void gpu_permute(struct gpu *g, const size_t *perm, size_t n);
/** First half kick by dt_kick and drift by dt of the resident particles
 *  with the SPH settings hp (with the time bins of gpu_set_bins: from
 *  bins.ti_old to bins.ti_new, drift_part_bins, which predicts the
 *  sleeping particles' equation of state with the materials mats); copy
 *  back the positions and smoothing lengths (what the CPU needs to decide
 *  on a rebuild and to build the neighbour lists). */
void gpu_drift(struct gpu *g, struct parts *p, double dt_kick, double dt,
               const struct hydro_props *hp, const struct material_table *mats);
/** The rk2/pc integrator's device arrays (tasks/drift/drift_integrate.c): for n
 *  particles ny doubles of state (*y0) and nrec records of nr doubles
 *  (r[0 .. nrec)); kept, and made again only for a larger n, until
 *  gpu_free. */
void gpu_rk_arrays(struct gpu *g, size_t n, int ny, int nr, int nrec, double **y0, double **r);
struct drift_stage;
/** A stage of rk2 or pc on the resident particles (drift_rk_stage, st's
 *  arrays those of gpu_rk_arrays), then the positions and smoothing
 *  lengths back to the host as gpu_drift; returns the largest error
 *  estimate (0 without st->err). */
double gpu_drift_stage(struct gpu *g, struct parts *p, const struct drift_stage *st,
                       const struct hydro_props *hp);
/** The step's start (y0, r1 of gpu_rk_arrays) back into the resident
 *  particles (drift_rk_restore). */
void gpu_rk_restore(struct gpu *g, const double *y0, const double *r1);
/** The watchdog (engine.c) on the resident particles.  gpu_watchdog_save:
 *  keep the positions before the drift on the device (a device copy, queued
 *  before the drift).  gpu_watchdog_moved: after the drift, the first
 *  particle that moved more than width since (or whose displacement is
 *  not a number), -1 if none; when there is one, the saved positions are
 *  copied into x0_host (x of every particle, then y, then z).
 *  gpu_watchdog_check: 1 if a double field of a particle is Inf or NaN, a
 *  density is negative, or u is negative for a material whose id is one of
 *  u_floor_ids[0..n_ids) (the host then copies the particles back and names
 *  it).  Each check is one pass over the device arrays and a read of a few
 *  words. */
void gpu_watchdog_save(struct gpu *g);
long gpu_watchdog_moved(struct gpu *g, double width, double *x0_host);
int gpu_watchdog_check(struct gpu *g, const int32_t *u_floor_ids, int n_ids);
/** Unregister the pinned particle arrays (before they are freed). */
void gpu_unpin(struct gpu *g);
/** Print the accumulated time of each stage. */
void gpu_print_timers(const struct gpu *g, FILE *f);
/** Bytes copied host -> device and device -> host so far. */
void gpu_bytes_moved(const struct gpu *g, double *h2d, double *d2h);
/** Device memory the run holds now (in use minus what the context took at
 *  gpu_init) and the device's total, in bytes. */
void gpu_memory_used(const struct gpu *g, double *run, double *total);
/** One line: the device memory the runner allocated, by use (its
 *  allocations' names), in bytes per particle of nparts, largest first. */
void gpu_memory_by_use(FILE *f, double nparts);
/** Free everything. */
void gpu_free(struct gpu *g);

#ifdef __cplusplus
}
#endif

#endif
