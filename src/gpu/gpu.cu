/* The GPU runner (gpu.h): device set-up, memory that is allocated once and
 * grown, two streams, pinned staging for the per-phase cell data, and the
 * FORCE phase as a sequence of batched kernels over every leaf cell:
 * density, ghost (h iteration, EOS), with solids gradient and extra ghost,
 * force, with brittle materials damage, and kick2.
 *
 * Stream 0 carries the particle fields and the kernels; stream 1 builds the
 * neighbour lists (gpu_lists.cu, or uploads the host's) and uploads the
 * leaves at the same time, and stream 0 waits for it on an event before the
 * first kernel.  The host waits only where it must
 * read something: the counter of particles still iterating h after each
 * round of the ghost, and the results at the end of the phase. */
#include <stdlib.h>
#include <string.h>

extern "C" {
#include "error.h"
#include "part.h"
}
#include "gpu.h"
#include "gpu_kernels.h"
#include "gpu_lists.h"
#include "material.h"

/** Fields the FORCE phase reads (copied to the device before it when the
 *  particles are not resident). */
static const char *const gpu_fields_in[] = {"x",  "y",   "z",  "vpx", "vpy", "vpz", "m",    "h",
                                            "up", "mat", "vx", "vy",  "vz",  "u",   "flags",
                                            "rho_full", "rho_fp", "alpha", "alpha_p", "e_clamp"};
/** Fields the FORCE phase writes (copied back after it). */
static const char *const gpu_fields_out[] = {
    "h",       "rho", "rho_dh", "wcount",  "wcount_dh", "div_v", "curl_vx", "curl_vy",
    "curl_vz", "P",   "cs",     "cl",      "balsara", "f_gradh",   "flags", "h_lo",    "h_hi",
    "ax",      "ay",  "az",     "du_dt",   "drho_dt",   "v_sig", "vx",      "vy",
    "vz",      "u",   "vpx",    "vpy",     "vpz",       "up",      "rho_full", "rho_fp",
    "xsphx",   "xsphy", "xsphz", "alpha", "alpha_p", "dalpha_dt", "e_clamp"};
/** Fields the gradient loop, the extra ghost and the stress terms read, and
 *  the kick integrates (solids). */
static const char *const gpu_fields_solid_in[] = {"Sxx",  "Sxy",  "Sxz",   "Syy",  "Syz",
                                                  "Szz",  "Spxx", "Spxy",  "Spxz", "Spyy",
                                                  "Spyz", "Spzz", "eps_p", "dmg",
                                                  "dmg_shear", "w_plastic"};
/** Fields they write. */
static const char *const gpu_fields_solid_out[] = {
    "gmxx", "gmxy", "gmxz", "gmyy", "gmyz", "gmzz", "gvxx", "gvxy", "gvxz", "gvyx",
    "gvyy", "gvyz", "gvzx", "gvzy", "gvzz", "Sxx",  "Sxy",  "Sxz",  "Syy",  "Syz",
    "Szz",  "Spxx", "Spxy", "Spxz", "Spyy", "Spyz", "Spzz", "dSxx", "dSxy", "dSxz",
    "dSyy", "dSyz", "dSzz", "Rxx",  "Rxy",  "Rxz",  "Ryy",  "Ryz",  "Rzz",  "eps_p",
    "dmg_shear", "w_plastic", "wvol"};
/** Fields the damage task reads (besides the above). */
static const char *const gpu_fields_damage_in[] = {"dmg", "dcbrt", "n_act", "n_flaws",
                                                   "flaw_first"};
/** Fields it writes. */
static const char *const gpu_fields_damage_out[] = {"dmg", "dcbrt", "n_act", "dmg_rate"};
#define GPU_NR_OF(a) ((int)(sizeof a / sizeof a[0]))
#define GPU_NR_IN GPU_NR_OF(gpu_fields_in)
#define GPU_NR_OUT GPU_NR_OF(gpu_fields_out)
#define GPU_NR_SOLID_IN GPU_NR_OF(gpu_fields_solid_in)
#define GPU_NR_SOLID_OUT GPU_NR_OF(gpu_fields_solid_out)
#define GPU_NR_DAMAGE_IN GPU_NR_OF(gpu_fields_damage_in)
#define GPU_NR_DAMAGE_OUT GPU_NR_OF(gpu_fields_damage_out)

