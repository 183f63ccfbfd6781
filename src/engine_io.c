/* The engine's outputs: the statistics file, snapshots and task dumps. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "src/engine_tasks.h"
#include "src/error.h"
#include "src/io/units.h"
#include "src/io/params.h"
#include "src/io/snapshot.h"
#include "src/mpi/halo.h"
#include "src/mpi/ranks.h"
#include "tasks/task_families.h"
#include "src/version.h"
#ifdef HAVE_CUDA
#include "src/gpu/gpu_engine.h"
#endif

/** Columns of the statistics file: one list for the header and the rows,
 *  X(bolide_name, swift_name, description, a, b, c): Bolide's one-word name,
 *  the name of SWIFT's column for the same quantity where SWIFT has one (its
 *  snake case is what swiftsimio.load_statistics calls it: "Kin. Energy" ->
 *  kin_energy), a description, and the dimension M^a L^b T^c of the unit
 *  (the step and the counts have none).
 *  The budget (theory/sph.md, "Conservation budget"): E_tot = E_kin + E_int
 *  + E_pot of the particles in the box; *_removed what the particles that
 *  left an open box took with them (their share m phi of the potential
 *  included); E_clamp the energy the kick's floor on u added (counted, not
 *  exchanged); W_plastic the plastic work of the radial returns (already a
 *  part of E_int: where the stress power went, not a term of the sum);
 *  dE = E_tot + E_removed - E_clamp - E_tot(start), which a conservative
 *  run keeps at the level of its time-integration error. */
#define ENGINE_STATS_COLUMNS(X)                                                                   \
  X(step, "Step", "Simulation step", 0, 0, 0)                                                     \
  X(time, "Time", "Time since the start of the simulation", 0, 0, 1)                              \
  X(dt, "dt", "Time-step of the step that ended here", 0, 0, 1)                                   \
  X(mass, "Total mass", "Total mass in the simulation", 1, 0, 0)                                  \
  X(px, "Mom. x", "Momentum of the simulation (x coordinate)", 1, 1, -1)                          \
  X(py, "Mom. y", "Momentum of the simulation (y coordinate)", 1, 1, -1)                          \
  X(pz, "Mom. z", "Momentum of the simulation (z coordinate)", 1, 1, -1)                          \
  X(Lx, "Ang. mom. x", "Angular momentum about the origin (x coordinate)", 1, 2, -1)              \
  X(Ly, "Ang. mom. y", "Angular momentum about the origin (y coordinate)", 1, 2, -1)              \
  X(Lz, "Ang. mom. z", "Angular momentum about the origin (z coordinate)", 1, 2, -1)              \
  X(E_kin, "Kin. Energy", "Total kinetic energy", 1, 2, -2)                                       \
  X(E_int, "Int. Energy", "Total internal energy", 1, 2, -2)                                      \
  X(E_pot, "Pot. energy", "Total potential energy of self-gravity and the external field", 1, 2,  \
    -2)                                                                                           \
  X(E_tot, "Tot. energy", "Total energy E_kin + E_int + E_pot", 1, 2, -2)                         \
  X(n_particles, "Particles", "Number of particles in the box", 0, 0, 0)                          \
  X(n_removed, "Removed particles", "Number of particles that left the open box", 0, 0, 0)        \
  X(m_removed, "Removed mass", "Mass the removed particles took with them", 1, 0, 0)              \
  X(E_removed, "Removed energy", "Energy the removed particles took with them", 1, 2, -2)         \
  X(px_removed, "Removed mom. x", "Momentum the removed particles took (x coordinate)", 1, 1, -1) \
  X(py_removed, "Removed mom. y", "Momentum the removed particles took (y coordinate)", 1, 1, -1) \
  X(pz_removed, "Removed mom. z", "Momentum the removed particles took (z coordinate)", 1, 1, -1) \
  X(Lx_removed, "Removed ang. mom. x", "Angular momentum the removed particles took (x)", 1, 2,   \
    -1)                                                                                           \
  X(Ly_removed, "Removed ang. mom. y", "Angular momentum the removed particles took (y)", 1, 2,   \
    -1)                                                                                           \
  X(Lz_removed, "Removed ang. mom. z", "Angular momentum the removed particles took (z)", 1, 2,   \
    -1)                                                                                           \
  X(E_clamp, "Clamp energy", "Energy added by the floor on the internal energy", 1, 2, -2)        \
  X(W_plastic, "Plastic work", "Plastic work (a part of the internal energy)", 1, 2, -2)          \
  X(dE, "Energy error", "Energy budget error E_tot + E_removed - E_clamp - E_tot(start)", 1, 2, -2)

