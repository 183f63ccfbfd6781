/* Cells: bookkeeping of cell bounds between rebuilds (see cell.h). */
#include "src/cell.h"

#include <math.h>

#include "src/part.h"

int cell_loop_leaf_max = 0;

void cell_leaf_bounds(const struct parts *p, struct cell *c) {
  double h_max = 0.0, d2_max = 0.0;
  for (size_t i = c->offset; i < c->offset + c->count; i++) {
    const double dx = p->x[i] - p->x0[i], dy = p->y[i] - p->y0[i], dz = p->z[i] - p->z0[i];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 > d2_max) d2_max = d2;
    if (p->h[i] > h_max) h_max = p->h[i];
  }
  c->h_max = h_max;
  c->dx_max = sqrt(d2_max);
}

/** h_max and dx_max of the split cell c from its progeny's. */
static void cell_bounds_from_progeny(struct cell *c) {
  c->h_max = 0.0;
  c->dx_max = 0.0;
  for (int q = 0; q < 8; q++) {
    const struct cell *child = c->progeny[q];
    if (!child) continue;
    if (child->h_max > c->h_max) c->h_max = child->h_max;
    if (child->dx_max > c->dx_max) c->dx_max = child->dx_max;
  }
}

void cell_gather_bounds(struct cell *c) {
  if (!c->split) return;
  for (int q = 0; q < 8; q++)
    if (c->progeny[q]) cell_gather_bounds(c->progeny[q]);
  cell_bounds_from_progeny(c);
}

void cell_update_bounds(const struct parts *p, struct cell *c) {
  if (!c->split) {
    cell_leaf_bounds(p, c);
    return;
  }
  for (int q = 0; q < 8; q++)
    if (c->progeny[q]) cell_update_bounds(p, c->progeny[q]);
  cell_bounds_from_progeny(c);
}

void cell_update_h_max(const struct parts *p, struct cell *c) {
  if (c->split) {
    c->h_max = 0.0;
    for (int q = 0; q < 8; q++) {
      struct cell *child = c->progeny[q];
      if (!child) continue;
      cell_update_h_max(p, child);
      if (child->h_max > c->h_max) c->h_max = child->h_max;
    }
    return;
  }
  double h_max = 0.0;
  for (size_t i = c->offset; i < c->offset + c->count; i++)
    if (p->h[i] > h_max) h_max = p->h[i];
  c->h_max = h_max;
}
