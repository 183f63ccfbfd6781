/* Multi-rank runs: ownership, migration and the foreign copies
 * (src/mpi/halo.h; theory/mpi.md, "Multi-rank runs"). */
#include "src/mpi/halo.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "config.h"
#include "src/cell.h"
#include "src/engine.h"
#include "src/engine_tasks.h"
#include "src/error.h"
#include "src/io/params.h"
#include "src/io/restart.h"
#include "src/mpi/partition.h"
#include "src/mpi/ranks.h"
#include "src/part.h"
#include "src/space.h"
#include "tasks/hydro/kernel.h"
#include "tasks/task_families.h"

#ifdef HAVE_MPI
#include <mpi.h>
#endif

/** A growable list of particle indices. */
struct halo_list {
  size_t *i;
  size_t n, cap;
};

struct halo {
  int nranks, me;
  /* the decomposition grid: the top-level grid of the first rebuild */
  int cdim[3];
  double width[3], dim[3];
  int periodic;
  int ncells;
  int *assign; /**< [ncells] the rank of each cell; NULL before the first rebuild */
  /* the exchange of the copies, fixed between two rebuilds */
  int *scount, *sdispl, *rcount, *rdispl; /**< [nranks] particles sent, received per rank */
  size_t *sidx;                           /**< [nsend] the particles sent, rank after rank */
  size_t *ridx;                           /**< [nrecv] where each received copy lives */
  size_t nsend, nrecv;
  size_t rec; /**< bytes of one particle's record: every field */
  char *sbuf, *rbuf;
  size_t sbuf_cap, rbuf_cap;
  /* for the closing line (halo_log) */
  double t_refresh,
      t_halo; /**< wall seconds in halo_refresh, in halo_rebuild_start + halo_rebuild */
  /** the rebuild's parts (wall seconds): removing the copies and migrating,
   *  choosing the copies, packing + exchanging + unpacking them, the cells
   *  with the copies and the index maps */
  double t_rebuild[4];
  long nr_refresh, nr_halo;
  double copies; /**< sum over rebuilds of the copies over the owned particles, all ranks */
  /* self-gravity's copies: every particle of the other ranks that is not a
   * copy above, refreshed in gravity's fields only (halo_refresh_gravity) */
  int gravity;                                /**< 1: self-gravity is on */
  int *gscount, *gsdispl, *grcount, *grdispl; /**< [nranks] particles sent, received per rank */
  size_t *gsidx, *gridx;                      /**< [gnsend] sent, [gnrecv] where received */
  size_t gnsend, gnrecv;
  double *gsbuf, *grbuf;
  size_t gsbuf_cap, grbuf_cap;
  char *gdbuf; /**< their fields for the device (halo_device.gravity) */
  size_t gdbuf_cap;
  double t_grefresh, gcopies;
  long nr_grefresh;
  /* the far field by the top-level cells' records (halo_gravity_records;
   * theory/mpi.md, "Self-gravity on several ranks"): per top-level cell of
   * the last rebuild's grid (gtop cells) */
  int grec_on;              /**< 1: gravity by records (an open box, the tree) */
  int gtop;                 /**< top-level cells of the arrays below */
  long long *gcount;        /**< [gtop] particles of every rank in the cell at the rebuild */
  int *gprov;               /**< [gtop] the rank that sends its record: the lowest that owns a
                                 particle of it (INT_MAX: empty) */
  unsigned char *gmine;     /**< [gtop] 1: this rank owns a particle of it */
  unsigned char *guse;      /**< [gtop] 1: the walks read it by its record (another rank's) */
  unsigned char *gcomplete; /**< [gtop] 1: every particle of it is on this rank */
  double *gbox;             /**< [6 gtop] the bounding box of its particles at the rebuild */
  int *gnrec, *gdrec;       /**< [nranks] records each rank sends, their offsets */
  double *grec;             /**< [gtop R] the records of the last exchange, every cell */
  int *grow;                /**< [gtop] the row of a cell's record of the last step in grec
                                 (-1: none); grec holds the non-empty cells' only */
  int rcdim[3];             /**< the grid of grec (the records' cells) */
  double *gsrec;            /**< this rank's records, packed */
  long gmisses;             /**< walks that needed a cell without its particles (this rank) */
  long gneed_rebuilds;      /**< rebuilds that chose the cells from the records */
  double gneed_frac;        /**< sum over them of the needed cells over the other ranks' ones */
  double t_grec;            /**< wall seconds in the exchanges of the records */
  long nr_grec;
  unsigned char *gpartial; /**< [gtop] gp.top_partial */
  /* repartitioning (halo_repartition) */
  double trigger;               /**< DomainDecomposition:trigger (0: never) */
  enum partition_method method; /**< DomainDecomposition:method (auto resolved) */
  long nr_repart, nr_tried;     /**< partitions made again and kept; tried */
  double imb_last;              /**< the measured imbalance at the last rebuild */
  /* the refreshes in flight (halo_refresh_start ... finish) */
#ifdef HAVE_MPI
  MPI_Request req, greq;
#endif
  int pending, gpending; /**< 1: in flight, 2: complete (MPI_Test), 0: none */
  int *xc, *gxc;         /**< [4 nranks] their byte counts and offsets */
  /* the fields of a refresh between stages: those the stage before wrote
   * (halo_fields): sel[k] of the refresh after stage k, its record bytes */
  unsigned char *sel[2];
  size_t rec_sel[2];
  int cur;                       /**< the refresh in flight: -1 every field, else k of sel[k] */
  const struct halo_device *dev; /**< the particles live on a GPU (halo_set_device) */
  double t_wait;                 /**< wall seconds waiting for them (not hidden by local work) */
};

/** The fields of a particle that gravity's walks read of a source, and
 *  whose values halo_refresh_gravity sends: position, mass, h (softening
 *  tied to h) and the acceleration of the last pass (the adaptive
 *  criterion's a_min). */
#define HALO_GRAVITY_FIELDS 8

#ifdef HAVE_MPI

/* ------------------------------------------------------------- records */

/** Pack particles idx[0 .. n) of p into dst, field after field (n values
 *  of each): a block of n records. */
static void halo_pack_sel(const struct parts *p, const size_t *idx, size_t n, char *dst,
                          const unsigned char *sel) {
  for (int f = 0; f < part_nr_fields; f++) {
    if (sel && !sel[f]) continue;
    const struct part_field *pf = &part_fields[f];
    const char *a = part_field_array(p, pf);
    if (!a) continue; /* (absent on every rank: not in the records, halo_record_bytes) */
    if (pf->size == 8)
      for (size_t k = 0; k < n; k++) memcpy(dst + 8 * k, a + 8 * idx[k], 8);
    else if (pf->size == 4)
      for (size_t k = 0; k < n; k++) memcpy(dst + 4 * k, a + 4 * idx[k], 4);
    else
      for (size_t k = 0; k < n; k++) memcpy(dst + pf->size * k, a + pf->size * idx[k], pf->size);
    dst += n * pf->size;
  }
}

/** Unpack a block of n records into particles slot[0 .. n) of p (slot
 *  NULL: first, first + 1, ...). */
static void halo_unpack_sel(struct parts *p, size_t first, const size_t *slot, size_t n,
                            const char *src, const unsigned char *sel) {
  for (int f = 0; f < part_nr_fields; f++) {
    if (sel && !sel[f]) continue;
    const struct part_field *pf = &part_fields[f];
    char *a = part_field_array(p, pf);
    if (!a) continue; /* (absent) */
    if (!slot)
      memcpy(a + pf->size * first, src, n * pf->size);
    else if (pf->size == 8)
      for (size_t k = 0; k < n; k++) memcpy(a + 8 * slot[k], src + 8 * k, 8);
    else if (pf->size == 4)
      for (size_t k = 0; k < n; k++) memcpy(a + 4 * slot[k], src + 4 * k, 4);
    else
      for (size_t k = 0; k < n; k++) memcpy(a + pf->size * slot[k], src + pf->size * k, pf->size);
    src += n * pf->size;
  }
}

static void halo_pack_block(const struct parts *p, const size_t *idx, size_t n, char *dst) {
  halo_pack_sel(p, idx, n, dst, NULL);
}

static void halo_unpack_block(struct parts *p, size_t first, const size_t *slot, size_t n,
                              const char *src) {
  halo_unpack_sel(p, first, slot, n, src, NULL);
}

/* The fields each family's step writes (the registry's column writes). */
#define HALO_WRITES_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  static const char *const halo_writes_##name[]                                     \
      __attribute__((unused)) = {NULL, TASK_UNPAREN writes};
TASK_FAMILIES(HALO_WRITES_)
#undef HALO_WRITES_

/** Mark in sel the fields of part_fields that family list l (n names)
 *  writes and p holds; its record bytes added to *rec. */
static void halo_fields(const struct parts *p, unsigned char *sel, size_t *rec,
                        const char *const *l, int n) {
  for (int k = 0; k < n; k++)
    for (int f = 0; f < part_nr_fields; f++)
      if (strcmp(part_fields[f].name, l[k]) == 0 && !sel[f] && !p->absent[f]) {
        sel[f] = 1;
        *rec += part_fields[f].size;
      }
}

static char *halo_grow(char **buf, size_t *cap, size_t need) {
  if (need > *cap) {
    free(*buf);
    *cap = need + need / 4 + 1;
    *buf = error_malloc(*cap, "MPI exchange buffer");
  }
  return *buf;
}

/** Alltoallv of records: scount[r] records to rank r from sbuf (rank
 *  order), rcount[r] from rank r into rbuf; counts in records. */
