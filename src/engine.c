#define _GNU_SOURCE /* sched_getaffinity */
/* The engine: initialisation and the time-step loop (see engine.h). */
#include "src/engine.h"

#include <dirent.h>
#include <errno.h>
#include <sched.h>
#include <signal.h>
#include <float.h>
#include <libgen.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "src/engine_tasks.h"
#include "src/error.h"
#include "src/io/ic.h"
#include "tasks/hydro/kernel.h"
#include "src/materials/material.h"
#include "src/io/params.h"
#include "src/materials/porosity_eos.h"
#include "src/io/restart.h"
#include "src/mpi/halo.h"
#include "src/mpi/ranks.h"
#include "src/version.h"
#include "tasks/task_families.h"
#include "src/gpu/gpu_policy.h"
#ifdef HAVE_CUDA
#include "src/gpu/gpu_engine.h"
#endif

/* ------------------------------------------------------------------------ */
/* initial conditions                                                        */

/** Resolve the IC path: relative paths are relative to the parameter file. */
static void engine_ic_path(const struct params *p, char *out, size_t len) {
  const char *f = params_get_string(p, "InitialConditions:file_name");
  if (f[0] == '/') {
    snprintf(out, len, "%s", f);
    return;
  }
  char tmp[PATH_MAX];
  snprintf(tmp, sizeof tmp, "%s", params_filename(p));
  const char *dir = dirname(tmp);
  if (strcmp(dir, ".") == 0)
    snprintf(out, len, "%s", f);
  else
    snprintf(out, len, "%s/%s", dir, f);
}

/** Smoothing lengths for ICs that have none: eta times the mean spacing of
 *  the bounding box (the iteration then finds each particle's own). */
static void engine_guess_h(struct engine *e) {
  struct parts *p = &e->parts;
  size_t missing = 0;
  for (size_t i = 0; i < p->count; i++) missing += !(p->h[i] > 0.0);
  if (missing == 0 || p->count == 0) return;
  double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
  for (size_t i = 0; i < p->count; i++) {
    const double x[3] = {p->x[i], p->y[i], p->z[i]};
    for (int k = 0; k < 3; k++) {
      if (x[k] < lo[k]) lo[k] = x[k];
      if (x[k] > hi[k]) hi[k] = x[k];
    }
  }
  double vol = 1.0;
  for (int k = 0; k < 3; k++) vol *= fmax(hi[k] - lo[k], 1e-300);
  const double h0 = e->hp.eta * cbrt(vol / (double)p->count);
  for (size_t i = 0; i < p->count; i++)
    if (!(p->h[i] > 0.0)) p->h[i] = h0;
  error_log(0, "%zu particles had no smoothing length: initial guess h = %g", missing, h0);
}

/** The number of cores this process may run on (its CPU affinity set). */
static int engine_nr_cores(void) {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    const int n = CPU_COUNT(&set);
    if (n > 0) return n;
  }
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? (int)n : 1;
}

/* ------------------------------------------------------------------------ */
/* output times                                                              */

static int engine_cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/** The snapshot times after time_begin: from Snapshots:output_list, or
 *  time_first + k delta_time; time_end is always an output time. */
static void engine_init_outputs(struct engine *e, double t0) {
  const struct params *p = e->params;
  const char *list = params_get_bool(p, "Snapshots:output_list_on")
                         ? params_get_string(p, "Snapshots:output_list")
                         : "";
  int cap = 16, n = 0;
  double *t = error_malloc(cap * sizeof(double), "output times");
  if (list[0]) {
    FILE *f = fopen(list, "r");
    if (!f) error_exit("%s: cannot open the output list: %s", list, strerror(errno));
    char line[256];
    int lineno = 0;
    while (fgets(line, sizeof line, f)) {
      lineno++;
      char *s = line;
      while (*s == ' ' || *s == '\t') s++;
      if (*s == '#' || *s == '\n' || *s == '\0') continue;
      if (!strncmp(s, "Time", 4)) continue; /* SWIFT's header line */
      char *end;
      const double v = strtod(s, &end);
      if (end == s || !isfinite(v))
        error_exit("%s:%d: expected an output time, found '%.40s'", list, lineno, s);
      if (n == cap) t = error_realloc(t, (cap *= 2) * sizeof(double), "output times");
      t[n++] = v;
    }
    fclose(f);
  } else {
    const double first = params_get_real(p, "Snapshots:time_first");
    const double delta = params_get_real(p, "Snapshots:delta_time");
    if (delta > 0.0) {
      for (long k = 0;; k++) {
        const double v = first + (double)k * delta;
        if (v > e->time_end * (1.0 + 1e-12)) break;
        if (k > 1000000)
          error_exit("Snapshots:delta_time %g gives more than a million snapshots", delta);
        if (n == cap) t = error_realloc(t, (cap *= 2) * sizeof(double), "output times");
        t[n++] = v;
      }
    } else if (first > t0 && first < e->time_end) {
      t[n++] = first;
    }
  }
  if (n == cap) t = error_realloc(t, (cap += 1) * sizeof(double), "output times");
  t[n++] = e->time_end;
  qsort(t, n, sizeof(double), engine_cmp_double);
  /* keep the times strictly after t0, without duplicates */
  int m = 0;
  for (int k = 0; k < n; k++) {
    if (t[k] <= t0 * (1.0 + 1e-14) + 1e-300 && t[k] <= t0) continue;
    if (m > 0 && fabs(t[k] - t[m - 1]) <= 1e-12 * fabs(t[k])) continue;
    if (t[k] > e->time_end) continue;
    t[m++] = t[k];
  }
  e->out_times = t;
  e->nr_out = m;
  e->next_out = 0;
}

/** Remove the temporary snapshot files (BASENAME_*.tmp, crash_step*.tmp) that
 *  a killed run left in the output folder. */
static void engine_remove_stale_snapshots(const struct engine *e) {
  DIR *d = opendir(e->outdir);
  if (!d) return;
  const size_t nb = strlen(e->snap_basename);
  struct dirent *ent;
  while ((ent = readdir(d))) {
    const char *n = ent->d_name;
    const size_t l = strlen(n);
    if (l < 4 || strcmp(n + l - 4, ".tmp")) continue;
    if (!((!strncmp(n, e->snap_basename, nb) && n[nb] == '_') || !strncmp(n, "crash_step", 10)))
      continue;
    char path[2400];
    snprintf(path, sizeof path, "%s/%s", e->outdir, n);
    if (unlink(path) == 0)
      error_log(0, "removed %s, left by a run that stopped while writing it", path);
  }
  closedir(d);
}

/** Create the output folder (and parents) if missing. */
static void engine_mkdir(const char *dir) {
  char tmp[1024];
  snprintf(tmp, sizeof tmp, "%s", dir);
  for (char *s = tmp + 1; *s; s++)
    if (*s == '/') {
      *s = '\0';
      if (mkdir(tmp, 0755) && errno != EEXIST)
        error_exit("%s: cannot create folder: %s", tmp, strerror(errno));
      *s = '/';
    }
  if (mkdir(tmp, 0755) && errno != EEXIST)
    error_exit("%s: cannot create folder: %s", tmp, strerror(errno));
}

/** Index of the particle field called name in part_fields. */
static int engine_field_index(const char *name) {
  for (int k = 0; k < part_nr_fields; k++)
    if (strcmp(part_fields[k].name, name) == 0) return k;
  error_bug("no particle field %s", name);
}

/** Distentions of porous materials from the initial conditions (file icname;
 *  has_alpha: the file has Distentions): alpha_0 of the material where the
 *  file has none, 1 for every other particle; then the check that the bulk
 *  density times alpha is the matrix density rho0 of the material's EOS
 *  within Porosity:ic_tolerance (Jutzi et al. 2008; theory/porosity.md). */
static void engine_init_porosity(struct engine *e, const char *icname, int has_alpha) {
  struct parts *p = &e->parts;
  for (int k = 0; k < e->mats->n; k++) {
    const struct material *m = &e->mats->mats[k];
    if (m->porosity.model != POROSITY_NONE) e->porous = 1;
  }
  const double tol = params_get_real(e->params, "Porosity:ic_tolerance");
  for (size_t i = 0; i < p->count; i++) {
    const struct material *m = material_table_find(e->mats, p->mat[i]);
    /* 0: not given (bolide-ic writes every IC field, zero where it has no value) */
    if (!m || m->porosity.model == POROSITY_NONE) {
      if (has_alpha && p->alpha[i] != 1.0 && p->alpha[i] != 0.0)
        error_exit(
            "%s: particle %zu (id %lld): Distentions is %g but material %d is not porous (must be "
            "1)",
            icname, i, (long long)p->id[i], p->alpha[i], (int)p->mat[i]);
      p->alpha[i] = p->alpha_p[i] = 1.0;
      continue;
    }
    const double alpha_0 = porosity_alpha_0(&m->porosity);
    if (!has_alpha || p->alpha[i] == 0.0) p->alpha[i] = alpha_0;
    if (!(p->alpha[i] >= 1.0) || p->alpha[i] > alpha_0)
      error_exit(
          "%s: particle %zu (id %lld): Distentions is %g (must be in [1, alpha_0 = %g] for "
          "material '%s')",
          icname, i, (long long)p->id[i], p->alpha[i], alpha_0, m->name);
    if (!(p->rho[i] > 0.0))
      error_exit(
          "%s: particle %zu (id %lld) of porous material '%s' has no density: porous bodies need "
          "Densities in the initial conditions (the bulk density rho0/alpha)",
          icname, i, (long long)p->id[i], m->name);
    const double err = porosity_check_ic(p->rho[i], p->alpha[i], m->rho0, tol);
    if (err > 0.0)
      error_exit(
          "%s: particle %zu (id %lld) of porous material '%s': density %g times distention %g is "
          "%g, "
          "not the matrix density rho0 = %g (relative difference %.3g > Porosity:ic_tolerance %g)",
          icname, i, (long long)p->id[i], m->name, p->rho[i], p->alpha[i], p->rho[i] * p->alpha[i],
          m->rho0, err, tol);
    p->alpha_p[i] = p->alpha[i];
  }
  if (e->porous) {
    size_t n = 0;
    for (size_t i = 0; i < p->count; i++) n += p->alpha[i] > 1.0;
    error_log(
        0,
        "porosity: %zu porous particles (P-alpha: Jutzi et al. 2008; epsilon-alpha: Wuennemann et "
        "al. 2006, Collins et al. 2011), distentions %s",
        n,
        has_alpha ? "from the initial conditions (alpha_0 where 0)" : "alpha_0 of their materials");
  }
}

