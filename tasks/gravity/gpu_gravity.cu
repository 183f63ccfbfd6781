/* Self-gravity's device state (gpu_gravity.h, struct gpu_grav): the cell tree as
 * index arrays (uploaded at rebuilds), the multipoles (each full
 * evaluation, from pinned staging), the local expansions (device only),
 * the interactions of the CPU walks (each full evaluation, grouped by
 * receiving cell on the device), and the
 * sequence of kernels of tasks/gravity/gravity_gpu.cu on stream 0, where
 * the particles are resident between steps.  Buffers are allocated once
 * and grown, never per step. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* no NVTX ranges from cub: they would export nvtx* symbols from this
 * object (tests/repo/test_symbols.py) and Bolide has no NVTX markers */
#define CCCL_DISABLE_NVTX
#include <cub/device/device_segmented_sort.cuh>

extern "C" {
#include "src/error.h"
}
#include "src/gpu/gpu.h"
#include "src/gpu/gpu_kernels.h"
#include "tasks/gravity/gpu_gravity.h"
#include "tasks/gravity/gravity_gpu.h"

/** A device buffer grown on demand (contents not kept). */
struct gpu_grav_buf {
  void *ptr;    /**< device memory */
  size_t bytes; /**< allocated */
};

/** Stages of one evaluation timed with events. */
enum { GG_UP, GG_GROUP, GG_FIELD, GG_L2L, GG_PART, GG_L2P, GG_DOWN, GG_N };
static const char *const gg_stage_names[GG_N] = {"upload",  "grouping", "M2L+P2L", "L2L",
                                                 "P2P+M2P", "L2P",      "ga back"};

/** Rounds of a walk timed one by one (the roots' round first; later ones
 *  add to the last). */
#define GG_ROUNDS 12

struct gpu_grav {
  struct gpu *g;                      /**< the device */
  struct gpu_grav_buf mp, field;      /**< multipoles, local expansions (by cell) */
  struct gpu_grav_buf offset, count;  /**< particle range of each cell */
  struct gpu_grav_buf l2l, leaf;      /**< L2L pairs (child then parent), leaves */
  struct gpu_grav_buf raw[2];         /**< part and field: the recorded pairs as uploaded */
  struct gpu_grav_buf start[2];       /**< part and field: counts, then start of each cell */
  struct gpu_grav_buf src[2];         /**< part and field: the sources grouped by cell */
  struct gpu_grav_buf cursor;         /**< scatter positions of each cell */
  struct gpu_grav_buf sorted[2];      /**< part and field: src with each cell's sources sorted */
  struct gpu_grav_buf sort_tmp;       /**< the segmented sort's scratch */
  int reproducible;                   /**< sort each cell's sources (gpu_grav_set_reproducible) */
  struct gpu_grav_buf centre;         /**< box centre of each cell (3 doubles) */
  struct gpu_grav_buf scale;          /**< a_min then h_support of each cell (upward pass) */
  struct gpu_grav_buf active;         /**< per cell: it receives (a step of active particles) */
  int active_on;                      /**< the coming evaluation is such a step
                                           (gpu_grav_set_active) */
  double *scale_host;                 /**< pinned copy of scale */
  int scale_host_cap;                 /**< its cells */
  int mp_on_device;                   /**< gpu_grav_up left this evaluation's multipoles */
  cudaEvent_t ev_up[2];               /**< the upward pass, copy back included */
  double t_up;                        /**< its accumulated milliseconds */
  long calls_up;                      /**< upward passes on the device */
  struct gpu_grav_buf progeny, split; /**< the tree for the walks (gravity_walk_tree_arrays) */
  struct gpu_grav_buf lo_hi;          /**< boxes of the top-level cells (walks) */
  struct gpu_grav_buf skip;           /**< the walks' skipped top-level cells (MPI ranks) */
  struct gpu_grav_buf top;            /**< the non-empty top-level cells of the roots */
  struct gpu_grav_buf wcount;         /**< 4 list counters, then the out-of-stack counter */
  struct gpu_grav_buf wlist[4];       /**< the walks' lists: targets, then sources (cap each) */
  unsigned long long wcap[4];         /**< their capacities (entries) */
  struct gpu_grav_buf wqueue[2];      /**< the walks' hand-on queues (3 ints per entry) */
  unsigned long long qcap;            /**< their capacity (entries) */
  long walk_rounds;                   /**< rounds of walkers, all walks */
  unsigned long long wn[4];           /**< entries of the last walk */
  int walk_on_device;                 /**< gpu_grav_walk left this evaluation's lists */
  cudaEvent_t ev_walk[2];             /**< the walks */
  double t_walk;                      /**< their accumulated milliseconds */
  long calls_walk, walk_retries;      /**< walks on the device; repeated for longer lists */
  cudaEvent_t ev_rnd[GG_ROUNDS + 1];  /**< the rounds of a walk's last attempt */
  double t_round[GG_ROUNDS];          /**< their milliseconds, walks after the first */
  double n_round[GG_ROUNDS];          /**< entries each round took, walks after the first */
  long walks_timed;                   /**< walks after the first (t_round, n_round) */
  double t_walk_first;                /**< the first walk's milliseconds (lists allocated) */
  struct gravity_gpu_groups gl[2];    /**< device views of them (last full evaluation) */
  struct gravity_multipole *mp_host;  /**< pinned staging of the multipoles */
  int mp_host_cap;                    /**< its length */
  int nr_cells;                       /**< cells of the tree */
  int nr_levels, *level_start;        /**< L2L levels (host copy) */
  int nr_leaves;                      /**< leaves */
  int block;                          /**< threads per block of the leaf kernels */
  int have_tree, have_eval;           /**< a tree was set; a full evaluation ran on it */
  cudaEvent_t ev[GG_N + 1];           /**< stage boundaries */
  double t[GG_N];                     /**< accumulated milliseconds per stage */
  long calls, replays;                /**< evaluations: all, of which replays */
  double bytes;                       /**< bytes moved (both ways) */
  double n_entries[2];                /**< grouped part and field interactions of the last */
};