static void halo_alltoallv(struct halo *H, const int *scount, const int *rcount, const char *sbuf,
                           char *rbuf) {
  const int n = H->nranks;
  int *sc = error_malloc(4 * (size_t)n * sizeof(int), "MPI exchange counts");
  int *sd = sc + n, *rc = sc + 2 * n, *rd = sc + 3 * n;
  long long so = 0, ro = 0;
  for (int r = 0; r < n; r++) {
    const long long sb = (long long)scount[r] * (long long)H->rec;
    const long long rb = (long long)rcount[r] * (long long)H->rec;
    if (so + sb > INT_MAX || ro + rb > INT_MAX)
      error_exit("MPI exchange of more than %d bytes per rank and step: use more ranks", INT_MAX);
    sc[r] = (int)sb;
    sd[r] = (int)so;
    rc[r] = (int)rb;
    rd[r] = (int)ro;
    so += sb;
    ro += rb;
  }
  MPI_Alltoallv(sbuf, sc, sd, MPI_BYTE, rbuf, rc, rd, MPI_BYTE, MPI_COMM_WORLD);
  free(sc);
}

/* ------------------------------------------------------------ geometry */

/** The decomposition cell's coordinate of x along k (wrapped in a periodic
 *  box, clamped in an open one). */
static int halo_coord(const struct halo *H, int k, double x) {
  if (H->periodic) x -= floor(x / H->dim[k]) * H->dim[k];
  int i = (int)floor(x / H->width[k]);
  if (i >= H->cdim[k]) i = H->cdim[k] - 1;
  if (i < 0) i = 0;
  return i;
}

static int halo_cell(const struct halo *H, int i, int j, int k) {
  return (i * H->cdim[1] + j) * H->cdim[2] + k;
}

static int halo_owner(const struct halo *H, const struct parts *p, size_t i) {
  return H->assign[halo_cell(H, halo_coord(H, 0, p->x[i]), halo_coord(H, 1, p->y[i]),
                             halo_coord(H, 2, p->z[i]))];
}

/** Squared distance of the point x from the box of the cell at grid
 *  coordinates c (not wrapped: c outside the grid is a periodic image). */
static double halo_box_d2(const struct halo *H, const double x[3], const int c[3]) {
  double d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double lo = c[k] * H->width[k], hi = lo + H->width[k];
    const double d = x[k] < lo ? lo - x[k] : (x[k] > hi ? x[k] - hi : 0.0);
    d2 += d * d;
  }
  return d2;
}

/** A cell near another: its grid coordinates, not wrapped (outside the
 *  grid: a periodic image), and its rank. */
struct halo_cand {
  int c[3];
  int r;
};

/** The cells of other ranks within D of the box of decomposition cell c
 *  (reach: the cells to look at around it), into *cand (capacity *cap,
 *  grown); their number. */
static int halo_cands(const struct halo *H, int c, int reach, double D, struct halo_cand **cand,
                      int *cap) {
  const int c0[3] = {c / (H->cdim[1] * H->cdim[2]), (c / H->cdim[2]) % H->cdim[1], c % H->cdim[2]};
  int q[3], w[3], n = 0;
  for (q[0] = c0[0] - reach; q[0] <= c0[0] + reach; q[0]++)
    for (q[1] = c0[1] - reach; q[1] <= c0[1] + reach; q[1]++)
      for (q[2] = c0[2] - reach; q[2] <= c0[2] + reach; q[2]++) {
        int ok = 1;
        double d2 = 0.0;
        for (int k = 0; k < 3; k++) {
          w[k] = q[k];
          if (w[k] < 0 || w[k] >= H->cdim[k]) {
            if (!H->periodic) ok = 0;
            w[k] = ((w[k] % H->cdim[k]) + H->cdim[k]) % H->cdim[k];
          }
          /* the gap between the two boxes along k: (|q - c0| - 1) widths */
          const int g = abs(q[k] - c0[k]) - 1;
          if (g > 0) d2 += (g * H->width[k]) * (g * H->width[k]);
        }
        if (!ok || d2 > D * D) continue;
        const int r = H->assign[halo_cell(H, w[0], w[1], w[2])];
        if (r == H->me) continue;
        if (n == *cap) {
          *cap = *cap ? 2 * *cap : 64;
          *cand = error_realloc(*cand, (size_t)*cap * sizeof **cand, "MPI halo cells");
        }
        (*cand)[n++] = (struct halo_cand){{q[0], q[1], q[2]}, r};
      }
  return n;
}

/** The decomposition cell of the point x, and x wrapped into a periodic box. */
static int halo_cell_of(const struct halo *H, const double xin[3], double x[3]) {
  int c[3];
  for (int k = 0; k < 3; k++) {
    x[k] = xin[k];
    if (H->periodic) x[k] -= floor(x[k] / H->dim[k]) * H->dim[k];
    c[k] = halo_coord(H, k, x[k]);
  }
  return halo_cell(H, c[0], c[1], c[2]);
}

/** The squared distance of x (wrapped) from the nearest of the cells cand
 *  of each rank into d2[r] (HUGE_VAL: none). */
static void halo_cands_d2(const struct halo *H, const double x[3], const struct halo_cand *cand,
                          int n, double *d2) {
  for (int r = 0; r < H->nranks; r++) d2[r] = HUGE_VAL;
  for (int k = 0; k < n; k++) {
    const double q = halo_box_d2(H, x, cand[k].c);
    if (q < d2[cand[k].r]) d2[cand[k].r] = q;
  }
}

/* ------------------------------------------------------------ the lists */

static void halo_list_push(struct halo_list *L, size_t i) {
  if (L->n == L->cap) {
    L->cap = L->cap ? 2 * L->cap : 1024;
    L->i = error_realloc(L->i, L->cap * sizeof(size_t), "MPI halo list");
  }
  L->i[L->n++] = i;
}

/** Remove the particles marked in drop (compacting; the order changes). */
static void halo_remove(struct parts *p, unsigned char *drop) {
  /* the moves first (each dropped slot takes the last particle; a source is
   * never an earlier move's destination), then applied field by field: one
   * array at a time stays in the caches, where a particle's copy across
   * every field touched a hundred arrays (0.2 s at 1.1e6 on 2 ranks) */
  struct halo_list moves = {0};
  size_t i = 0, count = p->count;
  while (i < count) {
    if (drop[i]) {
      const size_t last = count - 1;
      if (i != last) {
        halo_list_push(&moves, i);
        halo_list_push(&moves, last);
        drop[i] = drop[last];
      }
      count--;
    } else {
      i++;
    }
  }
  const size_t nm = moves.n / 2, *mv = moves.i;
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *f = &part_fields[k];
    char *a = part_field_array(p, f);
    if (!a) continue; /* (absent) */
    if (f->size == 8)
      for (size_t m = 0; m < nm; m++) ((uint64_t *)a)[mv[2 * m]] = ((uint64_t *)a)[mv[2 * m + 1]];
    else if (f->size == 4)
      for (size_t m = 0; m < nm; m++) ((uint32_t *)a)[mv[2 * m]] = ((uint32_t *)a)[mv[2 * m + 1]];
    else
      for (size_t m = 0; m < nm; m++)
        memcpy(a + f->size * mv[2 * m], a + f->size * mv[2 * m + 1], f->size);
  }
  free(moves.i);
  p->count = count;
}

/** The owned particles that left the rank's cells go to their owners. */
static void halo_migrate(struct engine *e) {
  struct halo *H = e->halo;
  struct parts *p = &e->parts;
  const int n = H->nranks;
  int *sc = error_calloc(2 * (size_t)n, sizeof(int), "MPI migration counts");
  int *rc = sc + n;
  int *owner = error_malloc(p->count * sizeof(int) + 1, "MPI migration owners");
  for (size_t i = 0; i < p->count; i++) {
    owner[i] = halo_owner(H, p, i);
    if (owner[i] != H->me) sc[owner[i]]++;
  }
  MPI_Alltoall(sc, 1, MPI_INT, rc, 1, MPI_INT, MPI_COMM_WORLD);
  size_t ns = 0, nr = 0;
  for (int r = 0; r < n; r++) {
    ns += (size_t)sc[r];
    nr += (size_t)rc[r];
  }
  char *sbuf = halo_grow(&H->sbuf, &H->sbuf_cap, ns * H->rec + 1);
  char *rbuf = halo_grow(&H->rbuf, &H->rbuf_cap, nr * H->rec + 1);
  size_t *pos = error_malloc((size_t)n * sizeof(size_t), "MPI migration offsets");
  size_t off = 0;
  for (int r = 0; r < n; r++) {
    pos[r] = off;
    off += (size_t)sc[r];
  }
  unsigned char *drop = error_calloc(p->count + 1, 1, "MPI migration marks");
  size_t *list = error_malloc(ns * sizeof(size_t) + 1, "MPI migration list");
  for (size_t i = 0; i < p->count; i++)
    if (owner[i] != H->me) {
      list[pos[owner[i]]++] = i;
      drop[i] = 1;
    }
  for (int r = 0, o = 0; r < n; o += sc[r], r++)
    halo_pack_block(p, list + o, (size_t)sc[r], sbuf + (size_t)o * H->rec);
  free(list);
  halo_alltoallv(H, sc, rc, sbuf, rbuf);
  halo_remove(p, drop);
  parts_reserve(p, p->count + nr);
  for (int r = 0, o = 0; r < n; o += rc[r], r++)
    halo_unpack_block(p, p->count + (size_t)o, NULL, (size_t)rc[r], rbuf + (size_t)o * H->rec);
  p->count += nr;
  free(drop);
  free(pos);
  free(owner);
  free(sc);
}

/** The cells of copies only, whose tasks have nothing to do
 *  (cell.foreign, ENGINE_CELL_SKIP), and the cells with a copy, whose tasks
 *  wait for the refresh (cell.copies, engine_run_force_stages). */