/** Positions and velocities that no run can follow, refused with one line
 *  (issue 18): in a periodic box, a position more than one box size outside
 *  [0, L) after the shift (wrapping 1e300 would silently give 0); a speed
 *  above that of light (1e200 moved every particle to one point in the first
 *  step, and the smoothing lengths were blamed minutes later). */
static void engine_check_ic_motion(const struct engine *e, const char *icname, const double box[3],
                                   int periodic) {
  const struct parts *p = &e->parts;
  const double c_light = 2.99792458e10 / units_cgs_factor(&e->us, 0, 1, -1);
  for (size_t i = 0; i < p->count; i++) {
    const double x[3] = {p->x[i], p->y[i], p->z[i]};
    for (int k = 0; periodic && k < 3; k++)
      if (!(x[k] >= -box[k] && x[k] < 2.0 * box[k]))
        error_exit(
            "%s: particle %zu (id %lld): position %c = %g is more than a box size outside the "
            "periodic box [0, %g)",
            icname, i, (long long)p->id[i], "xyz"[k], x[k], box[k]);
    const double v = hypot(hypot(p->vx[i], p->vy[i]), p->vz[i]);
    const struct material *mat = material_table_find(e->mats, p->mat[i]);
    if (mat && mat->boundary && v != 0.0)
      error_exit(
          "%s: particle %zu (id %lld): a fixed boundary particle (material %d '%s', "
          "boundary: true) must be at rest (speed %g)",
          icname, i, (long long)p->id[i], (int)p->mat[i], mat->name, v);
    if (!(v < c_light))
      error_exit(
          "%s: particle %zu (id %lld): speed %g is above the speed of light (%g in internal units)",
          icname, i, (long long)p->id[i], v, c_light);
  }
}

/** The hooks of every family at point when (TASK_FAMILY_HOOKS), in the
 *  registry's order. */
static void engine_family_hooks(struct engine *e, enum task_family_when when) {
#define ENGINE_FAMILY_HOOK_(family, at, fn) \
  if (when == task_family_at_##at) fn(e);
  TASK_FAMILY_HOOKS(ENGINE_FAMILY_HOOK_)
#undef ENGINE_FAMILY_HOOK_
}

/** The solid state and the fracture fields (part_solid_fields,
 *  part_damage_fields: 43 doubles and 6 damage fields, 384 of a particle's
 *  824 bytes) are not held in a run that never uses them: no stress (no
 *  material with strength or viscosity, no CSPM continuity, no free-surface
 *  detection: hp.solids), no damage (no brittle material), the
 *  kick-drift-kick scheme (the rk2 and pc integrators' states hold the
 *  stress), and every particle's values zero (what the initial conditions
 *  or a restart file gave stays).  The same on every rank.  The GPU leaves
 *  them off the device too (gpu_engine_absent).  Marks them in unused
 *  (part_nr_fields flags) and returns 1 where the run's settings allow it,
 *  else 0. */
static int engine_unused_fields(const struct engine *e, unsigned char *unused) {
  memset(unused, 0, (size_t)part_nr_fields);
  if (e->hp.solids || params_get_enum(e->params, "TimeIntegration:scheme") != ENGINE_SCHEME_KDK)
    return 0;
  for (int k = 0; k < e->mats->n; k++)
    if (material_is_brittle(&e->mats->mats[k])) return 0;
  for (int k = 0; k < part_nr_fields; k++)
    for (int g = 0; g < 2; g++) {
      const char *const *l = g ? part_damage_fields : part_solid_fields;
      const int n = g ? part_nr_damage_fields : part_nr_solid_fields;
      for (int q = 0; q < n; q++) unused[k] |= !strcmp(part_fields[k].name, l[q]);
    }
  return 1;
}

/** After the particles are read: the fields of engine_unused_fields dropped
 *  where every particle's values are zero (the initial conditions read
 *  without them leave nothing to drop). */
static void engine_drop_unused_fields(struct engine *e) {
  struct parts *p = &e->parts;
  unsigned char unused[PART_NR_FIELDS];
  int keep = !engine_unused_fields(e, unused);
  for (int k = 0; k < part_nr_fields && !keep; k++)
    if (unused[k] && !part_field_zero(p, k, 0, p->count)) keep = 1;
  if (ranks_size() > 1 && !e->opt.one_rank) keep = ranks_any(keep);
  if (keep) return;
  parts_drop(p, part_solid_fields, part_nr_solid_fields);
  parts_drop(p, part_damage_fields, part_nr_damage_fields);
}

/** Read the initial conditions named by the parameters into e->parts, with
 *  the box size (from the file or InitialConditions:box_size), the shift and
 *  the smoothing-length scaling applied. */
static void engine_read_ics(struct engine *e, char *icname, size_t len, double box[3]) {
  const struct params *params = e->params;
  engine_ic_path(params, icname, len);
  struct ic_info hdr;
  const int nids = e->mats->n;
  int32_t *ids = error_malloc(nids * sizeof(int32_t), "material ids");
  for (int k = 0; k < nids; k++) ids[k] = e->mats->mats[k].id;
  unsigned char unused[PART_NR_FIELDS];
  ic_read_unused(icname, &e->us, ids, nids, &e->parts, &hdr,
                 engine_unused_fields(e, unused) ? unused : NULL);
  free(ids);
  for (int k = 0; k < 3; k++) box[k] = hdr.box_size[k];
  double b[3];
  const int nb = params_get_real_array(params, "InitialConditions:box_size", b, 3);
  if (nb == 1)
    box[0] = box[1] = box[2] = b[0];
  else if (nb == 3)
    for (int k = 0; k < 3; k++) box[k] = b[k];
  else if (nb != 0)
    params_error(params, "InitialConditions:box_size", "expected 1 or 3 values, got %d", nb);
  for (int k = 0; k < 3; k++)
    if (!(box[k] > 0.0))
      error_exit("%s: the box size is not positive (%g); set InitialConditions:box_size", icname,
                 box[k]);
  double shift[3];
  params_get_real_array(params, "InitialConditions:shift", shift, 3);
  const double hscale = params_get_real(params, "InitialConditions:smoothing_length_scaling");
  for (size_t i = 0; i < e->parts.count; i++) {
    e->parts.x[i] += shift[0];
    e->parts.y[i] += shift[1];
    e->parts.z[i] += shift[2];
    e->parts.h[i] *= hscale;
    e->parts.vpx[i] = e->parts.vx[i];
    e->parts.vpy[i] = e->parts.vy[i];
    e->parts.vpz[i] = e->parts.vz[i];
    e->parts.up[i] = e->parts.u[i];
    /* continuity density from the ICs' Densities (0: from the first summation) */
    e->parts.rho_full[i] = e->parts.rho_fp[i] = e->parts.rho[i];
  }
  engine_family_hooks(e, task_family_at_ic);
  engine_check_ic_motion(e, icname, box, params_get_bool(params, "InitialConditions:periodic"));
  engine_init_porosity(e, icname, ic_field_read(&hdr, engine_field_index("alpha")));
}

/* ------------------------------------------------------------------------ */
/* signals and batch limits (issue 18 item 2)                                */

/** The signal received (0: none): the step loop writes a restart file and
 *  stops after the step in progress; a second signal stops at once. */
static volatile sig_atomic_t engine_signal;

static void engine_on_signal(int sig) {
  if (engine_signal) {
    static const char msg[] = "bolide: second signal: stopping at once, without a restart file\n";
    ssize_t r = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)r;
    _exit(128 + sig);
  }
  engine_signal = sig;
}

/** SIGTERM, SIGINT, SIGHUP and SIGUSR1 ask the run to stop with a restart file. */
static void engine_signals_install(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = engine_on_signal;
  sa.sa_flags = SA_RESTART;
  sigemptyset(&sa.sa_mask);
  const int sigs[] = {SIGTERM, SIGINT, SIGHUP, SIGUSR1};
  for (int k = 0; k < 4; k++) sigaction(sigs[k], &sa, NULL);
}

static const char *engine_signal_name(int sig) {
  switch (sig) {
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    case SIGHUP:
      return "SIGHUP";
    case SIGUSR1:
      return "SIGUSR1";
    default:
      return "a signal";
  }
}

/** Why the run must stop now with a restart file (a signal, the stop file
 *  in the restart folder, Restarts:max_run_time), written into why; 0: go
 *  on.  The stop file is removed. */
static int engine_must_stop(struct engine *e, char *why, size_t len) {
  if (engine_signal) {
    snprintf(why, len, "%s received", engine_signal_name(engine_signal));
    return 1;
  }
  char stop[1100];
  snprintf(stop, sizeof stop, "%s/stop", e->restart_dir);
  if (e->step % e->restart_stop_steps == 0 && access(stop, F_OK) == 0) {
    if (unlink(stop)) error_warning("%s: cannot remove the stop file: %s", stop, strerror(errno));
    snprintf(why, len, "stop file %.1000s found", stop);
    return 1;
  }
  if (e->restart_max_wall > 0.0 && error_walltime() >= e->restart_max_wall) {
    snprintf(why, len, "Restarts:max_run_time of %g h reached", e->restart_max_wall / 3600.0);
    return 1;
  }
  return 0;
}

/* ------------------------------------------------------------------------ */
/* the watchdog (issue 18 item 7)                                            */

/** Index of the top-level cell that holds particle i (cells own contiguous
 *  ranges), -1 if none. */
static int engine_cell_of(const struct engine *e, size_t i) {
  for (int c = 0; c < e->space.nr_top; c++)
    if (i >= e->space.cells[c].offset && i < e->space.cells[c].offset + e->space.cells[c].count)
      return c;
  return -1;
}

/** Stop the run: one line naming the particle, the field, the step and the
 *  cell; the state goes to a crash snapshot OUTDIR/crash_stepNNNNNN.hdf5 (no
 *  restart file: the last one stays the one to resume from). */