/** Make b hold at least bytes, allocated with bytes / spare more for the
 *  next call's growth (spare 0: none; contents lost). */
static void *gg_reserve_spare(struct gpu_grav_buf *b, size_t bytes, size_t spare,
                              const char *what) {
  if (bytes > b->bytes || !b->ptr) {
    if (b->ptr) gpu_dfree(b->ptr);
    b->bytes = bytes + (spare ? bytes / spare : 0) + 64;
    b->ptr = gpu_alloc(b->bytes, what);
  }
  return b->ptr;
}

/** gg_reserve_spare with half again: the buffers of the cells, whose
 *  count changes a little from rebuild to rebuild. */
static void *gg_reserve(struct gpu_grav_buf *b, size_t bytes, const char *what) {
  return gg_reserve_spare(b, bytes, 2, what);
}

/** Copy bytes from host to the device on stream s, counted. */
static void gg_up(struct gpu_grav *gg, cudaStream_t s, void *d, const void *h, size_t bytes) {
  if (bytes == 0) return;
  gpu_check(cudaMemcpyAsync(d, h, bytes, cudaMemcpyHostToDevice, s));
  gpu_bytes_add(gg->g, (double)bytes, 0.0);
  gg->bytes += (double)bytes;
}

extern "C" struct gpu_grav *gpu_grav_new(struct gpu *g) {
  struct gpu_grav *gg = (struct gpu_grav *)error_calloc(1, sizeof *gg, "GPU gravity state");
  gg->g = g;
  for (int k = 0; k <= GG_N; k++) gpu_check(cudaEventCreate(&gg->ev[k]));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventCreate(&gg->ev_up[k]));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventCreate(&gg->ev_walk[k]));
  for (int k = 0; k <= GG_ROUNDS; k++) gpu_check(cudaEventCreate(&gg->ev_rnd[k]));
  return gg;
}

extern "C" void gpu_grav_free(struct gpu_grav *gg) {
  if (!gg) return;
  struct gpu_grav_buf *bufs[31] = {
      &gg->mp,        &gg->field,     &gg->offset,    &gg->count,    &gg->l2l,      &gg->leaf,
      &gg->raw[0],    &gg->raw[1],    &gg->start[0],  &gg->start[1], &gg->src[0],   &gg->src[1],
      &gg->cursor,    &gg->centre,    &gg->scale,     &gg->progeny,  &gg->split,    &gg->lo_hi,
      &gg->wcount,    &gg->wlist[0],  &gg->wlist[1],  &gg->wlist[2], &gg->wlist[3], &gg->wqueue[0],
      &gg->wqueue[1], &gg->sorted[0], &gg->sorted[1], &gg->sort_tmp, &gg->active,   &gg->skip,
      &gg->top};
  for (int k = 0; k < 31; k++)
    if (bufs[k]->ptr) gpu_dfree(bufs[k]->ptr);
  if (gg->mp_host) gpu_check(cudaFreeHost(gg->mp_host));
  if (gg->scale_host) gpu_check(cudaFreeHost(gg->scale_host));
  for (int k = 0; k <= GG_N; k++) gpu_check(cudaEventDestroy(gg->ev[k]));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventDestroy(gg->ev_up[k]));
  for (int k = 0; k < 2; k++) gpu_check(cudaEventDestroy(gg->ev_walk[k]));
  for (int k = 0; k <= GG_ROUNDS; k++) gpu_check(cudaEventDestroy(gg->ev_rnd[k]));
  free(gg->level_start);
  free(gg);
}