/** Stages timed with events. */
enum gpu_stage {
  GPU_T_UPLOAD,
  GPU_T_DENSITY,
  GPU_T_GHOST,
  GPU_T_GRADIENT,
  GPU_T_FORCE,
  GPU_T_DAMAGE,
  GPU_T_WAIT,
  GPU_T_KICK,
  GPU_T_DOWNLOAD,
  GPU_T_N
};
static const char *const gpu_stage_names[GPU_T_N] = {
    "upload", "density", "ghost", "gradient(+extra ghost)", "force", "damage",
    "gravity(hybrid: wait + device part)", "kick2", "download"};

struct gpu {
  int device;                  /**< CUDA device number */
  char name[512];              /**< description for the log */
  size_t mem_base;             /**< device memory in use when the context was made (not the run's) */
  cudaStream_t stream[2];      /**< 0: fields and kernels; 1: cell data */
  cudaEvent_t ev[GPU_T_N + 1]; /**< stage boundaries of the last phase */
  cudaEvent_t cells_ready;     /**< stream 1 finished its upload */
  cudaEvent_t ev_drift[2];     /**< around the last drift */
  double t_drift;              /**< accumulated milliseconds of drifts (with the copy back) */
  long drifts;                 /**< drifts run */
  struct parts dev;            /**< device arrays of every particle field */
  size_t capacity;             /**< their length */
  int in[GPU_NR_IN + GPU_NR_SOLID_IN + GPU_NR_DAMAGE_IN];     /**< indices in part_fields */
  int out[GPU_NR_OUT + GPU_NR_SOLID_OUT + GPU_NR_DAMAGE_OUT]; /**< indices in part_fields */
  double *flaws_dev;                 /**< Weibull flaw thresholds (gpu_set_flaws) */
  size_t flaws_n, flaws_cap;         /**< their number and allocated length */
  void *cell_dev, *cell_host;        /**< device buffer and pinned staging of the leaf data */
  double *leaf_dt;                   /**< smallest time step of each leaf (in cell_dev) */
  size_t cell_bytes;                 /**< their size */
  int *counters_dev, *counters_host; /**< h-iteration counters (host side pinned) */
  struct material_table *mats_dev;   /**< the material table on the device */
  struct material_table *mats_host;  /**< pinned staging of it */
  double *table_dev[MATERIAL_MAX];   /**< device copies of tabulated EOS nodes (P, c2, T) */
  struct eos_table table_src[MATERIAL_MAX]; /**< the host tables they mirror */
  double t[GPU_T_N];                 /**< accumulated milliseconds per stage */
  long calls;                        /**< FORCE phases run */
  double bytes_h2d, bytes_d2h;       /**< traffic over the bus */
  double bytes_full;                 /**< of which the full copies (both ways) */
  long full_up, full_down;           /**< copies of every field (rebuilds, outputs) */
  void *pinned[PART_NR_FIELDS];      /**< host arrays registered as pinned memory, by field */
  size_t pinned_bytes;               /**< bytes per field registered */
  void (*kick_wait)(void *);         /**< called before the kick reads ga (gpu_set_kick_wait) */
  void *kick_wait_ctx;               /**< its argument */
};

void gpu_check_fail(cudaError_t err, const char *what, const char *file, int line) {
  error_exit("CUDA call %s failed at %s:%d: %s", what, file, line, cudaGetErrorString(err));
}

/** cudaMalloc that reports, when the device is full, what was needed and
 *  what is free. */
void *gpu_alloc(size_t bytes, const char *what) {
  void *ptr = NULL;
  if (bytes == 0) bytes = 8;
  const cudaError_t err = cudaMalloc(&ptr, bytes);
  if (err == cudaErrorMemoryAllocation) {
    size_t free_b = 0, total_b = 0;
    cudaGetLastError();
    cudaMemGetInfo(&free_b, &total_b);
    error_exit("GPU out of memory allocating %s: needed %.1f MiB, %.1f MiB free of %.1f MiB", what,
               bytes / 1048576.0, free_b / 1048576.0, total_b / 1048576.0);
  }
  gpu_check(err);
  return ptr;
}

