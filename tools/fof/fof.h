/* Friends-of-friends groups (Davis et al. 1985): two particles closer than
 * the linking length L are friends, and a group is a connected set of
 * friends.  O(N): a uniform grid of cells of side L (only occupied cells are
 * stored, sorted by key and found by one sweep per neighbour offset, so the
 * spread of the debris does not matter), each particle compared with the particles of its own and
 * its 26 neighbouring cells, groups merged by union-find with path halving and union by size
 * (Tarjan 1975). */
#ifndef BOLIDE_FOF_H
#define BOLIDE_FOF_H

#include <stddef.h>
#include <stdint.h>

/** Groups of the n particles at (x, y, z) with linking length L > 0; only
 *  particles with keep[i] != 0 take part (keep NULL: all).  group[i]: the
 *  group of particle i, numbered 0, 1, ... in the order of each group's
 *  lowest particle index; -1 for particles left out.  Returns the number of
 *  groups. */
int64_t fof_groups(size_t n, const double *x, const double *y, const double *z,
                   const unsigned char *keep, double L, int64_t *group);

/** The same by comparing every pair, O(N^2): the slow twin for the tests. */
int64_t fof_groups_brute(size_t n, const double *x, const double *y, const double *z,
                         const unsigned char *keep, double L, int64_t *group);

/** Groups with a linking length per particle: particles i and j are
 *  friends when closer than max(ell[i], ell[j]) (ell[i] > 0, such as a
 *  multiple of the smoothing length: the default of bolide-fof, which
 *  follows the particle spacing through the layers of a planet).  Cells of
 *  the median length; a particle with a k times longer one searches the
 *  (2k + 1)^3 cells around its own.  Same numbering as fof_groups. */
int64_t fof_groups_local(size_t n, const double *x, const double *y, const double *z,
                         const unsigned char *keep, const double *ell, int64_t *group);

/** The same by comparing every pair, O(N^2): the slow twin for the tests. */
int64_t fof_groups_local_brute(size_t n, const double *x, const double *y, const double *z,
                               const unsigned char *keep, const double *ell, int64_t *group);

/** Sort (key, index) pairs by key (keys >= 0): LSD radix sort, 16 bits a
 *  pass, O(n), stable.  Non-negative doubles sort the same way by their
 *  bit patterns. */
void fof_radix_sort(size_t n, int64_t *key, int64_t *idx);

#endif