extern "C" void gpu_grav_set_tree(struct gpu_grav *gg, const struct gpu_grav_tree *t) {
  cudaStream_t s = gpu_stream(gg->g, 0);
  const size_t nc = (size_t)t->nr_cells;
  gg_reserve(&gg->mp, nc * sizeof(struct gravity_multipole), "gravity multipoles");
  gg_reserve(&gg->field, nc * sizeof(struct gravity_field), "gravity local expansions");
  gg_up(gg, s, gg_reserve(&gg->offset, nc * sizeof(size_t), "gravity cells"), t->offset,
        nc * sizeof(size_t));
  gg_up(gg, s, gg_reserve(&gg->count, nc * sizeof(int), "gravity cells"), t->count,
        nc * sizeof(int));
  const size_t nl = (size_t)t->nr_l2l;
  int *l2l = (int *)gg_reserve(&gg->l2l, 2 * nl * sizeof(int), "gravity L2L pairs");
  gg_up(gg, s, l2l, t->l2l_child, nl * sizeof(int));
  gg_up(gg, s, l2l + nl, t->l2l_parent, nl * sizeof(int));
  gg_up(gg, s, gg_reserve(&gg->leaf, (size_t)t->nr_leaves * sizeof(int), "gravity leaves"), t->leaf,
        (size_t)t->nr_leaves * sizeof(int));
  gg_up(gg, s, gg_reserve(&gg->centre, 3 * nc * sizeof(double), "gravity cell centres"), t->centre,
        3 * nc * sizeof(double));
  gg_up(gg, s, gg_reserve(&gg->progeny, 8 * nc * sizeof(int), "gravity tree"), t->progeny,
        8 * nc * sizeof(int));
  gg_up(gg, s, gg_reserve(&gg->split, nc + 16, "gravity tree"), t->split, nc);
  gg->level_start =
      (int *)error_realloc(gg->level_start, (t->nr_levels + 1) * sizeof(int), "gravity levels");
  memcpy(gg->level_start, t->level_start, (t->nr_levels + 1) * sizeof(int));
  gg->nr_levels = t->nr_levels;
  gg->nr_leaves = t->nr_leaves;
  gg->nr_cells = t->nr_cells;
  /* a warp per 32 particles of the mean leaf */
  size_t np = 0;
  for (int k = 0; k < t->nr_leaves; k++) np += (size_t)t->count[t->leaf[k]];
  const double mean = t->nr_leaves ? (double)np / t->nr_leaves : 0.0;
  gg->block = mean <= 40.0 ? 32 : (mean <= 96.0 ? 64 : GPU_BLOCK);
  gg->have_tree = 1;
  gg->have_eval = 0;
  gg->mp_on_device = 0;
  gg->walk_on_device = 0;
  /* the host arrays may change once this returns */
  gpu_check(cudaStreamSynchronize(s));
}

extern "C" struct gravity_multipole *gpu_grav_multipoles(struct gpu_grav *gg, int nr_cells) {
  if (nr_cells > gg->mp_host_cap || !gg->mp_host) {
    if (gg->mp_host) gpu_check(cudaFreeHost(gg->mp_host));
    gg->mp_host_cap = nr_cells + nr_cells / 4 + 16;
    gpu_check(cudaMallocHost((void **)&gg->mp_host,
                             (size_t)gg->mp_host_cap * sizeof(struct gravity_multipole)));
  }
  return gg->mp_host;
}

/** End a stage timed by ev[0] (recorded at its start) on stream s: record
 *  ev[1], wait for it, return the milliseconds between the two. */
static double gg_stage_end(const cudaEvent_t ev[2], cudaStream_t s) {
  gpu_check(cudaEventRecord(ev[1], s));
  gpu_check(cudaEventSynchronize(ev[1]));
  float ms = 0.0f;
  gpu_check(cudaEventElapsedTime(&ms, ev[0], ev[1]));
  return ms;
}