static void engine_watchdog_fail(struct engine *e, size_t i, const char *what) {
  const int c = engine_cell_of(e, i);
  char path[2100];
  fflush(stdout);
  if (e->halo) {
    /* several MPI ranks: the other ranks do not stop here to gather; this
     * rank writes what it holds, its foreign copies included */
    snprintf(path, sizeof path, "%s/crash_step%06ld_rank%d.hdf5", e->outdir, e->step, ranks_rank());
    engine_snapshot_rank(e, path);
  } else {
    snprintf(path, sizeof path, "%s/crash_step%06ld.hdf5", e->outdir, e->step);
    engine_snapshot_to(e, path);
  }
  error_exit(
      "watchdog: step %ld (t = %g): particle id %lld (index %zu, top-level cell %d at (%g, %g, "
      "%g)): %s; "
      "crash snapshot %s, the last restart file stays the one to resume from",
      e->step, e->time, (long long)e->parts.id[i], i, c, c >= 0 ? e->space.cells[c].loc[0] : 0.0,
      c >= 0 ? e->space.cells[c].loc[1] : 0.0, c >= 0 ? e->space.cells[c].loc[2] : 0.0, what, path);
}

/** BOLIDE_TEST_INJECT=STEP:FIELD:VALUE (for the tests only): at the end of
 *  step STEP, particle field FIELD of the particle in the middle of the array
 *  is set to VALUE (nan, inf, -1, 1e9...). */
static void engine_watchdog_init(struct engine *e) {
  const char *s = getenv("BOLIDE_TEST_INJECT");
  if (!s || !*s) return;
  char field[32];
  long step;
  char value[64];
  if (sscanf(s, "%ld:%31[^:]:%63s", &step, field, value) != 3 || step < 1)
    error_exit("BOLIDE_TEST_INJECT '%s': expected STEP:FIELD:VALUE", s);
  char *end;
  e->wd_inject_value = strtod(value, &end);
  if (*end) error_exit("BOLIDE_TEST_INJECT '%s': '%s' is not a number", s, value);
  int k = 0;
  while (k < part_nr_fields &&
         (strcmp(part_fields[k].name, field) || part_fields[k].type != PART_DOUBLE))
    k++;
  if (k == part_nr_fields)
    error_exit("BOLIDE_TEST_INJECT '%s': no double particle field '%s'", s, field);
  snprintf(e->wd_inject_field, sizeof e->wd_inject_field, "%s", field);
  e->wd_inject_step = step;
  error_warning("BOLIDE_TEST_INJECT: %s of one particle set to %g at the end of step %ld", field,
                e->wd_inject_value, step);
}

/** Remember the positions before the drift (the displacement check; on
 *  the GPU a copy on the device). */
void engine_watchdog_before_drift(struct engine *e) {
#ifdef HAVE_CUDA
  if (e->gpu) {
    const double w0 = error_walltime();
    gpu_engine_watchdog_save(e);
    e->t_watchdog += error_walltime() - w0;
    return;
  }
#endif
  const struct parts *p = &e->parts;
  e->wd_x =
      error_realloc(e->wd_x, 3 * (p->count ? p->count : 1) * sizeof(double), "watchdog positions");
  memcpy(e->wd_x, p->x, p->count * sizeof(double));
  memcpy(e->wd_x + p->count, p->y, p->count * sizeof(double));
  memcpy(e->wd_x + 2 * p->count, p->z, p->count * sizeof(double));
}

/** After the drift: no particle may have moved more than the width of a
 *  top-level cell (the neighbour search would miss its neighbours). */
void engine_watchdog_after_drift(struct engine *e) {
  const struct parts *p = &e->parts;
  const size_t n = p->count;
  double w = e->space.width[0];
  for (int k = 1; k < 3; k++)
    if (e->space.width[k] < w) w = e->space.width[k];
  long gpu_bad = -1;
#ifdef HAVE_CUDA
  if (e->gpu) {
    /* the check on the device; the host's positions are those after the
     * drift (gpu_drift copies them back), the saved ones come back only
     * when a particle moved too far, for the loop below to name it */
    const double w0 = error_walltime();
    e->wd_x = error_realloc(e->wd_x, 3 * (n ? n : 1) * sizeof(double), "watchdog positions");
    gpu_bad = gpu_engine_watchdog_moved(e, w, e->wd_x);
    e->t_watchdog += error_walltime() - w0;
    if (gpu_bad < 0) return;
  }
#endif
  if (!e->wd_x) return;
  for (size_t i = 0; i < n; i++) {
    const double dx = p->x[i] - e->wd_x[i], dy = p->y[i] - e->wd_x[n + i],
                 dz = p->z[i] - e->wd_x[2 * n + i];
    const double d = sqrt(dx * dx + dy * dy + dz * dz);
    if (!(d <= w) && !(p->flags[i] & PART_FOREIGN)) {
      char what[256];
      snprintf(what, sizeof what, "moved %g in one step (dt %g), more than its cell (width %g)", d,
               e->dt, w);
      e->step++; /* the step in progress */
      engine_watchdog_fail(e, i, what);
    }
  }
  if (gpu_bad >= 0) {
    /* (a displacement within rounding of the width: the device's verdict) */
    char what[256];
    snprintf(what, sizeof what,
             "moved more than its cell (width %g) in one step (dt %g) on the GPU", w, e->dt);
    e->step++;
    engine_watchdog_fail(e, (size_t)gpu_bad, what);
  }
}

/** One thread's share of the finiteness check: the double fields k with
 *  k % nt == t; bad != 0 if one holds a NaN or an Inf. */
struct engine_wd_job {
  const struct parts *p;
  int t, nt;
  int foreign; /**< 1: leave the foreign copies out (their owners check them) */
  uint64_t bad;
};

static void *engine_watchdog_scan(void *arg) {
  struct engine_wd_job *j = arg;
  for (int k = j->t; k < part_nr_fields; k += j->nt) {
    const struct part_field *f = &part_fields[k];
    if (f->type != PART_DOUBLE || j->p->absent[k]) continue;
    const double *a = part_field_array(j->p, f);
    uint64_t bad = 0;
    /* exponent all ones: Inf or NaN (a loop the compiler vectorises) */
    if (j->foreign)
      for (size_t i = 0; i < j->p->count; i++) {
        uint64_t w;
        memcpy(&w, &a[i], sizeof w);
        bad |= (uint64_t)((w & 0x7ff0000000000000ULL) == 0x7ff0000000000000ULL &&
                          !(j->p->flags[i] & PART_FOREIGN));
      }
    else
      for (size_t i = 0; i < j->p->count; i++) {
        uint64_t w;
        memcpy(&w, &a[i], sizeof w);
        bad |= (uint64_t)((w & 0x7ff0000000000000ULL) == 0x7ff0000000000000ULL);
      }
    j->bad |= bad;
  }
  return NULL;
}

/** After the step: every field finite, no negative density, no negative
 *  internal energy where the EOS forbids it (u_floor). */
static void engine_watchdog_after_step(struct engine *e) {
  struct parts *p = &e->parts;
  if (e->wd_inject_step == e->step && p->count) {
#ifdef HAVE_CUDA
    gpu_engine_to_host(e); /* the particles of a GPU run: changed on the host, uploaded again */
#endif
    double *a = NULL;
    for (int k = 0; k < part_nr_fields; k++)
      if (!strcmp(part_fields[k].name, e->wd_inject_field))
        a = part_field_array(p, &part_fields[k]);
    if (!a)
      error_exit("BOLIDE_TEST_INJECT: the field %s is not held in this run (no stress, no damage)",
                 e->wd_inject_field);
    a[p->count / 2] = e->wd_inject_value;
#ifdef HAVE_CUDA
    gpu_engine_host_modified(e);
#endif
  }
  const double w0 = error_walltime();
#ifdef HAVE_CUDA
  if (e->gpu) {
    /* the check on the device (one pass over its arrays); only when it
     * finds something do the particles come back, for the loops below to
     * name the particle and write the crash snapshot */
    const int bad = gpu_engine_watchdog_check(e);
    e->t_watchdog += error_walltime() - w0;
    if (!bad) return;
    gpu_engine_to_host(e);
  }
#endif
  /* the fields split over the engine's threads (memory bound: one pass) */
  int nt = e->nr_threads < 1 ? 1 : e->nr_threads > 64 ? 64 : e->nr_threads;
  if (p->count < 10000) nt = 1;
  struct engine_wd_job job[64];
  pthread_t th[64];
  /* (threads started by thread 0 inherit its core: spread them) */
  if (nt > 1) runner_unpin_self(&e->sched.pool);
  for (int t = 0; t < nt; t++) {
    job[t] = (struct engine_wd_job){p, t, nt, e->nr_foreign > 0, 0};
    if (t > 0 && pthread_create(&th[t], NULL, engine_watchdog_scan, &job[t]))
      nt = t; /* fewer threads */
  }
  engine_watchdog_scan(&job[0]);
  uint64_t bad = 0;
  for (int t = 0; t < nt; t++) {
    if (t > 0) pthread_join(th[t], NULL);
    bad |= job[t].bad;
  }
  if (nt > 1) runner_repin_self(&e->sched.pool);
  e->t_watchdog += error_walltime() - w0;
  for (int k = 0; k < part_nr_fields && bad; k++) {
    const struct part_field *f = &part_fields[k];
    if (f->type != PART_DOUBLE || p->absent[k]) continue;
    const double *a = part_field_array(p, f);
    for (size_t i = 0; i < p->count; i++)
      if (!isfinite(a[i]) && !(p->flags[i] & PART_FOREIGN)) {
        char what[256];
        snprintf(what, sizeof what, "field %s is %g", f->name, a[i]);
        engine_watchdog_fail(e, i, what);
      }
  }
  for (size_t i = 0; i < p->count; i++) {
    char what[256];
    if (p->flags[i] & PART_FOREIGN) continue; /* (several MPI ranks: the owner checks it) */
    if (p->rho[i] < 0.0) {
      snprintf(what, sizeof what, "field rho is %g (negative density)", p->rho[i]);
      engine_watchdog_fail(e, i, what);
    }
    if (p->u[i] < 0.0) {
      const struct material *m = material_table_find(e->mats, p->mat[i]);
      if (m && m->u_floor) {
        snprintf(what, sizeof what,
                 "field u is %g (negative internal energy; material '%s' needs u >= 0)", p->u[i],
                 m->name);
        engine_watchdog_fail(e, i, what);
      }
    }
  }
  if (e->gpu)
    error_bug("watchdog: the GPU found a bad particle, the host none after copying them back");
}