/** Index of the field called name in part_fields. */
static int gpu_field_index(const char *name) {
  for (int k = 0; k < part_nr_fields; k++)
    if (strcmp(part_fields[k].name, name) == 0) return k;
  error_bug("no particle field %s", name);
}

/** Address of the array pointer of field k in the struct parts s. */
static void **gpu_field_slot(struct parts *s, int k) {
  return (void **)((char *)s + part_fields[k].offset);
}

extern "C" struct gpu *gpu_init(char *why, size_t len) {
  int n = 0;
  const cudaError_t err = cudaGetDeviceCount(&n);
  if (err != cudaSuccess || n == 0) {
    snprintf(why, len, "%s", err != cudaSuccess ? cudaGetErrorString(err) : "no CUDA device");
    cudaGetLastError();
    return NULL;
  }
  struct gpu *g = (struct gpu *)error_calloc(1, sizeof(struct gpu), "GPU state");
  g->device = 0;
  gpu_check(cudaSetDevice(g->device));
  cudaDeviceProp prop;
  gpu_check(cudaGetDeviceProperties(&prop, g->device));
  snprintf(g->name, sizeof g->name, "%.256s (%d SMs, %.1f GiB, compute capability %d.%d)",
           prop.name, prop.multiProcessorCount, prop.totalGlobalMem / 1073741824.0, prop.major,
           prop.minor);
  for (int k = 0; k < 2; k++)
    gpu_check(cudaStreamCreateWithFlags(&g->stream[k], cudaStreamNonBlocking));
  {
    size_t free_b = 0, total_b = 0;
    gpu_check(cudaMemGetInfo(&free_b, &total_b));
    g->mem_base = total_b - free_b;
  }
  for (int k = 0; k <= GPU_T_N; k++) gpu_check(cudaEventCreate(&g->ev[k]));
  gpu_check(cudaEventCreateWithFlags(&g->cells_ready, cudaEventDisableTiming));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventCreate(&g->ev_drift[k]));
  g->counters_dev = (int *)gpu_alloc(GPU_NR_COUNTERS * sizeof(int), "counters");
  gpu_check(cudaMallocHost((void **)&g->counters_host, GPU_NR_COUNTERS * sizeof(int)));
  g->mats_dev = (struct material_table *)gpu_alloc(sizeof(struct material_table), "material table");
  gpu_check(cudaMallocHost((void **)&g->mats_host, sizeof(struct material_table)));
  return g;
}

extern "C" const char *gpu_name(const struct gpu *g) {
  return g->name;
}

/** Grow the device particle arrays to at least n (contents are not kept:
 *  every phase uploads what it reads). */
static void gpu_reserve(struct gpu *g, size_t n) {
  if (n <= g->capacity) return;
  const size_t cap = n + n / 4 + 1024;
  for (int k = 0; k < part_nr_fields; k++) {
    void **slot = gpu_field_slot(&g->dev, k);
    if (*slot) gpu_check(cudaFree(*slot));
    char what[128];
    snprintf(what, sizeof what, "particle field %s (%zu particles)", part_fields[k].name, cap);
    *slot = gpu_alloc(cap * part_fields[k].size, what);
  }
  g->capacity = cap;
  g->dev.capacity = cap;
}

/** Round up to a multiple of 16 bytes. */
static size_t gpu_align(size_t b) {
  return (b + 15) & ~(size_t)15;
}

/** Pack the leaf data into pinned memory, upload it on stream 1 and return
 *  the device view. */