static void halo_mark_cells(struct engine *e) {
  const struct parts *p = &e->parts;
  struct space *s = &e->space;
  for (int c = 0; c < s->nr_cells; c++) {
    struct cell *cl = &s->cells[c];
    size_t nf = 0;
    for (size_t i = cl->offset; i < cl->offset + cl->count; i++)
      nf += (p->flags[i] & PART_FOREIGN) != 0;
    cl->foreign = cl->count > 0 && nf == cl->count;
    cl->copies = nf > 0;
  }
}

/** A new numbering of the parts of rank[] (over n ranks) that keeps as
 *  much of the cost w[] on the rank of old[] as it can (greedy on the
 *  overlap matrix: the largest overlap first). */
static void halo_relabel(int *rank, const int *old, const double *w, int ncells, int n) {
  double *ov = error_calloc((size_t)n * (size_t)n, sizeof(double), "MPI repartition");
  int *to = error_malloc(2 * (size_t)n * sizeof(int), "MPI repartition"), *taken = to + n;
  for (int c = 0; c < ncells; c++) ov[(size_t)rank[c] * n + old[c]] += w[c] + 1e-300;
  for (int r = 0; r < n; r++) to[r] = taken[r] = -1;
  for (int k = 0; k < n; k++) {
    int bi = -1, bj = -1;
    double best = -1.0;
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++)
        if (to[i] < 0 && taken[j] < 0 && ov[(size_t)i * n + j] > best)
          best = ov[(size_t)i * n + j], bi = i, bj = j;
    to[bi] = bj;
    taken[bj] = bi;
  }
  for (int c = 0; c < ncells; c++) rank[c] = to[rank[c]];
  free(to);
  free(ov);
}

/** max / mean of the cost of each rank's cells. */
static double halo_imbalance(const int *rank, const double *w, int ncells, int n) {
  double *rc = error_calloc((size_t)n, sizeof(double), "MPI repartition");
  double sum = 0.0, mx = 0.0;
  for (int c = 0; c < ncells; c++) rc[rank[c]] += w[c];
  for (int r = 0; r < n; r++) {
    sum += rc[r];
    mx = rc[r] > mx ? rc[r] : mx;
  }
  free(rc);
  return sum > 0.0 ? mx * n / sum : 1.0;
}

/** At a rebuild, before the particles move (DomainDecomposition:trigger):
 *  the measured cost of each top-level cell in the last step (the times of
 *  the tasks of the graph still in place, each cell's by its owner, summed
 *  over the ranks), the imbalance of the ranks; past the trigger, rank 0
 *  (its graph's edges, weighed with every rank's particle counts)
 *  partitions the cells again with those costs, and the new partition
 *  replaces H->assign if its imbalance is lower by half the trigger: the
 *  migration that follows moves the particles.  Only while the space's
 *  grid is the decomposition's (the costs are per cell of that grid). */
static void halo_repartition(struct engine *e) {
  struct halo *H = e->halo;
  struct space *s = &e->space;
  if (H->trigger <= 0.0 || !H->assign || e->sched.nr_tasks == 0 || s->nr_top != H->ncells) return;
  for (int k = 0; k < 3; k++)
    if (s->cdim[k] != H->cdim[k]) return;
  const int nc = H->ncells, n = H->nranks;
  struct partition_graph g;
  partition_graph_make(&g, s, &e->sched, 1);
  for (int c = 0; c < nc; c++)
    if (H->assign[c] != H->me) g.cost[c] = 0.0;
  double *cnt = error_calloc((size_t)nc, sizeof(double), "MPI repartition");
  const struct parts *p = &e->parts;
  for (size_t i = 0; i < p->count; i++)
    if (!(p->flags[i] & PART_FOREIGN))
      cnt[halo_cell(H, halo_coord(H, 0, p->x[i]), halo_coord(H, 1, p->y[i]),
                    halo_coord(H, 2, p->z[i]))] += 1.0;
  ranks_allreduce_doubles(g.cost, nc, RANKS_SUM);
  ranks_allreduce_doubles(cnt, nc, RANKS_SUM);
  /* the edges are rank 0's (each rank's graph has the pair tasks of its own
   * cells and copies): every edge between two cells with particles weighs
   * the particles of both, as a pair task's does in the one-rank graph */
  g.total_cost = g.total_comm = 0.0;
  for (int c = 0; c < nc; c++) {
    g.count[c] = (size_t)cnt[c];
    g.total_cost += g.cost[c];
    for (int k = g.xadj[c]; k < g.xadj[c + 1]; k++) {
      const int b = g.adj[k];
      g.comm[k] = cnt[c] > 0.0 && cnt[b] > 0.0 ? cnt[c] + cnt[b] : 0.0;
      g.total_comm += 0.5 * g.comm[k];
    }
  }
  free(cnt);
  const double imb = halo_imbalance(H->assign, g.cost, nc, n);
  H->imb_last = imb;
  if (imb <= 1.0 + H->trigger) {
    partition_graph_free(&g);
    return;
  }
  H->nr_tried++;
  int keep = 0;
  double imb_new = imb;
  int *assign = error_malloc((size_t)nc * sizeof(int), "MPI repartition");
  if (H->me == 0) {
    struct partition pt;
    partition_make(&pt, &g, n, H->method);
    memcpy(assign, pt.rank, (size_t)nc * sizeof(int));
    partition_free(&pt);
    halo_relabel(assign, H->assign, g.cost, nc, n);
    imb_new = halo_imbalance(assign, g.cost, nc, n);
    keep = imb_new < imb - 0.5 * H->trigger;
  }
  ranks_bcast_ints(&keep, 1);
  if (keep) {
    ranks_bcast_ints(assign, nc);
    double moved = 0.0, all = 0.0;
    for (int c = 0; c < nc; c++) {
      all += (double)g.count[c];
      if (assign[c] != H->assign[c]) moved += (double)g.count[c];
    }
    error_log(0,
              "domain decomposition again at step %ld: measured imbalance %.3f (trigger %g), "
              "the new partition's %.3f; %.1f%% of the particles change rank",
              e->step, imb, H->trigger, imb_new, all > 0.0 ? 100.0 * moved / all : 0.0);
    free(H->assign);
    H->assign = assign;
    H->nr_repart++;
  } else {
    error_log(1, "domain decomposition kept at step %ld: measured imbalance %.3f, a new one %.3f",
              e->step, imb, imb_new);
    free(assign);
  }
  partition_graph_free(&g);
}

/** The first rebuild: partition the top-level cells of the space (every
 *  rank holds every particle), keep the rank's own. */
static void halo_partition(struct engine *e) {
  struct halo *H = e->halo;
  struct space *s = &e->space;
  int ncells = s->nr_top;
  int *assign = NULL;
  if (H->me == 0) {
    struct partition_graph g;
    partition_graph_make(&g, s, NULL, 0);
    struct partition pt;
    partition_make(&pt, &g, H->nranks, H->method);
    error_log(0,
              "domain decomposition: %d ranks over %d top-level cells (%s), imbalance %.3f of "
              "the estimated costs",
              H->nranks, ncells,
              pt.method == partition_method_metis && !pt.fallback ? "METIS"
              : pt.method == partition_method_slabs               ? "slabs along x"
                                                                  : "Morton ranges",
              pt.imbalance);
    assign = pt.rank;
    pt.rank = NULL;
    partition_free(&pt);
    partition_graph_free(&g);
  }
  ranks_bcast_ints(&ncells, 1);
  if (H->me != 0) assign = error_malloc((size_t)ncells * sizeof(int), "MPI partition");
  ranks_bcast_ints(assign, ncells);
  H->assign = assign;
  H->ncells = ncells;
  for (int k = 0; k < 3; k++) {
    H->cdim[k] = s->cdim[k];
    H->width[k] = s->width[k];
    H->dim[k] = s->dim[k];
  }
  H->periodic = s->periodic;
  struct parts *p = &e->parts;
  unsigned char *drop = error_calloc(p->count + 1, 1, "MPI partition marks");
  for (size_t i = 0; i < p->count; i++) drop[i] = halo_owner(H, p, i) != H->me;
  halo_remove(p, drop);
  free(drop);
  if (space_rebuild(s) != 0) error_bug("particles removed by the second rebuild of the partition");
}

/* ------------------------------------------------------- restart files */

/* The rank's part of a restart: the decomposition and the exchange lists
 * of the last rebuild (the particles, their copies included, are in the
 * rank's restart file), in STEM.halo.bin beside STEM.bin, rotated the same
 * way (STEM.halo.prev.bin), with the step, so that the one matching the
 * restart file read is found. */
#define HALO_MAGIC 0x314f4c4148444c42ULL /* "BLDHALO1" */

static void halo_put(FILE *f, const char *path, const void *d, size_t n, uint64_t *h) {
  if (n && fwrite(d, 1, n, f) != n)
    error_exit("%s: cannot write (disk full?): %s", path, strerror(errno));
  *h = restart_checksum(d, n, *h);
}