/* ------------------------------------------------------------------------ */

/** The ranks that run the particles: 1 with --partition's one rank, or
 *  without MPI. */
static int engine_ranks(const struct engine *e) {
  return ranks_size() > 1 && !e->opt.one_rank ? ranks_size() : 1;
}

/** --restart: which files to read (rank 0 decides, every rank learns).  -1:
 *  the run's own layout (STEM.bin with one rank, STEM_rankNNNN.bin of this
 *  number of ranks), also when no file exists (restart_read then says so);
 *  n > 1: the files of a run on n other ranks; 0: a one-rank run's STEM.bin
 *  read by several ranks. */
static int engine_restart_layout(const struct engine *e) {
  const int m = engine_ranks(e);
  int v = -1;
  if (ranks_rank() == 0) {
    int n = 0;
    const int one = restart_layout(e->restart_base, &n);
    if (n < 0 && !(m == 1 && one))
      error_exit("%s_rank0000.bin: not a restart file this build can read: %s", e->restart_base,
                 "resume it with the build that wrote it, or start the run again");
    if (m > 1 && n == m)
      v = -1;
    else if (m == 1 && one)
      v = -1;
    else if (n > 1)
      v = n;
    else if (one)
      v = 0;
  }
  if (m > 1) ranks_bcast_ints(&v, 1);
  return v;
}

void engine_init(struct engine *e, const struct params *params, const struct engine_options *opt) {
  memset(e, 0, sizeof *e);
  e->params = params;
  e->opt = *opt;
  units_init_from_params(&e->us, params);
  hydro_props_init(&e->hp, params);
  engine_family_hooks(e, task_family_at_init); /* self-gravity: e->gp, e->grav */
  if (!e->gp.enabled && !e->hp.enabled)
    params_error(params, "SPH:hydro", "neither hydrodynamics nor self-gravity is switched on");
  e->restarts = params_get_bool(params, "Restarts:enable");
  e->restart_dt_wall = 3600.0 * params_get_real(params, "Restarts:delta_hours");
  snprintf(e->restart_dir, sizeof e->restart_dir, "%s",
           params_get_string(params, "Restarts:subdir"));
  e->restart_delta_steps = params_get_int(params, "Restarts:delta_steps");
  e->restart_max_wall = 3600.0 * params_get_real(params, "Restarts:max_run_time");
  e->restart_stop_steps = params_get_int(params, "Restarts:stop_steps");
  snprintf(e->restart_base, sizeof e->restart_base, "%s/%s", e->restart_dir,
           params_get_string(params, "Restarts:basename"));
  snprintf(e->restart_stem, sizeof e->restart_stem, "%s", e->restart_base);
  if (ranks_size() > 1 && !e->opt.one_rank) {
    /* several MPI ranks: one file per rank (src/mpi/halo.h) */
    const size_t l = strlen(e->restart_stem);
    snprintf(e->restart_stem + l, sizeof e->restart_stem - l, "_rank%04d", ranks_rank());
  }
  engine_signals_install();
  restart_remove_stale(e->restart_stem);
  engine_watchdog_init(e);

  e->mats = error_calloc(1, sizeof(struct material_table), "material table");
  material_table_init(e->mats);
  material_table_from_params(e->mats, params);
  material_table_convert_units(e->mats, &e->us);
  /* solids: the gradient tasks and stress terms run only when a material
   * carries a deviatoric stress (strength, or a viscous fluid) */
  for (int k = 0; k < e->mats->n; k++)
    if (material_has_stress(&e->mats->mats[k])) e->hp.solids = 1;
  /* the CSPM continuity equation takes div v, and the free-surface detection
   * its kernel sum, from the gradient tasks: run them */
  if (e->hp.continuity_cspm || e->hp.free_surface) e->hp.solids = 1;
  /* the uniform external field (theory/boundaries.md), SWIFT's key in cm/s^2 */
  double g_cgs[3];
  params_get_real_array(params, "ConstantPotential:g_cgs", g_cgs, 3);
  for (int k = 0; k < 3; k++) {
    e->hp.g_ext[k] = g_cgs[k] / units_cgs_factor(&e->us, 0, 1, -2);
    if (g_cgs[k] != 0.0) e->hp.external = 1;
  }

  e->time = params_get_real(params, "TimeIntegration:time_begin");
  e->time_end = params_get_real(params, "TimeIntegration:time_end");
  e->dt_min = params_get_real(params, "TimeIntegration:dt_min");
  e->dt_max = params_get_real(params, "TimeIntegration:dt_max");
  if (e->time_end < e->time)
    params_error(params, "TimeIntegration:time_end", "time_end (%g) is before time_begin (%g)",
                 e->time_end, e->time);
  if (e->dt_min > e->dt_max)
    params_error(params, "TimeIntegration:dt_min", "dt_min (%g) is larger than dt_max (%g)",
                 e->dt_min, e->dt_max);
  e->individual = !params_get_bool(params, "TimeIntegration:global_step");
  e->hp.bin_limit =
      e->individual ? (int)params_get_int(params, "TimeIntegration:max_bin_ratio") : 0;
  e->hp.wake_density = e->hp.bin_limit > 0 && e->hp.bin_limit < TIMELINE_NR_BINS &&
                       params_get_enum(params, "TimeIntegration:limiter_wake") == 1;
  /* the time line of individual time steps (with the global step only to
   * report the bins that the particles' own limits would give, the
   * timesteps file) */
  e->timeline = timeline_make(e->time, e->time_end > e->time ? e->time_end : e->time + 1.0,
                              e->dt_max > 0.0 ? e->dt_max : e->time_end - e->time);

  double box[3];
  int periodic = params_get_bool(params, "InitialConditions:periodic");
  char icname[PATH_MAX];
  struct restart_state rs;
  memset(&rs, 0, sizeof rs);
  if (opt->restart) {
    /* the output times from time_begin: the file's output index counts in this list */
    engine_init_outputs(e, e->time);
    e->params_text = params_to_string(params);
    int32_t *ids = error_malloc((e->mats->n ? e->mats->n : 1) * sizeof(int32_t), "material ids");
    int32_t *u_floor =
        error_malloc((e->mats->n ? e->mats->n : 1) * sizeof(int32_t), "material flags");
    for (int k = 0; k < e->mats->n; k++) {
      ids[k] = e->mats->mats[k].id;
      u_floor[k] = e->mats->mats[k].u_floor;
    }
    const int64_t grav_doubles = gravity_cell_doubles();
    const struct restart_expect ex = {e->params_text, ids,          e->mats->n,
                                      e->nr_out,      e->time,      e->time_end,
                                      u_floor,        grav_doubles, flaws_check_values};
    struct restart_data rd;
    const int from = engine_restart_layout(e);
    if (from < 0) {
      restart_read(e->restart_stem, &ex, &rd, icname, sizeof icname);
    } else {
      /* another number of ranks wrote the files: their particles together,
       * every rank holding all of them as it would the initial conditions
       * (the first rebuild partitions them) */
      restart_read_ranks(e->restart_base, from, &ex, &rd, icname, sizeof icname);
      error_log(0, "resuming the files of a run on %d rank%s (%s ...) on %d", from > 0 ? from : 1,
                from > 1 ? "s" : "", icname, engine_ranks(e));
      e->restart_regrouped = 1;
      if (ranks_rank() != 0) { /* (rank 0 counts what left the box) */
        memset(&rd.st.removed, 0, sizeof rd.st.removed);
        rd.st.nr_removed = 0;
      }
    }
    snprintf(e->restart_file, sizeof e->restart_file, "%s", icname);
    free(ids);
    free(u_floor);
    rs = rd.st;
    e->parts = rd.p;
    e->flaw_eps = rd.flaw_eps;
    e->nr_flaws = rd.nr_flaws;
    e->restart_cells = rd.cells;
    gravity_restart_read(e, &rd.grav);
    for (int k = 0; k < 3; k++) box[k] = rs.box[k];
    periodic = (int)rs.periodic;
    e->time = rs.time;
    e->dt = rs.dt;
    e->step = rs.step;
    e->updates = rs.updates;
    e->nr_removed = rs.nr_removed;
    e->snap_index = (int)rs.snap_index;
    e->restart_dt_next = rs.dt_next;
    e->restart_h_max = rs.rebuild_h_max;
    e->need_rebuild = (int)rs.need_rebuild;
    e->restart_stats_offset = rs.stats_offset;
    e->ti_current = rs.ti_current;
    e->restarted = 1;
  } else {
    /* several ranks read the same file: rank 0 first, so that a problem
     * with it (missing, a dataset absent, a NaN, a negative mass) is
     * reported in one line, not once per rank (the others wait, and
     * mpirun stops them when rank 0 exits), as for the parameter file */
    const int first = ranks_size() > 1 && !opt->one_rank;
    int ics_ok = 0;
    if (first && ranks_rank() != 0) ranks_bcast_ints(&ics_ok, 1);
    engine_read_ics(e, icname, sizeof icname, box);
    if (first && ranks_rank() == 0) {
      ics_ok = 1;
      ranks_bcast_ints(&ics_ok, 1);
    }
  }
  if (opt->restart)
    for (int k = 0; k < e->mats->n; k++)
      e->porous |= e->mats->mats[k].porosity.model != POROSITY_NONE;
  engine_guess_h(e);
  snprintf(e->input_file, sizeof e->input_file, "%s", icname);
  engine_family_hooks(e, task_family_at_start);
  if (e->gp.enabled && periodic)
    params_error(params, "InitialConditions:periodic",
                 "self-gravity in a periodic box is not implemented");
  error_log(0, "read %zu particles from %s (box %g x %g x %g, %s)", e->parts.count, icname, box[0],
            box[1], box[2], periodic ? "periodic" : "open");

  /* outputs */
  const char *subdir = params_get_string(params, "Snapshots:subdir");
  snprintf(e->outdir, sizeof e->outdir, "%s", subdir);
  snprintf(e->snap_basename, sizeof e->snap_basename, "%s",
           params_get_string(params, "Snapshots:basename"));
  e->write_acc = params_get_bool(params, "Snapshots:accelerations");
  e->snap_enabled = params_get_bool(params, "Snapshots:enabled");
  e->compression = (int)params_get_int(params, "Snapshots:compression");
  e->stats_dt = params_get_real(params, "Statistics:delta_time");
  e->dump_tasks = params_get_int(params, "Scheduler:dump_tasks");
  e->cell_task_size = (int)params_get_int(params, "Scheduler:cell_task_size");
  e->grav_task_size = (int)params_get_int(params, "Scheduler:gravity_task_size");
  if (!e->restarted) engine_init_outputs(e, e->time);
  if (e->restarted) {
    e->next_out = (int)rs.next_out;
    e->next_stats = rs.next_stats;
  }

  /* cells and workers */
  /* self-gravity wants small leaves (P2P between neighbouring leaves is most of
   * its cost; BENCHMARKS.md): 32 unless the user chose */
  int split_size = (int)params_get_int(params, "Scheduler:cell_split_size");
  if (e->gp.enabled && !params_given(params, "Scheduler:cell_split_size")) split_size = 32;
  cell_loop_leaf_max = (int)params_get_int(params, "Scheduler:cpu_leaf_size");
  space_init(&e->space, &e->parts, box, periodic, split_size,
             (int)params_get_int(params, "Scheduler:max_top_level_cells"));
  e->space.max_drift_fraction = params_get_real(params, "Scheduler:rebuild_fraction");
  if (e->restarted) {
    e->space.removed = rs.removed;
    e->budget0 = rs.start;
  }
  e->nr_threads = opt->nr_threads > 0 ? opt->nr_threads : engine_nr_cores();
  e->space.nr_threads = e->nr_threads;
  error_log(0, "Bolide %s (git %s), kernel %s, %d threads, %s", PACKAGE_VERSION, BOLIDE_GIT_HASH,
            BOLIDE_KERNEL_NAME, e->nr_threads,
#ifdef HAVE_CUDA
            "CUDA build"
#else
            "CPU-only build: every task runs on the CPU"
#endif
  );
  error_log(0, "configured with: %s",
            BOLIDE_CONFIGURE_ARGS[0] ? BOLIDE_CONFIGURE_ARGS : "(defaults)");
  material_table_log(e->mats);
  if (e->hp.solids)
    error_log(0,
              "solids: gradient tasks on (correction tensor %s, %s momentum form, artificial "
              "stress eps %g n %g%s)",
              e->hp.gradient_correction ? "on" : "off",
              e->hp.momentum_form == HYDRO_MOMENTUM_SYMMETRIC ? "symmetric" : "standard",
              e->hp.as_eps, e->hp.as_n, e->hp.continuity_cspm ? ", CSPM continuity" : "");
  drift_integrate_init(e);
  engine_drop_unused_fields(e);
  error_log(0, "particle memory: %zu bytes per particle%s", parts_bytes_held(&e->parts),
            parts_bytes_held(&e->parts) < parts_bytes_per_particle()
                ? " (the solid and damage fields not held: no stress, no damage, kick-drift-kick)"
                : "");
  if (opt->check_only) {
    printf("%s: parameters, materials and initial conditions are valid (%zu particles)\n",
           params_filename(params), e->parts.count);
    return;
  }

  engine_mkdir(e->outdir);
  if (e->restarts) engine_mkdir(e->restart_dir); /* where the stop file goes */
  if (ranks_rank() == 0) { /* (one writer of the run's files with several MPI ranks) */
    engine_remove_stale_snapshots(e);
    char path[2048];
    snprintf(path, sizeof path, "%s/used_parameters.yml", e->outdir);
    params_write_used(params, path);
  }
  if (!e->params_text) e->params_text = params_to_string(params);
  engine_stats_open(e);

#ifdef HAVE_CUDA
  gpu_engine_near(e); /* (the workers pinned near this rank's GPU) */
#endif
  scheduler_init(&e->sched, e->nr_threads);
  e->sched.fixed_costs = params_get_bool(params, "Scheduler:deterministic");
  /* several MPI ranks: each its GPU (self-gravity then on the CPU workers:
   * gpu_engine_init) */
#ifdef HAVE_CUDA
  gpu_engine_init(e);
#else
  (void)gpu_policy_read(params); /* checked in every build; every task runs on the CPU */
#endif
  halo_init(e); /* (several MPI ranks: src/mpi/halo.c) */
}