static struct gpu_leaves_dev gpu_upload_cells(struct gpu *g, const struct gpu_leaves *lv) {
  /* lists built on the device stay there */
  const size_t n = (size_t)lv->n, nn = lv->lists ? 0 : (size_t)lv->nr_ngb;
  const size_t sz[8] = {n * sizeof(size_t),      n * sizeof(int),       n * sizeof(double),
                        n * sizeof(double),      (lv->lists ? 0 : n + 1) * sizeof(int), nn * sizeof(int),
                        3 * nn * sizeof(double), n * sizeof(double)};
  size_t off[8], total = 0;
  for (int k = 0; k < 8; k++) {
    off[k] = total;
    total += gpu_align(sz[k]);
  }
  if (total > g->cell_bytes) {
    if (g->cell_dev) gpu_check(cudaFree(g->cell_dev));
    if (g->cell_host) gpu_check(cudaFreeHost(g->cell_host));
    g->cell_bytes = total + total / 2;
    g->cell_dev = gpu_alloc(g->cell_bytes, "leaf cells and neighbour lists");
    gpu_check(cudaMallocHost(&g->cell_host, g->cell_bytes));
  }
  char *h = (char *)g->cell_host, *d = (char *)g->cell_dev;
  const void *src[7] = {lv->offset,    lv->count,    lv->h_cap,    lv->h_list_cap,
                        lv->ngb_start, lv->ngb_leaf, lv->ngb_shift};
  for (int k = 0; k < 7; k++)
    if (sz[k]) memcpy(h + off[k], src[k], sz[k]);
  gpu_check(cudaMemcpyAsync(d, h, off[7], cudaMemcpyHostToDevice, g->stream[1]));
  gpu_check(cudaEventRecord(g->cells_ready, g->stream[1]));
  g->bytes_h2d += (double)off[7];
  struct gpu_leaves_dev dv;
  dv.n = lv->n;
  /* a warp per 32 particles of the mean leaf, so few threads idle */
  const double mean =
      lv->n ? (double)(lv->offset[lv->n - 1] + lv->count[lv->n - 1] - lv->offset[0]) / lv->n : 0.0;
  dv.block = mean <= 40.0 ? 32 : (mean <= 96.0 ? 64 : GPU_BLOCK);
  dv.offset = (const size_t *)(d + off[0]);
  dv.count = (const int *)(d + off[1]);
  dv.h_cap = (const double *)(d + off[2]);
  dv.h_list_cap = (const double *)(d + off[3]);
  dv.ngb_start = (const int *)(d + off[4]);
  dv.ngb_leaf = (const int *)(d + off[5]);
  dv.ngb_shift = (const double *)(d + off[6]);
  if (lv->lists) gpu_lists_view(lv->lists, &dv.ngb_start, &dv.ngb_leaf, &dv.ngb_shift);
  g->leaf_dt = (double *)(d + off[7]);
  return dv;
}

/** Copy fields idx[0..n) of particles [0, count) between host and device on stream s. */
static void gpu_copy_fields(struct gpu *g, struct parts *p, const int *idx, int n, int to_device) {
  for (int k = 0; k < n; k++) {
    const int f = idx[k];
    void *hp = *gpu_field_slot(p, f), *dp = *gpu_field_slot(&g->dev, f);
    const size_t bytes = p->count * part_fields[f].size;
    if (to_device)
      gpu_check(cudaMemcpyAsync(dp, hp, bytes, cudaMemcpyHostToDevice, g->stream[0]));
    else
      gpu_check(cudaMemcpyAsync(hp, dp, bytes, cudaMemcpyDeviceToHost, g->stream[0]));
    if (to_device)
      g->bytes_h2d += (double)bytes;
    else
      g->bytes_d2h += (double)bytes;
  }
}

/** The indices (in part_fields) of the fields a FORCE phase reads (out = 0)
 *  or writes (out = 1), for fluids, solids and damage; returns their
 *  number.  A field named twice is copied once. */
static int gpu_phase_fields(int *idx, int solids, int damage, int out) {
  int n = 0;
  const char *const *lists[3] = {out ? gpu_fields_out : gpu_fields_in,
                                 out ? gpu_fields_solid_out : gpu_fields_solid_in,
                                 out ? gpu_fields_damage_out : gpu_fields_damage_in};
  const int len[3] = {out ? GPU_NR_OUT : GPU_NR_IN, out ? GPU_NR_SOLID_OUT : GPU_NR_SOLID_IN,
                      out ? GPU_NR_DAMAGE_OUT : GPU_NR_DAMAGE_IN};
  const int use[3] = {1, solids, damage};
  for (int l = 0; l < 3; l++)
    if (use[l])
      for (int k = 0; k < len[l]; k++) {
        const int f = gpu_field_index(lists[l][k]);
        int seen = 0;
        for (int q = 0; q < n; q++) seen |= idx[q] == f;
        if (!seen) idx[n++] = f;
      }
  return n;
}