/** The unit of dimension M^a L^b T^c in unyt's words ("gram * cm**2 *
 *  s**-2"), "" for none. */
static void engine_stats_unit(int a, int b, int c, char *buf, size_t len) {
  const char *sym[3] = {"gram", "cm", "s"};
  const int e[3] = {a, b, c};
  buf[0] = '\0';
  for (int k = 0; k < 3; k++) {
    if (!e[k]) continue;
    const size_t n = strlen(buf);
    if (e[k] == 1)
      snprintf(buf + n, len - n, "%s%s", n ? " * " : "", sym[k]);
    else
      snprintf(buf + n, len - n, "%s%s**%d", n ? " * " : "", sym[k], e[k]);
  }
}

/** The header of the statistics file, in SWIFT's layout: "# (N) description"
 *  and "#      Unit = FACTOR UNIT" per column (one unit each), Bolide's
 *  names on a "# step time ..." line, SWIFT's column names last (separated by
 *  two blanks or more), so that swiftsimio.load_statistics reads the file
 *  and Bolide's tools find their names. */
static void engine_stats_header(struct engine *e, FILE *f) {
  char unit[96];
  int col = 0;
  fprintf(f, "# Bolide %s statistics file (SWIFT's layout: swiftsimio.load_statistics reads it)\n",
          PACKAGE_VERSION);
  fprintf(f, "######################################################\n");
  fprintf(f,
          "# The quantities are all given in internal units: mass %g g, length %g cm, time %g s\n",
          e->us.mass_cgs, e->us.length_cgs, e->us.time_cgs);
  fprintf(f, "#\n");
#define ENGINE_STATS_DESC(n, swift, desc, a, b, c)                                   \
  engine_stats_unit(a, b, c, unit, sizeof unit);                                     \
  fprintf(f, "# (%d)%*s%s\n", col, col < 10 ? 2 : 1, "", desc);                      \
  if (unit[0])                                                                       \
    fprintf(f, "#      Unit = %.16e %s\n", units_cgs_factor(&e->us, a, b, c), unit); \
  else                                                                               \
    fprintf(f, "#      Unit = dimensionless\n");                                     \
  col++;
  ENGINE_STATS_COLUMNS(ENGINE_STATS_DESC)
#undef ENGINE_STATS_DESC
  fprintf(f, "#\n# Bolide's names of the columns:\n#");
#define ENGINE_STATS_NAME(n, swift, desc, a, b, c) fprintf(f, " %s", #n);
  ENGINE_STATS_COLUMNS(ENGINE_STATS_NAME)
#undef ENGINE_STATS_NAME
  fprintf(f, "\n#");
#define ENGINE_STATS_SWIFT(n, swift, desc, a, b, c) fprintf(f, "  %s", swift);
  ENGINE_STATS_COLUMNS(ENGINE_STATS_SWIFT)
#undef ENGINE_STATS_SWIFT
  fprintf(f, "\n");
}

/** The particles of the run (of every rank), mirror ghosts and foreign
 *  copies left out. */
static size_t engine_nr_real(const struct engine *e) {
  return e->halo ? (size_t)e->nr_owned_all : e->parts.count - e->nr_mirror;
}

/** SWIFT's Statistics:time_first: the first line then, the next every
 *  delta_time after it. */
static void engine_stats_first_time(struct engine *e) {
  e->next_stats = e->time;
  if (params_given(e->params, "Statistics:time_first"))
    e->next_stats = fmax(e->time, params_get_real(e->params, "Statistics:time_first"));
}

/** The step of the last data line of the statistics file path (-1: none):
 *  a run resumed from the restart file written at the end of a finished run
 *  (a kill before it exited) must not add the closing line again. */
static long engine_stats_file_last_step(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  char buf[8192];
  long step = -1;
  if (fseek(f, 0, SEEK_END) == 0) {
    const long end = ftell(f);
    const long from = end > (long)sizeof buf - 1 ? end - (long)sizeof buf + 1 : 0;
    if (fseek(f, from, SEEK_SET) == 0) {
      const size_t n = fread(buf, 1, sizeof buf - 1, f);
      buf[n] = '\0';
      /* the last complete line that is not a comment */
      char *line = strtok(buf, "\n");
      while (line) {
        long v;
        if (line[0] != '#' && sscanf(line, "%ld", &v) == 1) step = v;
        line = strtok(NULL, "\n");
      }
    }
  }
  fclose(f);
  return step;
}

