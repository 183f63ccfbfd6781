/* Mirror ghost particles at plane walls (Boundaries:planes; theory/boundaries.md,
 * "Mirror ghosts").
 *
 * The ghosts are particles of the particle arrays, flagged PART_MIRROR.
 * Each is the image of one real particle (its index msrc) through one plane
 * (msrc_plane).  The loops of the FORCE phase treat them as any particle,
 * but the ghost task keeps their h (ghost_cpu.c), the kick skips them
 * (kick_cpu.c), the statistics and the snapshots leave them out
 * (engine_io.c): their density sums, grad-h factor, Balsara switch,
 * velocity gradient, viscous stress and free-surface flag are computed in
 * the step, from their own neighbours, which are the mirror images of their
 * sources' wherever a ghost can reach a real particle (below), so that the
 * pair of a real particle and a ghost is the mirror image of the pair of the
 * ghost's source and the real particle's ghost, with no lag.  Their
 * accelerations are computed too and never used.
 *
 * Their life, through the registry's hooks (tasks/task_families.h):
 *  - rebuild_start: the ghosts are removed;
 *  - rebuild: after the space's rebuild of the real particles, every real
 *    particle in front of a plane and closer to it than (2 + f) w gets a
 *    ghost (w the widest top-level cell, f Scheduler:rebuild_fraction), and
 *    the space is rebuilt again with them (msrc follows the sort).  Between
 *    two rebuilds no particle moves more than f w and no kernel support H
 *    exceeds w (space_should_rebuild), so a ghost within reach of a real
 *    particle is closer than w to the plane, its source's neighbours are
 *    closer than 2 w, and they were closer than (2 + f) w at the rebuild:
 *    they all have their ghosts, the neighbours of the first ghost;
 *  - force: before every FORCE phase (after the drift and any rebuild),
 *    each ghost takes its source's predicted state, mirrored: position,
 *    velocity (free or no slip), stress tensors; continuity density,
 *    energy, smoothing length, material as they are; then the cells' drift
 *    bounds and h_max are computed again (cell_update_bounds).
 *
 * CPU only (the refresh writes the host's arrays between the phases): the
 * GPU runner, self-gravity (the ghosts would carry mass), individual time
 * steps and restart files are refused with one line naming
 * Boundaries:planes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "src/cell.h"
#include "src/engine.h"
#include "src/error.h"
#include "src/io/params.h"
#include "src/part.h"
#include "src/space.h"
#include "tasks/task_families.h"

/** Largest number of planes (the length of engine.planes). */
#define DRIFT_MIRROR_MAX 8

void drift_mirror_init(struct engine *e) {
  double v[6 * DRIFT_MIRROR_MAX];
  const int n = params_get_real_array(e->params, "Boundaries:planes", v, 6 * DRIFT_MIRROR_MAX);
  e->nr_planes = n / 6;
  e->mirror_no_slip = params_get_enum(e->params, "Boundaries:slip") == 1;
  e->nr_mirror = 0;
  for (int k = 0; k < e->nr_planes; k++) {
    const double *q = v + 6 * k;
    const double nn = sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5]);
    if (!(nn > 0.0) || !isfinite(nn))
      params_error(e->params, "Boundaries:planes",
                   "plane %d: the normal (%g, %g, %g) must be non-zero and finite", k + 1, q[3],
                   q[4], q[5]);
    for (int d = 0; d < 3; d++) {
      e->planes[k][d] = q[d];
      e->planes[k][3 + d] = q[3 + d] / nn;
    }
  }
}

void drift_mirror_clean(struct engine *e) {
  e->nr_planes = 0;
  e->nr_mirror = 0;
}

/** The runs the ghosts do not support yet, refused with one line. */
static void drift_mirror_check(const struct engine *e) {
  const char *why = NULL;
  if (e->gpu)
    why = "mirror ghosts run on the CPU only: run with --no-gpu (or Scheduler:gpu: off)";
  else if (e->gp.enabled)
    why = "mirror ghosts cannot be combined with self-gravity (Gravity:enabled) yet";
  else if (e->individual)
    why = "mirror ghosts need the global time step (TimeIntegration:global_step: true)";
  else if (e->restarts)
    why = "mirror ghosts cannot be combined with restart files (Restarts:enable) yet";
  if (why) params_error(e->params, "Boundaries:planes", "%s", why);
}

void drift_mirror_strip(struct engine *e) {
  if (!e->nr_mirror) return;
  struct parts *p = &e->parts;
  size_t i = 0;
  while (i < p->count) {
    if (p->flags[i] & PART_MIRROR) {
      if (i != p->count - 1) parts_copy_one(p, i, p->count - 1);
      p->count--;
    } else {
      i++;
    }
  }
  e->nr_mirror = 0;
}

