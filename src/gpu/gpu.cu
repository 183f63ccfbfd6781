/* The GPU runner (gpu.h): device set-up, memory that is allocated once and
 * grown, two streams, pinned staging for the per-phase cell data, and the
 * FORCE phase as a sequence of batched kernels over every leaf cell: the
 * GPU steps of the task families in the registry (tasks/task_families.h),
 * in their order along the graph: density, ghost (h iteration, EOS), with
 * solids gradient and extra ghost, force, with brittle materials damage,
 * gravity joining, and kick2.
 *
 * Stream 0 carries the particle fields and the kernels; stream 1 builds the
 * neighbour lists (gpu_lists.cu, or uploads the host's) and uploads the
 * leaves at the same time, and stream 0 waits for it on an event before the
 * first kernel.  The host waits only where it must
 * read something: the counter of particles still iterating h after each
 * round of the ghost, and the results at the end of the phase. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern "C" {
#include "src/error.h"
#include "src/part.h"
}
#include "src/gpu/gpu.h"
#include "src/gpu/gpu_kernels.h"
#include "src/gpu/gpu_lists.h"
#include "src/materials/material.h"

/** The steps of the FORCE phase: one per task family with a GPU step, from
 *  the registry (tasks/task_families.h), with the particle fields each
 *  reads and writes. */
struct gpu_step {
  const char *stage;                        /**< the name of its timer */
  int place;                                /**< its rank along the graph: the order of the steps */
  int when;                                 /**< enum gpu_when: in which phases it runs */
  int (*fn)(struct gpu_phase *);            /**< the step (NULL: the family has none) */
  const char *const *reads, *const *writes; /**< its fields */
  int nr_reads, nr_writes;                  /**< their numbers */
};
/** Column when of the registry. */
enum gpu_when { GPU_WHEN_ALWAYS, GPU_WHEN_SOLIDS, GPU_WHEN_BRITTLE };
#define GPU_STEP_FN_STEP(fn) fn
#define GPU_STEP_FN_NOSTEP NULL
#define GPU_STEP_ONE_STEP(fn) +1
#define GPU_STEP_ONE_NOSTEP
#define GPU_STEP_FIELDS_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  static const char *const gpu_reads_##name[] = {NULL, TASK_UNPAREN reads};             \
  static const char *const gpu_writes_##name[] = {NULL, TASK_UNPAREN writes};
TASK_FAMILIES(GPU_STEP_FIELDS_)
#undef GPU_STEP_FIELDS_
#define GPU_NR_OF(a) ((int)(sizeof a / sizeof a[0]))
/** Every family's row, by registry order (the lists start with a NULL, so
 *  that an empty one is valid C++). */