void engine_stats_open(struct engine *e) {
  if (ranks_rank() != 0) {
    /* several MPI ranks: rank 0 writes the files, every rank computes (and
     * learns from rank 0 whether the step resumed has its line already) */
    e->stats = e->timesteps = NULL;
    int last = -1;
    if (e->restarted && !e->opt.one_rank) ranks_bcast_ints(&last, 1);
    e->stats_last_step = last == 0 ? e->step : -1;
    engine_stats_first_time(e);
    return;
  }
  char path[2048];
  snprintf(path, sizeof path, "%s/%s.txt", e->outdir,
           params_get_string(e->params, "Statistics:energy_file_name"));
  /* a resumed run appends to the file of the run it continues, cut to its
   * length when the restart file was written (the lines of the steps after
   * it come again) */
  if (e->restarted) {
    struct stat sb;
    if (stat(path, &sb) == 0 && sb.st_size > e->restart_stats_offset) {
      if (truncate(path, (off_t)e->restart_stats_offset))
        error_exit("%s: cannot cut the statistics file to %ld bytes: %s", path,
                   e->restart_stats_offset, strerror(errno));
    } else if (stat(path, &sb) || sb.st_size < e->restart_stats_offset) {
      error_warning(
          "%s: shorter than when the restart file was written (%ld bytes): lines are missing", path,
          e->restart_stats_offset);
    }
  }
  e->stats = fopen(path, e->restarted ? "a" : "w");
  if (!e->stats) error_exit("%s: cannot create the statistics file", path);
  e->stats_last_step = e->restarted ? engine_stats_file_last_step(path) : -1;
  if (e->restarted && ranks_size() > 1 && !e->opt.one_rank) {
    int last = e->stats_last_step == e->step ? 0 : -1; /* (0: this step has its line) */
    ranks_bcast_ints(&last, 1);
  }
  if (e->stats_last_step != e->step) e->stats_last_step = -1;
  /* the timesteps file (SWIFT's Statistics:timestep_file_name): one line
   * per step; a resumed run appends (the steps between the restart file
   * and the stop come twice) */
  snprintf(path, sizeof path, "%s/%s.txt", e->outdir,
           params_get_string(e->params, "Statistics:timestep_file_name"));
  e->timesteps = fopen(path, e->restarted ? "a" : "w");
  if (!e->timesteps) error_exit("%s: cannot create the timesteps file", path);
  if (e->restarted) return; /* (no comment line: the file stays one table) */
  fprintf(e->timesteps,
          "# Bolide %s time steps, one line per step (SWIFT's timesteps file)\n"
          "# Time and time-step in internal units (%g s); wall-clock time of the step in ms\n"
          "# Updates: the particles kicked (with time bins those that ended their step, issue 20)\n"
          "# Bin-min, Bin-max: the time bins (src/timeline.h) of the particles' own limits after "
          "the step;\n"
          "# Active-fraction: the particle updates individual time steps would do per step of "
          "Bin-min,\n"
          "# as a fraction of this global step's (0 0 -1: not counted, as on the GPU)\n"
          "# %8s %16s %16s %14s %16s %7s %7s %15s\n",
          PACKAGE_VERSION, e->us.time_cgs, "Step", "Time", "Time-step", "Updates",
          "Wall-clock time", "Bin-min", "Bin-max", "Active-fraction");
  fflush(e->timesteps);
  engine_stats_header(e, e->stats);
  fflush(e->stats);
  engine_stats_first_time(e);
}

void engine_timesteps_write(struct engine *e, double wall_step) {
  if (!e->timesteps) return;
  int b_min = -1, b_max = -1;
  for (int b = 0; b <= TIMELINE_NR_BINS; b++)
    if (e->bins[b] > 0) {
      if (b_min < 0) b_min = b;
      b_max = b;
    }
  /* (with time bins the particles that ended their step: e->nr_active) */
  const size_t updates = e->individual ? (size_t)e->nr_active : engine_nr_real(e);
  fprintf(e->timesteps, "  %8ld %16.9e %16.9e %14zu %16.6f %7d %7d %15.6f\n", e->step, e->time,
          e->dt, updates, 1e3 * wall_step, b_min < 0 ? 0 : b_min, b_max < 0 ? 0 : b_max,
          b_min < 0 ? -1.0 : timeline_active_fraction(e->bins));
  if (fflush(e->timesteps)) error_exit("cannot write the timesteps file (disk full?)");
}