void halo_write_restart(const struct engine *e) {
  const struct halo *H = e->halo;
  if (!H) return;
  char path[1400], prev[1400], tmp[1400];
  snprintf(path, sizeof path, "%s.halo.bin", e->restart_stem);
  snprintf(prev, sizeof prev, "%s.halo.prev.bin", e->restart_stem);
  snprintf(tmp, sizeof tmp, "%s.halo.bin.tmp", e->restart_stem);
  FILE *f = fopen(tmp, "wb");
  if (!f) error_exit("%s: cannot create: %s", tmp, strerror(errno));
  const int n = H->nranks;
  int64_t head[14] = {(int64_t)HALO_MAGIC,
                      e->step,
                      n,
                      H->me,
                      H->ncells,
                      H->cdim[0],
                      H->cdim[1],
                      H->cdim[2],
                      H->periodic,
                      (int64_t)H->nsend,
                      (int64_t)H->gnsend,
                      (int64_t)H->nrecv,
                      (int64_t)H->gnrecv,
                      H->nr_repart};
  const double geo[6] = {H->width[0], H->width[1], H->width[2], H->dim[0], H->dim[1], H->dim[2]};
  uint64_t h = RESTART_HASH_INIT;
  halo_put(f, tmp, head, sizeof head, &h);
  halo_put(f, tmp, geo, sizeof geo, &h);
  halo_put(f, tmp, H->scount, 4 * (size_t)n * sizeof(int), &h);
  halo_put(f, tmp, H->gscount, 4 * (size_t)n * sizeof(int), &h);
  halo_put(f, tmp, H->assign, (size_t)H->ncells * sizeof(int), &h);
  for (size_t k = 0; k < H->nsend; k++) {
    const int64_t v = (int64_t)H->sidx[k];
    halo_put(f, tmp, &v, 8, &h);
  }
  for (size_t k = 0; k < H->gnsend; k++) {
    const int64_t v = (int64_t)H->gsidx[k];
    halo_put(f, tmp, &v, 8, &h);
  }
  if (fwrite(&h, 8, 1, f) != 1 || fflush(f) || fsync(fileno(f)))
    error_exit("%s: cannot write (disk full?): %s", tmp, strerror(errno));
  if (fclose(f)) error_exit("%s: cannot write (disk full?): %s", tmp, strerror(errno));
  if (access(path, F_OK) == 0) {
    if (unlink(prev) && errno != ENOENT) error_exit("%s: cannot remove: %s", prev, strerror(errno));
    if (link(path, prev) && rename(path, prev))
      error_exit("%s: cannot rename to %s: %s", path, prev, strerror(errno));
  }
  if (rename(tmp, path)) error_exit("%s: cannot rename to %s: %s", tmp, path, strerror(errno));
}

/** Read the state of path into H if it is a valid file of this rank for
 *  step; else 0 with why. */
static int halo_read_file(struct halo *H, const char *path, long step, size_t np, char *why,
                          size_t len) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    snprintf(why, len, "%s: cannot open: %s", path, strerror(errno));
    return 0;
  }
  fseek(f, 0, SEEK_END);
  const long sz = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *buf = error_malloc(sz > 0 ? (size_t)sz : 1, "MPI restart");
  const int ok_read = sz >= 8 && fread(buf, 1, (size_t)sz, f) == (size_t)sz;
  fclose(f);
  int ok = 0;
  int64_t head[14];
  const size_t n = (size_t)H->nranks;
  if (!ok_read || (size_t)sz < sizeof head + 48 + 8) {
    snprintf(why, len, "%s: too short", path);
  } else {
    uint64_t sum;
    memcpy(&sum, buf + sz - 8, 8);
    memcpy(head, buf, sizeof head);
    const size_t want = sizeof head + 48 + 8 * n * sizeof(int) + (size_t)head[4] * sizeof(int) +
                        8 * (size_t)(head[9] + head[10]) + 8;
    if (restart_checksum(buf, (size_t)sz - 8, RESTART_HASH_INIT) != sum)
      snprintf(why, len, "%s: checksum mismatch", path);
    else if (head[0] != (int64_t)HALO_MAGIC)
      snprintf(why, len, "%s: not a Bolide MPI restart file", path);
    else if (head[2] != H->nranks || head[3] != H->me)
      snprintf(why, len, "%s: written by rank %lld of %lld, read by rank %d of %d", path,
               (long long)head[3], (long long)head[2], H->me, H->nranks);
    else if (head[1] != step)
      snprintf(why, len, "%s: of step %lld, the restart file of step %ld", path, (long long)head[1],
               step);
    else if (head[4] < 1 || head[9] < 0 || head[10] < 0 || head[11] < 0 || head[12] < 0 ||
             (size_t)sz != want || (size_t)(head[11] + head[12]) > np)
      snprintf(why, len, "%s: corrupt sizes", path);
    else
      ok = 1;
  }
  if (ok) {
    const char *q = buf + sizeof head;
    double geo[6];
    memcpy(geo, q, 48), q += 48;
    H->ncells = (int)head[4];
    for (int k = 0; k < 3; k++) {
      H->cdim[k] = (int)head[5 + k];
      H->width[k] = geo[k];
      H->dim[k] = geo[3 + k];
    }
    H->periodic = (int)head[8];
    H->nsend = (size_t)head[9];
    H->gnsend = (size_t)head[10];
    H->nrecv = (size_t)head[11];
    H->gnrecv = (size_t)head[12];
    H->nr_repart = (long)head[13];
    memcpy(H->scount, q, 4 * n * sizeof(int)), q += 4 * n * sizeof(int);
    memcpy(H->gscount, q, 4 * n * sizeof(int)), q += 4 * n * sizeof(int);
    H->assign = error_malloc((size_t)H->ncells * sizeof(int), "MPI partition");
    memcpy(H->assign, q, (size_t)H->ncells * sizeof(int)), q += (size_t)H->ncells * sizeof(int);
    H->sidx = error_malloc(H->nsend * sizeof(size_t) + 1, "MPI halo send list");
    H->gsidx = error_malloc(H->gnsend * sizeof(size_t) + 1, "MPI halo send list");
    for (size_t k = 0; k < H->nsend + H->gnsend; k++, q += 8) {
      int64_t v;
      memcpy(&v, q, 8);
      if (v < 0 || (size_t)v >= np) {
        snprintf(why, len, "%s: particle index %lld out of range", path, (long long)v);
        ok = 0;
        break;
      }
      if (k < H->nsend)
        H->sidx[k] = (size_t)v;
      else
        H->gsidx[k - H->nsend] = (size_t)v;
    }
    for (int c = 0; ok && c < H->ncells; c++)
      if (H->assign[c] < 0 || H->assign[c] >= H->nranks) {
        snprintf(why, len, "%s: cell %d assigned to rank %d", path, c, H->assign[c]);
        ok = 0;
      }
    if (!ok) {
      free(H->assign);
      H->assign = NULL;
    }
  }
  free(buf);
  return ok;
}

/** A resumed multi-rank run: every rank resumes the same step; the
 *  decomposition and the exchange lists from the rank's STEM.halo.bin (or
 *  .prev); the flaw thresholds of every rank's file gathered into one array
 *  (the restart file holds the rank's particles' slices; the migration
 *  sends a particle's offset into the array all ranks share). */
static void halo_read_restart(struct engine *e) {
  struct halo *H = e->halo;
  long long st[2] = {e->step, -e->step};
  ranks_allreduce_llongs(st, 2, RANKS_MIN);
  if (st[0] != -st[1])
    error_exit(
        "%s: the ranks' restart files are of different steps (%lld to %lld): resume from "
        "files written together",
        e->restart_file, st[0], -st[1]);
  char path[1400], why[2][1600];
  snprintf(path, sizeof path, "%s.halo.bin", e->restart_stem);
  if (!halo_read_file(H, path, e->step, e->parts.count, why[0], sizeof why[0])) {
    snprintf(path, sizeof path, "%s.halo.prev.bin", e->restart_stem);
    if (!halo_read_file(H, path, e->step, e->parts.count, why[1], sizeof why[1]))
      error_exit("rank %d: no MPI restart file of step %ld: %s; %s", H->me, e->step, why[0],
                 why[1]);
  }
  /* the flaws: every rank's array, one after the other */
  const int n = H->nranks;
  long long *cnt = error_calloc((size_t)n, sizeof(long long), "MPI flaws");
  cnt[H->me] = e->nr_flaws;
  ranks_allreduce_llongs(cnt, n, RANKS_SUM);
  long long total = 0, mine = 0;
  int *rc = error_malloc(2 * (size_t)n * sizeof(int), "MPI flaws"), *rd = rc + n;
  for (int r = 0; r < n; r++) {
    if (r == H->me) mine = total;
    if (total + cnt[r] > INT_MAX) error_exit("more than %d Weibull flaws on the ranks", INT_MAX);
    rc[r] = (int)cnt[r];
    rd[r] = (int)total;
    total += cnt[r];
  }
  if (total > 0) {
    double *all = error_malloc((size_t)total * sizeof(double), "flaw thresholds");
    MPI_Allgatherv(e->flaw_eps, rc[H->me], MPI_DOUBLE, all, rc, rd, MPI_DOUBLE, MPI_COMM_WORLD);
    free(e->flaw_eps);
    e->flaw_eps = all;
    e->nr_flaws = total;
    for (size_t i = 0; i < e->parts.count; i++)
      if (e->parts.n_flaws[i] > 0) e->parts.flaw_first[i] += mine;
  }
  free(rc);
  free(cnt);
}

/* ------------------------------------------- gravity's top-level records */

/** Per top-level cell of the space's grid (the rebuild's, or the restored
 *  cells', restored 1): the particles of every rank in it, the rank that
 *  sends its record (the lowest that owns one of them), whether this rank
 *  owns one, and the bounding box of all of them, at the rebuild (x, or
 *  x0 of the restored cells: the positions they were sorted by). */