extern "C" void gpu_set_flaws(struct gpu *g, const double *eps, size_t n) {
  if (n > g->flaws_cap) {
    if (g->flaws_dev) gpu_check(cudaFree(g->flaws_dev));
    char what[128];
    snprintf(what, sizeof what, "Weibull flaw thresholds (%zu)", n);
    g->flaws_dev = (double *)gpu_alloc(n * sizeof(double), what);
    g->flaws_cap = n;
  }
  g->flaws_n = n;
  if (n) gpu_check(cudaMemcpy(g->flaws_dev, eps, n * sizeof(double), cudaMemcpyHostToDevice));
  g->bytes_h2d += (double)(n * sizeof(double));
}

/** The material table as the device sees it: a copy of mats whose tabulated
 *  EOS point at device copies of their nodes.  A table is uploaded once
 *  (tables are constant during a run) and again only when the host table
 *  it mirrors changes (other arrays or grid). */
static void gpu_stage_materials(struct gpu *g, const struct material_table *mats) {
  memcpy(g->mats_host, mats, sizeof *mats);
  for (int k = 0; k < mats->n; k++) {
    if (mats->mats[k].eos_type != EOS_TABLE) continue;
    const struct eos_table *t = &mats->mats[k].eos.table;
    const size_t nn = (size_t)t->n_rho * (size_t)t->n_u, nf = t->T ? 3 : 2;
    if (!g->table_dev[k] || memcmp(&g->table_src[k], t, sizeof *t) != 0) {
      if (g->table_dev[k]) gpu_check(cudaFree(g->table_dev[k]));
      char what[160];
      snprintf(what, sizeof what, "tabulated EOS of material %s (%zu nodes)", mats->mats[k].name,
               nn);
      g->table_dev[k] = (double *)gpu_alloc(nf * nn * sizeof(double), what);
      const double *src[3] = {t->P, t->c2, t->T};
      for (size_t f = 0; f < nf; f++)
        gpu_check(cudaMemcpy(g->table_dev[k] + f * nn, src[f], nn * sizeof(double),
                             cudaMemcpyHostToDevice));
      g->bytes_h2d += (double)(nf * nn * sizeof(double));
      g->table_src[k] = *t;
    }
    struct eos_table *d = &g->mats_host->mats[k].eos.table;
    d->P = g->table_dev[k];
    d->c2 = g->table_dev[k] + nn;
    d->T = t->T ? g->table_dev[k] + 2 * nn : NULL;
  }
}

/** Read the counters of the h iteration (waits for stream 0). */
static void gpu_read_counters(struct gpu *g) {
  gpu_check(cudaMemcpyAsync(g->counters_host, g->counters_dev, GPU_NR_COUNTERS * sizeof(int),
                            cudaMemcpyDeviceToHost, g->stream[0]));
  gpu_check(cudaStreamSynchronize(g->stream[0]));
}

