/* The hydro neighbour lists of the GPU runner, built on the device.
 *
 * For each FORCE phase whose lists cannot be reused (gpu_cells_force), the
 * host flattens the cells below the task cells into nodes (depth first,
 * each node with the index of the node after its sub-tree), marks the
 * list leaves and uploads the nodes with the task cells' neighbours and
 * their periodic shifts.  One device thread per leaf L then walks the
 * nodes of each neighbouring task cell, skipping every sub-tree that
 * gpu_list_accept rejects, and keeps the leaves it accepts: a counting
 * pass, a scan, a filling pass.  The lists (ngb_start, ngb_leaf and the
 * shifts' codes, gpu_shift_code) stay on the device.
 *
 * The acceptance test is the one function below, shared by the device
 * walk and the host's dual walk (gpu_cells_build, kept for the tests and as
 * Scheduler:gpu_lists: host): a leaf pair is kept when the bounding boxes
 * come within growth * kernel_gamma * max(h_max) plus both drifts plus the
 * reuse margin.  Both walks test internal nodes with the same bound
 * loosened by 1e-12 (the bounds of a cell enclose those of its progeny, so
 * pruning never drops a pair the leaf test keeps) and leaf pairs with the
 * exact bound: both keep exactly the leaf pairs that pass the exact test,
 * in the same order (task-cell neighbours in order, leaves depth first). */
#ifndef BOLIDE_GPU_LISTS_H
#define BOLIDE_GPU_LISTS_H

#include <math.h>

#include "src/inline.h"
#include "tasks/hydro/kernel.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Fraction of its kernel support a leaf may drift after the lists were
 *  built before they are built again: a margin in the lists' reach that lets
 *  most steps reuse them. */
#define GPU_LIST_SLACK 0.1

/** The lists' reach in units of each leaf's h_max when built: the room for
 *  the h iteration to grow h in a phase (a phase whose h outgrows it widens
 *  them by 1.5 and starts again; gpu_cells_force). */
#define GPU_LIST_GROWTH 1.25

/** What the acceptance test reads of a cell. */
struct gpu_list_box {
  double bmin[3], bmax[3]; /**< bounding box of the particles at rebuild */
  double loc[3], width[3]; /**< the cell's box (scale of the rounding margin) */
  double h_max;            /**< largest smoothing length */
  double dx_max;           /**< largest drift since the rebuild */
};

/** A non-empty cell below a task cell, in depth-first order. */
struct gpu_list_node {
  struct gpu_list_box box; /**< its bounds */
  int leaf;                /**< list leaf number, or -1 where the lists descend further */
  int skip;                /**< the node after its sub-tree */
};

/* Products and sums that no compiler contracts into fused multiply-adds, so
 * that host and device round alike. */
#if defined(__CUDA_ARCH__)
#define GPU_LIST_MUL(a, b) __dmul_rn((a), (b))
#define GPU_LIST_ADD(a, b) __dadd_rn((a), (b))
#elif defined(__FP_FAST_FMA)
BOLIDE_INLINE double gpu_list_mul_(double a, double b) {
  volatile double r = a * b;
  return r;
}
#define GPU_LIST_MUL(a, b) gpu_list_mul_((a), (b))
#define GPU_LIST_ADD(a, b) ((a) + (b))
#else
#define GPU_LIST_MUL(a, b) ((a) * (b))
#define GPU_LIST_ADD(a, b) ((a) + (b))
#endif

/** 1 if the lists keep the pair (a, b + shift): the boxes come within
 *  growth * kernel_gamma * max(h_max) + both drifts + GPU_LIST_SLACK of
 *  both supports (widened by 1e-10 relative and 1e-13 of the coordinates'
 *  scale, as the CPU loops' pruning, so that no pair the particle test
 *  keeps is lost to rounding).  prune = 1: the bound is loosened by 1e-12
 *  more (a test on a cell whose progeny are tested after). */
BOLIDE_INLINE int gpu_list_accept(const struct gpu_list_box *a, const struct gpu_list_box *b,
                                  const double shift[3], double growth, int prune) {
  const double hm = a->h_max > b->h_max ? a->h_max : b->h_max;
  const double R = GPU_LIST_ADD(
      GPU_LIST_ADD(GPU_LIST_ADD(GPU_LIST_MUL(GPU_LIST_MUL(growth, kernel_gamma), hm), a->dx_max),
                   b->dx_max),
      GPU_LIST_MUL(GPU_LIST_MUL(GPU_LIST_SLACK, kernel_gamma), GPU_LIST_ADD(a->h_max, b->h_max)));
  double scale = 0.0, d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double t = fabs(a->loc[k]) + a->width[k] + fabs(b->loc[k]) + b->width[k] + fabs(shift[k]);
    scale += t;
    const double lo = GPU_LIST_ADD(GPU_LIST_ADD(b->bmin[k], shift[k]), -a->bmax[k]);
    const double hi = GPU_LIST_ADD(GPU_LIST_ADD(a->bmin[k], -b->bmax[k]), -shift[k]);
    const double g = lo > hi ? lo : hi;
    if (g > 0.0) d2 = GPU_LIST_ADD(d2, GPU_LIST_MUL(g, g));
  }
  double Rs = GPU_LIST_ADD(GPU_LIST_MUL(R, 1.0 + 1e-10), GPU_LIST_MUL(1e-13, scale));
  if (prune) Rs = GPU_LIST_MUL(Rs, 1.0 + 1e-12);
  return !(d2 > GPU_LIST_MUL(Rs, Rs));
}