static void halo_gravity_cells(struct engine *e, int restored) {
  struct halo *H = e->halo;
  const struct space *s = &e->space;
  const struct parts *p = &e->parts;
  const int nt = s->nr_top;
  if (H->gtop != nt) {
    H->gcount = error_realloc(H->gcount, (size_t)nt * sizeof(long long), "MPI gravity cells");
    H->gprov = error_realloc(H->gprov, (size_t)nt * sizeof(int), "MPI gravity cells");
    H->gmine = error_realloc(H->gmine, 3 * (size_t)nt, "MPI gravity cells");
    H->guse = H->gmine + nt;
    H->gcomplete = H->gmine + 2 * (size_t)nt;
    H->gbox = error_realloc(H->gbox, 6 * (size_t)nt * sizeof(double), "MPI gravity cells");
    H->gtop = nt;
  }
  /* (the box as minima: lo, then -hi) */
  double *box = H->gbox;
  for (size_t k = 0; k < 6 * (size_t)nt; k++) box[k] = HUGE_VAL;
  memset(H->gcount, 0, (size_t)nt * sizeof(long long));
  /* (the positions the cells were sorted by: x at a rebuild, x0 restored) */
  const double *px = restored ? p->x0 : p->x, *py = restored ? p->y0 : p->y,
               *pz = restored ? p->z0 : p->z;
  for (size_t i = 0; i < p->count; i++) {
    if (p->flags[i] & PART_FOREIGN) continue;
    const double x[3] = {px[i], py[i], pz[i]};
    const int c = space_top_cell_of(s, x[0], x[1], x[2]);
    H->gcount[c]++;
    for (int k = 0; k < 3; k++) {
      box[6 * c + k] = fmin(box[6 * c + k], x[k]);
      box[6 * c + 3 + k] = fmin(box[6 * c + 3 + k], -x[k]);
    }
  }
  double *prov = error_malloc((size_t)nt * sizeof(double) + 1, "MPI gravity cells");
  for (int c = 0; c < nt; c++) {
    H->gmine[c] = H->gcount[c] > 0;
    prov[c] = H->gcount[c] > 0 ? (double)H->me : (double)INT_MAX;
  }
  ranks_allreduce_llongs(H->gcount, nt, RANKS_SUM);
  ranks_allreduce_doubles(box, 6 * nt, RANKS_MIN);
  ranks_allreduce_doubles(prov, nt, RANKS_MIN);
  H->gnrec = error_realloc(H->gnrec, 2 * (size_t)H->nranks * sizeof(int), "MPI gravity cells");
  H->gdrec = H->gnrec + H->nranks;
  memset(H->gnrec, 0, (size_t)H->nranks * sizeof(int));
  for (int c = 0; c < nt; c++) {
    H->gprov[c] = (int)prov[c];
    if (H->gprov[c] < H->nranks) H->gnrec[H->gprov[c]]++;
    for (int k = 0; k < 3; k++) box[6 * c + 3 + k] = -box[6 * c + 3 + k];
  }
  free(prov);
}

/** After the cells are built: which cells' particles are all here, which
 *  the walks read by their records, and the records' arrays for this grid. */
static void halo_gravity_complete(struct engine *e) {
  struct halo *H = e->halo;
  const struct space *s = &e->space;
  const int nt = H->gtop;
  H->gpartial = error_realloc(H->gpartial, (size_t)nt + 1, "MPI gravity cells");
  for (int c = 0; c < nt; c++) {
    H->gcomplete[c] = (long long)s->cells[c].count == H->gcount[c];
    H->guse[c] = H->gcount[c] > 0 && !H->gmine[c];
    H->gpartial[c] = H->guse[c] && !H->gcomplete[c];
    if (H->gmine[c] && !H->gcomplete[c])
      error_bug("MPI: top-level cell %d holds %zu of its %lld particles on a rank that owns some",
                c, s->cells[c].count, H->gcount[c]);
  }
  e->gp.top_partial = H->gpartial;
  if (!H->grec || H->rcdim[0] != s->cdim[0] || H->rcdim[1] != s->cdim[1] ||
      H->rcdim[2] != s->cdim[2]) {
    free(H->grec);
    H->grec = error_malloc(1, "MPI gravity records");
    H->grow = error_realloc(H->grow, (size_t)nt * sizeof(int) + 1, "MPI gravity records");
    for (int c = 0; c < nt; c++) H->grow[c] = -1;
    for (int k = 0; k < 3; k++) H->rcdim[k] = s->cdim[k];
  }
}

/** At a rebuild, before the copies are chosen: the top-level cells whose
 *  particles each rank's walks may need until the next rebuild, [nranks]
 *  rows of nr_top flags (gravity_top_needed, from the records of the last
 *  step); NULL where gravity does not go by records, every flag set where
 *  there are no records of this grid yet (the first rebuild). */
static unsigned char *halo_gravity_need(struct engine *e) {
  struct halo *H = e->halo;
  const struct space *s = &e->space;
  H->grec_on = H->gravity && !s->periodic && !e->gp.direct;
  e->gp.top_partial = NULL;
  if (!H->grec_on) return NULL;
  halo_gravity_cells(e, 0);
  const int nt = s->nr_top, n = H->nranks;
  unsigned char *need = error_malloc((size_t)n * (size_t)nt + 1, "MPI gravity cells");
  unsigned char *row = need + (size_t)H->me * nt;
  const int usable = H->grec && H->rcdim[0] == s->cdim[0] && H->rcdim[1] == s->cdim[1] &&
                     H->rcdim[2] == s->cdim[2];
  if (usable) {
    double wmin = s->width[0];
    for (int k = 1; k < 3; k++) wmin = s->width[k] < wmin ? s->width[k] : wmin;
    /* (the margin's drift at least a quarter of a cell width, also where
     * Scheduler:rebuild_fraction is smaller: with 0 and 0.05 of a width the
     * walks of the reference impact missed, theory/mpi.md) */
    gravity_top_needed(e, H->grec, H->grow, H->gmine, H->gcount, H->gbox,
                       fmax(s->max_drift_fraction, 0.25) * wmin, row);
    double v[2] = {0.0, 0.0};
    for (int c = 0; c < nt; c++)
      if (H->gcount[c] > 0 && !H->gmine[c]) {
        v[0] += row[c];
        v[1] += 1.0;
      }
    ranks_allreduce_doubles(v, 2, RANKS_SUM);
    H->gneed_frac += v[1] > 0.0 ? v[0] / v[1] : 0.0;
    H->gneed_rebuilds++;
  } else {
    memset(row, 1, (size_t)nt);
  }
  MPI_Allgather(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, need, nt, MPI_BYTE, MPI_COMM_WORLD);
  return need;
}

void halo_restored(struct engine *e) {
  struct halo *H = e->halo;
  if (!H) return;
  struct parts *p = &e->parts;
  free(H->ridx);
  free(H->gridx);
  H->ridx = error_malloc(H->nrecv * sizeof(size_t) + 1, "MPI halo receive list");
  H->gridx = error_malloc(H->gnrecv * sizeof(size_t) + 1, "MPI halo receive list");
  size_t seen = 0;
  for (size_t i = 0; i < p->count; i++)
    if (p->flags[i] & PART_FOREIGN) {
      const size_t m = (size_t)p->msrc[i];
      if (m < H->nrecv)
        H->ridx[m] = i;
      else if (m - H->nrecv < H->gnrecv)
        H->gridx[m - H->nrecv] = i;
      else
        error_exit("%s: a foreign copy with an invalid number", e->restart_file);
      seen++;
    }
  if (seen != H->nrecv + H->gnrecv)
    error_exit("%s: %zu foreign copies, the MPI restart file says %zu", e->restart_file, seen,
               H->nrecv + H->gnrecv);
  halo_mark_cells(e);
  H->grec_on = H->gravity && !e->space.periodic && !e->gp.direct;
  e->gp.top_partial = NULL;
  if (H->grec_on) {
    halo_gravity_cells(e, 1);
    halo_gravity_complete(e);
  }
  e->nr_foreign = seen;
  long long owned = (long long)(p->count - seen);
  ranks_allreduce_llongs(&owned, 1, RANKS_SUM);
  e->nr_owned_all = owned;
}

#endif /* HAVE_MPI */

#ifndef HAVE_MPI
void halo_write_restart(const struct engine *e) {
  (void)e;
}
void halo_restored(struct engine *e) {
  (void)e;
}
#endif

void halo_init(struct engine *e) {
  e->halo = NULL;
  e->nr_foreign = 0;
  e->nr_owned_all = (long long)e->parts.count;
  if (ranks_size() < 2 || e->opt.one_rank) return;
  const char *why = NULL;
  if (e->gp.enabled && e->gp.reuse_steps > 0)
    why = "multi-rank runs cannot reuse gravity's far field (Gravity:reuse_steps > 0) yet";
  else if (e->individual)
    why = "multi-rank runs need the global time step (TimeIntegration:global_step: true) yet";
  else if (e->nr_planes)
    why = "multi-rank runs cannot be combined with mirror planes (Boundaries:planes) yet";
  else if (e->scheme != ENGINE_SCHEME_KDK)
    why = "multi-rank runs integrate with TimeIntegration:scheme kdk only yet";
  if (why) error_exit("%d MPI ranks: %s (theory/mpi.md)", ranks_size(), why);
#ifdef HAVE_MPI
  struct halo *H = error_calloc(1, sizeof *H, "MPI halo");
  H->nranks = ranks_size();
  H->me = ranks_rank();
  H->rec = parts_bytes_held(&e->parts);
  H->scount = error_calloc(4 * (size_t)H->nranks, sizeof(int), "MPI halo counts");
  H->sdispl = H->scount + H->nranks;
  H->rcount = H->scount + 2 * H->nranks;
  H->rdispl = H->scount + 3 * H->nranks;
  H->gravity = e->gp.enabled;
  H->trigger = params_get_real(e->params, "DomainDecomposition:trigger");
  /* auto|metis|morton|slabs: 0 picks METIS where the build has it */
  const int method = params_get_enum(e->params, "DomainDecomposition:method");
  if (method == 1 && !partition_have_metis())
    error_exit(
        "%s: DomainDecomposition:method: metis, but this build has no METIS (configure "
        "--with-mpi found no libmetis-dev); use auto, morton or slabs",
        params_filename(e->params));
  H->method = method == 0
                  ? (partition_have_metis() ? partition_method_metis : partition_method_morton)
                  : (enum partition_method)(method - 1);
  H->gscount = error_calloc(4 * (size_t)H->nranks, sizeof(int), "MPI halo counts");
  H->gsdispl = H->gscount + H->nranks;
  H->grcount = H->gscount + 2 * H->nranks;
  H->grdispl = H->gscount + 3 * H->nranks;
  H->xc = error_calloc(8 * (size_t)H->nranks, sizeof(int), "MPI exchange counts");
  /* the refreshes between stages: what the stage before wrote (density and
   * ghost; gradient and extra ghost) */
  for (int k = 0; k < 2; k++)
    H->sel[k] = error_calloc((size_t)part_nr_fields, 1, "MPI refresh fields");
#define HALO_N_(a) ((int)(sizeof a / sizeof a[0]) - 1)
  halo_fields(&e->parts, H->sel[0], &H->rec_sel[0], halo_writes_density + 1,
              HALO_N_(halo_writes_density));
  halo_fields(&e->parts, H->sel[0], &H->rec_sel[0], halo_writes_ghost + 1,
              HALO_N_(halo_writes_ghost));
  halo_fields(&e->parts, H->sel[1], &H->rec_sel[1], halo_writes_gradient + 1,
              HALO_N_(halo_writes_gradient));
#undef HALO_N_
  H->gxc = H->xc + 4 * H->nranks;
  e->halo = H;
  if (e->restarted && !e->restart_regrouped) halo_read_restart(e);
#endif
}