/** What the particles removed from the open box took with them, summed
 *  over the ranks (collective with several), and their number. */
static void engine_removed(const struct engine *e, struct budget_removed *r, long long *n) {
  *r = e->space.removed;
  *n = e->nr_removed;
  if (!e->halo) return;
  ranks_allreduce_doubles((double *)r, (int)(sizeof *r / sizeof(double)), RANKS_SUM);
  ranks_allreduce_llongs(n, 1, RANKS_SUM);
}

/** The totals of the particles in the box, and what the counters hold. */
struct engine_totals {
  double mass, p[3], L[3], E_kin, E_int, E_pot, p_abs, E_clamp, W_plastic;
  double mr[3]; /**< sum of m x: the centre of mass times the mass */
  double E_ext; /**< the part of E_pot of the external field, -sum m g.x */
};

/** Sum the particles' totals (the particles must be on the host). */
static void engine_totals(const struct engine *e, struct engine_totals *t) {
  const struct parts *p = &e->parts;
  memset(t, 0, sizeof *t);
  for (size_t i = 0; i < p->count; i++) {
    if (p->flags[i] & PART_NOT_OWNED) continue; /* (mirror ghosts, foreign copies) */
    const double m = p->m[i];
    const double vx = p->vx[i], vy = p->vy[i], vz = p->vz[i];
    const double x = p->x[i], y = p->y[i], z = p->z[i];
    t->mass += m;
    t->mr[0] += m * x;
    t->mr[1] += m * y;
    t->mr[2] += m * z;
    t->p[0] += m * vx;
    t->p[1] += m * vy;
    t->p[2] += m * vz;
    t->L[0] += m * (y * vz - z * vy);
    t->L[1] += m * (z * vx - x * vz);
    t->L[2] += m * (x * vy - y * vx);
    const double v2 = vx * vx + vy * vy + vz * vz;
    t->E_kin += 0.5 * m * v2;
    t->p_abs += m * sqrt(v2);
    t->E_int += m * p->u[i];
    t->E_clamp += m * p->e_clamp[i];
    if (p->w_plastic) t->W_plastic += m * p->w_plastic[i];
  }
  t->E_pot = e->gp.enabled ? gravity_potential_energy(p) : 0.0;
  if (e->hp.external) {
    /* the uniform field ConstantPotential:g_cgs: phi = -g.x (theory/boundaries.md) */
    const double *g = e->hp.g_ext;
    for (size_t i = 0; i < p->count; i++)
      if (!(p->flags[i] & PART_NOT_OWNED))
        t->E_ext -= p->m[i] * (g[0] * p->x[i] + g[1] * p->y[i] + g[2] * p->z[i]);
    t->E_pot += t->E_ext;
  }
  t->E_clamp += e->space.removed.E_clamp;
  t->W_plastic += e->space.removed.W_plastic;
  /* several MPI ranks: the sums of all (every member a double) */
  if (e->halo) ranks_allreduce_doubles((double *)t, (int)(sizeof *t / sizeof(double)), RANKS_SUM);
}

/** Remember the totals of the start (the first statistics line of a run
 *  that does not resume one). */
static void engine_budget_start(struct engine *e, const struct engine_totals *t) {
  struct budget_start *b = &e->budget0;
  b->E_tot = t->E_kin + t->E_int + t->E_pot;
  b->E_pot = t->E_pot - t->E_ext; /* (the scale of energy errors: self-gravity's alone; the
                                      external field's depends on the origin) */
  b->E_abs = fabs(t->E_kin) + fabs(t->E_int) + fabs(t->E_pot);
  for (int k = 0; k < 3; k++) {
    b->p[k] = t->p[k];
    b->L[k] = t->L[k];
  }
  b->p_abs = t->p_abs;
  for (int k = 0; k < 3; k++) b->com[k] = t->mass > 0.0 ? t->mr[k] / t->mass : 0.0;
  b->set = 1.0;
}