/** The periodic shift of a list entry, kept on the device as one byte
 *  instead of three doubles (the lists' largest part): every shift is 0 or
 *  plus or minus the box's side on each axis (src/space.c), so the code is
 *  9 (s_x + 1) + 3 (s_y + 1) + (s_z + 1) with s_d its sign, and the shift
 *  is s_d dim[d] again, bit for bit, with dim the box's sides (the largest
 *  magnitude of the shifts on each axis: gpu_shift_dims). */
BOLIDE_INLINE unsigned char gpu_shift_code(const double s[3]) {
  return (unsigned char)(9 * ((s[0] > 0.0) - (s[0] < 0.0) + 1) +
                         3 * ((s[1] > 0.0) - (s[1] < 0.0) + 1) + ((s[2] > 0.0) - (s[2] < 0.0) + 1));
}

/** The shift of code c (gpu_shift_code) in a box of sides dim. */
BOLIDE_INLINE void gpu_shift_of(unsigned char c, const double dim[3], double s[3]) {
  s[0] = (double)(c / 9 - 1) * dim[0];
  s[1] = (double)((c / 3) % 3 - 1) * dim[1];
  s[2] = (double)(c % 3 - 1) * dim[2];
}

/** The box sides of n shifts (3 doubles each; dim[d] 0 where no shift moves
 *  along d); 1 if every shift is one gpu_shift_code can hold (each
 *  component 0 or plus or minus dim[d]), else 0. */
int gpu_shift_dims(const double *shift, long n, double dim[3]);

struct gpu;
/** The device lists and the buffers of their build (opaque), allocated
 *  once and grown. */
struct gpu_lists;

/** What the build reads (host arrays; the nodes in gpu_lists_nodes' staging). */
struct gpu_list_input {
  int nr_leaves;              /**< list leaves */
  const int *leaf_node;       /**< node of each leaf */
  const int *leaf_tc;         /**< task cell of each leaf */
  int nr_tc;                  /**< task cells */
  const int *tc_node;         /**< nr_tc + 1: task cell t's nodes are [tc_node[t], tc_node[t+1]) */
  const int *tc_ngb_start;    /**< nr_tc + 1: its neighbours are [tc_ngb_start[t], [t+1]) */
  const int *tc_ngb;          /**< neighbouring task cell of each entry (itself included) */
  const double *tc_ngb_shift; /**< 3 per entry: added to the neighbour's positions */
  int nr_nodes;               /**< nodes written to the staging */
  double growth;              /**< reach factor of gpu_list_accept */
};

/** The device lists of g (freed by gpu_lists_free, before or after gpu_free). */
struct gpu_lists *gpu_lists_new(struct gpu *g);
void gpu_lists_free(struct gpu_lists *l);
/** Pinned host staging for at least n nodes, for the caller to fill before
 *  gpu_lists_build (contents are not kept when it grows). */
struct gpu_list_node *gpu_lists_nodes(struct gpu_lists *l, int n);
/** Upload the nodes and the neighbours of the task cells and build the lists
 *  on the device (stream 1 of the runner; the host waits once, for the
 *  number of entries).  Returns the number of entries. */
long gpu_lists_build(struct gpu_lists *l, const struct gpu_list_input *in);
/** Copy the lists built last to the host (tests): ngb_start (nr_leaves + 1),
 *  ngb_leaf and ngb_shift (3 per entry), sized as gpu_lists_build said. */
void gpu_lists_download(const struct gpu_lists *l, int *ngb_start, int *ngb_leaf,
                        double *ngb_shift);
/** Device pointers of the lists built last (for the runner's kernels): the
 *  shifts as codes (gpu_shift_code) of a box of sides dim. */
void gpu_lists_view(const struct gpu_lists *l, const int **ngb_start, const int **ngb_leaf,
                    const unsigned char **ngb_code, double dim[3]);
/** Milliseconds the device spent on builds (CUDA events, copies included) and
 *  builds run. */
double gpu_lists_device_ms(struct gpu_lists *l, long *builds);

#ifdef __cplusplus
}
#endif

#endif
