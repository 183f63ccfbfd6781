/* The ghost task: smoothing-length iteration and equation of state for the
 * particles of one top-level cell (DESIGN.md: "ghost finishes the density
 * sums, iterates the smoothing length to the target neighbour number
 * (re-running density for particles that need it), and evaluates the
 * equation of state"). */
#include "ghost_cpu.h"

#include <math.h>

#include "density/density_cpu.h"
#include "error.h"
#include "ghost_iact.h"
#include "hydro_parts.h"
#include "kernel.h"
#include "material.h"

/** Add the particle's own contribution to its density sums. */
static void ghost_add_self(struct parts *p, size_t i) {
  struct density_acc a = {0, 0, 0, 0, 0, {0, 0, 0}};
  density_self_term(1.0 / p->h[i], p->m[i], &a);
  hydro_density_add(p, i, &a);
}

/** One iteration step for particle i; sets PART_H_CONVERGED when done.
 *  Returns 1 if the particle was capped at the cells' limit. */
static int ghost_step(struct parts *p, size_t i, const struct hydro_props *hp, double h_cap) {
  double h = p->h[i];
  const double hmax = hp->h_max < h_cap ? hp->h_max : h_cap;
  const int r = ghost_h_iterate(&h, &p->h_lo[i], &p->h_hi[i], p->wcount[i], p->wcount_dh[i], hp->eta,
                                hp->h_tolerance, hmax);
  int capped = 0;
  if (r == GHOST_H_CONVERGED) {
    p->flags[i] |= PART_H_CONVERGED;
    if (h >= h_cap && h_cap < hp->h_max) capped = 1;
    /* keep the h the sums were computed with */
  } else {
    p->h[i] = h;
  }
  return capped;
}

/** Density-derived quantities and the equation of state of particle i. */
static void ghost_finish(struct parts *p, size_t i, const struct hydro_props *hp,
                         const struct material_table *mats) {
  const double rho = p->rho[i];
  const double h = p->h[i];
  p->f_gradh[i] = 1.0 / (1.0 + h * p->rho_dh[i] / (3.0 * rho));
  const double rho_inv = 1.0 / rho;
  p->div_v[i] *= rho_inv;
  p->curl_vx[i] *= rho_inv;
  p->curl_vy[i] *= rho_inv;
  p->curl_vz[i] *= rho_inv;
  /* continuity equation: the summed density served the h iteration and the
   * grad-h factor; the EOS and the force loop use the integrated density
   * (started from the summation where the initial conditions had none) */
  if (hp->continuity) {
    if (!(p->rho_full[i] > 0.0)) p->rho_full[i] = p->rho_fp[i] = rho;
    p->rho[i] = p->rho_fp[i];
  }
  const struct material *mat = material_table_find(mats, p->mat[i]);
  double P, cs;
  material_eos(mat, p->rho[i], p->up[i], &P, &cs);
  p->P[i] = P;
  p->cs[i] = cs;
  const double curl = sqrt(p->curl_vx[i] * p->curl_vx[i] + p->curl_vy[i] * p->curl_vy[i] +
                           p->curl_vz[i] * p->curl_vz[i]);
  p->balsara[i] = hp->balsara ? ghost_balsara(p->div_v[i], curl, cs, h) : 1.0;
  /* zero the force sums here: every force task of the cell runs after its ghost */
  hydro_force_reset(p, i);
  if (hp->solids) hydro_gradient_reset(p, i);
}

int ghost_cell_cpu(struct parts *p, struct cell *c, const struct ghost_ngbs *ngbs,
                   const struct hydro_props *hp, const struct material_table *mats,
                   double H_limit) {
  const size_t beg = c->offset, end = c->offset + c->count;
  const double h_cap = H_limit / kernel_gamma;
  int capped = 0;
  size_t left = 0;
  for (size_t i = beg; i < end; i++) {
    p->flags[i] &= ~PART_H_CONVERGED;
    p->h_lo[i] = 0.0;
    p->h_hi[i] = 1e300;
    ghost_add_self(p, i);
    capped |= ghost_step(p, i, hp, h_cap);
    left += !(p->flags[i] & PART_H_CONVERGED);
  }
  for (int iter = 1; left > 0; iter++) {
    if (iter > hp->max_iterations) {
      for (size_t i = beg; i < end; i++)
        if (!(p->flags[i] & PART_H_CONVERGED))
          error_exit("smoothing length of particle %zu (id %lld) at (%g, %g, %g) did not converge in %d "
                     "iterations (h = %g, bracket [%g, %g]); raise SPH:max_ghost_iterations or check "
                     "the initial conditions",
                     i, (long long)p->id[i], p->x[i], p->y[i], p->z[i], hp->max_iterations, p->h[i],
                     p->h_lo[i], p->h_hi[i]);
    }
    /* redo the sums of the particles still iterating, with their new h */
    for (size_t i = beg; i < end; i++)
      if (!(p->flags[i] & PART_H_CONVERGED)) hydro_density_reset(p, i);
    cell_update_h_max(p, c);
    for (int k = 0; k < ngbs->n; k++) density_gather_unconverged_cpu(p, c, ngbs->cells[k], ngbs->shift[k]);
    left = 0;
    for (size_t i = beg; i < end; i++) {
      if (p->flags[i] & PART_H_CONVERGED) continue;
      ghost_add_self(p, i);
      capped |= ghost_step(p, i, hp, h_cap);
      left += !(p->flags[i] & PART_H_CONVERGED);
    }
  }
  cell_update_h_max(p, c);
  for (size_t i = beg; i < end; i++) ghost_finish(p, i, hp, mats);
  return capped;
}