/* ------------------------------------------------------------------------ */

/** (engine_rebuild_regrouped) Particle ids with their positions, by id. */
struct engine_id_pos {
  int64_t id;
  double x[3];
};
static int engine_cmp_id_pos(const void *a, const void *b) {
  const int64_t u = ((const struct engine_id_pos *)a)->id,
                v = ((const struct engine_id_pos *)b)->id;
  return (u > v) - (u < v);
}

/** The first rebuild of a run resumed from the files of another number of
 *  ranks (restart_read_ranks: every rank holds every particle): the cells
 *  of the uninterrupted run's last rebuild, as space_restore makes them,
 *  but through the decomposition of this number of ranks.  The particles
 *  are put at their positions of that rebuild (x0), the grid of its h_max
 *  chosen, the space rebuilt, partitioned and given its copies
 *  (halo_rebuild's first call), then every particle, copies included, put
 *  back at its position.  The tree of self-gravity, whose multipoles
 *  depend on the cells, is then the uninterrupted run's until its next
 *  rebuild, and the resumed run agrees with it to round-off. */
static void engine_rebuild_regrouped(struct engine *e) {
  struct parts *p = &e->parts;
  const size_t n = p->count;
  struct engine_id_pos *keep = error_malloc(n * sizeof *keep + 1, "restart positions");
  for (size_t i = 0; i < n; i++) {
    keep[i].id = p->id[i];
    keep[i].x[0] = p->x[i], keep[i].x[1] = p->y[i], keep[i].x[2] = p->z[i];
    p->x[i] = p->x0[i], p->y[i] = p->y0[i], p->z[i] = p->z0[i];
  }
  qsort(keep, n, sizeof *keep, engine_cmp_id_pos);
  halo_rebuild_start(e);
  engine_family_hooks(e, task_family_at_rebuild_start);
  e->space.restore_h_max = e->restart_h_max;
  e->space.h_max_floor = 0.0; /* (every rank takes the file's h_max) */
  size_t removed = space_rebuild(&e->space);
  engine_family_hooks(e, task_family_at_rebuild);
  halo_rebuild(e);
  e->space.restore_h_max = 0.0;
  if (removed)
    error_exit("%s: %zu particles were outside the box at the last rebuild", e->restart_file,
               removed);
  for (size_t i = 0; i < p->count; i++) {
    const struct engine_id_pos key = {p->id[i], {0.0, 0.0, 0.0}};
    const struct engine_id_pos *k = bsearch(&key, keep, n, sizeof *keep, engine_cmp_id_pos);
    if (!k) error_bug("particle %lld lost by the first rebuild", (long long)p->id[i]);
    p->x[i] = k->x[0], p->y[i] = k->x[1], p->z[i] = k->x[2];
  }
  free(keep);
  for (int c = 0; c < e->space.nr_top; c++) cell_update_bounds(p, &e->space.cells[c]);
}

/** The most particles removed at one rebuild whose pairs' potential energy
 *  is summed directly (engine_rebuild; 1.25e9 pairs, a few seconds). */
#define ENGINE_GONE_PAIRS_MAX 50000

void engine_rebuild(struct engine *e) {
  const double w0 = error_walltime();
  /* the rebuild's threads (space.c) would inherit thread 0's one core */
  runner_unpin_self(&e->sched.pool);
  int on_device = 0; /* the GPU reorders its resident particles (gpu_engine_rebuild_begin) */
#ifdef HAVE_CUDA
  on_device = gpu_engine_rebuild_begin(e);
#else
  (void)on_device;
#endif
  const double w1 = error_walltime();
  size_t removed = 0;
  if (e->restart_h_max > 0.0 && e->restart_regrouped) {
    engine_rebuild_regrouped(e);
    e->restart_h_max = 0.0;
  } else if (e->restart_h_max > 0.0) {
    /* resumed: the cells of the uninterrupted run's last rebuild */
    space_restore(&e->space, e->restart_h_max, e->restart_cells.h_max, e->restart_cells.dx_max,
                  (int)e->restart_cells.n, "restart file");
    e->restart_h_max = 0.0;
    free(e->restart_cells.h_max);
    free(e->restart_cells.dx_max);
    memset(&e->restart_cells, 0, sizeof e->restart_cells);
    halo_restored(e); /* (several MPI ranks: the copies found again) */
  } else {
    /* (mirror ghosts: removed before, made again after, tasks/drift/drift_mirror.c;
     * several MPI ranks: the foreign copies likewise, src/mpi/halo.c) */
    halo_rebuild_start(e);
    engine_family_hooks(e, task_family_at_rebuild_start);
    /* (several MPI ranks after the first rebuild: the cells are made once,
     * with the copies, by halo_rebuild) */
    removed = halo_partitioned(e) ? space_prepare(&e->space) : space_rebuild(&e->space);
#ifdef HAVE_CUDA
    if (on_device) gpu_engine_rebuild_end(e);
#endif
    engine_family_hooks(e, task_family_at_rebuild);
    if (halo_rebuild(e) && ranks_rank() != 0) removed = 0; /* (rank 0 counts the first's) */
  }
  e->nr_removed += (long long)removed;
  if (e->gp.enabled && e->space.nr_gone > 1) {
    /* the m pot of the particles removed together counted each of their
     * pairs twice, the potential energy lost once (theory/sph.md section
     * 9); summed directly, so not for a group whose n^2/2 pairs would stall
     * the rebuild (seconds beyond ENGINE_GONE_PAIRS_MAX particles) */
    if (e->space.nr_gone <= ENGINE_GONE_PAIRS_MAX)
      e->space.removed.E -= gravity_pairs_energy(e->space.gone, e->space.nr_gone, &e->gp);
    else
      error_log(0,
                "warning: %zu particles left the box at one rebuild: the potential energy of "
                "their pairs (more than %d particles) is not subtracted from what they took, and "
                "the budget's E_removed counts it twice",
                e->space.nr_gone, ENGINE_GONE_PAIRS_MAX);
  }
  e->space.nr_gone = 0;
  const double w2 = error_walltime();
  engine_make_graph(e);
  runner_repin_self(&e->sched.pool);
  const double w3 = error_walltime();
  if (e->nr_rebuild == 0) {
    const double first[4] = {w3 - w0, w1 - w0, w2 - w1, w3 - w2};
    memcpy(e->t_rebuild_first, first, sizeof first);
  }
  e->t_rebuild += w3 - w0;
  e->t_rebuild_part[0] += w1 - w0;
  e->t_rebuild_part[1] += w2 - w1;
  e->t_rebuild_part[2] += w3 - w2;
  e->nr_rebuild++;
}