int halo_partitioned(const struct engine *e) {
  return e->halo && e->halo->assign;
}

void halo_rebuild_start(struct engine *e) {
  struct halo *H = e->halo;
  if (!H) return;
#ifdef HAVE_MPI
  const double w0 = error_walltime();
  halo_repartition(e);
  struct parts *p = &e->parts;
  if (e->nr_foreign) {
    unsigned char *drop = error_calloc(p->count + 1, 1, "MPI halo marks");
    for (size_t i = 0; i < p->count; i++) drop[i] = (p->flags[i] & PART_FOREIGN) != 0;
    halo_remove(p, drop);
    free(drop);
    e->nr_foreign = 0;
  }
  if (H->assign) halo_migrate(e);
  double h_max = 0.0;
  for (size_t i = 0; i < p->count; i++)
    if (p->h[i] > h_max && isfinite(p->h[i])) h_max = p->h[i];
  ranks_allreduce_doubles(&h_max, 1, RANKS_MAX);
  e->space.h_max_floor = h_max;
  H->t_halo += error_walltime() - w0;
  H->t_rebuild[0] += error_walltime() - w0;
#endif
}

void halo_gravity_records(struct engine *e) {
  struct halo *H = e->halo;
  if (!H || !H->grec_on) return;
#ifdef HAVE_MPI
  const double w0 = error_walltime();
  const int nt = H->gtop, R = gravity_top_record_doubles(), n = H->nranks;
  long long total = 0;
  for (int r = 0; r < n; r++) {
    if ((long long)H->gnrec[r] * R > INT_MAX) error_exit("MPI: too many top-level cells per rank");
    H->gdrec[r] = (int)(total * R);
    total += H->gnrec[r];
  }
  if (total * R > INT_MAX) error_exit("MPI: too many top-level cells for gravity's records");
  H->gsrec =
      error_realloc(H->gsrec, (size_t)H->gnrec[H->me] * R * sizeof(double) + 1, "MPI records");
  double *all = error_malloc((size_t)total * R * sizeof(double) + 1, "MPI gravity records");
  int *cnt = error_malloc((size_t)n * sizeof(int), "MPI gravity records");
  int k = 0;
  for (int c = 0; c < nt; c++)
    if (H->gprov[c] == H->me) gravity_top_record_pack(e, c, H->gsrec + (size_t)k++ * R);
  for (int r = 0; r < n; r++) cnt[r] = H->gnrec[r] * R;
  MPI_Allgatherv(H->gsrec, k * R, MPI_DOUBLE, all, cnt, H->gdrec, MPI_DOUBLE, MPI_COMM_WORLD);
  /* (each rank's records come in the order of its cells; they are kept as
   * they came, each cell's row noted) */
  for (int r = 0; r < n; r++) cnt[r] = H->gdrec[r] / R;
  for (int c = 0; c < nt; c++) H->grow[c] = H->gprov[c] < n ? cnt[H->gprov[c]]++ : -1;
  free(cnt);
  free(H->grec);
  H->grec = all;
  gravity_top_records_use(e, H->grec, H->grow, H->guse, H->gcomplete);
  H->t_grec += error_walltime() - w0;
  H->nr_grec++;
#endif
}

void halo_gravity_after(struct engine *e) {
  struct halo *H = e->halo;
  if (!H || !H->grec_on) return;
  const long m = gravity_remote_misses(1);
  if (m > 0) {
    /* the next step rebuilds, choosing the cells from this step's records */
    H->gmisses += m;
    e->need_rebuild = 1;
  }
}

int halo_gravity_by_records(const struct engine *e) {
  return e->halo && e->halo->grec_on;
}

int halo_rebuild(struct engine *e) {
  struct halo *H = e->halo;
  if (!H) return 0;
  int first = 0;
#ifdef HAVE_MPI
  const double w0 = error_walltime();
  struct space *s = &e->space;
  struct parts *p = &e->parts;
  if (!H->assign) {
    halo_partition(e);
    first = 1;
    /* every rank removed the same particles from the open box: rank 0 counts them */
    if (H->me != 0) memset(&s->removed, 0, sizeof s->removed);
  }
  const double wsel = error_walltime(); /* (the first rebuild's partition not counted below) */
  long long owned = (long long)p->count;
  ranks_allreduce_llongs(&owned, 1, RANKS_SUM);
  e->nr_owned_all = owned;

  /* which ranks need which particles: those within a reach of a cell of
   * theirs (at this rebuild; a reach covers an interaction until the next
   * one, drift included: engine_graph.c) */
  const double D = engine_reach(s);
  double wmin = H->width[0];
  for (int k = 1; k < 3; k++) wmin = H->width[k] < wmin ? H->width[k] : wmin;
  const int nc = (int)ceil(D / wmin);
  const int n = H->nranks;
  struct halo_list *L = error_calloc(2 * (size_t)n, sizeof *L, "MPI halo lists");
  struct halo_list *G = L + n; /* gravity's copies: the rest */
  double *d2 = error_malloc((size_t)n * sizeof(double), "MPI halo distances");
  /* the cells of other ranks near the particle's decomposition cell (made
   * again only when the cell changes: the particles come mostly in the
   * order of the cells of the last rebuild) */
  struct halo_cand *cand = NULL;
  int ncand = 0, cap = 0, last = -1;
  /* gravity's copies: the particles of the top-level cells whose particles
   * the rank's walks may need (NULL: every particle) */
  unsigned char *need = halo_gravity_need(e);
  const size_t nt = (size_t)s->nr_top;
  for (size_t i = 0; i < p->count; i++) {
    const double xi[3] = {p->x[i], p->y[i], p->z[i]};
    double x[3];
    const int c = halo_cell_of(H, xi, x);
    if (c != last) ncand = halo_cands(H, c, nc, D, &cand, &cap), last = c;
    if (ncand) halo_cands_d2(H, x, cand, ncand, d2);
    const size_t tc = need ? (size_t)space_top_cell_of(s, xi[0], xi[1], xi[2]) : 0;
    for (int r = 0; r < n; r++) {
      if (r == H->me) continue;
      if (ncand && d2[r] <= D * D)
        halo_list_push(&L[r], i);
      else if (H->gravity && (!need || need[(size_t)r * nt + tc]))
        halo_list_push(&G[r], i);
    }
  }
  free(need);
  const double w1 = error_walltime();
  H->t_rebuild[1] += w1 - wsel;
  /* counts: [copies, gravity's copies] for each rank */
  int *sc2 = error_malloc(4 * (size_t)n * sizeof(int), "MPI halo counts");
  int *rc2 = sc2 + 2 * n;
  for (int r = 0; r < n; r++) {
    sc2[2 * r] = (int)L[r].n;
    sc2[2 * r + 1] = (int)G[r].n;
  }
  MPI_Alltoall(sc2, 2, MPI_INT, rc2, 2, MPI_INT, MPI_COMM_WORLD);
  int *sall = error_malloc(2 * (size_t)n * sizeof(int), "MPI halo counts"), *rall = sall + n;
  H->nsend = H->nrecv = H->gnsend = H->gnrecv = 0;
  for (int r = 0; r < n; r++) {
    H->scount[r] = sc2[2 * r];
    H->gscount[r] = sc2[2 * r + 1];
    H->rcount[r] = rc2[2 * r];
    H->grcount[r] = rc2[2 * r + 1];
    H->nsend += (size_t)H->scount[r];
    H->gnsend += (size_t)H->gscount[r];
    H->nrecv += (size_t)H->rcount[r];
    H->gnrecv += (size_t)H->grcount[r];
    sall[r] = H->scount[r] + H->gscount[r];
    rall[r] = H->rcount[r] + H->grcount[r];
  }
  free(sc2);
  free(H->sidx);
  free(H->gsidx);
  H->sidx = error_malloc(H->nsend * sizeof(size_t) + 1, "MPI halo send list");
  H->gsidx = error_malloc(H->gnsend * sizeof(size_t) + 1, "MPI halo send list");
  const size_t ns = H->nsend + H->gnsend, nr = H->nrecv + H->gnrecv;
  char *sbuf = halo_grow(&H->sbuf, &H->sbuf_cap, ns * H->rec + 1);
  char *rbuf = halo_grow(&H->rbuf, &H->rbuf_cap, nr * H->rec + 1);
  /* to rank r: its copies, then its gravity's copies (every field, once) */
  size_t k = 0, gk = 0, o = 0;
  for (int r = 0; r < n; r++) {
    H->sdispl[r] = (int)k;
    H->gsdispl[r] = (int)gk;
    halo_pack_block(p, L[r].i, L[r].n, sbuf + o * H->rec);
    o += L[r].n;
    halo_pack_block(p, G[r].i, G[r].n, sbuf + o * H->rec);
    o += G[r].n;
    for (size_t m = 0; m < L[r].n; m++) H->sidx[k++] = L[r].i[m];
    for (size_t m = 0; m < G[r].n; m++) H->gsidx[gk++] = G[r].i[m];
    free(L[r].i);
    free(G[r].i);
  }
  free(L);
  halo_alltoallv(H, sall, rall, sbuf, rbuf);
  /* the copies, after the owned particles: msrc numbers them, the copies
   * first, then gravity's */
  const size_t n0 = p->count;
  parts_reserve(p, n0 + nr);
  size_t q = 0, gq = 0, at = n0;
  o = 0;
  for (int r = 0; r < n; r++) {
    H->rdispl[r] = (int)q;
    H->grdispl[r] = (int)gq;
    halo_unpack_block(p, at, NULL, (size_t)H->rcount[r], rbuf + o * H->rec);
    for (int m = 0; m < H->rcount[r]; m++, at++) p->msrc[at] = (int64_t)q++;
    o += (size_t)H->rcount[r];
    halo_unpack_block(p, at, NULL, (size_t)H->grcount[r], rbuf + o * H->rec);
    for (int m = 0; m < H->grcount[r]; m++, at++) p->msrc[at] = (int64_t)(H->nrecv + gq++);
    o += (size_t)H->grcount[r];
  }
  for (size_t m = n0; m < n0 + nr; m++) p->flags[m] |= PART_FOREIGN;
  free(sall);
  p->count = n0 + nr;
  e->nr_foreign = nr;
  free(d2);
  free(cand);
  const double w2 = error_walltime();
  H->t_rebuild[2] += w2 - w1;
  /* the cells of both, and where the sent and received particles are now
   * (the sort's permutation: new index i holds old index sort_index[i]) */
  if (space_rebuild(s) != 0) error_bug("particles removed by the rebuild with the halo");
  size_t *inv = error_malloc(p->count * sizeof(size_t) + 1, "MPI halo index");
  for (size_t i = 0; i < p->count; i++) inv[s->sort_index[i]] = i;
  for (size_t m = 0; m < H->nsend; m++) H->sidx[m] = inv[H->sidx[m]];
  for (size_t m = 0; m < H->gnsend; m++) H->gsidx[m] = inv[H->gsidx[m]];
  free(inv);
  free(H->ridx);
  free(H->gridx);
  H->ridx = error_malloc(H->nrecv * sizeof(size_t) + 1, "MPI halo receive list");
  H->gridx = error_malloc(H->gnrecv * sizeof(size_t) + 1, "MPI halo receive list");
  for (size_t i = 0; i < p->count; i++)
    if (p->flags[i] & PART_FOREIGN) {
      const size_t m = (size_t)p->msrc[i];
      if (m < H->nrecv)
        H->ridx[m] = i;
      else
        H->gridx[m - H->nrecv] = i;
    }
  halo_mark_cells(e);
  if (H->grec_on) halo_gravity_complete(e);
  H->t_rebuild[3] += error_walltime() - w2;
  /* every rank's share, on rank 0's log (-v) */
  double v[3] = {(double)(p->count - nr), (double)H->nrecv, (double)H->gnrecv};
  ranks_allreduce_doubles(v, 3, RANKS_SUM);
  H->copies += v[1] / (v[0] > 0.0 ? v[0] : 1.0);
  H->gcopies += v[2] / (v[0] > 0.0 ? v[0] : 1.0);
  H->nr_halo++;
  error_log(1,
            "halo: rank 0 owns %zu particles and holds %zu copies (and %zu for gravity); all "
            "ranks: %.0f, %.0f, %.0f",
            p->count - nr, H->nrecv, H->gnrecv, v[0], v[1], v[2]);
  H->t_halo += error_walltime() - w0;
#else
  (void)first;
#endif
  return first;
}