/** Signed distance of particle i from plane k, positive in front of it. */
static double drift_mirror_distance(const struct engine *e, const struct parts *p, size_t i,
                                    int k) {
  const double *q = e->planes[k];
  return (p->x[i] - q[0]) * q[3] + (p->y[i] - q[1]) * q[4] + (p->z[i] - q[2]) * q[5];
}

/** The symmetric tensor (xx xy xz yy yz zz) t[0..5] reflected through the
 *  plane of unit normal n: Q t Q with Q = I - 2 n n^T. */
static void drift_mirror_tensor(const double n[3], double t[6]) {
  const double T[3][3] = {{t[0], t[1], t[2]}, {t[1], t[3], t[4]}, {t[2], t[4], t[5]}};
  double Q[3][3], QT[3][3], R[3][3];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) Q[a][b] = (a == b) - 2.0 * n[a] * n[b];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      QT[a][b] = 0.0;
      for (int c = 0; c < 3; c++) QT[a][b] += Q[a][c] * T[c][b];
    }
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      R[a][b] = 0.0;
      for (int c = 0; c < 3; c++) R[a][b] += QT[a][c] * Q[c][b];
    }
  t[0] = R[0][0];
  t[1] = R[0][1];
  t[2] = R[0][2];
  t[3] = R[1][1];
  t[4] = R[1][2];
  t[5] = R[2][2];
}

/** The velocity (vx, vy, vz) of a ghost of plane normal n: free slip
 *  reverses its normal component (the mirror image of the vector), no slip
 *  the whole of it (the velocity 2 v_wall - v of a wall at rest). */
static void drift_mirror_velocity(const double n[3], int no_slip, double *vx, double *vy,
                                  double *vz) {
  if (no_slip) {
    *vx = -*vx;
    *vy = -*vy;
    *vz = -*vz;
    return;
  }
  const double vn = *vx * n[0] + *vy * n[1] + *vz * n[2];
  *vx -= 2.0 * vn * n[0];
  *vy -= 2.0 * vn * n[1];
  *vz -= 2.0 * vn * n[2];
}

/** Ghost g becomes the image of its source (msrc) through its plane
 *  (msrc_plane): every field copied, then position, velocities and stress
 *  tensors mirrored; x0 (the position at the rebuild, which the rebuild
 *  criterion compares with) stays its own. */
static void drift_mirror_set(struct engine *e, size_t g) {
  struct parts *p = &e->parts;
  const size_t src = (size_t)p->msrc[g];
  const int k = p->msrc_plane[g];
  const double x0 = p->x0[g], y0 = p->y0[g], z0 = p->z0[g];
  parts_copy_one(p, g, src);
  p->x0[g] = x0;
  p->y0[g] = y0;
  p->z0[g] = z0;
  p->msrc[g] = (int64_t)src;
  p->msrc_plane[g] = k;
  const double *n = e->planes[k] + 3;
  const double d = 2.0 * drift_mirror_distance(e, p, src, k);
  p->x[g] -= d * n[0];
  p->y[g] -= d * n[1];
  p->z[g] -= d * n[2];
  /* the velocity the interactions read (vp) is the ghost's of B4; the
   * velocity, acceleration and XSPH term the next drift moves it with are
   * the mirror images of its source's, so that the drift keeps it (to
   * round-off) at the image of its drifted source, where the cells' drift
   * bounds (dx_max) expect it before this refresh puts it there */
  drift_mirror_velocity(n, e->mirror_no_slip, &p->vpx[g], &p->vpy[g], &p->vpz[g]);
  drift_mirror_velocity(n, 0, &p->vx[g], &p->vy[g], &p->vz[g]);
  drift_mirror_velocity(n, 0, &p->ax[g], &p->ay[g], &p->az[g]);
  drift_mirror_velocity(n, 0, &p->xsphx[g], &p->xsphy[g], &p->xsphz[g]);
  double t[6];
#define DRIFT_MIRROR_TENSOR_(S)                                                   \
  t[0] = p->S##xx[g], t[1] = p->S##xy[g], t[2] = p->S##xz[g], t[3] = p->S##yy[g], \
  t[4] = p->S##yz[g], t[5] = p->S##zz[g];                                         \
  drift_mirror_tensor(n, t);                                                      \
  p->S##xx[g] = t[0], p->S##xy[g] = t[1], p->S##xz[g] = t[2], p->S##yy[g] = t[3], \
  p->S##yz[g] = t[4], p->S##zz[g] = t[5];
  if (p->Sxx) { /* (a run without stress holds none: parts_drop) */
    DRIFT_MIRROR_TENSOR_(S)
    DRIFT_MIRROR_TENSOR_(Sp)
    DRIFT_MIRROR_TENSOR_(R)
  }
#undef DRIFT_MIRROR_TENSOR_
  p->flags[g] = (p->flags[src] & ~PART_INACTIVE) | PART_MIRROR;
}