/** The change of the angular momentum since the start about the start's
 *  centre of mass c (a fixed point), relative to its value then: L_c =
 *  L - c x p with L and p the totals now (the removed particles' added),
 *  so that a momentum error does not count again as one of angular
 *  momentum at the origin's lever arm (the bodies of an impact sit at the
 *  box's centre, ten and more of their radii from its corner).  Returns
 *  |L_c - L_c(0)| / |L_c(0)|, or -1 where L_c(0) is 0. */
static double engine_dL_about_com(const struct budget_start *b, const double L[3],
                                  const double p[3]) {
  const double *c = b->com;
  double dL2 = 0.0, L02 = 0.0;
  for (int k = 0; k < 3; k++) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const double L0 = b->L[k] - (c[k1] * b->p[k2] - c[k2] * b->p[k1]);
    const double dL = L[k] - (c[k1] * p[k2] - c[k2] * p[k1]) - L0;
    dL2 += dL * dL;
    L02 += L0 * L0;
  }
  return L02 > 0.0 ? sqrt(dL2 / L02) : -1.0;
}

/** The angular-momentum check (Statistics:max_angular_momentum_change,
 *  issue 24 item 5, for runs moved over from miluphcuda): with the budget's
 *  L(0) and the angular momentum the particles that left an open box took
 *  with them, a run whose |L + L_removed - L(0)| / |L(0)| exceeds the bound
 *  writes a crash snapshot OUTDIR/crash_stepNNNNNN.hdf5 and stops with one
 *  line and exit status 3.  Called at every line of the statistics file
 *  (where the particles are on the host anyway). */
static void engine_check_angular_momentum(struct engine *e, const struct engine_totals *t,
                                          const struct budget_removed *r) {
  const double bound = params_get_real(e->params, "Statistics:max_angular_momentum_change");
  if (!(bound > 0.0)) return;
  const double L[3] = {t->L[0] + r->L[0], t->L[1] + r->L[1], t->L[2] + r->L[2]};
  const double p[3] = {t->p[0] + r->p[0], t->p[1] + r->p[1], t->p[2] + r->p[2]};
  /* (as the budget line; < 0: nothing to compare with, a warning at the start) */
  const double rel = engine_dL_about_com(&e->budget0, L, p);
  if (!(rel > bound)) return;
  char path[2100];
  snprintf(path, sizeof path, "%s/crash_step%06ld.hdf5", e->outdir, e->step);
  engine_snapshot_to(e, path);
  error_exit_status(
      3,
      "angular momentum check: |L - L(0)| / |L(0)| = %.3e (about the start's centre of mass) at "
      "step %ld (t = %g) exceeds Statistics:max_angular_momentum_change = %g; crash snapshot %s",
      rel, e->step, e->time, bound, path);
}

/** The start of the angular-momentum check: it needs an open box (a periodic
 *  box does not conserve L) and some angular momentum to measure against. */
static void engine_check_angular_momentum_start(struct engine *e) {
  const double bound = params_get_real(e->params, "Statistics:max_angular_momentum_change");
  if (!(bound > 0.0)) return;
  if (e->space.periodic)
    params_error(e->params, "Statistics:max_angular_momentum_change",
                 "the angular-momentum check needs an open box (a periodic box does not conserve "
                 "angular momentum)");
  const struct budget_start *b = &e->budget0;
  if (engine_dL_about_com(b, b->L, b->p) < 0.0) /* (about the start's centre of mass) */
    error_warning(
        "Statistics:max_angular_momentum_change: the angular momentum is 0 at the start; "
        "the check is off");
}

void engine_stats_write(struct engine *e) {
#ifdef HAVE_CUDA
  gpu_engine_to_host(e); /* the particles may be resident on the GPU */
#endif
  struct engine_totals t;
  engine_totals(e, &t);
  if (!(e->budget0.set > 0.0)) {
    engine_budget_start(e, &t);
    engine_check_angular_momentum_start(e);
  }
  struct budget_removed rm;
  long long nr_removed;
  engine_removed(e, &rm, &nr_removed);
  const struct budget_removed *r = &rm;
  const double etot = t.E_kin + t.E_int + t.E_pot;
  const double dE = etot + r->E - t.E_clamp - e->budget0.E_tot;
  e->stats_last_step = e->step;
  if (!e->stats) { /* (another MPI rank than 0) */
    engine_check_angular_momentum(e, &t, r);
    return;
  }
  fprintf(
      e->stats,
      "%ld %.12e %.6e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %zu %lld"
      " %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.6e\n",
      e->step, e->time, e->dt, t.mass, t.p[0], t.p[1], t.p[2], t.L[0], t.L[1], t.L[2], t.E_kin,
      t.E_int, t.E_pot, etot, engine_nr_real(e), nr_removed, r->m, r->E, r->p[0], r->p[1], r->p[2],
      r->L[0], r->L[1], r->L[2], t.E_clamp, t.W_plastic, dE);
  if (fflush(e->stats)) error_exit("cannot write the statistics file (disk full?)");
  engine_check_angular_momentum(e, &t, r);
}