#ifdef HAVE_MPI
/** Byte counts and offsets of an exchange of scount[r] records of rec bytes
 *  to rank r (sdispl[r] records in), rcount[r] from it, into c[0 .. 4n). */
static void halo_counts(int n, size_t rec, const int *scount, const int *sdispl, const int *rcount,
                        const int *rdispl, int *c) {
  for (int r = 0; r < n; r++) {
    const long long v[4] = {
        (long long)scount[r] * (long long)rec, (long long)sdispl[r] * (long long)rec,
        (long long)rcount[r] * (long long)rec, (long long)rdispl[r] * (long long)rec};
    for (int k = 0; k < 4; k++) {
      if (v[k] > INT_MAX)
        error_exit("MPI exchange of more than %d bytes per rank and step: use more ranks", INT_MAX);
      c[k * n + r] = (int)v[k];
    }
  }
}
#endif

void halo_refresh_start(struct engine *e, int after) {
  struct halo *H = e->halo;
  if (!H || H->pending) return;
#ifdef HAVE_MPI
  const double w0 = error_walltime();
  struct parts *p = &e->parts;
  const unsigned char *sel = after < 0 ? NULL : H->sel[after];
  const size_t rec = after < 0 ? H->rec : H->rec_sel[after];
  H->cur = after;
  char *sbuf = halo_grow(&H->sbuf, &H->sbuf_cap, H->nsend * rec + 1);
  halo_grow(&H->rbuf, &H->rbuf_cap, H->nrecv * rec + 1);
  for (int r = 0; r < H->nranks; r++)
    if (H->dev)
      H->dev->pack(H->dev->ctx, H->sidx + H->sdispl[r], (size_t)H->scount[r],
                   sbuf + (size_t)H->sdispl[r] * rec, sel);
    else
      halo_pack_sel(p, H->sidx + H->sdispl[r], (size_t)H->scount[r],
                    sbuf + (size_t)H->sdispl[r] * rec, sel);
  const int n = H->nranks;
  halo_counts(n, rec, H->scount, H->sdispl, H->rcount, H->rdispl, H->xc);
  MPI_Ialltoallv(sbuf, H->xc, H->xc + n, MPI_BYTE, H->rbuf, H->xc + 2 * n, H->xc + 3 * n, MPI_BYTE,
                 MPI_COMM_WORLD, &H->req);
  H->pending = 1;
  H->t_refresh += error_walltime() - w0;
#else
  (void)after;
#endif
}

void halo_refresh_finish(struct engine *e) {
  struct halo *H = e->halo;
  if (!H || !H->pending) return;
#ifdef HAVE_MPI
  const double w0 = error_walltime();
  struct parts *p = &e->parts;
  MPI_Wait(&H->req, MPI_STATUS_IGNORE);
  H->pending = 0;
  const double w1 = error_walltime();
  H->t_wait += w1 - w0;
  const unsigned char *sel = H->cur < 0 ? NULL : H->sel[H->cur];
  const size_t rec = H->cur < 0 ? H->rec : H->rec_sel[H->cur];
  for (int r = 0; r < H->nranks; r++) {
    halo_unpack_sel(p, 0, H->ridx + H->rdispl[r], (size_t)H->rcount[r],
                    H->rbuf + (size_t)H->rdispl[r] * rec, sel);
    if (H->dev)
      H->dev->unpack(H->dev->ctx, H->ridx + H->rdispl[r], (size_t)H->rcount[r],
                     H->rbuf + (size_t)H->rdispl[r] * rec, sel, (int64_t)H->rdispl[r]);
  }
  for (size_t q = 0; q < H->nrecv; q++) {
    const size_t g = H->ridx[q];
    p->flags[g] |= PART_FOREIGN;
    p->msrc[g] = (int64_t)q;
  }
  /* the copies moved (and took their owners' h): the loops' pruning needs
   * the bounds again */
  for (int c = 0; c < e->space.nr_top; c++)
    if (e->space.cells[c].count) cell_update_bounds(p, &e->space.cells[c]);
  H->t_refresh += error_walltime() - w0;
  H->nr_refresh++;
#endif
}

void halo_set_device(struct engine *e, const struct halo_device *dev) {
  if (e->halo) e->halo->dev = dev;
}

void halo_refresh(struct engine *e) {
  halo_refresh_start(e, -1);
  halo_refresh_finish(e);
}

void halo_poll(void *ctx) {
#ifdef HAVE_MPI
  struct halo *H = ((struct engine *)ctx)->halo;
  int done;
  /* (MPI's non-blocking collectives progress inside MPI calls) */
  if (H->pending == 1) {
    MPI_Test(&H->req, &done, MPI_STATUS_IGNORE);
    H->pending = done ? 2 : 1;
  }
  if (H->gpending == 1) {
    MPI_Test(&H->greq, &done, MPI_STATUS_IGNORE);
    H->gpending = done ? 2 : 1;
  }
#else
  (void)ctx;
#endif
}