extern "C" void gpu_grav_up(struct gpu_grav *gg, struct parts *p, int order, double h_factor,
                            int resident, const struct gravity_multipole **mp, const double **a_min,
                            const double **h_support) {
  if (!gg->have_tree) error_bug("gpu_grav_up before gpu_grav_set_tree");
  cudaStream_t s = gpu_stream(gg->g, 0);
  struct parts dp = gpu_device_parts(gg->g, p->count);
  gpu_check(cudaEventRecord(gg->ev_up[0], s));
  if (!resident) {
    static const char *const in[8] = {"x", "y", "z", "m", "h", "gax", "gay", "gaz"};
    gpu_copy_named(gg->g, p, in, 8, 1);
    gg->bytes += 8.0 * (double)p->count * sizeof(double);
  }
  const size_t nc = (size_t)gg->nr_cells;
  double *scale =
      (double *)gg_reserve(&gg->scale, 2 * nc * sizeof(double) + 16, "gravity cell scales");
  struct gravity_gpu_up u;
  u.mp = (struct gravity_multipole *)gg->mp.ptr;
  u.a_min = scale;
  u.h_support = scale + nc;
  u.centre = (const double *)gg->centre.ptr;
  u.offset = (const size_t *)gg->offset.ptr;
  u.count = (const int *)gg->count.ptr;
  u.h_factor = h_factor;
  u.order = order;
  u.active = gg->active_on
                 ? (unsigned char *)gg_reserve(&gg->active, nc + 16, "gravity active cells")
                 : NULL;
  const int nl = gg->level_start[gg->nr_levels];
  const int *l2l = (const int *)gg->l2l.ptr;
  gravity_up_gpu_launch(s, dp, u, (int)nc, (const int *)gg->leaf.ptr, gg->nr_leaves, l2l, l2l + nl,
                        gg->level_start, gg->nr_levels);
  gg->mp_on_device = 1;
  if (mp) {
    /* back for the walks, into pinned staging */
    struct gravity_multipole *mh = gpu_grav_multipoles(gg, (int)nc);
    if ((int)nc > gg->scale_host_cap || !gg->scale_host) {
      if (gg->scale_host) gpu_check(cudaFreeHost(gg->scale_host));
      gg->scale_host_cap = (int)nc + (int)nc / 4 + 16;
      gpu_check(cudaMallocHost((void **)&gg->scale_host,
                               2 * (size_t)gg->scale_host_cap * sizeof(double)));
    }
    gpu_check(cudaMemcpyAsync(mh, u.mp, nc * sizeof(struct gravity_multipole),
                              cudaMemcpyDeviceToHost, s));
    gpu_check(
        cudaMemcpyAsync(gg->scale_host, scale, 2 * nc * sizeof(double), cudaMemcpyDeviceToHost, s));
    const double down = (double)nc * (sizeof(struct gravity_multipole) + 2 * sizeof(double));
    gpu_bytes_add(gg->g, 0.0, down);
    gg->bytes += down;
    *mp = mh;
    *a_min = gg->scale_host;
    *h_support = gg->scale_host + nc;
  }
  gg->t_up += gg_stage_end(gg->ev_up, s);
  gg->calls_up++;
}

