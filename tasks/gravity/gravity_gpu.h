/* Internal interface between self-gravity's device code
 * (tasks/gravity/gpu_gravity.cu) and its kernels (gravity_gpu.cu: the
 * operators; gravity_tree_gpu.cu: the upward pass and the walks).  CUDA C++
 * only. */
#ifndef BOLIDE_GRAVITY_GPU_H
#define BOLIDE_GRAVITY_GPU_H

#include "src/gpu/gpu_kernels.h"
#include "tasks/gravity/gravity_walk.h"

/** Threads per block of the one-thread-per-cell kernels. */
#define GRAVITY_GPU_CELL_BLOCK 64
/** Threads per block of the field kernel (M2L, P2L): one warp per cell. */
#define GRAVITY_GPU_FIELD_BLOCK 128

/** Instantiate kernel K for the orders 1..GRAVITY_ORDER_MAX and launch the
 *  one of d.order on stream s (the gravity kernels). */
#define GRAVITY_GPU_DISPATCH(K, grid, block, ...)                   \
  switch (d.order) {                                                \
    case 1:                                                         \
      K<1><<<(grid), (block), 0, s>>>(__VA_ARGS__);                 \
      break;                                                        \
    case 2:                                                         \
      K<2><<<(grid), (block), 0, s>>>(__VA_ARGS__);                 \
      break;                                                        \
    case 3:                                                         \
      K<3><<<(grid), (block), 0, s>>>(__VA_ARGS__);                 \
      break;                                                        \
    case 4:                                                         \
      K<4><<<(grid), (block), 0, s>>>(__VA_ARGS__);                 \
      break;                                                        \
    default:                                                        \
      K<GRAVITY_ORDER_MAX><<<(grid), (block), 0, s>>>(__VA_ARGS__); \
      break;                                                        \
  }                                                                 \
  gpu_check_launch(K)

/** The gravity tree on the device (tasks/gravity/gpu_gravity.cu), by cell index. */
struct gravity_gpu_dev {
  const struct gravity_multipole *mp; /**< multipole of each cell (CPU's gravity_up) */
  struct gravity_field *field;        /**< local expansion of each cell */
  const size_t *offset;               /**< first particle of each cell */
  const int *count;                   /**< its particles */
  double G, eps, eps2;                /**< constant, softening, softening^2 in the expansions */
  int softening, order;               /**< enum gravity_softening, expansion order */
  const unsigned char *active;        /**< a step of active particles only: per cell, whether it
                                           receives (gravity_walk_tree.active); NULL: all */
};

/** The upward pass on the device (gravity_up_gpu_launch): by cell index. */
struct gravity_gpu_up {
  struct gravity_multipole *mp; /**< multipoles (out) */
  double *a_min, *h_support;    /**< struct gravity_cell's a_min and h_support (out) */
  const double *centre;         /**< 3 per cell: the box centre (a massless cell's centre) */
  const size_t *offset;         /**< first particle of each cell */
  const int *count;             /**< its particles */
  double h_factor;              /**< Gravity:softening_h_factor */
  int order;                    /**< expansion order */
  unsigned char *active;        /**< a step of active particles only: per cell, whether it holds
                                     a particle that ends its step (out); NULL: not such a step */
};

/** Recorded interactions grouped by receiving cell (tasks/gravity/gpu_gravity.cu). */
struct gravity_gpu_groups {
  int nr_cells; /**< cells */
  /** nr_cells + 1: cell c's sources are [start[c], start[c+1]) (64 bits:
   *  at 1.1e8 particles the M2L and P2L lists pass 2^31 entries) */
  const unsigned long long *start;
  const int *source; /**< the sources (struct gravity_gpu_rec) */
};

/** Gravity (tasks/gravity/gravity_tree_gpu.cu): the upward pass, P2M at the
 *  leaves, then M2M level by level from the deepest (level_start on the
 *  host: the pairs (child, parent) of level L are [level_start[L],
 *  level_start[L + 1]), a parent's children consecutive, in progeny
 *  order); every cell of nr_cells written (empty ones: zero at their
 *  centre). */
void gravity_up_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_up u, int nr_cells,
                           const int *leaf, int nr_leaves, const int *child, const int *parent,
                           const int *level_start, int nr_levels);
/** Gravity (tasks/gravity/gravity_tree_gpu.cu): the first round of the
 *  walks of gravity_walk.h, from every pair of the nt top-level cells
 *  (boxes lo_hi: 6 doubles each; h_support_top: the constant support of
 *  the near test; skip, top: gravity_walk_root's, on the device, or NULL),
 *  recorded in L (counters on the device); what the walkers leave goes to
 *  out; *deep (device) counts walks out of stack. */
void gravity_walk_roots_gpu_launch(cudaStream_t s, struct gravity_walk_tree T,
                                   struct gravity_walk_params wp, struct gravity_walk_lists L,
                                   struct gravity_walk_queue out, const double *lo_hi, int nt,
                                   double h_support_top, const unsigned char *skip, const int *top,
                                   int *deep);
/** A later round: the entries of in (n_in on the host: the device's *in.n
 *  as read after the last round), what is left again to out. */
void gravity_walk_queue_gpu_launch(cudaStream_t s, struct gravity_walk_tree T,
                                   struct gravity_walk_params wp, struct gravity_walk_lists L,
                                   struct gravity_walk_queue in, unsigned long long n_in,
                                   struct gravity_walk_queue out, int *deep);
/** Gravity (tasks/gravity/gravity_gpu.cu): M2L and P2L of every cell
 *  with sources in l, stored as its field. */
void gravity_field_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                              struct gravity_gpu_groups l);
/** L2L of the parent-child pairs [k0, k1) (one tree level). */
void gravity_l2l_gpu_launch(cudaStream_t s, struct gravity_gpu_dev d, const int *child,
                            const int *parent, int k0, int k1);
/** P2P and M2P of the leaves leaf[0..nr_leaves) from their sources in l,
 *  added to pot and ga. */
void gravity_part_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                             struct gravity_gpu_groups l, const int *leaf, int nr_leaves,
                             int block);
/** ga and pot of the particles of the leaves leaf[0..nr_leaves) that
 *  receive (d.active, required) set to zero. */
void gravity_zero_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                             const int *leaf, int nr_leaves, int block);
/** L2P at the leaves leaf[0..nr_leaves) that receive (d.active; NULL:
 *  all), added to pot and ga. */
void gravity_l2p_gpu_launch(cudaStream_t s, struct parts p, struct gravity_gpu_dev d,
                            const int *leaf, int nr_leaves, int block);

#endif
