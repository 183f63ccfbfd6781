/* The tree of the walks' tests (test_gravity_walk, test_gravity_remote):
 * a set of gset_fill_walk in a space, the gravity settings they share and
 * the cells' gravity state, zeroed. */
#ifndef BOLIDE_TESTS_GRAVITY_WALK_SET_H
#define BOLIDE_TESTS_GRAVITY_WALK_SET_H

#include <stdlib.h>
#include <string.h>

#include "src/part.h"
#include "src/space.h"
#include "tasks/gravity/gravity_cpu.h"
#include "tests/helpers/gravity_sets.h"

struct gset_tree {
  struct parts p;          /**< the particles (the space points at them: do not move t) */
  struct space sp;         /**< rebuilt once */
  struct gravity_props gp; /**< G 1, theta 0.5, spline softening 2e-3, default order and
                                epsilon_fmm */
  struct gravity_cell *gc; /**< one per cell of sp, zeroed */
};

/** t: n particles of gset_fill_walk (drand48 seeded with seed) about the
 *  centre of a box of side box, leaves of at most 16, at most max_top
 *  top-level cells per direction. */
static inline void gset_tree_make(struct gset_tree *t, size_t n, long seed, int two_bodies,
                                  double box, int max_top) {
  parts_alloc(&t->p, n);
  t->p.count = n;
  srand48(seed);
  const double c[3] = {0.5 * box, 0.5 * box, 0.5 * box}, b[3] = {box, box, box};
  gset_fill_walk(&t->p, n, c, two_bodies);
  space_init(&t->sp, &t->p, b, 0, 16, max_top);
  space_rebuild(&t->sp);
  gravity_props_set(&t->gp, 1.0, 0.5, 2e-3, GRAVITY_SOFTENING_SPLINE, GRAVITY_ORDER_DEFAULT);
  t->gp.epsilon_fmm = GRAVITY_EPSILON_FMM_DEFAULT;
  int cap = 0;
  t->gc = gravity_cells_reserve(NULL, &cap, t->sp.cells_capacity);
  memset(t->gc, 0, (size_t)cap * sizeof *t->gc);
}

static inline void gset_tree_free(struct gset_tree *t) {
  free(t->gc);
  space_free(&t->sp);
  parts_free(&t->p);
}

#endif