void drift_mirror_make(struct engine *e) {
  if (!e->nr_planes) return;
  drift_mirror_check(e);
  struct space *s = &e->space;
  struct parts *p = &e->parts;
  double band = 0.0;
  for (int d = 0; d < 3; d++) band = s->width[d] > band ? s->width[d] : band;
  band *= 2.0 + s->max_drift_fraction;
  const size_t n = p->count;
  size_t add = 0;
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < e->nr_planes; k++) {
      const double d = drift_mirror_distance(e, p, i, k);
      add += d >= 0.0 && d < band;
    }
  if (!add) return;
  parts_reserve(p, n + add);
  size_t g = n;
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < e->nr_planes; k++) {
      const double d = drift_mirror_distance(e, p, i, k);
      if (!(d >= 0.0 && d < band)) continue;
      p->msrc[g] = (int64_t)i;
      p->msrc_plane[g] = k;
      p->count = g + 1;
      drift_mirror_set(e, g);
      const double x[3] = {p->x[g], p->y[g], p->z[g]};
      for (int c = 0; c < 3; c++)
        if (!(x[c] >= 0.0 && x[c] < s->dim[c]))
          params_error(e->params, "Boundaries:planes",
                       "plane %d: the mirror image of particle id %lld falls outside the box at "
                       "(%g, %g, %g): leave %g ((2 + Scheduler:rebuild_fraction) top-level "
                       "cell widths) between the plane and the side of the box behind it",
                       k + 1, (long long)p->id[i], x[0], x[1], x[2], band);
      g++;
    }
  e->nr_mirror = add;
  /* the cells of real particles and ghosts; the sort's permutation (new
   * index i holds old index sort_index[i]) carries the sources' indices */
  if (space_rebuild(s) != 0)
    error_exit("Boundaries:planes: particles were removed by the rebuild with the ghosts");
  const size_t m = p->count;
  int64_t *inv = error_malloc(m * sizeof(int64_t) + 1, "mirror ghost index");
  for (size_t i = 0; i < m; i++) inv[s->sort_index[i]] = (int64_t)i;
  for (size_t i = 0; i < m; i++)
    if (p->flags[i] & PART_MIRROR) p->msrc[i] = inv[p->msrc[i]];
  free(inv);
  error_log(1, "mirror ghosts: %zu at %d plane(s), band %g", add, e->nr_planes, band);
}

/** A real particle that the drift took behind plane k (d < 0) is put back
 *  in front of it, at its mirror image, with the normal components of its
 *  velocities reversed (a specular reflection: its kinetic energy is kept).
 *  Head-on with its own ghost, a particle at distance d from the plane feels
 *  a repulsion through grad W(2 d), which vanishes as d goes to 0: a block
 *  striking the plane at a tenth of the sound speed otherwise passes it
 *  (theory/boundaries.md). */
static void drift_mirror_reflect(struct engine *e, size_t i, int k) {
  struct parts *p = &e->parts;
  const double d = drift_mirror_distance(e, p, i, k);
  if (!(d < 0.0)) return;
  const double *n = e->planes[k] + 3;
  p->x[i] -= 2.0 * d * n[0];
  p->y[i] -= 2.0 * d * n[1];
  p->z[i] -= 2.0 * d * n[2];
  drift_mirror_velocity(n, 0, &p->vx[i], &p->vy[i], &p->vz[i]);
  drift_mirror_velocity(n, 0, &p->vpx[i], &p->vpy[i], &p->vpz[i]);
}

void drift_mirror_refresh(struct engine *e) {
  if (!e->nr_mirror) return;
  struct parts *p = &e->parts;
  for (size_t i = 0; i < p->count; i++)
    if (!(p->flags[i] & PART_MIRROR))
      for (int k = 0; k < e->nr_planes; k++) drift_mirror_reflect(e, i, k);
  for (size_t i = 0; i < p->count; i++)
    if (p->flags[i] & PART_MIRROR) drift_mirror_set(e, i);
  /* the ghosts moved (and took their sources' h) after the drift set the
   * cells' bounds: the loops' pruning needs them again */
  for (int c = 0; c < e->space.nr_top; c++)
    if (e->space.cells[c].count) cell_update_bounds(p, &e->space.cells[c]);
}