/** 1 if the cells or the task graph no longer hold every interaction: the
 *  space's own criterion, or a kernel support plus twice the largest drift
 *  beyond the reach of the pair tasks (engine_graph.c). */
int engine_should_rebuild(const struct engine *e) {
  if (e->halo) {
    /* several MPI ranks: the owned particles of all (collective) */
    double dmax, hmax;
    halo_bounds(e, &dmax, &hmax);
    return space_should_rebuild_at(&e->space, dmax, hmax) ||
           kernel_gamma * hmax + 2.0 * dmax > e->reach;
  }
  if (space_should_rebuild(&e->space)) return 1;
  double h_max = 0.0, dx_max = 0.0;
  for (int t = 0; t < e->nr_tcells; t++) {
    if (e->tcells[t]->h_max > h_max) h_max = e->tcells[t]->h_max;
    if (e->tcells[t]->dx_max > dx_max) dx_max = e->tcells[t]->dx_max;
  }
  return kernel_gamma * h_max + 2.0 * dx_max > e->reach;
}

/** Save the state for --restart. */
static void engine_write_restart(struct engine *e) {
#ifdef HAVE_CUDA
  gpu_engine_to_host(e);
#endif
  struct restart_state st;
  memset(&st, 0, sizeof st);
  st.time = e->time;
  st.dt = e->dt;
  st.ti_current = e->ti_current;
  st.dt_next = e->dt_max;
  for (int t = 0; t < e->nr_tcells; t++)
    if (e->cell_dt_min[t] < st.dt_next) st.dt_next = e->cell_dt_min[t];
  st.step = e->step;
  st.updates = e->updates;
  st.nr_removed = e->nr_removed;
  st.snap_index = e->snap_index;
  st.next_out = e->next_out;
  st.next_stats = e->next_stats;
  for (int k = 0; k < 3; k++) st.box[k] = e->space.dim[k];
  st.periodic = e->space.periodic;
  st.removed = e->space.removed;
  st.start = e->budget0;
  st.rebuild_h_max = e->space.h_max;
  st.need_rebuild = atomic_load((_Atomic int *)&e->need_rebuild) ? 1 : 0;
  if (e->stats) {
    if (fflush(e->stats)) error_exit("cannot write the statistics file (disk full?)");
    st.stats_offset = ftell(e->stats);
  }
  const int nc = e->space.nr_cells;
  struct restart_cells cells = {
      nc, error_malloc(2 * (size_t)nc * sizeof(double) + 1, "restart cells"), NULL};
  cells.dx_max = cells.h_max + nc;
  for (int c = 0; c < nc; c++) {
    cells.h_max[c] = e->space.cells[c].h_max;
    cells.dx_max[c] = e->space.cells[c].dx_max;
  }
  engine_mkdir(e->restart_dir);
  struct restart_gravity grav;
  gravity_restart_save(e, &grav);
  st.nr_ranks = engine_ranks(e);
  st.rank = st.nr_ranks > 1 ? ranks_rank() : 0;
  halo_write_restart(e); /* (several MPI ranks: the decomposition and exchange lists) */
  restart_write(e->restart_stem, &st, &e->parts, e->flaw_eps, &cells, e->params_text, &grav);
  if (!e->restart_layout_done) {
    /* this run's files are complete on every rank: those of other rank
     * counts (and, resumed from such, the .prev files they left) go */
    if (st.nr_ranks > 1) ranks_any(0); /* (a barrier) */
    if (ranks_rank() == 0)
      restart_remove_layouts(e->restart_base, (int)st.nr_ranks, e->restart_regrouped);
    e->restart_layout_done = 1;
  }
  restart_gravity_free(&grav);
  free(cells.h_max);
  e->restart_last_wall = error_walltime();
  error_log(0, "restart file %s.bin at step %ld, t = %g", e->restart_stem, e->step, e->time);
}

/** The stage of a task of the FORCE phase with several MPI ranks: 0 the
 *  density sums and the ghost, 1 the gradient sums and the extra ghost
 *  (solids), 2 the rest (forces, damage, kick), except, where gravity's far
 *  field goes by the top-level cells' records (halo_gravity_records), 3
 *  the long-range walks and what follows them (mark bit 2,
 *  engine_mark_halo_tasks). */
static int engine_force_stage(const struct task *t) {
  if (t->mark & 2) return 3;
  if (t->subtype == task_subtype_density || t->type == task_type_ghost) return 0;
  if (t->subtype == task_subtype_gradient || t->type == task_type_extra_ghost) return 1;
  return 2;
}

/** The FORCE-phase tasks that must wait for the refresh of the copies
 *  before their stage (task.mark): those on a cell holding a copy
 *  (cell.copies), the gravity tasks (every other particle is a copy for
 *  them), and whatever follows one of them within its stage. */
static void engine_mark_halo_tasks(struct engine *e) {
  struct scheduler *s = &e->sched;
  for (int i = 0; i < s->nr_tasks; i++) scheduler_task(s, i)->mark = 0;
  if (halo_gravity_by_records(e)) {
    /* stage 3: the long-range walks, after the records' exchange */
    for (int k = 0; k < e->phase_count[ENGINE_PHASE_FORCE]; k++) {
      struct task *t = e->phase_tasks[ENGINE_PHASE_FORCE][k];
      if (t->type == task_type_grav_long_range) t->mark = 2;
    }
    for (int i = 0; i < s->nr_tasks; i++) {
      const struct task *t = s->order[i];
      if (t->mark & 2)
        for (int k = 0; k < t->nr_unlocks; k++) t->unlocks[k]->mark = 2;
    }
  }
  for (int k = 0; k < e->phase_count[ENGINE_PHASE_FORCE]; k++) {
    struct task *t = e->phase_tasks[ENGINE_PHASE_FORCE][k];
    const struct cell *ci = t->ci, *cj = t->cj;
    if (t->subtype == task_subtype_grav || (ci && ci->copies) || (cj && cj->copies)) t->mark |= 1;
  }
  for (int i = 0; i < s->nr_tasks; i++) { /* (a topological order) */
    const struct task *t = s->order[i];
    if (!(t->mark & 1)) continue;
    const int st = engine_force_stage(t);
    for (int k = 0; k < t->nr_unlocks; k++)
      if (engine_force_stage(t->unlocks[k]) == st) t->unlocks[k]->mark |= 1;
  }
}

/** Several MPI ranks: the FORCE phase in stages (engine_force_stage), the
 *  foreign copies taking their owners' results between them, so that the
 *  force on an owned particle reads its neighbours' densities, pressures
 *  and (solids) velocity gradients as their owners computed them, and no
 *  copy's sums are computed (src/mpi/halo.c; theory/mpi.md, "Multi-rank
 *  runs").  The tasks the graph orders after a task of an earlier stage
 *  find it done.  Each stage runs in two parts: first the tasks that need
 *  no copy while the copies' exchange is in flight (thread 0 lets MPI
 *  progress it between its tasks), then, once it has arrived, the others
 *  (engine_mark_halo_tasks). */
static void engine_run_force_stages(struct engine *e) {
  engine_mark_halo_tasks(e);
  halo_refresh_start(e, -1); /* (every field: the drift and the kick changed them) */
  const int records = halo_gravity_by_records(e);
  for (int stage = 0; stage < 4; stage++) {
    if (stage == 1 && !e->hp.solids) continue;
    if (stage == 3) {
      if (!records) break;
      /* the upward pass is done: the records, then the long-range walks */
      halo_gravity_records(e);
      for (int k = 0; k < e->phase_count[ENGINE_PHASE_FORCE]; k++) {
        struct task *t = e->phase_tasks[ENGINE_PHASE_FORCE][k];
        t->skip = engine_force_stage(t) != 3;
      }
      scheduler_run(&e->sched, engine_run_task, e);
      halo_gravity_after(e);
      break;
    }
    if (stage == 2) halo_refresh_gravity_start(e); /* (the gravity tasks run in the last stage) */
    for (int part = 0; part < 2; part++) {
      for (int k = 0; k < e->phase_count[ENGINE_PHASE_FORCE]; k++) {
        struct task *t = e->phase_tasks[ENGINE_PHASE_FORCE][k];
        t->skip = engine_force_stage(t) != stage || (t->mark & 1) != part;
      }
      e->sched.poll = part == 0 ? halo_poll : NULL;
      e->sched.poll_ctx = e;
      scheduler_run(&e->sched, engine_run_task, e);
      e->sched.poll = NULL;
      if (part == 0) {
        halo_refresh_finish(e);
        halo_refresh_gravity_finish(e);
      }
    }
    if (stage < 2) halo_refresh_start(e, stage); /* (what this stage wrote) */
  }
}

void engine_run_gravity_stages(struct engine *e, scheduler_run_fn fn) {
  struct scheduler *s = &e->sched;
  engine_mark_halo_tasks(e); /* (stage 3: mark bit 2) */
  const int records = halo_gravity_by_records(e);
  unsigned char *run = error_malloc((size_t)s->nr_tasks + 1, "gravity stages");
  for (int i = 0; i < s->nr_tasks; i++) run[i] = !scheduler_task(s, i)->skip;
  halo_refresh_gravity(e);
  for (int stage = 2; stage <= 3; stage++) {
    if (stage == 3) {
      if (!records) break;
      halo_gravity_records(e);
    }
    for (int i = 0; i < s->nr_tasks; i++) {
      struct task *t = scheduler_task(s, i);
      t->skip = !run[i] || (records && (t->mark & 2 ? 3 : 2) != stage);
    }
    scheduler_run(s, fn, e);
  }
  if (records) halo_gravity_after(e);
  free(run);
}