extern "C" void gpu_grav_walk(struct gpu_grav *gg, const double *lo_hi, int nr_top, double theta,
                              double h_support, double G, double epsilon_fmm, double h_factor,
                              int order, const unsigned char *skip, const int *top) {
  if (!gg->mp_on_device) error_bug("gpu_grav_walk without this evaluation's gpu_grav_up");
  cudaStream_t s = gpu_stream(gg->g, 0);
  const size_t nc = (size_t)gg->nr_cells;
  gpu_check(cudaEventRecord(gg->ev_walk[0], s));
  double *dlo = (double *)gg_reserve(&gg->lo_hi, 6 * (size_t)nr_top * sizeof(double) + 16,
                                     "gravity top-level boxes");
  gg_up(gg, s, dlo, lo_hi, 6 * (size_t)nr_top * sizeof(double));
  unsigned char *dskip = NULL;
  int *dtop = NULL;
  if (skip) {
    dskip = (unsigned char *)gg_reserve(&gg->skip, (size_t)nr_top + 16, "gravity top-level skips");
    gg_up(gg, s, dskip, skip, (size_t)nr_top);
  }
  if (top) {
    dtop =
        (int *)gg_reserve(&gg->top, (size_t)nr_top * sizeof(int) + 16, "gravity top-level cells");
    gg_up(gg, s, dtop, top, (size_t)nr_top * sizeof(int));
  }
  struct gravity_walk_tree T;
  T.progeny = (const int *)gg->progeny.ptr;
  T.count = (const int *)gg->count.ptr;
  T.split = (const unsigned char *)gg->split.ptr;
  T.mp = (const struct gravity_multipole *)gg->mp.ptr;
  T.a_min = (const double *)gg->scale.ptr;
  T.h_support = (const double *)gg->scale.ptr + nc;
  T.active = gg->active_on ? (const unsigned char *)gg->active.ptr : NULL;
  struct gravity_walk_params wp;
  wp.G = G;
  wp.theta = theta;
  wp.epsilon_fmm = epsilon_fmm;
  wp.h_support = h_support;
  wp.h_factor = h_factor;
  wp.order = order;
  /* counters: the 4 lists', the two queues', then the out-of-stack count */
  unsigned long long *cnt = (unsigned long long *)gg_reserve(
      &gg->wcount, 6 * sizeof(unsigned long long) + sizeof(int) + 16, "gravity walk counters");
  int *deep = (int *)(cnt + 6);
  /* first capacities: those of the last walk, or 64 entries per cell */
  for (int k = 0; k < 4; k++)
    if (gg->wcap[k] == 0) gg->wcap[k] = 64 * (unsigned long long)nc + 1024;
  /* (a walker that finds the queue full walks to the end alone: at 4 per
   * cell the first walk of the 1.1e6 reference impact, whose widest round
   * hands on about 8 entries per cell, took 5 to 8 times the later ones) */
  if (gg->qcap == 0) gg->qcap = 12 * (unsigned long long)nc + 65536;
  for (int attempt = 0;; attempt++) {
    struct gravity_walk_lists L;
    for (int k = 0; k < 4; k++) {
      /* (the capacity has the room to grow: wcap) */
      int *b = (int *)gg_reserve_spare(&gg->wlist[k], 2 * gg->wcap[k] * sizeof(int), 0,
                                       "gravity walk lists");
      L.target[k] = b;
      L.source[k] = b + gg->wcap[k];
      L.cap[k] = gg->wcap[k];
    }
    L.n = cnt;
    struct gravity_walk_queue Q[2];
    for (int k = 0; k < 2; k++) {
      Q[k].item =
          (int *)gg_reserve(&gg->wqueue[k], 3 * gg->qcap * sizeof(int), "gravity walk queues");
      Q[k].n = cnt + 4 + k;
      Q[k].cap = gg->qcap;
    }
    gpu_check(cudaMemsetAsync(cnt, 0, 6 * sizeof(unsigned long long) + sizeof(int), s));
    /* each round from its launch to the next one's (the count read back
     * and the host's turn included) */
    gpu_check(cudaEventRecord(gg->ev_rnd[0], s));
    gravity_walk_roots_gpu_launch(s, T, wp, L, Q[0], dlo, nr_top, h_support, dskip, dtop, deep);
    /* rounds on what the walkers handed on, until none is left */
    unsigned long long hn[4], q_most = 0, taken[GG_ROUNDS] = {0};
    int rounds = 1;
    for (int cur = 0;; cur ^= 1) {
      unsigned long long m;
      gpu_check(cudaMemcpyAsync(&m, cnt + 4 + cur, sizeof m, cudaMemcpyDeviceToHost, s));
      gpu_check(cudaStreamSynchronize(s));
      if (m > q_most) q_most = m;
      if (m == 0) break;
      if (rounds < GG_ROUNDS) gpu_check(cudaEventRecord(gg->ev_rnd[rounds], s));
      taken[rounds < GG_ROUNDS ? rounds : GG_ROUNDS - 1] += m;
      rounds++;
      /* the other queue (empty, or walked by the round before) takes what is left */
      gpu_check(cudaMemsetAsync(cnt + 4 + (cur ^ 1), 0, sizeof(unsigned long long), s));
      gravity_walk_queue_gpu_launch(s, T, wp, L, Q[cur], m < gg->qcap ? m : gg->qcap, Q[cur ^ 1],
                                    deep);
      gg->walk_rounds++;
    }
    const int timed = rounds < GG_ROUNDS ? rounds : GG_ROUNDS;
    gpu_check(cudaEventRecord(gg->ev_rnd[timed], s));
    /* a queue that was too small slowed the walk (its walkers kept what
     * did not fit): the next walk gets room for all */
    if (q_most > gg->qcap) gg->qcap = q_most + q_most / 4;
    int hdeep;
    gpu_check(cudaMemcpyAsync(hn, cnt, sizeof hn, cudaMemcpyDeviceToHost, s));
    gpu_check(cudaMemcpyAsync(&hdeep, deep, sizeof hdeep, cudaMemcpyDeviceToHost, s));
    gpu_check(cudaStreamSynchronize(s));
    if (hdeep)
      error_exit(
          "gravity on the GPU: %d walkers found their stack (%d entries, "
          "GRAVITY_WALK_STACK) and the hand-on queue full; Scheduler:gpu_walks: host walks "
          "on the CPU",
          hdeep, GRAVITY_WALK_STACK);
    int grown = 0;
    for (int k = 0; k < 4; k++) {
      gg->wn[k] = hn[k];
      if (hn[k] > gg->wcap[k]) {
        gg->wcap[k] = hn[k] + hn[k] / 4 + 1024;
        grown = 1;
      }
    }
    if (!grown) {
      if (gg->calls_walk > 0) {
        /* (the stream was synchronised after the last event) */
        for (int r = 0; r < timed; r++) {
          float ms = 0.0f;
          gpu_check(cudaEventElapsedTime(&ms, gg->ev_rnd[r], gg->ev_rnd[r + 1]));
          gg->t_round[r] += ms;
          gg->n_round[r] += (double)taken[r];
        }
        gg->walks_timed++;
      }
      break;
    }
    if (attempt > 2) error_bug("the GPU walk's lists did not fit after growing");
    gg->walk_retries++;
  }
  const double ms = gg_stage_end(gg->ev_walk, s);
  if (gg->calls_walk == 0) gg->t_walk_first = ms;
  gg->t_walk += ms;
  gg->calls_walk++;
  gg->walk_on_device = 1;
}