static const struct gpu_step gpu_steps[task_family_count] = {
#define GPU_STEP_ROW_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  {stage,                                                                            \
   place,                                                                            \
   GPU_WHEN_##when,                                                                  \
   GPU_STEP_FN_##gpu,                                                                \
   gpu_reads_##name + 1,                                                             \
   gpu_writes_##name + 1,                                                            \
   GPU_NR_OF(gpu_reads_##name) - 1,                                                  \
   GPU_NR_OF(gpu_writes_##name) - 1},
    TASK_FAMILIES(GPU_STEP_ROW_)
#undef GPU_STEP_ROW_
};
/** The number of steps (families with one). */
#define GPU_STEP_COUNT_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  GPU_STEP_ONE_##gpu
enum { GPU_NR_STEPS = 0 TASK_FAMILIES(GPU_STEP_COUNT_) };
#undef GPU_STEP_COUNT_

/** Stages timed with events: the upload, the steps in order, the download. */
#define GPU_T_N (GPU_NR_STEPS + 2)

struct gpu {
  int device;             /**< CUDA device number */
  char name[512];         /**< description for the log */
  size_t mem_base;        /**< device memory in use when the context was made (not the run's) */
  cudaStream_t stream[2]; /**< 0: fields and kernels; 1: cell data */
  cudaEvent_t ev[GPU_T_N + 1]; /**< stage boundaries of the last phase */
  cudaEvent_t cells_ready;     /**< stream 1 finished its upload */
  cudaEvent_t ev_drift[2];     /**< around the last drift */
  double t_drift;              /**< accumulated milliseconds of drifts (with the copy back) */
  long drifts;                 /**< drifts run */
  struct parts dev;            /**< device arrays of the particle fields (NULL: absent) */
  unsigned char absent[PART_NR_FIELDS]; /**< fields the run never uses: not on the device */
  size_t capacity;                      /**< their length */
  int in[PART_NR_FIELDS];               /**< indices in part_fields of the fields a phase reads */
  int out[PART_NR_FIELDS];              /**< of those it writes */
  int order[GPU_NR_STEPS];              /**< the families with a step, by place (gpu_init) */
  double *flaws_dev;                    /**< Weibull flaw thresholds (gpu_set_flaws) */
  size_t flaws_n, flaws_cap;            /**< their number and allocated length */
  void *cell_dev, *cell_host;           /**< device buffer and pinned staging of the leaf data */
  double *leaf_dt;                      /**< smallest time step of each leaf (in cell_dev) */
  size_t cell_bytes;                    /**< their size */
  int *counters_dev, *counters_host;    /**< h-iteration counters (host side pinned) */
  struct material_table *mats_dev;      /**< the material table on the device */
  struct material_table *mats_host;     /**< pinned staging of it */
  double *table_dev[MATERIAL_MAX];      /**< device copies of tabulated EOS nodes (P, c2, T) */
  struct eos_table table_src[MATERIAL_MAX]; /**< the host tables they mirror */
  double t[GPU_T_N];                        /**< accumulated milliseconds per stage */
  long calls;                               /**< FORCE phases run */
  double bytes_h2d, bytes_d2h;              /**< traffic over the bus */
  double bytes_full;                        /**< of which the full copies (both ways) */
  long full_up, full_down;                  /**< copies of every field (rebuilds, outputs) */
  void *pinned[PART_NR_FIELDS]; /**< host arrays registered as pinned memory, by field */
  size_t pinned_bytes;          /**< bytes per field registered */
  void (*kick_wait)(void *);    /**< called before the kick reads ga (gpu_set_kick_wait) */
  struct gpu_bins bins;         /**< time bins of the kicks and drifts (gpu_set_bins) */
  void *kick_wait_ctx;          /**< its argument */
  double *wd_x0;                /**< watchdog: positions before the drift (3 x wd_cap) */
  size_t wd_cap;                /**< their allocated length per coordinate */
  unsigned long long *wd_dev;   /**< watchdog: first bad particle per check (GPU_WD_N) */
  unsigned long long *wd_host;  /**< pinned copy of it */
  double *rk_buf;               /**< the rk2/pc integrator's arrays (gpu_rk_arrays) */
  size_t rk_bytes;              /**< their size */
  unsigned long long *rk_err;   /**< the largest error estimate of a stage */
  size_t *perm_dev;             /**< a rebuild's permutation on the device (gpu_permute) */
  void *perm_buf;               /**< its work array: one field's new order (8 bytes each) */
  size_t perm_cap;              /**< their allocated length */
  long permutes;                /**< rebuilds that reordered the resident particles */
  double t_permute;             /**< their milliseconds (permutation up, every field reordered) */
  double *h_start;              /**< h at the start of the last FORCE phase (gpu_restore_h) */
  size_t h_start_cap;           /**< its allocated length */
  void (*stage_hook)(void *, int);   /**< between the stages of a phase (gpu_set_stage_hook) */
  void *stage_ctx;                   /**< its argument */
  size_t *halo_idx;                  /**< particle indices of a block of records (gpu_halo_pack) */
  char *halo_buf;                    /**< the block's records on the device */
  char *halo_host;                   /**< and in pinned host memory */
  size_t halo_idx_cap, halo_buf_cap; /**< their allocated lengths (elements, bytes) */
  double t_halo;                     /**< milliseconds packing and unpacking records */
};

/** Slots of the watchdog's results (gpu_watchdog_check): one per double
 *  field (its first non-finite value), then negative density, forbidden
 *  negative u and the displacement. */
#define GPU_WD_N (PART_NR_FIELDS + 3)

void gpu_check_fail(cudaError_t err, const char *what, const char *file, int line) {
  error_exit("CUDA call %s failed at %s:%d: %s", what, file, line, cudaGetErrorString(err));
}

/* The live device allocations, by use (what gpu_alloc was told up to its
 * first " (", so that "particle fields (x, n particles)" counts as
 * "particle fields"): the run's memory report (gpu_memory_by_use).
 * Allocations come from the runner's thread and the gravity's; a mutex
 * orders them. */
struct gpu_mem_entry {
  void *ptr;
  size_t bytes;
  char use[48];
};
static struct gpu_mem_entry *gpu_mem_tab;
static int gpu_mem_n, gpu_mem_cap;
static pthread_mutex_t gpu_mem_lock = PTHREAD_MUTEX_INITIALIZER;

/** cudaMalloc that reports, when the device is full, what was needed and
 *  what is free; the allocation joins the table above. */
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
  pthread_mutex_lock(&gpu_mem_lock);
  if (gpu_mem_n == gpu_mem_cap) {
    gpu_mem_cap = gpu_mem_cap ? 2 * gpu_mem_cap : 256;
    gpu_mem_tab = (struct gpu_mem_entry *)error_realloc(
        gpu_mem_tab, gpu_mem_cap * sizeof *gpu_mem_tab, "GPU allocation table");
  }
  struct gpu_mem_entry *m = gpu_mem_tab + gpu_mem_n++;
  m->ptr = ptr;
  m->bytes = bytes;
  const char *end = strstr(what, " (");
  const size_t len = end ? (size_t)(end - what) : strlen(what);
  snprintf(m->use, sizeof m->use, "%.*s", (int)len, what);
  pthread_mutex_unlock(&gpu_mem_lock);
  return ptr;
}

void gpu_dfree(void *ptr) {
  if (!ptr) return;
  pthread_mutex_lock(&gpu_mem_lock);
  for (int k = 0; k < gpu_mem_n; k++)
    if (gpu_mem_tab[k].ptr == ptr) {
      gpu_mem_tab[k] = gpu_mem_tab[--gpu_mem_n];
      break;
    }
  pthread_mutex_unlock(&gpu_mem_lock);
  gpu_check(cudaFree(ptr));
}

extern "C" void gpu_memory_by_use(FILE *f, double nparts) {
  pthread_mutex_lock(&gpu_mem_lock);
  /* the uses in order of first appearance, their bytes summed */
  struct gpu_mem_entry *u =
      (struct gpu_mem_entry *)error_calloc(gpu_mem_n + 1, sizeof *u, "GPU memory report");
  int nu = 0;
  double total = 0.0;
  for (int k = 0; k < gpu_mem_n; k++) {
    int q = 0;
    while (q < nu && strcmp(u[q].use, gpu_mem_tab[k].use)) q++;
    if (q == nu) memcpy(u[nu++].use, gpu_mem_tab[k].use, sizeof u->use);
    u[q].bytes += gpu_mem_tab[k].bytes;
    total += (double)gpu_mem_tab[k].bytes;
  }
  pthread_mutex_unlock(&gpu_mem_lock);
  /* largest first */
  for (int a = 1; a < nu; a++)
    for (int b = a; b > 0 && u[b].bytes > u[b - 1].bytes; b--) {
      const struct gpu_mem_entry t = u[b];
      u[b] = u[b - 1];
      u[b - 1] = t;
    }
  fprintf(f, "GPU memory by use, bytes per particle (%.1f MiB allocated by the runner):",
          total / 1048576.0);
  for (int q = 0; q < nu; q++)
    fprintf(f, "%s %s %.0f", q ? ";" : "", u[q].use, nparts > 0 ? u[q].bytes / nparts : 0.0);
  fprintf(f, "\n");
  free(u);
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

extern "C" int gpu_bus_ids(char *ids, size_t len, int max) {
  int nd = 0;
  if (cudaGetDeviceCount(&nd) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  if (nd > max) nd = max;
  for (int d = 0; d < nd; d++)
    if (cudaDeviceGetPCIBusId(ids + (size_t)d * len, (int)len, d) != cudaSuccess) {
      cudaGetLastError();
      return 0;
    }
  return nd;
}

extern "C" struct gpu *gpu_init(int device, char *why, size_t len) {
  int nd = 0;
  const cudaError_t err = cudaGetDeviceCount(&nd);
  if (err != cudaSuccess || nd == 0) {
    snprintf(why, len, "%s", err != cudaSuccess ? cudaGetErrorString(err) : "no CUDA device");
    cudaGetLastError();
    return NULL;
  }
  struct gpu *g = (struct gpu *)error_calloc(1, sizeof(struct gpu), "GPU state");
  g->device = (device < 0 ? 0 : device) % nd;
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
  /* the steps by their place along the graph (ties: registry order) */
  int n = 0;
  for (int f = 0; f < task_family_count; f++)
    if (gpu_steps[f].fn) {
      int k = n++;
      for (; k > 0 && gpu_steps[g->order[k - 1]].place > gpu_steps[f].place; k--)
        g->order[k] = g->order[k - 1];
      g->order[k] = f;
    }
  g->wd_dev =
      (unsigned long long *)gpu_alloc(GPU_WD_N * sizeof(unsigned long long), "watchdog flags");
  gpu_check(cudaMallocHost((void **)&g->wd_host, GPU_WD_N * sizeof(unsigned long long)));
  return g;
}

extern "C" int gpu_set_absent(struct gpu *g, const char *const *names, int n) {
  if (g->capacity > 0) error_bug("gpu_set_absent after the particle arrays were made");
  int bytes = 0;
  for (int k = 0; k < n; k++) {
    const int f = gpu_field_index(names[k]);
    if (!g->absent[f]) bytes += (int)part_fields[f].size;
    g->absent[f] = 1;
  }
  return bytes;
}

extern "C" const char *gpu_name(const struct gpu *g) {
  return g->name;
}

/** Grow the device particle arrays to at least n (contents are not kept:
 *  every phase uploads what it reads).  The margin is small: the arrays are
 *  the largest part of the device's memory (theory/scheduler.md, "The GPU's
 *  memory"), and the particle count grows only where every field goes up
 *  again anyway (mirror ghosts, foreign copies, a resumed run). */
static void gpu_reserve(struct gpu *g, size_t n) {
  if (n <= g->capacity) return;
  const size_t cap = n + n / 32 + 1024;
  for (int k = 0; k < part_nr_fields; k++) {
    void **slot = gpu_field_slot(&g->dev, k);
    if (*slot) gpu_dfree(*slot);
    *slot = NULL;
    if (g->absent[k]) continue;
    char what[128];
    snprintf(what, sizeof what, "particle fields (%s, %zu particles)", part_fields[k].name, cap);
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
  const size_t sz[8] = {n * sizeof(size_t),
                        n * sizeof(int),
                        n * sizeof(double),
                        n * sizeof(double),
                        (lv->lists ? 0 : n + 1) * sizeof(int),
                        nn * sizeof(int),
                        nn * sizeof(unsigned char),
                        3 * n * sizeof(double)};
  size_t off[8], total = 0;
  for (int k = 0; k < 8; k++) {
    off[k] = total;
    total += gpu_align(sz[k]);
  }
  if (total > g->cell_bytes) {
    if (g->cell_dev) gpu_dfree(g->cell_dev);
    if (g->cell_host) gpu_check(cudaFreeHost(g->cell_host));
    g->cell_bytes = total + total / 2;
    g->cell_dev = gpu_alloc(g->cell_bytes, "leaf cells and neighbour lists");
    gpu_check(cudaMallocHost(&g->cell_host, g->cell_bytes));
  }
  char *h = (char *)g->cell_host, *d = (char *)g->cell_dev;
  const void *src[6] = {lv->offset,     lv->count,     lv->h_cap,
                        lv->h_list_cap, lv->ngb_start, lv->ngb_leaf};
  for (int k = 0; k < 6; k++)
    if (sz[k]) memcpy(h + off[k], src[k], sz[k]);
  /* the host's lists: their shifts as codes (gpu_shift_code) */
  double dim[3] = {0.0, 0.0, 0.0};
  if (nn) {
    if (!gpu_shift_dims(lv->ngb_shift, (long)nn, dim))
      error_bug("GPU lists: a periodic shift is not 0 or the box's side");
    unsigned char *code = (unsigned char *)(h + off[6]);
    for (size_t k = 0; k < nn; k++) code[k] = gpu_shift_code(lv->ngb_shift + 3 * k);
  }
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
  dv.ngb_code = (const unsigned char *)(d + off[6]);
  for (int k = 0; k < 3; k++) dv.dim[k] = dim[k];
  if (lv->lists) gpu_lists_view(lv->lists, &dv.ngb_start, &dv.ngb_leaf, &dv.ngb_code, dv.dim);
  g->leaf_dt = (double *)(d + off[7]);
  return dv;
}

/** Copy fields idx[0..n) of particles [0, count) between host and device on stream s. */
static void gpu_copy_fields(struct gpu *g, struct parts *p, const int *idx, int n, int to_device) {
  for (int k = 0; k < n; k++) {
    const int f = idx[k];
    void *hp = *gpu_field_slot(p, f), *dp = *gpu_field_slot(&g->dev, f);
    if (!dp) continue; /* (absent: the host's copy is the only one) */
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

/** 1 if step f runs in a phase with (solids, damage): column when. */
static int gpu_step_runs(int f, int solids, int damage) {
  const int w = gpu_steps[f].when;
  return w == GPU_WHEN_ALWAYS || (w == GPU_WHEN_SOLIDS && solids) ||
         (w == GPU_WHEN_BRITTLE && damage);
}

/** The indices (in part_fields) of the fields a FORCE phase reads (out = 0)
 *  or writes (out = 1): those of the steps that run in it (gpu_step_runs);
 *  returns their number.  A field named twice is copied once. */
static int gpu_phase_fields(const struct gpu *g, int *idx, int solids, int damage, int out) {
  int n = 0;
  for (int k = 0; k < GPU_NR_STEPS; k++) {
    const int f = g->order[k];
    if (!gpu_step_runs(f, solids, damage)) continue;
    const int len = out ? gpu_steps[f].nr_writes : gpu_steps[f].nr_reads;
    for (int l = 0; l < len; l++) {
      const int i = gpu_field_index(out ? gpu_steps[f].writes[l] : gpu_steps[f].reads[l]);
      int seen = 0;
      for (int q = 0; q < n; q++) seen |= idx[q] == i;
      if (!seen) idx[n++] = i;
    }
  }
  return n;
}

extern "C" void gpu_set_flaws(struct gpu *g, const double *eps, size_t n) {
  if (n > g->flaws_cap) {
    if (g->flaws_dev) gpu_dfree(g->flaws_dev);
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
    /* after the node arrays: the ln axes of a table that is not log-spaced */
    const size_t nr = t->ln_rho ? (size_t)t->n_rho : 0, nu = t->ln_u ? (size_t)t->n_u : 0;
    const size_t total = nf * nn + nr + nu;
    if (!g->table_dev[k] || memcmp(&g->table_src[k], t, sizeof *t) != 0) {
      if (g->table_dev[k]) gpu_dfree(g->table_dev[k]);
      char what[160];
      snprintf(what, sizeof what, "tabulated EOS of material %s (%zu nodes)", mats->mats[k].name,
               nn);
      g->table_dev[k] = (double *)gpu_alloc(total * sizeof(double), what);
      const double *src[3] = {t->P, t->c2, t->T};
      for (size_t f = 0; f < nf; f++)
        gpu_check(cudaMemcpy(g->table_dev[k] + f * nn, src[f], nn * sizeof(double),
                             cudaMemcpyHostToDevice));
      if (nr)
        gpu_check(cudaMemcpy(g->table_dev[k] + nf * nn, t->ln_rho, nr * sizeof(double),
                             cudaMemcpyHostToDevice));
      if (nu)
        gpu_check(cudaMemcpy(g->table_dev[k] + nf * nn + nr, t->ln_u, nu * sizeof(double),
                             cudaMemcpyHostToDevice));
      g->bytes_h2d += (double)(total * sizeof(double));
      g->table_src[k] = *t;
    }
    struct eos_table *d = &g->mats_host->mats[k].eos.table;
    d->P = g->table_dev[k];
    d->c2 = g->table_dev[k] + nn;
    d->T = t->T ? g->table_dev[k] + 2 * nn : NULL;
    d->ln_rho = nr ? g->table_dev[k] + nf * nn : NULL;
    d->ln_u = nu ? g->table_dev[k] + nf * nn + nr : NULL;
  }
}

void gpu_phase_read_counters(struct gpu_phase *ph) {
  gpu_check(cudaMemcpyAsync(ph->counters_host, ph->counters, GPU_NR_COUNTERS * sizeof(int),
                            cudaMemcpyDeviceToHost, ph->s));
  gpu_check(cudaStreamSynchronize(ph->s));
}

extern "C" void gpu_force_phase(struct gpu *g, struct parts *p, const struct gpu_leaves *lv,
                                const struct hydro_props *hp, const struct material_table *mats,
                                const struct gpu_damage *dmg, const struct gpu_gravity *grav,
                                double dt_kick, double *leaf_dt_min, int resident,
                                struct gpu_force_out *out) {
  cudaStream_t s = g->stream[0];
  memset(out, 0, sizeof *out);
  const int damage = dmg && dmg->enabled;
  const int nr_in = gpu_phase_fields(g, g->in, hp->solids, damage, 0);
  const int nr_out = gpu_phase_fields(g, g->out, hp->solids, damage, 1);
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
  /* the h the phase starts from: a repeat after an overflow starts there
   * again (gpu_restore_h), as the CPU's iteration does */
  if (g->h_start_cap < p->count) {
    if (g->h_start) gpu_dfree(g->h_start);
    g->h_start_cap = g->capacity;
    g->h_start = (double *)gpu_alloc(g->h_start_cap * sizeof(double), "the phase's starting h");
  }
  gpu_check(cudaMemcpyAsync(g->h_start, g->dev.h, p->count * sizeof(double),
                            cudaMemcpyDeviceToDevice, s));
  gpu_check(cudaStreamWaitEvent(s, g->cells_ready, 0));
  gpu_check(cudaEventRecord(g->ev[1], s));

  /* the steps of the families, in their order along the graph (registry):
   * density, ghost (the h iteration), with solids gradient and extra ghost,
   * force, with damage the damage update, gravity joining (the hybrid
   * runner's hook), kick2 and the time steps */
  struct gpu_phase ph;
  ph.s = s;
  ph.dev = g->dev;
  ph.lv = dv;
  ph.hp = *hp;
  ph.mats = g->mats_dev;
  ph.flaws = g->flaws_dev;
  ph.damage = damage;
  ph.dmg_dt = damage ? dmg->dt : 0.0;
  ph.dmg_max_change = damage ? dmg->max_change : 0.0;
  ph.grav.enabled = 0;
  ph.grav.eps = ph.grav.eta = ph.grav.h_factor = 0.0;
  if (grav) ph.grav = *grav;
  ph.dt_kick = dt_kick;
  ph.bins = g->bins;
  ph.leaf_dt = g->leaf_dt;
  ph.counters = g->counters_dev;
  ph.counters_host = g->counters_host;
  ph.wait = g->kick_wait;
  ph.wait_ctx = g->kick_wait_ctx;
  ph.out = out;
  for (int k = 0; k < GPU_NR_STEPS; k++) {
    const int f = g->order[k];
    if (gpu_step_runs(f, hp->solids, damage) && gpu_steps[f].fn(&ph)) {
      /* the lists were too short for the new h (the ghost's step): hand h
       * back for new lists; the host's h changes here, so whatever runs
       * beside this phase finishes first */
      if (g->kick_wait) g->kick_wait(g->kick_wait_ctx);
      const int ih = gpu_field_index("h");
      gpu_copy_fields(g, p, &ih, 1, 0);
      gpu_check(cudaStreamSynchronize(s));
      return;
    }
    /* several MPI ranks: the copies take their owners' results of the
     * stage that ends here (the density sums and the ghost; the gradient
     * and the extra ghost), as between the CPU's stages (engine.c,
     * engine_run_force_stages) */
    if (g->stage_hook && (f == task_family_ghost || f == task_family_gradient) &&
        gpu_step_runs(f, hp->solids, damage)) {
      gpu_check(cudaStreamSynchronize(s));
      g->stage_hook(g->stage_ctx, f == task_family_ghost ? 0 : 1);
    }
    gpu_check(cudaEventRecord(g->ev[2 + k], s));
  }
  double *leaf_dt = g->leaf_dt;
  if (!resident) gpu_copy_fields(g, p, g->out, nr_out, 0);
  gpu_check(cudaMemcpyAsync(leaf_dt_min, leaf_dt,
                            (g->bins.on ? 3 : 1) * (size_t)lv->n * sizeof(double),
                            cudaMemcpyDeviceToHost, s));
  gpu_check(cudaEventRecord(g->ev[GPU_T_N], s));
  gpu_check(cudaStreamSynchronize(s));
  for (int k = 0; k < GPU_T_N; k++) {
    float ms = 0.0f;
    gpu_check(cudaEventElapsedTime(&ms, g->ev[k], g->ev[k + 1]));
    g->t[k] += ms;
  }
  g->calls++;
}

extern "C" void gpu_restore_h(struct gpu *g, struct parts *p, int resident) {
  if (!g->h_start || p->count != g->dev.count) error_bug("no FORCE phase's h to restore");
  const size_t bytes = p->count * sizeof(double);
  if (resident)
    gpu_check(cudaMemcpyAsync(g->dev.h, g->h_start, bytes, cudaMemcpyDeviceToDevice, g->stream[0]));
  else {
    gpu_check(cudaMemcpyAsync(p->h, g->h_start, bytes, cudaMemcpyDeviceToHost, g->stream[0]));
    g->bytes_d2h += (double)bytes;
  }
  gpu_check(cudaStreamSynchronize(g->stream[0]));
}

extern "C" void gpu_set_bins(struct gpu *g, const struct gpu_bins *bins) {
  if (bins)
    g->bins = *bins;
  else
    memset(&g->bins, 0, sizeof g->bins);
}

extern "C" void gpu_set_kick_wait(struct gpu *g, void (*fn)(void *), void *ctx) {
  g->kick_wait = fn;
  g->kick_wait_ctx = ctx;
}

extern "C" void gpu_set_stage_hook(struct gpu *g, void (*fn)(void *, int), void *ctx) {
  g->stage_hook = fn;
  g->stage_ctx = ctx;
}

/* ------------------------------------------- records of several MPI ranks */

/** The fields of a block of records on the device: field k's array a[k]
 *  (elements of size[k] bytes) and its values' place off[k] in the device
 *  buffer. */
struct gpu_halo_table {
  char *a[PART_NR_FIELDS];
  size_t off[PART_NR_FIELDS];
  int size[PART_NR_FIELDS];
};

/** One element of one field (blockIdx.y) between array and buffer: gather
 *  (buf[k] = a[idx[k]]) or scatter (a[idx[k]] = buf[k]). */
__global__ static void gpu_halo_move_kernel(struct gpu_halo_table t, const size_t *idx, size_t n,
                                            char *buf, int gather) {
  const size_t k = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const int f = blockIdx.y;
  const size_t size = (size_t)t.size[f], i = idx[k];
  char *a = t.a[f], *b = buf + t.off[f];
  if (size == 8) {
    unsigned long long *x = (unsigned long long *)a, *y = (unsigned long long *)b;
    if (gather)
      y[k] = x[i];
    else
      x[i] = y[k];
  } else if (size == 4) {
    unsigned int *x = (unsigned int *)a, *y = (unsigned int *)b;
    if (gather)
      y[k] = x[i];
    else
      x[i] = y[k];
  } else {
    for (size_t q = 0; q < size; q++)
      if (gather)
        b[size * k + q] = a[size * i + q];
      else
        a[size * i + q] = b[size * k + q];
  }
}

/** The copies' marks, as halo_refresh_finish sets them on the host. */
__global__ static void gpu_halo_mark_kernel(int *flags, int64_t *msrc, const size_t *slot, size_t n,
                                            int64_t q0) {
  const size_t k = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  flags[slot[k]] |= PART_FOREIGN;
  if (msrc) msrc[slot[k]] = q0 + (int64_t)k;
}

/** The staging of a block of n records (bytes on the device and in the
 *  pinned host buffer), and its indices up. */
static void gpu_halo_stage(struct gpu *g, const size_t *idx, size_t n, size_t bytes) {
  if (n > g->halo_idx_cap) {
    if (g->halo_idx) gpu_dfree(g->halo_idx);
    g->halo_idx_cap = n + n / 4 + 1024;
    g->halo_idx = (size_t *)gpu_alloc(g->halo_idx_cap * sizeof(size_t), "MPI records");
  }
  if (bytes > g->halo_buf_cap) {
    if (g->halo_buf) gpu_dfree(g->halo_buf);
    if (g->halo_host) gpu_check(cudaFreeHost(g->halo_host));
    g->halo_buf_cap = bytes + bytes / 4 + 4096;
    g->halo_buf = (char *)gpu_alloc(g->halo_buf_cap, "MPI records");
    gpu_check(cudaMallocHost((void **)&g->halo_host, g->halo_buf_cap));
  }
  gpu_check(
      cudaMemcpyAsync(g->halo_idx, idx, n * sizeof(size_t), cudaMemcpyHostToDevice, g->stream[0]));
  g->bytes_h2d += (double)(n * sizeof(size_t));
}

/** The table of the fields of sel (NULL: every field) that the device
 *  holds, for n records: their blocks' places in the device buffer (16-byte
 *  aligned) and in the host's records (hoff, one after the other), and
 *  the staging of that length with the particles idx up (gpu_halo_stage);
 *  returns their number and in *bytes the device buffer's length. */
static int gpu_halo_fields(struct gpu *g, const unsigned char *sel, const size_t *idx, size_t n,
                           struct gpu_halo_table *t, size_t *hoff, size_t *bytes) {
  int nf = 0;
  size_t off = 0, doff = 0;
  for (int f = 0; f < part_nr_fields; f++) {
    /* (absent: on neither side, not in the records) */
    if ((sel && !sel[f]) || g->absent[f]) continue;
    const size_t size = part_fields[f].size;
    char *dp = (char *)*gpu_field_slot((struct parts *)&g->dev, f);
    if (dp) {
      t->a[nf] = dp;
      t->size[nf] = (int)size;
      t->off[nf] = doff;
      hoff[nf++] = off;
      doff += (n * size + 15) & ~(size_t)15;
    }
    off += n * size;
  }
  *bytes = doff;
  gpu_halo_stage(g, idx, n, doff);
  return nf;
}

extern "C" void gpu_halo_pack(struct gpu *g, const struct parts *p, const size_t *idx, size_t n,
                              char *dst, const unsigned char *sel) {
  if (n == 0) return;
  cudaStream_t s = g->stream[0];
  const double w0 = error_walltime();
  struct gpu_halo_table t;
  size_t hoff[PART_NR_FIELDS], bytes;
  const int nf = gpu_halo_fields(g, sel, idx, n, &t, hoff, &bytes);
  if (nf > 0) {
    const dim3 grid((unsigned)((n + GPU_BLOCK - 1) / GPU_BLOCK), (unsigned)nf);
    gpu_halo_move_kernel<<<grid, GPU_BLOCK, 0, s>>>(t, g->halo_idx, n, g->halo_buf, 1);
    gpu_check_launch(gpu_halo_move_kernel);
    gpu_check(cudaMemcpyAsync(g->halo_host, g->halo_buf, bytes, cudaMemcpyDeviceToHost, s));
    g->bytes_d2h += (double)bytes;
  }
  gpu_check(cudaStreamSynchronize(s));
  /* the blocks into the host's records; a field the device does not hold
   * (absent) from the host's copy, the only one */
  size_t off = 0;
  int q = 0;
  for (int f = 0; f < part_nr_fields; f++) {
    if ((sel && !sel[f]) || g->absent[f]) continue;
    const size_t size = part_fields[f].size;
    if (q < nf && hoff[q] == off) {
      memcpy(dst + off, g->halo_host + t.off[q], n * size);
      q++;
    } else {
      const char *a = (const char *)*gpu_field_slot((struct parts *)p, f);
      for (size_t k = 0; k < n; k++) memcpy(dst + off + size * k, a + size * idx[k], size);
    }
    off += n * size;
  }
  g->t_halo += 1e3 * (error_walltime() - w0);
}

extern "C" void gpu_halo_unpack(struct gpu *g, const size_t *slot, size_t n, const char *src,
                                const unsigned char *sel, int64_t q0) {
  if (n == 0) return;
  cudaStream_t s = g->stream[0];
  const double w0 = error_walltime();
  struct gpu_halo_table t;
  size_t hoff[PART_NR_FIELDS], bytes;
  const int nf = gpu_halo_fields(g, sel, slot, n, &t, hoff, &bytes);
  for (int q = 0; q < nf; q++)
    memcpy(g->halo_host + t.off[q], src + hoff[q], n * (size_t)t.size[q]);
  const unsigned nb = (unsigned)((n + GPU_BLOCK - 1) / GPU_BLOCK);
  if (nf > 0) {
    gpu_check(cudaMemcpyAsync(g->halo_buf, g->halo_host, bytes, cudaMemcpyHostToDevice, s));
    g->bytes_h2d += (double)bytes;
    const dim3 grid(nb, (unsigned)nf);
    gpu_halo_move_kernel<<<grid, GPU_BLOCK, 0, s>>>(t, g->halo_idx, n, g->halo_buf, 0);
    gpu_check_launch(gpu_halo_move_kernel);
  }
  gpu_halo_mark_kernel<<<nb, GPU_BLOCK, 0, s>>>(g->dev.flags, g->dev.msrc, g->halo_idx, n, q0);
  gpu_check_launch(gpu_halo_mark_kernel);
  gpu_check(cudaStreamSynchronize(s));
  g->t_halo += 1e3 * (error_walltime() - w0);
}

extern "C" double gpu_halo_ms(const struct gpu *g) {
  return g->t_halo;
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
    if (!a) continue; /* (absent on the host: parts_drop) */
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
    if (g->absent[f]) continue;
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
    if (g->absent[f]) continue;
    const size_t bytes = p->count * part_fields[f].size;
    gpu_check(cudaMemcpyAsync(*gpu_field_slot(p, f), *gpu_field_slot(&g->dev, f), bytes,
                              cudaMemcpyDeviceToHost, g->stream[0]));
    g->bytes_d2h += (double)bytes;
    g->bytes_full += (double)bytes;
  }
  gpu_check(cudaStreamSynchronize(g->stream[0]));
}

/** dst[i] = src[perm[i]] for i < n, elements of 8 or 4 bytes. */
template <typename T>
__global__ static void gpu_gather_kernel(T *dst, const T *src, const size_t *perm, size_t n) {
  const size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) dst[i] = src[perm[i]];
}

extern "C" void gpu_permute(struct gpu *g, const size_t *perm, size_t n) {
  if (n != g->dev.count) error_bug("GPU and host particle counts differ");
  if (n == 0) return;
  if (n > g->perm_cap) {
    if (g->perm_dev) gpu_dfree(g->perm_dev);
    if (g->perm_buf) gpu_dfree(g->perm_buf);
    const size_t cap = g->capacity > n ? g->capacity : n;
    g->perm_dev = (size_t *)gpu_alloc(cap * sizeof(size_t), "the rebuild's permutation");
    g->perm_buf = gpu_alloc(cap * 8, "the rebuild's reordering buffer");
    g->perm_cap = cap;
  }
  cudaStream_t s = g->stream[0];
  cudaEvent_t e0, e1;
  gpu_check(cudaEventCreate(&e0));
  gpu_check(cudaEventCreate(&e1));
  gpu_check(cudaEventRecord(e0, s));
  gpu_check(cudaMemcpyAsync(g->perm_dev, perm, n * sizeof(size_t), cudaMemcpyHostToDevice, s));
  g->bytes_h2d += (double)(n * sizeof(size_t));
  const int threads = 256;
  const unsigned blocks = (unsigned)((n + threads - 1) / threads);
  for (int f = 0; f < part_nr_fields; f++) {
    void *a = *gpu_field_slot(&g->dev, f);
    if (!a) continue;
    const size_t sz = part_fields[f].size;
    if (sz == 8)
      gpu_gather_kernel<<<blocks, threads, 0, s>>>((uint64_t *)g->perm_buf, (const uint64_t *)a,
                                                   g->perm_dev, n);
    else if (sz == 4)
      gpu_gather_kernel<<<blocks, threads, 0, s>>>((uint32_t *)g->perm_buf, (const uint32_t *)a,
                                                   g->perm_dev, n);
    else
      error_bug("particle field %s has an element size of %zu bytes", part_fields[f].name, sz);
    gpu_check(cudaGetLastError());
    gpu_check(cudaMemcpyAsync(a, g->perm_buf, n * sz, cudaMemcpyDeviceToDevice, s));
  }
  /* x0 = x, as space_rebuild sets it */
  const char *const xn[3] = {"x", "y", "z"}, *const x0n[3] = {"x0", "y0", "z0"};
  for (int k = 0; k < 3; k++)
    gpu_check(cudaMemcpyAsync(*gpu_field_slot(&g->dev, gpu_field_index(x0n[k])),
                              *gpu_field_slot(&g->dev, gpu_field_index(xn[k])), n * sizeof(double),
                              cudaMemcpyDeviceToDevice, s));
  gpu_check(cudaEventRecord(e1, s));
  gpu_check(cudaStreamSynchronize(s));
  float ms = 0.0f;
  gpu_check(cudaEventElapsedTime(&ms, e0, e1));
  gpu_check(cudaEventDestroy(e0));
  gpu_check(cudaEventDestroy(e1));
  g->t_permute += ms;
  g->permutes++;
}

extern "C" void gpu_copy_some(struct gpu *g, struct parts *p, const char *const *names, int n,
                              int to_device) {
  if (p->count != g->dev.count) error_bug("GPU and host particle counts differ");
  gpu_pin(g, p);
  gpu_copy_named(g, p, names, n, to_device);
  gpu_check(cudaStreamSynchronize(g->stream[0]));
}

/** After a drift's kernel on stream 0: the positions and smoothing lengths
 *  back to the host (what the rebuild test and the neighbour lists read),
 *  with err_bits the stage's error estimate (gpu_drift_stage; NULL: none),
 *  then the drift's time. */
static void gpu_drift_finish(struct gpu *g, struct parts *p, unsigned long long *err_bits) {
  cudaStream_t s = g->stream[0];
  const int idx[4] = {gpu_field_index("x"), gpu_field_index("y"), gpu_field_index("z"),
                      gpu_field_index("h")};
  gpu_copy_fields(g, p, idx, 4, 0);
  if (err_bits)
    gpu_check(cudaMemcpyAsync(err_bits, g->rk_err, sizeof *err_bits, cudaMemcpyDeviceToHost, s));
  gpu_check(cudaEventRecord(g->ev_drift[1], s));
  gpu_check(cudaStreamSynchronize(s));
  float ms = 0.0f;
  gpu_check(cudaEventElapsedTime(&ms, g->ev_drift[0], g->ev_drift[1]));
  g->t_drift += ms;
  g->drifts++;
}

extern "C" void gpu_drift(struct gpu *g, struct parts *p, double dt_kick, double dt,
                          const struct hydro_props *hp, const struct material_table *mats) {
  if (p->count != g->dev.count) error_bug("GPU and host particle counts differ");
  gpu_pin(g, p);
  cudaStream_t s = g->stream[0];
  gpu_check(cudaEventRecord(g->ev_drift[0], s));
  if (g->bins.on) {
    /* the materials of the sleeping particles' prediction (a resumed run
     * drifts before its first force phase has uploaded them) */
    gpu_stage_materials(g, mats);
    gpu_check(cudaMemcpyAsync(g->mats_dev, g->mats_host, sizeof *mats, cudaMemcpyHostToDevice, s));
    drift_bins_gpu_launch(s, g->dev, &g->bins, *hp, g->mats_dev);
  } else {
    drift_gpu_launch(s, g->dev, dt_kick, dt, hp->xsph, hp->h_max, hp->h_continuity);
  }
  gpu_drift_finish(g, p, NULL);
}

extern "C" void gpu_rk_arrays(struct gpu *g, size_t n, int ny, int nr, int nrec, double **y0,
                              double **r) {
  const size_t bytes = (n ? n : 1) * (size_t)(ny + nrec * nr) * sizeof(double);
  if (bytes > g->rk_bytes) {
    if (g->rk_buf) gpu_dfree(g->rk_buf);
    g->rk_buf = (double *)gpu_alloc(bytes, "the rk2/pc schemes' stage states");
    g->rk_bytes = bytes;
  }
  if (!g->rk_err)
    g->rk_err = (unsigned long long *)gpu_alloc(sizeof *g->rk_err, "the rk2/pc schemes' error");
  *y0 = g->rk_buf;
  for (int k = 0; k < nrec; k++) r[k] = g->rk_buf + (n ? n : 1) * (size_t)(ny + k * nr);
}

extern "C" double gpu_drift_stage(struct gpu *g, struct parts *p, const struct drift_stage *st,
                                  const struct hydro_props *hp) {
  if (p->count != g->dev.count) error_bug("GPU and host particle counts differ");
  gpu_pin(g, p);
  cudaStream_t s = g->stream[0];
  gpu_check(cudaEventRecord(g->ev_drift[0], s));
  gpu_check(cudaMemsetAsync(g->rk_err, 0, sizeof *g->rk_err, s));
  drift_stage_gpu_launch(s, g->dev, st, *hp, g->rk_err);
  unsigned long long bits = 0;
  gpu_drift_finish(g, p, &bits);
  double err;
  memcpy(&err, &bits, sizeof err);
  return err;
}

extern "C" void gpu_rk_restore(struct gpu *g, const double *y0, const double *r1) {
  drift_restore_gpu_launch(g->stream[0], g->dev, y0, r1);
  gpu_check(cudaStreamSynchronize(g->stream[0]));
}

/* ------------------------------------------------------------------------ */
/* the watchdog (engine.c): the checks of the CPU's engine_watchdog_* on the  */
/* resident particles, each a pass over the device arrays that records the    */
/* first bad particle per check (atomicMin); the host reads GPU_WD_N words    */
/* and, only when one is set, copies the particles back to name it.           */

/** The double fields to check (pointers into the device arrays). */
struct gpu_wd_fields {
  const double *a[PART_NR_FIELDS];
  int n;
};

/** Materials whose EOS forbids u < 0 (material.u_floor), by id. */
struct gpu_wd_mats {
  int32_t id[MATERIAL_MAX];
  int n;
};

/** Finiteness: blockIdx.y picks the field; a particle whose value has an
 *  exponent of all ones (Inf, NaN) is a candidate for slot blockIdx.y.
 *  Negative density and, for the u_floor materials, negative u go to the
 *  slots after the fields (block row 0 checks them). */
__global__ static void gpu_wd_scan_kernel(struct gpu_wd_fields f, const double *rho,
                                          const double *u, const int32_t *mat, struct gpu_wd_mats m,
                                          size_t n, unsigned long long *first) {
  const int k = blockIdx.y;
  const double *a = f.a[k];
  for (size_t i = blockIdx.x * (size_t)blockDim.x + threadIdx.x; i < n;
       i += (size_t)gridDim.x * blockDim.x) {
    const unsigned long long w = (unsigned long long)__double_as_longlong(a[i]);
    if ((w & 0x7ff0000000000000ULL) == 0x7ff0000000000000ULL)
      atomicMin(&first[k], (unsigned long long)i);
    if (k == 0) {
      if (rho[i] < 0.0) atomicMin(&first[PART_NR_FIELDS], (unsigned long long)i);
      if (u[i] < 0.0)
        for (int q = 0; q < m.n; q++)
          if (mat[i] == m.id[q]) atomicMin(&first[PART_NR_FIELDS + 1], (unsigned long long)i);
    }
  }
}

/** Displacement since gpu_watchdog_save: |x - x0| (without fused
 *  multiply-adds, as the CPU's check computes it) above width, or not a
 *  number, is a candidate for the last slot. */
__global__ static void gpu_wd_move_kernel(const double *x, const double *y, const double *z,
                                          const double *x0, size_t cap, size_t n, double width,
                                          unsigned long long *first) {
  for (size_t i = blockIdx.x * (size_t)blockDim.x + threadIdx.x; i < n;
       i += (size_t)gridDim.x * blockDim.x) {
    const double dx = __dsub_rn(x[i], x0[i]), dy = __dsub_rn(y[i], x0[cap + i]),
                 dz = __dsub_rn(z[i], x0[2 * cap + i]);
    const double d =
        __dsqrt_rn(__dadd_rn(__dadd_rn(__dmul_rn(dx, dx), __dmul_rn(dy, dy)), __dmul_rn(dz, dz)));
    if (!(d <= width)) atomicMin(&first[PART_NR_FIELDS + 2], (unsigned long long)i);
  }
}

/** Blocks of a grid-stride pass over n particles. */
static unsigned gpu_wd_blocks(size_t n) {
  size_t b = (n + 255) / 256;
  if (b > 4096) b = 4096;
  return b ? (unsigned)b : 1u;
}

extern "C" void gpu_watchdog_save(struct gpu *g) {
  const size_t n = g->dev.count;
  if (n == 0) return;
  if (n > g->wd_cap) {
    if (g->wd_x0) gpu_dfree(g->wd_x0);
    g->wd_cap = g->capacity > n ? g->capacity : n;
    g->wd_x0 = (double *)gpu_alloc(3 * g->wd_cap * sizeof(double), "watchdog positions");
  }
  cudaStream_t s = g->stream[0];
  gpu_check(cudaMemcpyAsync(g->wd_x0, g->dev.x, n * sizeof(double), cudaMemcpyDeviceToDevice, s));
  gpu_check(cudaMemcpyAsync(g->wd_x0 + g->wd_cap, g->dev.y, n * sizeof(double),
                            cudaMemcpyDeviceToDevice, s));
  gpu_check(cudaMemcpyAsync(g->wd_x0 + 2 * g->wd_cap, g->dev.z, n * sizeof(double),
                            cudaMemcpyDeviceToDevice, s));
}

/** Run the queued watchdog kernels' results back: the GPU_WD_N slots. */
static void gpu_wd_read(struct gpu *g) {
  cudaStream_t s = g->stream[0];
  gpu_check(cudaMemcpyAsync(g->wd_host, g->wd_dev, GPU_WD_N * sizeof(unsigned long long),
                            cudaMemcpyDeviceToHost, s));
  gpu_check(cudaStreamSynchronize(s));
  g->bytes_d2h += GPU_WD_N * sizeof(unsigned long long);
}

extern "C" long gpu_watchdog_moved(struct gpu *g, double width, double *x0_host) {
  const size_t n = g->dev.count;
  if (!g->wd_x0 || n > g->wd_cap || n == 0) return -1;
  cudaStream_t s = g->stream[0];
  gpu_check(cudaMemsetAsync(g->wd_dev, 0xff, GPU_WD_N * sizeof(unsigned long long), s));
  gpu_wd_move_kernel<<<gpu_wd_blocks(n), 256, 0, s>>>(g->dev.x, g->dev.y, g->dev.z, g->wd_x0,
                                                      g->wd_cap, n, width, g->wd_dev);
  gpu_check(cudaGetLastError());
  gpu_wd_read(g);
  const unsigned long long i = g->wd_host[PART_NR_FIELDS + 2];
  if (i == ~0ULL) return -1;
  for (int c = 0; c < 3; c++)
    gpu_check(cudaMemcpyAsync(x0_host + c * n, g->wd_x0 + c * g->wd_cap, n * sizeof(double),
                              cudaMemcpyDeviceToHost, s));
  gpu_check(cudaStreamSynchronize(s));
  return (long)i;
}

extern "C" int gpu_watchdog_check(struct gpu *g, const int32_t *u_floor_ids, int n_ids) {
  const size_t n = g->dev.count;
  if (n == 0) return 0;
  struct gpu_wd_fields f;
  f.n = 0;
  for (int k = 0; k < part_nr_fields; k++)
    if (part_fields[k].type == PART_DOUBLE && *gpu_field_slot(&g->dev, k))
      f.a[f.n++] = (const double *)*gpu_field_slot(&g->dev, k);
  struct gpu_wd_mats m;
  m.n = n_ids < MATERIAL_MAX ? n_ids : MATERIAL_MAX;
  for (int q = 0; q < m.n; q++) m.id[q] = u_floor_ids[q];
  cudaStream_t s = g->stream[0];
  gpu_check(cudaMemsetAsync(g->wd_dev, 0xff, GPU_WD_N * sizeof(unsigned long long), s));
  unsigned bx = gpu_wd_blocks(n);
  if (bx > 256) bx = 256; /* times the fields: enough blocks to fill the device */
  gpu_wd_scan_kernel<<<dim3(bx, (unsigned)f.n), 256, 0, s>>>(f, g->dev.rho, g->dev.u, g->dev.mat, m,
                                                             n, g->wd_dev);
  gpu_check(cudaGetLastError());
  gpu_wd_read(g);
  for (int k = 0; k < PART_NR_FIELDS + 2; k++) /* (the slots of no field stay unset) */
    if (g->wd_host[k] != ~0ULL) return 1;
  return 0;
}

extern "C" void gpu_print_timers(const struct gpu *g, FILE *f) {
  if (g->calls == 0) return;
  fprintf(f, "GPU (%s), %ld force phases, ms per phase:", g->name, g->calls);
  for (int k = 0; k < GPU_T_N; k++) {
    const char *name = k == 0             ? "upload"
                       : k == GPU_T_N - 1 ? "download"
                                          : gpu_steps[g->order[k - 1]].stage;
    fprintf(f, " %s %.3f", name, g->t[k] / g->calls);
  }
  if (g->drifts) fprintf(f, " drift(+x,h back) %.3f", g->t_drift / g->drifts);
  fprintf(f, "; %ld full uploads, %ld full downloads", g->full_up, g->full_down);
  if (g->permutes)
    fprintf(f, "; %ld rebuilds reordered on the device, %.3f ms each", g->permutes,
            g->t_permute / g->permutes);
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
  if (g->rk_buf) gpu_dfree(g->rk_buf);
  if (g->rk_err) gpu_dfree(g->rk_err);
  if (g->perm_dev) gpu_dfree(g->perm_dev);
  if (g->perm_buf) gpu_dfree(g->perm_buf);
  if (g->h_start) gpu_dfree(g->h_start);
  if (g->halo_idx) gpu_dfree(g->halo_idx);
  if (g->halo_buf) gpu_dfree(g->halo_buf);
  if (g->halo_host) gpu_check(cudaFreeHost(g->halo_host));
  for (int k = 0; k < part_nr_fields; k++) {
    void **slot = gpu_field_slot(&g->dev, k);
    if (*slot) gpu_dfree(*slot);
  }
  if (g->cell_dev) gpu_dfree(g->cell_dev);
  if (g->cell_host) gpu_check(cudaFreeHost(g->cell_host));
  gpu_dfree(g->counters_dev);
  gpu_check(cudaFreeHost(g->counters_host));
  gpu_dfree(g->mats_dev);
  for (int k = 0; k < MATERIAL_MAX; k++)
    if (g->table_dev[k]) gpu_dfree(g->table_dev[k]);
  if (g->flaws_dev) gpu_dfree(g->flaws_dev);
  gpu_check(cudaFreeHost(g->mats_host));
  if (g->wd_x0) gpu_dfree(g->wd_x0);
  gpu_dfree(g->wd_dev);
  gpu_check(cudaFreeHost(g->wd_host));
  for (int k = 0; k <= GPU_T_N; k++) gpu_check(cudaEventDestroy(g->ev[k]));
  gpu_check(cudaEventDestroy(g->cells_ready));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventDestroy(g->ev_drift[k]));
  for (int k = 0; k < 2; k++) gpu_check(cudaStreamDestroy(g->stream[k]));
  free(g);
}