void halo_refresh_gravity_start(struct engine *e) {
  struct halo *H = e->halo;
  if (!H || !H->gravity || H->gpending) return;
#ifdef HAVE_MPI
  const double w0 = error_walltime();
  struct parts *p = &e->parts;
  const int F = HALO_GRAVITY_FIELDS;
  if (H->gnsend * F > INT_MAX || H->gnrecv * F > INT_MAX)
    error_exit("MPI exchange of more than %d values per rank and step: use more ranks", INT_MAX);
  if (H->gnsend * F > H->gsbuf_cap) {
    free(H->gsbuf);
    H->gsbuf_cap = H->gnsend * F + 1;
    H->gsbuf = error_malloc(H->gsbuf_cap * sizeof(double), "MPI exchange buffer");
  }
  if (H->gnrecv * F > H->grbuf_cap) {
    free(H->grbuf);
    H->grbuf_cap = H->gnrecv * F + 1;
    H->grbuf = error_malloc(H->grbuf_cap * sizeof(double), "MPI exchange buffer");
  }
  double *b = H->gsbuf;
  for (size_t k = 0; k < H->gnsend; k++, b += F) {
    const size_t i = H->gsidx[k];
    b[0] = p->x[i], b[1] = p->y[i], b[2] = p->z[i], b[3] = p->m[i], b[4] = p->h[i];
    b[5] = p->gax[i], b[6] = p->gay[i], b[7] = p->gaz[i];
  }
  halo_counts(H->nranks, F * sizeof(double), H->gscount, H->gsdispl, H->grcount, H->grdispl,
              H->gxc);
  const int n = H->nranks;
  MPI_Ialltoallv(H->gsbuf, H->gxc, H->gxc + n, MPI_BYTE, H->grbuf, H->gxc + 2 * n, H->gxc + 3 * n,
                 MPI_BYTE, MPI_COMM_WORLD, &H->greq);
  H->gpending = 1;
  H->t_grefresh += error_walltime() - w0;
#endif
}

void halo_refresh_gravity_finish(struct engine *e) {
  struct halo *H = e->halo;
  if (!H || !H->gpending) return;
#ifdef HAVE_MPI
  const double w0 = error_walltime();
  struct parts *p = &e->parts;
  MPI_Wait(&H->greq, MPI_STATUS_IGNORE);
  H->gpending = 0;
  H->t_wait += error_walltime() - w0;
  const int F = HALO_GRAVITY_FIELDS;
  const double *b = H->grbuf;
  for (size_t k = 0; k < H->gnrecv; k++, b += F) {
    const size_t i = H->gridx[k];
    p->x[i] = b[0], p->y[i] = b[1], p->z[i] = b[2], p->m[i] = b[3], p->h[i] = b[4];
    p->gax[i] = b[5], p->gay[i] = b[6], p->gaz[i] = b[7];
  }
  if (H->dev && H->dev->gravity && H->gnrecv > 0) {
    /* the GPU computes gravity's interactions: the fields its P2P reads,
     * and the acceleration of the last pass that its upward pass reads
     * (the adaptive criterion's a_min), into the device's copies */
    unsigned char sel[PART_NR_FIELDS];
    size_t bytes = 0;
    for (int f = 0; f < part_nr_fields; f++) {
      const char *nm = part_fields[f].name;
      sel[f] = !strcmp(nm, "x") || !strcmp(nm, "y") || !strcmp(nm, "z") || !strcmp(nm, "m") ||
               !strcmp(nm, "h") || !strcmp(nm, "gax") || !strcmp(nm, "gay") || !strcmp(nm, "gaz");
      bytes += sel[f] ? part_fields[f].size : 0;
    }
    char *blk = halo_grow(&H->gdbuf, &H->gdbuf_cap, H->gnrecv * bytes + 1);
    halo_pack_sel(p, H->gridx, H->gnrecv, blk, sel);
    H->dev->unpack(H->dev->ctx, H->gridx, H->gnrecv, blk, sel, (int64_t)H->nrecv);
  }
  H->t_grefresh += error_walltime() - w0;
  H->nr_grefresh++;
#endif
}

void halo_refresh_gravity(struct engine *e) {
  halo_refresh_gravity_start(e);
  halo_refresh_gravity_finish(e);
}

void halo_log(const struct engine *e) {
  const struct halo *H = e->halo;
  if (!H) return;
  error_log(0,
            "MPI: %d ranks; foreign copies %.1f%% of the owned particles (average over %ld "
            "rebuilds); rank 0: %.4f s per refresh of the copies (packing, unpacking and the "
            "wait), of which %.4f s waiting for the exchange beyond the local work that hid "
            "it; %.4f s per rebuild in the exchanges and halo (cells and order include them)",
            H->nranks, H->nr_halo ? 100.0 * H->copies / (double)H->nr_halo : 0.0, H->nr_halo,
            H->nr_refresh ? H->t_refresh / (double)H->nr_refresh : 0.0,
            H->nr_refresh ? H->t_wait / (double)H->nr_refresh : 0.0,
            H->nr_halo ? H->t_halo / (double)H->nr_halo : 0.0);
  if (H->nr_halo) {
    const double k = 1.0 / (double)H->nr_halo;
    error_log(0,
              "MPI: rank 0's rebuild, per rebuild: %.4f s removing the copies and migrating "
              "particles, %.4f s choosing the copies (the first rebuild's partition left out), "
              "%.4f s packing, exchanging and unpacking "
              "them, %.4f s the cells with the copies and the index maps",
              H->t_rebuild[0] * k, H->t_rebuild[1] * k, H->t_rebuild[2] * k, H->t_rebuild[3] * k);
  }
  if (H->trigger > 0.0)
    error_log(0,
              "MPI: domain decomposed again %ld times (of %ld rebuilds past the trigger %g); "
              "measured imbalance at the last rebuild %.3f",
              H->nr_repart, H->nr_tried, H->trigger, H->imb_last);
  if (H->gravity)
    error_log(0,
              "MPI: gravity's copies (the other ranks' particles that the walks may open, their "
              "position, mass, h and acceleration) %.1f%% of the owned particles (average over "
              "the rebuilds); rank 0: %.4f s per refresh",
              H->nr_halo ? 100.0 * H->gcopies / (double)H->nr_halo : 0.0,
              H->nr_grefresh ? H->t_grefresh / (double)H->nr_grefresh : 0.0);
  if (H->grec_on) {
    long long m = H->gmisses;
    ranks_allreduce_llongs(&m, 1, RANKS_SUM);
    error_log(0,
              "MPI: gravity's far field by the top-level cells' records: %ld of %ld rebuilds "
              "chose the cells to copy from them, %.1f%% of the other ranks' non-empty cells "
              "on average; %lld misses (a walk that needed a cell's particles that were not "
              "here: its multipole taken instead, and a rebuild); rank 0: %.4f s per exchange "
              "of the records",
              H->gneed_rebuilds, H->nr_halo,
              H->gneed_rebuilds ? 100.0 * H->gneed_frac / (double)H->gneed_rebuilds : 100.0, m,
              H->nr_grec ? H->t_grec / (double)H->nr_grec : 0.0);
  }
}

void halo_bounds(const struct engine *e, double *dmax, double *h_max) {
  const struct parts *p = &e->parts;
  double v[2] = {0.0, 0.0};
  for (size_t i = 0; i < p->count; i++) {
    if (p->flags[i] & PART_FOREIGN) continue;
    const double dx = p->x[i] - p->x0[i], dy = p->y[i] - p->y0[i], dz = p->z[i] - p->z0[i];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 > v[0]) v[0] = d2;
    if (p->h[i] > v[1]) v[1] = p->h[i];
  }
  ranks_allreduce_doubles(v, 2, RANKS_MAX);
  *dmax = sqrt(v[0]);
  *h_max = v[1];
}

void halo_gather(const struct engine *e, struct parts *out) {
  memset(out, 0, sizeof *out);
#ifdef HAVE_MPI
  const struct halo *H = e->halo;
  const struct parts *p = &e->parts;
  const size_t rec = H->rec;
  const size_t mine = p->count - e->nr_foreign;
  char *buf = error_malloc(mine * rec + 1, "snapshot gather");
  size_t *list = error_malloc(mine * sizeof(size_t) + 1, "snapshot gather");
  size_t k = 0;
  for (size_t i = 0; i < p->count; i++)
    if (!(p->flags[i] & PART_NOT_OWNED)) list[k++] = i;
  halo_pack_block(p, list, k, buf);
  free(list);
  const long long bytes = (long long)(mine * rec);
  if (bytes > INT_MAX)
    error_exit("snapshot: more than %d bytes on one rank: use more ranks", INT_MAX);
  int nb = (int)bytes;
  int *counts = NULL, *displ = NULL;
  char *all = NULL;
  long long total = 0;
  if (H->me == 0) counts = error_malloc(2 * (size_t)H->nranks * sizeof(int), "snapshot gather");
  MPI_Gather(&nb, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (H->me == 0) {
    displ = counts + H->nranks;
    for (int r = 0; r < H->nranks; r++) {
      if (total > INT_MAX) error_exit("snapshot: more than %d bytes to gather", INT_MAX);
      displ[r] = (int)total;
      total += counts[r];
    }
    all = error_malloc((size_t)total + 1, "snapshot gather");
  }
  MPI_Gatherv(buf, nb, MPI_BYTE, all, counts, displ, MPI_BYTE, 0, MPI_COMM_WORLD);
  free(buf);
  if (H->me == 0) {
    const size_t n = (size_t)total / rec;
    parts_alloc_like(out, n, p);
    out->count = n;
    for (int r = 0; r < H->nranks; r++)
      halo_unpack_block(out, (size_t)displ[r] / rec, NULL, (size_t)counts[r] / rec, all + displ[r]);
    free(all);
    free(counts);
  }
#else
  (void)e;
#endif
}

void halo_free(struct engine *e) {
  struct halo *H = e->halo;
  if (!H) return;
  free(H->assign);
  free(H->scount);
  free(H->sidx);
  free(H->ridx);
  free(H->sbuf);
  free(H->rbuf);
  free(H->gscount);
  free(H->xc);
  free(H->sel[0]);
  free(H->sel[1]);
  free(H->gsidx);
  free(H->gridx);
  free(H->gsbuf);
  free(H->grbuf);
  free(H->gdbuf);
  free(H->gcount);
  free(H->gprov);
  free(H->gmine);
  free(H->gbox);
  free(H->gnrec);
  free(H->grec);
  free(H->grow);
  free(H->gsrec);
  free(H->gpartial);
  free(H);
  e->halo = NULL;
}