/** Run the tasks of one phase on every worker. */
void engine_run_phase(struct engine *e, int phase) {
  if (phase == ENGINE_PHASE_FORCE) engine_family_hooks(e, task_family_at_force);
#ifdef HAVE_CUDA
  if (e->gpu) {
    if (phase == ENGINE_PHASE_FORCE)
      gpu_engine_force(e);
    else
      gpu_engine_drift(e);
    return;
  }
#endif
  engine_activate_phase(e, phase);
  if (e->halo && phase == ENGINE_PHASE_FORCE) {
    engine_run_force_stages(e);
    return;
  }
  scheduler_run(&e->sched, engine_run_task, e);
}

/** The particles by time bin of their own limit after this step's kick
 *  (the CPU kick's cell_bins; the GPU kick does not count them yet: all 0)
 *  into e->bins, and what time bins would have updated to the run's sums. */
static void engine_bins_collect(struct engine *e) {
  memset(e->bins, 0, sizeof e->bins);
  if (e->gpu) return;
  for (int t = 0; t < e->nr_tcells; t++)
    for (int b = 0; b <= TIMELINE_NR_BINS; b++)
      e->bins[b] += e->cell_bins[(size_t)t * (TIMELINE_NR_BINS + 1) + b];
  e->bin_updates += timeline_active_fraction(e->bins) * (double)e->parts.count;
  e->bin_all += (double)e->parts.count;
}

/** The particles kicked in the last step: all with the global step. */
static void engine_count_active(struct engine *e) {
  e->nr_active = e->halo ? (int64_t)e->nr_owned_all : (int64_t)e->parts.count;
  if (!e->individual) return;
  e->nr_active = 0;
  for (int t = 0; t < e->nr_tcells; t++) e->nr_active += e->cell_kick[t].active;
}

/** The next global time step: the smallest particle step, limited by dt_max,
 *  the next output time and the end of the run. */
double engine_next_dt(struct engine *e) {
  double dt = e->dt_max;
  for (int t = 0; t < e->nr_tcells; t++)
    if (e->cell_dt_min[t] < dt) dt = e->cell_dt_min[t];
  if (e->halo) ranks_allreduce_doubles(&dt, 1, RANKS_MIN);
  if (dt < e->dt_min) {
    char why[512];
    kick_dt_culprit(e, why, sizeof why);
    error_exit("time step %g at t = %g is below TimeIntegration:dt_min = %g: %s", dt, e->time,
               e->dt_min, why);
  }
  if (e->next_out < e->nr_out) {
    const double to_out = e->out_times[e->next_out] - e->time;
    if (to_out > 0.0 && dt >= to_out)
      dt = to_out;
    else if (to_out > 0.0 && dt > 0.5 * to_out && dt < to_out)
      dt = 0.5 * to_out; /* no sliver steps */
  }
  if (e->time + dt > e->time_end) dt = e->time_end - e->time;
  /* a time so large in magnitude that the step is below its spacing would
   * loop for ever at the same t */
  if (dt > 0.0 && e->time + dt == e->time)
    error_exit(
        "time step %g cannot advance the time t = %g (the spacing of doubles there is %g): "
        "TimeIntegration:time_begin or time_end too large in magnitude for the run's time steps",
        dt, e->time, nextafter(fabs(e->time), INFINITY) - fabs(e->time));
  return dt;
}

/** With individual time steps: the end of the next step on the time line
 *  (the earliest end of a particle's step, or the next output time if it
 *  comes first) into e->ti_next, and its length. */
static double engine_next_dt_bins(struct engine *e) {
  const struct timeline *tl = &e->timeline;
  const integertime_t end = (integertime_t)1 << TIMELINE_NR_BINS;
  integertime_t ti = end;
  double dt_lim = HUGE_VAL;
  int64_t bin0 = 0;
  for (int t = 0; t < e->nr_tcells; t++) {
    if (e->cell_kick[t].ti_end_min < ti) ti = e->cell_kick[t].ti_end_min;
    if (e->cell_dt_min[t] < dt_lim) dt_lim = e->cell_dt_min[t];
    bin0 += e->cell_bins[(size_t)t * (TIMELINE_NR_BINS + 1)];
  }
  if (dt_lim < e->dt_min || bin0 > 0) {
    char why[512];
    kick_dt_culprit(e, why, sizeof why);
    error_exit("time step %g at t = %g is below %s = %g: %s", dt_lim, e->time,
               bin0 > 0 ? "the time line's shortest step (two ticks of (time_end - time_begin) / "
                          "2^56)"
                        : "TimeIntegration:dt_min",
               bin0 > 0 ? 2.0 * tl->time_base : e->dt_min, why);
  }
  if (e->next_out < e->nr_out) {
    const integertime_t ti_out = timeline_integer_time(tl, e->out_times[e->next_out]);
    if (ti_out > e->ti_current && ti_out < ti) ti = ti_out;
  }
  e->ti_next = ti;
  return (double)(ti - e->ti_current) * tl->time_base;
}

/** With individual time steps after a rebuild between the drift and the
 *  FORCE phase: the task cells' counts of particles that end their step
 *  (cell.active, ENGINE_CELL_IDLE), which the drift counted in the cells of
 *  before. */
static void engine_count_active_cells(struct engine *e) {
  for (int t = 0; t < e->nr_tcells; t++) {
    struct cell *c = e->tcells[t];
    int n = 0;
    for (size_t i = c->offset; i < c->offset + c->count; i++) n += !PART_IS_INACTIVE(&e->parts, i);
    c->active = n;
  }
}

/** With individual time steps after a resumed run's start: the earliest
 *  end of a particle's step from the particles' bins (what the kick of the
 *  step before the restart file left in e->cell_kick). */
static void engine_bins_resume(struct engine *e) {
  integertime_t ti = INT64_MAX;
  for (size_t i = 0; i < e->parts.count; i++) {
    const int b = e->parts.time_bin[i];
    const integertime_t end = timeline_next_sync(b > 0 ? b : 1, e->ti_current);
    if (end < ti) ti = end;
  }
  for (int t = 0; t < e->nr_tcells; t++) {
    e->cell_kick[t].ti_end_min = t == 0 ? ti : INT64_MAX;
    e->cell_kick[t].active = 0;
  }
  memset(e->cell_bins, 0, (size_t)e->nr_tcells * (TIMELINE_NR_BINS + 1) * sizeof(int64_t));
}

/** With individual time steps a particle in the middle of its step holds
 *  the state of its step's middle (velocities, u, stresses, continuity
 *  density, distention) and the predicted state of now (vp, up, Sp, rho_fp,
 *  alpha_p); a kicked one holds the same in both.  Snapshots and statistics
 *  show the state of now: this swaps the two sets of arrays (twice: back). */
static void engine_sync_view(struct engine *e) {
  if (!e->individual) return;
#ifdef HAVE_CUDA
  gpu_engine_to_host(e); /* (the arrays swapped must be the current ones) */
#endif
  struct parts *p = &e->parts;
#define ENGINE_SWAP(a, b) \
  do {                    \
    double *tmp_ = p->a;  \
    p->a = p->b;          \
    p->b = tmp_;          \
  } while (0)
  ENGINE_SWAP(vx, vpx);
  ENGINE_SWAP(vy, vpy);
  ENGINE_SWAP(vz, vpz);
  ENGINE_SWAP(u, up);
  ENGINE_SWAP(Sxx, Spxx);
  ENGINE_SWAP(Sxy, Spxy);
  ENGINE_SWAP(Sxz, Spxz);
  ENGINE_SWAP(Syy, Spyy);
  ENGINE_SWAP(Syz, Spyz);
  ENGINE_SWAP(Szz, Spzz);
  ENGINE_SWAP(rho_full, rho_fp);
  ENGINE_SWAP(alpha, alpha_p);
#undef ENGINE_SWAP
}

/** A snapshot of the state of now (engine_sync_view). */
static void engine_snapshot_now(struct engine *e) {
  engine_sync_view(e);
  engine_snapshot(e);
  engine_sync_view(e);
}

/** Compute densities, forces and time steps without kicking (t = time_begin). */
static void engine_first_force(struct engine *e) {
  e->first_force = 1;
  e->dt = 0.0;
  e->ti_next = e->ti_current;
  engine_family_hooks(e, task_family_at_first_force);
  e->gp.replay = 0;
  /* the adaptive criterion's scale |ga| for the first evaluation (issue 25):
   * one cheaper geometric pass on the host, uploaded with the particles */
  if (gravity_estimate_first(e)) {
#ifdef HAVE_CUDA
    if (e->gpu) gpu_engine_host_modified(e);
#endif
  }
  engine_run_phase(e, ENGINE_PHASE_FORCE);
  gravity_reuse_remember(e);
  e->first_force = 0;
}

/** One step of the kick-drift-kick leapfrog (TimeIntegration:scheme: kdk),
 *  with the global step or in time bins: the first half kicks and the
 *  drift, a rebuild when the particles have moved too far, the FORCE phase
 *  with the second half kicks.  Returns 0 when there is no step to take. */
static int engine_step_kdk(struct engine *e) {
  e->dt = e->individual ? engine_next_dt_bins(e) : engine_next_dt(e);
  if (!(e->dt > 0.0)) return 0;
  engine_watchdog_before_drift(e);
  engine_run_phase(e, ENGINE_PHASE_DRIFT);
  engine_watchdog_after_drift(e);
  if (e->individual) {
    e->ti_current = e->ti_next;
    e->time = e->ti_current == (integertime_t)1 << TIMELINE_NR_BINS
                  ? e->time_end
                  : timeline_time(&e->timeline, e->ti_current);
  } else {
    e->time += e->dt;
  }
  if (e->next_out < e->nr_out && fabs(e->time - e->out_times[e->next_out]) <= 1e-12 * fabs(e->time))
    e->time = e->out_times[e->next_out];
  int rebuilt = 0;
  int rebuild = atomic_load((_Atomic int *)&e->need_rebuild);
  rebuild = e->halo ? ranks_any(engine_should_rebuild(e) || rebuild)
                    : rebuild || engine_should_rebuild(e);
  if (rebuild) {
    atomic_store((_Atomic int *)&e->need_rebuild, 0);
    /* a particle that leaves the box takes its state of now (space.c) */
    e->space.clock =
        (struct space_clock){1, e->dt, e->individual ? &e->timeline : NULL, e->ti_current};
    engine_rebuild(e);
    e->space.clock.set = 0;
    rebuilt = 1;
    if (e->individual) engine_count_active_cells(e);
  }
  /* (the same test as after the phase: an output needs every potential) */
  gravity_active_decide(e, e->time >= e->next_stats || e->time >= e->time_end ||
                               (e->next_out < e->nr_out && e->time >= e->out_times[e->next_out]));
  gravity_reuse_decide(e, rebuilt);
  const double wf = error_walltime();
  engine_run_phase(e, ENGINE_PHASE_FORCE);
  e->t_eval += error_walltime() - wf;
  e->nr_eval++;
  return 1;
}