/** Add 1 to cnt[t[k]] for k < n. */
__global__ void gpu_grav_count_kernel(const int *__restrict__ t, size_t n,
                                      unsigned long long *cnt) {
  for (size_t k = blockIdx.x * (size_t)blockDim.x + threadIdx.x; k < n;
       k += (size_t)gridDim.x * blockDim.x)
    atomicAdd(cnt + t[k], 1ULL);
}

/** The counts c[0..n) become their exclusive prefix sums, c[n] the total (one block). */
__global__ void gpu_grav_scan_kernel(unsigned long long *c, int n) {
  gpu_block_exclusive_scan(c, n);
}

/** Entry k < n goes to the next free place of cell t[k]: out = s[k]. */
__global__ void gpu_grav_scatter_kernel(const int *__restrict__ t, const int *__restrict__ s,
                                        size_t n, unsigned long long *cursor, int *out) {
  for (size_t k = blockIdx.x * (size_t)blockDim.x + threadIdx.x; k < n;
       k += (size_t)gridDim.x * blockDim.x)
    out[atomicAdd(cursor + t[k], 1ULL)] = s[k];
}

/** Grid of the grid-stride kernels over n entries. */
static int gg_grid(size_t n) {
  const size_t g = (n + 255) / 256;
  return g > 4096 ? 4096 : (g ? (int)g : 1);
}

/** Group the interactions of kind k (0: part, 1: field), given on the
 *  device as n1 one-way (t1[i] receives from s1[i]) and n2 mutual (a2[i]
 *  and b2[i] receive from each other), by receiving cell; the device view. */
static struct gravity_gpu_groups gg_group_dev(struct gpu_grav *gg, int k, const int *t1,
                                              const int *s1, size_t n1, const int *a2,
                                              const int *b2, size_t n2, cudaStream_t s) {
  const size_t ntot = n1 + 2 * n2;
  const int nc = gg->nr_cells;
  typedef unsigned long long ull;
  ull *start = (ull *)gg_reserve(&gg->start[k], ((size_t)nc + 1) * sizeof(ull), "gravity lists");
  ull *cursor = (ull *)gg_reserve(&gg->cursor, ((size_t)nc + 1) * sizeof(ull), "gravity lists");
  /* (the lists are the largest of gravity's buffers: an eighth to grow) */
  int *out =
      (int *)gg_reserve_spare(&gg->src[k], ntot * sizeof(int) + 16, 8, "grouped gravity lists");
  gpu_check(cudaMemsetAsync(start, 0, ((size_t)nc + 1) * sizeof(ull), s));
  gpu_grav_count_kernel<<<gg_grid(n1), 256, 0, s>>>(t1, n1, start);
  gpu_check_launch(gpu_grav_count_kernel);
  gpu_grav_count_kernel<<<gg_grid(n2), 256, 0, s>>>(a2, n2, start);
  gpu_check_launch(gpu_grav_count_kernel);
  gpu_grav_count_kernel<<<gg_grid(n2), 256, 0, s>>>(b2, n2, start);
  gpu_check_launch(gpu_grav_count_kernel);
  gpu_grav_scan_kernel<<<1, 1024, 0, s>>>(start, nc);
  gpu_check_launch(gpu_grav_scan_kernel);
  gpu_check(cudaMemcpyAsync(cursor, start, (size_t)nc * sizeof(ull), cudaMemcpyDeviceToDevice, s));
  gpu_grav_scatter_kernel<<<gg_grid(n1), 256, 0, s>>>(t1, s1, n1, cursor, out);
  gpu_check_launch(gpu_grav_scatter_kernel);
  gpu_grav_scatter_kernel<<<gg_grid(n2), 256, 0, s>>>(a2, b2, n2, cursor, out);
  gpu_check_launch(gpu_grav_scatter_kernel);
  gpu_grav_scatter_kernel<<<gg_grid(n2), 256, 0, s>>>(b2, a2, n2, cursor, out);
  gpu_check_launch(gpu_grav_scatter_kernel);
  struct gravity_gpu_groups v;
  v.nr_cells = nc;
  v.start = start;
  v.source = out;
  gg->n_entries[k] = (double)ntot;
  if (!gg->reproducible) return v;
  if (ntot > (size_t)INT_MAX)
    error_exit(
        "Gravity:gpu_reproducible: %zu gravity interactions of one kind, more than the "
        "sort of the GPU lists takes (2^31 - 1); run without it",
        ntot);
  /* a cell's sources come in the order of the atomics (the walks' appends,
   * the scatter's cursors), which changes from run to run: sorted, the
   * sums of every cell, and so the run, are the same each time */
  int *sorted =
      (int *)gg_reserve_spare(&gg->sorted[k], ntot * sizeof(int) + 16, 8, "sorted gravity lists");
  size_t tmp_bytes = 0;
  gpu_check(cub::DeviceSegmentedSort::SortKeys(NULL, tmp_bytes, out, sorted, (int)ntot, nc, start,
                                               start + 1, s));
  void *tmp = gg_reserve(&gg->sort_tmp, tmp_bytes + 16, "gravity list sort");
  gpu_check(cub::DeviceSegmentedSort::SortKeys(tmp, tmp_bytes, out, sorted, (int)ntot, nc, start,
                                               start + 1, s));
  v.source = sorted;
  return v;
}