void engine_stats_close(struct engine *e) {
  /* the closing line, unless this step has one already (-n 1 with lines
   * every step wrote step 1 twice) */
  if (e->stats_last_step != e->step) engine_stats_write(e);
}

void engine_stats_first(struct engine *e) {
  /* the budget starts now, whether or not Statistics:time_first puts the
   * first line later */
  if (!(e->budget0.set > 0.0)) {
#ifdef HAVE_CUDA
    gpu_engine_to_host(e);
#endif
    struct engine_totals t;
    engine_totals(e, &t);
    engine_budget_start(e, &t);
    engine_check_angular_momentum_start(e);
  }
  engine_stats_maybe(e);
}

void engine_budget_summary(struct engine *e) {
#ifdef HAVE_CUDA
  gpu_engine_to_host(e);
#endif
  struct engine_totals t;
  engine_totals(e, &t);
  const struct budget_start *b = &e->budget0;
  struct budget_removed rm;
  long long nr_removed;
  engine_removed(e, &rm, &nr_removed);
  const struct budget_removed *r = &rm;
  if (!(b->set > 0.0)) return;
  const double etot = t.E_kin + t.E_int + t.E_pot;
  const double dE = etot + r->E - t.E_clamp - b->E_tot;
  /* the scale of energy errors: |E_pot(0)| with self-gravity (as SWIFT's
   * planetary runs report it), else the sum of the magnitudes of the parts */
  const double Escale = fabs(b->E_pot) > 0.0 ? fabs(b->E_pot) : b->E_abs;
  double dp2 = 0.0, dL2 = 0.0, L02 = 0.0, L[3], p[3];
  for (int k = 0; k < 3; k++) {
    L[k] = t.L[k] + r->L[k];
    p[k] = t.p[k] + r->p[k];
    dp2 += (p[k] - b->p[k]) * (p[k] - b->p[k]);
    dL2 += (L[k] - b->L[k]) * (L[k] - b->L[k]);
    L02 += b->L[k] * b->L[k];
  }
  const double dLc = engine_dL_about_com(b, L, p);
  error_log(
      0,
      "conservation budget against the start: dE / |%s| = %.3e (E_tot %+.6e -> %+.6e; removed "
      "with %lld particles %+.3e; kick's floor on u %+.3e; plastic work %.3e, part of E_int)",
      fabs(b->E_pot) > 0.0 ? "E_pot(0)" : "E(0)", Escale > 0.0 ? dE / Escale : 0.0, b->E_tot, etot,
      nr_removed, r->E, t.E_clamp, t.W_plastic);
  error_log(0,
            "conservation budget against the start: |dL| / |L(0)| = %.3e about the centre of mass "
            "of the start (%.3e about the origin), |dp| / sum m|v|(0) = %.3e",
            dLc > 0.0 ? dLc : 0.0, L02 > 0.0 ? sqrt(dL2 / L02) : 0.0,
            b->p_abs > 0.0 ? sqrt(dp2) / b->p_abs : 0.0);
}

void engine_stats_maybe(struct engine *e) {
  if (e->time >= e->next_stats || e->time >= e->time_end) {
    engine_stats_write(e);
    /* the next multiple of stats_dt after now: by addition as always, but
     * after 1000 additions in one jump (a stats_dt of 1e-308 would take for
     * ever), and at least the next double (at a time of large magnitude
     * adding stats_dt changes nothing) */
    if (e->stats_dt > 0.0)
      for (int k = 0; e->next_stats <= e->time; k++) {
        double next = e->next_stats + e->stats_dt;
        if (k == 1000)
          next =
              e->next_stats + e->stats_dt * (floor((e->time - e->next_stats) / e->stats_dt) + 1.0);
        e->next_stats = next > e->next_stats ? next : nextafter(e->time, INFINITY);
      }
  }
}

