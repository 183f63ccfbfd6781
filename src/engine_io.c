/* The engine's outputs: the statistics file, snapshots and task dumps. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine_tasks.h"
#include "error.h"
#include "params.h"
#include "snapshot.h"
#include "version.h"
#ifdef HAVE_CUDA
#include "gpu/gpu_engine.h"
#endif

/** Columns of the statistics file: one list for the header and the rows. */
#define ENGINE_STATS_COLUMNS(X)                                                    \
  X(step) X(time) X(dt) X(mass) X(px) X(py) X(pz) X(Lx) X(Ly) X(Lz) X(E_kin) X(E_int) \
  X(E_pot) X(E_tot) X(n_particles) X(n_removed)

void engine_stats_open(struct engine *e) {
  char path[2048];
  snprintf(path, sizeof path, "%s/%s.txt", e->outdir, params_get_string(e->params, "Statistics:energy_file_name"));
  /* a resumed run appends to the file of the run it continues */
  e->stats = fopen(path, e->restarted ? "a" : "w");
  if (!e->stats) error_exit("%s: cannot create the statistics file", path);
  if (e->restarted) {
    fprintf(e->stats, "# resumed from a restart file at step %ld\n", e->step);
    return;
  }
  fprintf(e->stats, "# Bolide %s statistics, internal units (mass %g g, length %g cm, time %g s)\n", PACKAGE_VERSION,
          e->us.mass_cgs, e->us.length_cgs, e->us.time_cgs);
  fprintf(e->stats, "#");
#define ENGINE_STATS_NAME(n) fprintf(e->stats, " %s", #n);
  ENGINE_STATS_COLUMNS(ENGINE_STATS_NAME)
#undef ENGINE_STATS_NAME
  fprintf(e->stats, "\n");
  fflush(e->stats);
  e->next_stats = e->time;
}

void engine_stats_write(struct engine *e) {
#ifdef HAVE_CUDA
  gpu_engine_to_host(e); /* the particles may be resident on the GPU */
#endif
  const struct parts *p = &e->parts;
  double mass = 0, px = 0, py = 0, pz = 0, Lx = 0, Ly = 0, Lz = 0, ekin = 0, eint = 0;
  for (size_t i = 0; i < p->count; i++) {
    const double m = p->m[i];
    const double vx = p->vx[i], vy = p->vy[i], vz = p->vz[i];
    const double x = p->x[i], y = p->y[i], z = p->z[i];
    mass += m;
    px += m * vx;
    py += m * vy;
    pz += m * vz;
    Lx += m * (y * vz - z * vy);
    Ly += m * (z * vx - x * vz);
    Lz += m * (x * vy - y * vx);
    ekin += 0.5 * m * (vx * vx + vy * vy + vz * vz);
    eint += m * p->u[i];
  }
  const double epot = e->gp.enabled ? gravity_potential_energy(p) : 0.0;
  fprintf(e->stats, "%ld %.12e %.6e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %.12e %zu %lld\n",
          e->step, e->time, e->dt, mass, px, py, pz, Lx, Ly, Lz, ekin, eint, epot, ekin + eint + epot, p->count,
          e->nr_removed);
  if (fflush(e->stats)) error_exit("cannot write the statistics file (disk full?)");
}

void engine_stats_maybe(struct engine *e) {
  if (e->time >= e->next_stats || e->time >= e->time_end) {
    engine_stats_write(e);
    if (e->stats_dt > 0.0)
      while (e->next_stats <= e->time) e->next_stats += e->stats_dt;
  }
}

void engine_snapshot(struct engine *e) {
#ifdef HAVE_CUDA
  gpu_engine_to_host(e);
#endif
  char path[2048];
  snprintf(path, sizeof path, "%s/%s_%04d.hdf5", e->outdir, e->snap_basename, e->snap_index);
  struct snapshot_meta meta;
  memset(&meta, 0, sizeof meta);
  meta.time = e->time;
  for (int k = 0; k < 3; k++) meta.box_size[k] = e->space.dim[k];
  meta.periodic = e->space.periodic;
  meta.run_name = params_get_string(e->params, "MetaData:run_name");
  meta.params = e->params_text;
  meta.hydro = e->hp.enabled;
  meta.self_gravity = e->gp.enabled;
  meta.compression = e->compression;
  snapshot_write(path, &meta, &e->parts, &e->us, e->write_acc);
  error_log(0, "snapshot %s at t = %g", path, e->time);
  e->snap_index++;
}

void engine_dump_tasks(struct engine *e) {
  char path[2048];
  snprintf(path, sizeof path, "%s/tasks_step%06ld.txt", e->outdir, e->step);
  FILE *f = fopen(path, "w");
  if (!f) error_exit("%s: cannot create the task dump", path);
  scheduler_dump_tasks(&e->sched, f);
  fclose(f);
}