/** Upload the lists of kind k (0: part, 1: field) of the workers' records
 *  and group them by receiving cell on the device; the device view. */
static struct gravity_gpu_groups gg_group(struct gpu_grav *gg, int k,
                                          const struct gravity_gpu_rec *rec, int nr_rec,
                                          cudaStream_t s) {
  if (gg->walk_on_device) {
    /* the device's walk: part/field one-way in list k, mutual in list k + 2 */
    const struct gpu_grav_buf *one = &gg->wlist[k], *mut = &gg->wlist[k + 2];
    const int *o = (const int *)one->ptr, *m = (const int *)mut->ptr;
    return gg_group_dev(gg, k, o, o + gg->wcap[k], gg->wn[k], m, m + gg->wcap[k + 2], gg->wn[k + 2],
                        s);
  }
  size_t n1 = 0, n2 = 0;
  for (int w = 0; w < nr_rec; w++) {
    n1 += (k ? rec[w].field : rec[w].part).n;
    n2 += (k ? rec[w].field_sym : rec[w].part_sym).n;
  }
  /* raw: one-way targets, sources; mutual firsts, seconds */
  int *raw = (int *)gg_reserve(&gg->raw[k], (2 * n1 + 2 * n2) * sizeof(int) + 16,
                               k ? "recorded M2L/P2L" : "recorded P2P/M2P");
  int *t1 = raw, *s1 = raw + n1, *a2 = raw + 2 * n1, *b2 = raw + 2 * n1 + n2;
  size_t o1 = 0, o2 = 0;
  for (int w = 0; w < nr_rec; w++) {
    const struct gravity_rec_list *l = k ? &rec[w].field : &rec[w].part;
    const struct gravity_rec_list *m = k ? &rec[w].field_sym : &rec[w].part_sym;
    gg_up(gg, s, t1 + o1, l->target, l->n * sizeof(int));
    gg_up(gg, s, s1 + o1, l->source, l->n * sizeof(int));
    gg_up(gg, s, a2 + o2, m->target, m->n * sizeof(int));
    gg_up(gg, s, b2 + o2, m->source, m->n * sizeof(int));
    o1 += l->n;
    o2 += m->n;
  }
  return gg_group_dev(gg, k, t1, s1, n1, a2, b2, n2, s);
}