void engine_run(struct engine *e) {
  const double t_begin = e->time;
  const long step_begin = e->step;
  if (e->opt.max_steps == 0) {
    /* the initial conditions as read, in their order, nothing computed
     * (what --steps 0 is for, whatever Snapshots:enabled says) */
    e->snap_enabled = 1;
    engine_snapshot(e);
    error_log(0, "--steps 0: wrote the initial conditions as snapshot, stopping");
    return;
  }
  engine_rebuild(e);
  if (!e->restarted) {
    engine_first_force(e);
    engine_sync_view(e);
    engine_stats_first(e);
    engine_snapshot(e);
    engine_sync_view(e);
  } else {
    /* every force, rate and time step of the end of the last step is in the
     * restart file: recomputing them now would use corrected instead of
     * predicted velocities and change the run */
    for (int t = 0; t < e->nr_tcells; t++) e->cell_dt_min[t] = e->restart_dt_next;
    if (e->individual) engine_bins_resume(e);
    gravity_restart_restore(e);
    error_log(0, "resumed from %s at step %ld, t = %g", e->restart_file, e->step, e->time);
  }
  e->wall_start = error_walltime();
  e->restart_last_wall = e->wall_start;
  char stop_why[1300] = "";
  const int rank0 = ranks_rank() == 0;
  if (rank0) printf("#   step           time             dt      updates    wall[s]     ETA[s]\n");
  while (e->time < e->time_end && (e->opt.max_steps < 0 || e->step < e->opt.max_steps)) {
    const double w0 = error_walltime();
    if (e->scheme == ENGINE_SCHEME_KDK) {
      if (!engine_step_kdk(e)) break;
    } else if (!drift_integrate_step(e)) {
      break;
    }
    engine_bins_collect(e);
    engine_count_active(e);
    gravity_reuse_remember(e);
    e->step++;
    e->updates += (long long)e->nr_active;
    engine_watchdog_after_step(e);
    if (e->dump_tasks > 0 && e->step % e->dump_tasks == 0) engine_dump_tasks(e);
    /* (a GPU run's particles come back to the host only for an output) */
    const int output = e->time >= e->next_stats || e->time >= e->time_end ||
                       (e->next_out < e->nr_out && e->time >= e->out_times[e->next_out]);
    if (output) engine_sync_view(e);
    engine_stats_maybe(e);
    if (e->next_out < e->nr_out && e->time >= e->out_times[e->next_out]) {
      engine_snapshot(e);
      while (e->next_out < e->nr_out && e->out_times[e->next_out] <= e->time) e->next_out++;
    }
    if (output) engine_sync_view(e);
    const double w1 = error_walltime();
    /* the fraction done of the simulated time, or of the steps asked for
     * (--steps) where that ends the run first */
    double frac = (e->time - t_begin) / fmax(e->time_end - t_begin, 1e-300);
    if (e->opt.max_steps > 0) {
      const double fs = (double)(e->step - step_begin) / (double)(e->opt.max_steps - step_begin);
      if (fs > frac) frac = fs;
    }
    const double eta = frac > 0 ? (w1 - e->wall_start) * (1.0 - frac) / frac : 0.0;
    if (rank0)
      printf("%8ld %14.6e %14.6e %12lld %10.4f %10.1f\n", e->step, e->time, e->dt,
             (long long)e->nr_active, w1 - w0, eta);
    engine_timesteps_write(e, w1 - w0);
    fflush(stdout);
    if (e->time < e->time_end && e->halo) {
      /* several MPI ranks stop together, each writing its restart file */
      const int stop = engine_must_stop(e, stop_why, sizeof stop_why);
      if (ranks_any(stop)) {
        if (!stop) snprintf(stop_why, sizeof stop_why, "another MPI rank was asked to stop");
        break;
      }
    }
    if (e->time < e->time_end && !e->halo && engine_must_stop(e, stop_why, sizeof stop_why)) break;
    /* (not at the last step: the file written after the loop follows; several
     * MPI ranks write theirs together: any rank's wall clock decides) */
    int due_wall = w1 - e->restart_last_wall >= e->restart_dt_wall;
    if (e->halo && e->restarts) due_wall = ranks_any(due_wall);
    if (e->restarts &&
        (due_wall || (e->restart_delta_steps > 0 && e->step % e->restart_delta_steps == 0)) &&
        e->time < e->time_end && (e->opt.max_steps < 0 || e->step < e->opt.max_steps)) {
      /* (the run goes on without a rebuild: a run resumed from the file
       * restores the cells of the last one, space_restore) */
      engine_write_restart(e);
    }
  }
  const int stopped = stop_why[0] != '\0';
  if (!stopped && !e->restarts && e->next_out < e->nr_out &&
      e->out_times[e->nr_out - 1] > e->time) {
    /* stopped by --steps without restart files: keep the last state */
    engine_snapshot_now(e);
  }
  /* the restart file first: a run resumed from it truncates the statistics
   * file to its length then, dropping the closing line written now */
  if (e->restarts || stopped) engine_write_restart(e);
  if (stopped && ranks_rank() == 0)
    fprintf(stderr,
            "bolide: %s: wrote %s.bin%s at step %ld (t = %g) and stopped; resume with --restart\n",
            stop_why, e->restart_stem, e->halo ? " (and one file per rank)" : "", e->step, e->time);
  engine_sync_view(e);
  engine_stats_close(e);
  engine_budget_summary(e);
  engine_sync_view(e);
  const double wall = error_walltime() - e->wall_start;
  error_log(0, "done: %ld steps to t = %g in %.2f s (%.3g particle updates per second)", e->step,
            e->time, wall, wall > 0 ? (double)e->updates / wall : 0.0);
  if (e->nr_removed)
    error_log(0, "%lld particles left the open box and were removed", e->nr_removed);
  if (e->individual)
    error_log(0,
              "time bins: %lld particle updates in %ld steps, %.1f%% of the particles per step on "
              "average",
              e->updates, e->step,
              e->step > 0 && e->parts.count > 0
                  ? 100.0 * (double)e->updates / ((double)e->step * (double)e->parts.count)
                  : 0.0);
  else if (e->bin_all > 0.0)
    error_log(0,
              "time bins: individual time steps (issue 20; TimeIntegration:global_step) would have "
              "updated %.1f%% of the particles per step of the smallest bin on average (the "
              "timesteps file "
              "has the bins and the fraction of each step)",
              100.0 * e->bin_updates / e->bin_all);
  if (e->nr_eval)
    error_log(0, "derivative evaluations (FORCE phases of the steps): %ld, %.4f s each on average",
              e->nr_eval, e->t_eval / e->nr_eval);
  if (e->nr_eval && e->hp.enabled && !e->hp.h_continuity && e->parts.count > 0)
    error_log(0,
              "smoothing lengths: the density sums of %.3g particles redone per evaluation of "
              "the steps on average (%.1f%% of the particles; SPH:h_tolerance %g)",
              (double)e->h_resummed / (double)e->nr_eval,
              100.0 * (double)e->h_resummed / ((double)e->nr_eval * (double)e->parts.count),
              e->hp.h_tolerance);
  if (e->nr_rebuild > 1) {
    /* the first sorts the file's order and is not what a long run repeats */
    const double n = (double)(e->nr_rebuild - 1);
    error_log(0,
              "rebuilds (cells, particle order, task graph): %ld, %.4f s each on average after "
              "the first (particles back from the GPU %.4f, cells and order %.4f, task graph "
              "%.4f); the first %.4f s",
              e->nr_rebuild, (e->t_rebuild - e->t_rebuild_first[0]) / n,
              (e->t_rebuild_part[0] - e->t_rebuild_first[1]) / n,
              (e->t_rebuild_part[1] - e->t_rebuild_first[2]) / n,
              (e->t_rebuild_part[2] - e->t_rebuild_first[3]) / n, e->t_rebuild_first[0]);
    const struct space *s = &e->space;
    if (s->nr_timed > 0)
      error_log(0,
                "rebuilds' cells and order, seconds each on average after the first: sort by "
                "top-level cell %.4f, octrees %.4f, reorder %.4f, boxes %.4f (rebuilds timed: %d)",
                s->t_parts[0] / s->nr_timed, s->t_parts[1] / s->nr_timed,
                s->t_parts[2] / s->nr_timed, s->t_parts[3] / s->nr_timed, s->nr_timed);
  } else if (e->nr_rebuild == 1) {
    error_log(0,
              "rebuilds (cells, particle order, task graph): 1, the first %.4f s (cells and order "
              "%.4f, task graph %.4f)",
              e->t_rebuild_first[0], e->t_rebuild_first[2], e->t_rebuild_first[3]);
  }
  error_log(0, "watchdog: %.4f s per step on average (every field of every particle checked)",
            e->step > 0 ? e->t_watchdog / (double)e->step : 0.0);
  drift_integrate_log(e);
  gravity_log_end(e);
  halo_log(e);
  if (rank0) scheduler_print_timers(&e->sched, stdout);
#ifdef HAVE_CUDA
  if (rank0) gpu_engine_print(e, stdout); /* (several MPI ranks: rank 0's GPU) */
#endif
}

void engine_clean(struct engine *e) {
  halo_free(e);
#ifdef HAVE_CUDA
  gpu_engine_free(e);
#endif
  if (!e->opt.check_only) {
    engine_graph_clean(e);
    scheduler_free(&e->sched);
    space_free(&e->space);
  }
  if (e->stats) fclose(e->stats);
  if (e->timesteps) fclose(e->timesteps);
  free(e->out_times);
  free(e->cell_dt_min);
  free(e->cell_bins);
  free(e->cell_kick);
  free(e->wd_x);
  drift_integrate_free(e);
  free(e->flaw_eps);
  free(e->params_text);
  engine_family_hooks(e, task_family_at_clean); /* self-gravity's state */
  if (e->mats) material_table_free(e->mats);
  free(e->mats);
  parts_free(&e->parts);
}