extern "C" void gpu_force_phase(struct gpu *g, struct parts *p, const struct gpu_leaves *lv,
                                const struct hydro_props *hp, const struct material_table *mats,
                                const struct gpu_damage *dmg, const struct gpu_gravity *grav,
                                double dt_kick, double *leaf_dt_min, int resident,
                                struct gpu_force_out *out) {
  cudaStream_t s = g->stream[0];
  memset(out, 0, sizeof *out);
  const int damage = dmg && dmg->enabled;
  const int nr_in = gpu_phase_fields(g->in, hp->solids, damage, 0);
  const int nr_out = gpu_phase_fields(g->out, hp->solids, damage, 1);
  if (resident && (p->count != g->dev.count || !g->dev.x))
    error_bug("GPU particle arrays are not resident");
  gpu_reserve(g, p->count);
  g->dev.count = p->count;
  gpu_check(cudaEventRecord(g->ev[0], s));
  const struct gpu_leaves_dev dv = gpu_upload_cells(g, lv);
  if (!resident) gpu_copy_fields(g, p, g->in, nr_in, 1);
  gpu_stage_materials(g, mats);
  gpu_check(cudaMemcpyAsync(g->mats_dev, g->mats_host, sizeof *mats, cudaMemcpyHostToDevice, s));
  gpu_check(cudaMemsetAsync(g->counters_dev, 0, GPU_NR_COUNTERS * sizeof(int), s));
  gpu_check(cudaStreamWaitEvent(s, g->cells_ready, 0));
  gpu_check(cudaEventRecord(g->ev[1], s));

  /* density of every particle, then the h iteration: density again for the
   * particles still iterating until none is left (ghost_cpu.c's loop) */
  density_gpu_launch(s, g->dev, dv, 0);
  gpu_check(cudaEventRecord(g->ev[2], s));
  ghost_gpu_start_launch(s, g->dev, dv, *hp, g->counters_dev);
  gpu_read_counters(g);
  int iter = 1;
  while (g->counters_host[GPU_LEFT] > 0 && !g->counters_host[GPU_OVERFLOW]) {
    if (iter > hp->max_iterations)
      error_exit(
          "the smoothing lengths of %d particles did not converge in %d iterations on the GPU; "
          "raise "
          "SPH:max_ghost_iterations or check the initial conditions",
          g->counters_host[GPU_LEFT], hp->max_iterations);
    gpu_check(cudaMemsetAsync(g->counters_dev + GPU_LEFT, 0, sizeof(int), s));
    density_gpu_launch(s, g->dev, dv, 1);
    ghost_gpu_step_launch(s, g->dev, dv, *hp, g->counters_dev);
    gpu_read_counters(g);
    iter++;
  }
  out->iterations = iter;
  out->capped = g->counters_host[GPU_CAPPED];
  if (g->counters_host[GPU_OVERFLOW]) {
    /* the lists were too short for the new h: hand h back for new lists */
    out->overflow = 1;
    /* the host's h changes below: let whatever runs beside this phase finish first */
    if (g->kick_wait) g->kick_wait(g->kick_wait_ctx);
    const int ih = gpu_field_index("h");
    gpu_copy_fields(g, p, &ih, 1, 0);
    gpu_check(cudaStreamSynchronize(s));
    return;
  }
  ghost_gpu_finish_launch(s, g->dev, dv, *hp, g->mats_dev);
  gpu_check(cudaEventRecord(g->ev[3], s));
  if (hp->solids) {
    /* ghost -> gradient -> extra ghost -> force (engine_graph.c) */
    gradient_gpu_launch(s, g->dev, dv);
    extra_ghost_gpu_launch(s, g->dev, *hp, g->mats_dev);
  }
  gpu_check(cudaEventRecord(g->ev[4], s));
  force_gpu_launch(s, g->dev, dv, *hp);
  gpu_check(cudaEventRecord(g->ev[5], s));
  /* force -> damage -> kick2 */
  if (damage) damage_gpu_launch(s, g->dev, g->mats_dev, g->flaws_dev, dmg->dt);
  gpu_check(cudaEventRecord(g->ev[6], s));
  /* hybrid runs: ga is being computed beside this phase; complete on the
   * device once this returns (its device part, if any, queued on stream 0) */
  if (g->kick_wait) g->kick_wait(g->kick_wait_ctx);
  gpu_check(cudaEventRecord(g->ev[7], s));
  double *leaf_dt = g->leaf_dt;
  struct gpu_gravity gr = {0, 0.0, 0.0};
  if (grav) gr = *grav;
  kick2_gpu_launch(s, g->dev, dv, *hp, g->mats_dev, dt_kick, damage ? dmg->max_change : 0.0, gr,
                   leaf_dt);
  gpu_check(cudaEventRecord(g->ev[8], s));
  if (!resident) gpu_copy_fields(g, p, g->out, nr_out, 0);
  gpu_check(cudaMemcpyAsync(leaf_dt_min, leaf_dt, (size_t)lv->n * sizeof(double),
                            cudaMemcpyDeviceToHost, s));
  gpu_check(cudaEventRecord(g->ev[9], s));
  gpu_check(cudaStreamSynchronize(s));
  for (int k = 0; k < GPU_T_N; k++) {
    float ms = 0.0f;
    gpu_check(cudaEventElapsedTime(&ms, g->ev[k], g->ev[k + 1]));
    g->t[k] += ms;
  }
  g->calls++;
}