extern "C" void gpu_grav_run(struct gpu_grav *gg, struct parts *p,
                             const struct gravity_gpu_rec *rec, int nr_rec, double G, double eps,
                             int softening, double eps2, int order, int resident, int replay) {
  if (!gg->have_tree) error_bug("gpu_grav_run before gpu_grav_set_tree");
  if (replay && !gg->have_eval) error_bug("gravity replay on the GPU without a full evaluation");
  cudaStream_t s = gpu_stream(gg->g, 0);
  static const char *const xyzm[4] = {"x", "y", "z", "m"};
  static const char *const out[4] = {"gax", "gay", "gaz", "pot"};
  struct parts dp = gpu_device_parts(gg->g, p->count);
  gpu_check(cudaEventRecord(gg->ev[GG_UP], s));
  if (!resident) gpu_copy_named(gg->g, p, xyzm, 4, 1);
  const size_t n = p->count;
  struct gravity_gpu_dev d;
  d.mp = (const struct gravity_multipole *)gg->mp.ptr;
  d.field = (struct gravity_field *)gg->field.ptr;
  d.offset = (const size_t *)gg->offset.ptr;
  d.count = (const int *)gg->count.ptr;
  d.G = G;
  d.eps = eps;
  d.eps2 = eps2;
  d.softening = softening;
  d.order = order;
  /* a step of active particles only (the upward pass marked the cells, the
   * walk recorded their interactions only): the particles of the other
   * leaves keep their ga and pot */
  d.active = gg->active_on && !replay ? (const unsigned char *)gg->active.ptr : NULL;
  if (d.active) {
    gravity_zero_gpu_launch(s, dp, d, (const int *)gg->leaf.ptr, gg->nr_leaves, gg->block);
  } else {
    gpu_check(cudaMemsetAsync(dp.gax, 0, n * sizeof(double), s));
    gpu_check(cudaMemsetAsync(dp.gay, 0, n * sizeof(double), s));
    gpu_check(cudaMemsetAsync(dp.gaz, 0, n * sizeof(double), s));
    gpu_check(cudaMemsetAsync(dp.pot, 0, n * sizeof(double), s));
  }
  const size_t nc = (size_t)gg->nr_cells;
  if (!replay && !gg->mp_on_device)
    gg_up(gg, s, gg->mp.ptr, gg->mp_host, nc * sizeof(struct gravity_multipole));
  gg->mp_on_device = 0;
  if (replay) gg->walk_on_device = 0;
  gpu_check(cudaEventRecord(gg->ev[GG_GROUP], s));
  if (!replay) {
    gg->gl[0] = gg_group(gg, 0, rec, nr_rec, s);
    gg->gl[1] = gg_group(gg, 1, rec, nr_rec, s);
    gg->walk_on_device = 0;
    gpu_check(cudaMemsetAsync(gg->field.ptr, 0, nc * sizeof(struct gravity_field), s));
  }
  gpu_check(cudaEventRecord(gg->ev[GG_FIELD], s));
  if (!replay) gravity_field_gpu_launch(s, dp, d, gg->gl[1]);
  gpu_check(cudaEventRecord(gg->ev[GG_L2L], s));
  if (!replay) {
    const int *l2l = (const int *)gg->l2l.ptr;
    const int nl = gg->level_start[gg->nr_levels];
    for (int L = 0; L < gg->nr_levels; L++)
      gravity_l2l_gpu_launch(s, d, l2l, l2l + nl, gg->level_start[L], gg->level_start[L + 1]);
  }
  gpu_check(cudaEventRecord(gg->ev[GG_PART], s));
  gravity_part_gpu_launch(s, dp, d, gg->gl[0], (const int *)gg->leaf.ptr, gg->nr_leaves, gg->block);
  gpu_check(cudaEventRecord(gg->ev[GG_L2P], s));
  gravity_l2p_gpu_launch(s, dp, d, (const int *)gg->leaf.ptr, gg->nr_leaves, gg->block);
  gpu_check(cudaEventRecord(gg->ev[GG_DOWN], s));
  /* ga and pot back: the host's next gravity_up reads |ga| (the adaptive
   * criterion's scale), the statistics read pot */
  gpu_copy_named(gg->g, p, out, 4, 0);
  gpu_check(cudaEventRecord(gg->ev[GG_N], s));
  gpu_check(cudaStreamSynchronize(s));
  gg->bytes += 4.0 * (double)n * sizeof(double) * (resident ? 1.0 : 2.0);
  for (int k = 0; k < GG_N; k++) {
    float ms = 0.0f;
    gpu_check(cudaEventElapsedTime(&ms, gg->ev[k], gg->ev[k + 1]));
    gg->t[k] += ms;
  }
  gg->have_eval = 1;
  gg->calls++;
  gg->replays += replay;
}

extern "C" void gpu_grav_set_reproducible(struct gpu_grav *gg, int on) {
  gg->reproducible = on;
}

extern "C" void gpu_grav_set_active(struct gpu_grav *gg, int on) {
  gg->active_on = on;
}

extern "C" void gpu_grav_print(const struct gpu_grav *gg, FILE *f) {
  if (!gg || gg->calls == 0) return;
  fprintf(f, "GPU gravity, %ld evaluations (%ld replays), ms per evaluation:", gg->calls,
          gg->replays);
  for (int k = 0; k < GG_N; k++) fprintf(f, " %s %.3f", gg_stage_names[k], gg->t[k] / gg->calls);
  if (gg->calls_up)
    fprintf(f, "; %ld upward passes (P2M, M2M) on the device, %.3f ms each (copy back included)",
            gg->calls_up, gg->t_up / gg->calls_up);
  if (gg->calls_walk)
    fprintf(f,
            "; %ld walks on the device, %.3f ms each (%.1f rounds of walkers; %ld repeated "
            "with longer lists)",
            gg->calls_walk, gg->t_walk / gg->calls_walk,
            1.0 + (double)gg->walk_rounds / (double)(gg->calls_walk + gg->walk_retries),
            gg->walk_retries);
  if (gg->walks_timed) {
    fprintf(f, "; the first walk %.3f ms; the %ld after it, ms each by round (entries taken):",
            gg->t_walk_first, gg->walks_timed);
    const double w = (double)gg->walks_timed;
    for (int r = 0; r < GG_ROUNDS && gg->t_round[r] > 0.0; r++)
      if (r == 0)
        fprintf(f, " roots %.3f", gg->t_round[0] / w);
      else
        fprintf(f, " %d%s %.3f (%.0f)", r, r == GG_ROUNDS - 1 ? "+" : "", gg->t_round[r] / w,
                gg->n_round[r] / w);
  }
  fprintf(f, "; bus %.1f MB per evaluation; last full evaluation %.3g P2P/M2P, %.3g M2L/P2L\n",
          gg->bytes / gg->calls / 1e6, gg->n_entries[0], gg->n_entries[1]);
}