void engine_snapshot(struct engine *e) {
  if (!e->snap_enabled) return; /* (Snapshots:enabled: false) */
  char path[2048];
  snprintf(path, sizeof path, "%s/%s_%04d.hdf5", e->outdir, e->snap_basename, e->snap_index);
  engine_snapshot_to(e, path);
  e->snap_index++;
  if (ranks_rank() == 0) snapshot_write_series(e->outdir, e->snap_basename, e->snap_index);
}

/** A copy of the particles without the mirror ghosts and the foreign
 *  copies (PART_NOT_OWNED; the snapshots' particles). */
static void engine_real_parts(const struct engine *e, struct parts *out) {
  const struct parts *p = &e->parts;
  parts_alloc_like(out, p->count - e->nr_mirror - e->nr_foreign, p);
  size_t n = 0;
  for (size_t i = 0; i < p->count; i++) {
    if (p->flags[i] & PART_NOT_OWNED) continue;
    for (int f = 0; f < part_nr_fields; f++) {
      const struct part_field *pf = &part_fields[f];
      if (p->absent[f]) continue;
      memcpy((char *)part_field_array(out, pf) + n * pf->size,
             (const char *)part_field_array(p, pf) + i * pf->size, pf->size);
    }
    n++;
  }
}

/** The snapshot's header of the run now. */
static void engine_snapshot_meta(const struct engine *e, struct snapshot_meta *meta) {
  memset(meta, 0, sizeof *meta);
  meta->time = e->time;
  for (int k = 0; k < 3; k++) meta->box_size[k] = e->space.dim[k];
  meta->periodic = e->space.periodic;
  meta->run_name = params_get_string(e->params, "MetaData:run_name");
  meta->params = e->params_text;
  meta->hydro = e->hp.enabled;
  meta->self_gravity = e->gp.enabled;
  meta->compression = e->compression;
}

void engine_snapshot_rank(struct engine *e, const char *path) {
#ifdef HAVE_CUDA
  gpu_engine_to_host(e);
#endif
  struct snapshot_meta meta;
  engine_snapshot_meta(e, &meta);
  snapshot_write(path, &meta, &e->parts, &e->us, e->write_acc);
}

void engine_snapshot_to(struct engine *e, const char *path) {
#ifdef HAVE_CUDA
  gpu_engine_to_host(e);
#endif
  struct snapshot_meta meta;
  engine_snapshot_meta(e, &meta);
  if (e->halo && snapshot_parallel()) {
    /* several MPI ranks: one file, each rank writing its own particles'
     * rows (parallel HDF5) */
    struct parts own;
    engine_real_parts(e, &own);
    snapshot_write_ranks(path, &meta, &own, &e->us, e->write_acc);
    parts_free(&own);
  } else if (e->halo) {
    /* several MPI ranks without parallel HDF5: rank 0 gathers every rank's
     * own and writes them */
    struct parts all;
    halo_gather(e, &all);
    if (ranks_rank() == 0) snapshot_write(path, &meta, &all, &e->us, e->write_acc);
    parts_free(&all);
  } else if (e->nr_mirror) {
    /* the real particles only: a copy without the mirror ghosts */
    struct parts real;
    engine_real_parts(e, &real);
    snapshot_write(path, &meta, &real, &e->us, e->write_acc);
    parts_free(&real);
  } else {
    snapshot_write(path, &meta, &e->parts, &e->us, e->write_acc);
  }
  error_log(0, "snapshot %s at t = %g%s", path, e->time,
            e->halo ? (snapshot_parallel() ? " (every rank its rows: parallel HDF5)"
                                           : " (gathered on rank 0)")
                    : "");
}

void engine_dump_tasks(struct engine *e) {
  char path[2048];
  if (e->halo) /* (several MPI ranks: a file per rank) */
    snprintf(path, sizeof path, "%s/tasks_step%06ld_rank%d.txt", e->outdir, e->step, ranks_rank());
  else
    snprintf(path, sizeof path, "%s/tasks_step%06ld.txt", e->outdir, e->step);
  FILE *f = fopen(path, "w");
  if (!f) error_exit("%s: cannot create the task dump", path);
  scheduler_dump_tasks(&e->sched, f);
  fclose(f);
}