extern "C" void gpu_set_kick_wait(struct gpu *g, void (*fn)(void *), void *ctx) {
  g->kick_wait = fn;
  g->kick_wait_ctx = ctx;
}

extern "C" void gpu_upload_gravity(struct gpu *g, struct parts *p) {
  static const char *const names[4] = {"gax", "gay", "gaz", "pot"};
  if (p->count != g->dev.count) error_bug("GPU and host particle counts differ");
  gpu_copy_named(g, p, names, 4, 1);
}

extern "C" int gpu_set_blocking_sync(struct gpu *g) {
  (void)g;
  const cudaError_t err = cudaSetDeviceFlags(cudaDeviceScheduleBlockingSync);
  if (err != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return 1;
}

cudaStream_t gpu_stream(struct gpu *g, int k) {
  return g->stream[k];
}

struct parts gpu_device_parts(struct gpu *g, size_t count) {
  gpu_reserve(g, count);
  g->dev.count = count;
  return g->dev;
}

void gpu_copy_named(struct gpu *g, struct parts *p, const char *const *names, int n,
                    int to_device) {
  int idx[PART_NR_FIELDS];
  for (int k = 0; k < n; k++) idx[k] = gpu_field_index(names[k]);
  gpu_copy_fields(g, p, idx, n, to_device);
}

void gpu_bytes_add(struct gpu *g, double h2d, double d2h) {
  g->bytes_h2d += h2d;
  g->bytes_d2h += d2h;
}

/** Register the particle arrays of p as pinned (page-locked) memory, so
 *  that copies run at the bus's full rate and asynchronously; again when
 *  the arrays moved (parts_reserve). */
static void gpu_pin(struct gpu *g, const struct parts *p) {
  int same = g->pinned_bytes == p->capacity;
  for (int f = 0; f < part_nr_fields && same; f++)
    same = g->pinned[f] == *gpu_field_slot((struct parts *)p, f);
  if (same) return;
  gpu_unpin(g);
  for (int f = 0; f < part_nr_fields; f++) {
    void *a = *gpu_field_slot((struct parts *)p, f);
    gpu_check(cudaHostRegister(a, p->capacity * part_fields[f].size, cudaHostRegisterDefault));
    g->pinned[f] = a;
  }
  g->pinned_bytes = p->capacity;
}

extern "C" void gpu_unpin(struct gpu *g) {
  for (int f = 0; f < part_nr_fields; f++)
    if (g->pinned[f]) {
      gpu_check(cudaHostUnregister(g->pinned[f]));
      g->pinned[f] = NULL;
    }
  g->pinned_bytes = 0;
}

extern "C" void gpu_upload_all(struct gpu *g, const struct parts *p) {
  gpu_pin(g, p);
  g->full_up++;
  gpu_reserve(g, p->count);
  g->dev.count = p->count;
  for (int f = 0; f < part_nr_fields; f++) {
    const size_t bytes = p->count * part_fields[f].size;
    gpu_check(cudaMemcpyAsync(*gpu_field_slot(&g->dev, f), *gpu_field_slot((struct parts *)p, f),
                              bytes, cudaMemcpyHostToDevice, g->stream[0]));
    g->bytes_h2d += (double)bytes;
    g->bytes_full += (double)bytes;
  }
  gpu_check(cudaStreamSynchronize(g->stream[0]));
}

extern "C" void gpu_download_all(struct gpu *g, struct parts *p) {
  if (p->count != g->dev.count) error_bug("GPU and host particle counts differ");
  gpu_pin(g, p);
  g->full_down++;
  for (int f = 0; f < part_nr_fields; f++) {
    const size_t bytes = p->count * part_fields[f].size;
    gpu_check(cudaMemcpyAsync(*gpu_field_slot(p, f), *gpu_field_slot(&g->dev, f), bytes,
                              cudaMemcpyDeviceToHost, g->stream[0]));
    g->bytes_d2h += (double)bytes;
    g->bytes_full += (double)bytes;
  }
  gpu_check(cudaStreamSynchronize(g->stream[0]));
}

extern "C" void gpu_drift(struct gpu *g, struct parts *p, double dt_kick, double dt, double xsph,
                          double h_max) {
  if (p->count != g->dev.count) error_bug("GPU and host particle counts differ");
  gpu_pin(g, p);
  cudaStream_t s = g->stream[0];
  gpu_check(cudaEventRecord(g->ev_drift[0], s));
  drift_gpu_launch(s, g->dev, dt_kick, dt, xsph, h_max);
  const int idx[4] = {gpu_field_index("x"), gpu_field_index("y"), gpu_field_index("z"),
                      gpu_field_index("h")};
  gpu_copy_fields(g, p, idx, 4, 0);
  gpu_check(cudaEventRecord(g->ev_drift[1], s));
  gpu_check(cudaStreamSynchronize(s));
  float ms = 0.0f;
  gpu_check(cudaEventElapsedTime(&ms, g->ev_drift[0], g->ev_drift[1]));
  g->t_drift += ms;
  g->drifts++;
}

extern "C" void gpu_print_timers(const struct gpu *g, FILE *f) {
  if (g->calls == 0) return;
  fprintf(f, "GPU (%s), %ld force phases, ms per phase:", g->name, g->calls);
  for (int k = 0; k < GPU_T_N; k++) fprintf(f, " %s %.3f", gpu_stage_names[k], g->t[k] / g->calls);
  if (g->drifts) fprintf(f, " drift(+x,h back) %.3f", g->t_drift / g->drifts);
  fprintf(f, "; %ld full uploads, %ld full downloads", g->full_up, g->full_down);
  fprintf(f, "; bus %.1f MB up, %.1f MB down per step", g->bytes_h2d / g->calls / 1e6,
          g->bytes_d2h / g->calls / 1e6);
  /* what a run moves between its outputs and rebuilds, which copy every
   * field (start, rebuild, snapshot, end) */
  fprintf(f, "; between the full copies %.1f MB per step\n",
          (g->bytes_h2d + g->bytes_d2h - g->bytes_full) / g->calls / 1e6);
}

extern "C" void gpu_memory_used(const struct gpu *g, double *run, double *total) {
  size_t free_b = 0, total_b = 0;
  gpu_check(cudaMemGetInfo(&free_b, &total_b));
  *run = (double)(total_b - free_b) - (double)g->mem_base;
  *total = (double)total_b;
}

extern "C" void gpu_bytes_moved(const struct gpu *g, double *h2d, double *d2h) {
  *h2d = g->bytes_h2d;
  *d2h = g->bytes_d2h;
}

extern "C" void gpu_free(struct gpu *g) {
  if (!g) return;
  gpu_unpin(g);
  for (int k = 0; k < part_nr_fields; k++) {
    void **slot = gpu_field_slot(&g->dev, k);
    if (*slot) gpu_check(cudaFree(*slot));
  }
  if (g->cell_dev) gpu_check(cudaFree(g->cell_dev));
  if (g->cell_host) gpu_check(cudaFreeHost(g->cell_host));
  gpu_check(cudaFree(g->counters_dev));
  gpu_check(cudaFreeHost(g->counters_host));
  gpu_check(cudaFree(g->mats_dev));
  for (int k = 0; k < MATERIAL_MAX; k++)
    if (g->table_dev[k]) gpu_check(cudaFree(g->table_dev[k]));
  if (g->flaws_dev) gpu_check(cudaFree(g->flaws_dev));
  gpu_check(cudaFreeHost(g->mats_host));
  for (int k = 0; k <= GPU_T_N; k++) gpu_check(cudaEventDestroy(g->ev[k]));
  gpu_check(cudaEventDestroy(g->cells_ready));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventDestroy(g->ev_drift[k]));
  for (int k = 0; k < 2; k++) gpu_check(cudaStreamDestroy(g->stream[k]));
  free(g);
}
