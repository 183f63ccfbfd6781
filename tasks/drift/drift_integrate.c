/* The Runge-Kutta 2 and predictor-corrector integrators
 * (TimeIntegration:scheme: rk2 | pc; theory/integrators.md).
 *
 * A step of either is a sequence of stages.  Each stage is the DRIFT phase
 * with e->stage set (the drift tasks put every particle's state
 * y0 + dt sum_k a_k f(r_k), drift_rk.h) followed by a FORCE phase that
 * evaluates the rates there (the kick tasks add gravity and compute the
 * time step but kick nothing: dt_kick = 0).  The evaluation at the end of a
 * step is the first of the next (r_1), as the leapfrog's is.
 *
 *   pc  (Heun):    y* = y0 + dt f(y0);  y1 = y0 + dt/2 (f(y0) + f(y*))
 *   rk2 (midpoint, with Kutta's third-order rule on the same stages for
 *        the error):
 *        k1 = f(y0), k2 = f(y0 + dt/2 k1), k3 = f(y0 + dt (2 k2 - k1));
 *        y1 = y0 + dt k2;  error = |dt/6 (k1 - 2 k2 + k3)|.
 *
 * Particles keep their order within a step: a rebuild that a stage needs
 * (particles about to leave the cells' reach) puts the step's start back
 * into the particle arrays, rebuilds and takes the step again. */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "src/engine.h"
#include "src/engine_tasks.h"
#include "src/error.h"
#include "src/io/params.h"
#include "tasks/drift/drift_rk.h"
#include "tasks/task_families.h"
#ifdef HAVE_CUDA
#include "src/gpu/gpu_engine.h"
#endif

/** What the integrator keeps between the stages of a step. */
struct drift_integrator {
  double tol;      /**< TimeIntegration:rk2_tolerance */
  double *y0;      /**< the state at the step's start, DRIFT_RK_NY per particle */
  double *r1, *r2; /**< the evaluations at its start and (rk2) at its middle */
  size_t cap;      /**< particles the arrays hold */
  int on_gpu;      /**< the arrays are the device's (gpu_engine_rk_arrays) */
  long rejected;   /**< rk2 steps taken again with a shorter step */
  long redone;     /**< steps taken again after a rebuild in their middle */
  long stages;     /**< evaluations inside the steps (the ends' not counted) */
  double err_last; /**< the error of the last rk2 step */
};

void drift_integrate_init(struct engine *e) {
  static const char *names[] = {"kdk", "rk2", "pc"};
  e->scheme = params_get_enum(e->params, "TimeIntegration:scheme");
  if (e->scheme == ENGINE_SCHEME_KDK) return;
  const char *name = names[e->scheme];
  if (e->individual)
    params_error(e->params, "TimeIntegration:scheme",
                 "scheme %s takes one step for every particle: set TimeIntegration:global_step: "
                 "true (time bins run with kdk only)",
                 name);
  struct drift_integrator *rk = error_calloc(1, sizeof *rk, "integrator state");
  rk->tol = params_get_real(e->params, "TimeIntegration:rk2_tolerance");
  e->rk = rk;
  error_log(0, "time integration: %s (%s), %s", name,
            e->scheme == ENGINE_SCHEME_RK2
                ? "midpoint rule, error from Kutta's third-order rule, three evaluations per step"
                : "Euler predictor, trapezoidal corrector, two evaluations per step",
            e->scheme == ENGINE_SCHEME_RK2 ? "adaptive step" : "the Courant step");
}

void drift_integrate_free(struct engine *e) {
  if (!e->rk) return;
  if (!e->rk->on_gpu) {
    free(e->rk->y0);
    free(e->rk->r1);
    free(e->rk->r2);
  }
  free(e->stage_err);
  free(e->rk);
  e->rk = NULL;
  e->stage_err = NULL;
}

/** The arrays for the particles of now (their number changes only at
 *  rebuilds, between steps or at a step taken again). */
static void drift_integrate_alloc(struct engine *e) {
  struct drift_integrator *rk = e->rk;
  const size_t n = e->parts.count ? e->parts.count : 1;
#ifdef HAVE_CUDA
  if (e->gpu) {
    /* on the device, beside the resident particles */
    double *r[2] = {NULL, NULL};
    gpu_engine_rk_arrays(e, DRIFT_RK_NY, DRIFT_RK_NR, e->scheme == ENGINE_SCHEME_RK2 ? 2 : 1,
                         &rk->y0, r);
    rk->r1 = r[0];
    rk->r2 = r[1];
    rk->on_gpu = 1;
  }
#endif
  if (!rk->on_gpu && n > rk->cap) {
    rk->y0 = error_realloc(rk->y0, n * DRIFT_RK_NY * sizeof(double), "integrator state");
    rk->r1 = error_realloc(rk->r1, n * DRIFT_RK_NR * sizeof(double), "integrator rates");
    if (e->scheme == ENGINE_SCHEME_RK2)
      rk->r2 = error_realloc(rk->r2, n * DRIFT_RK_NR * sizeof(double), "integrator rates");
    rk->cap = n;
  }
  e->stage_err = error_realloc(e->stage_err, (e->nr_tcells ? e->nr_tcells : 1) * sizeof(double),
                               "stage errors");
}

/** One stage: the drift tasks put st at time t (e->time during its
 *  evaluation, when eval); returns the largest error estimate.  *moved: 1
 *  when the particles now lie beyond the reach of the cells' tasks. */
static double drift_integrate_stage(struct engine *e, const struct drift_stage *st, int *moved) {
  e->stage = st;
  for (int t = 0; t < e->nr_tcells; t++) e->stage_err[t] = 0.0;
  engine_run_phase(e, ENGINE_PHASE_DRIFT);
  e->stage = NULL;
  double err = 0.0;
  for (int t = 0; t < e->nr_tcells; t++)
    if (e->stage_err[t] > err) err = e->stage_err[t];
  *moved = engine_should_rebuild(e);
  return err;
}

/** A derivative evaluation (the FORCE phase) of the state the last stage
 *  put; rebuilt: a rebuild came before it (no far field to reuse). */
static void drift_integrate_eval(struct engine *e, int rebuilt, int final) {
  e->stage_eval = !final;
  e->hp.stage_end = final;
  gravity_active_decide(e, 1);
  gravity_reuse_decide(e, rebuilt);
  const double wf = error_walltime();
  engine_run_phase(e, ENGINE_PHASE_FORCE);
  e->t_eval += error_walltime() - wf;
  e->nr_eval++;
  gravity_reuse_remember(e);
  e->stage_eval = e->hp.stage_end = 0;
  if (!final) e->rk->stages++;
}

/** The step's start back into the particle arrays (state and the
 *  evaluation there), for a rebuild before the step is taken again. */
static void drift_integrate_restore(struct engine *e) {
  struct drift_integrator *rk = e->rk;
#ifdef HAVE_CUDA
  if (rk->on_gpu) {
    gpu_engine_rk_restore(e, rk->y0, rk->r1);
    return;
  }
#endif
  for (size_t i = 0; i < e->parts.count; i++)
    drift_rk_restore(&e->parts, i, rk->y0 + (size_t)DRIFT_RK_NY * i,
                     rk->r1 + (size_t)DRIFT_RK_NR * i);
}

int drift_integrate_step(struct engine *e) {
  struct drift_integrator *rk = e->rk;
  const int rk2 = e->scheme == ENGINE_SCHEME_RK2;
  e->dt = engine_next_dt(e);
  if (!(e->dt > 0.0)) return 0;
  const double t0 = e->time;
  int rebuilt = 0;
  if (atomic_load((_Atomic int *)&e->need_rebuild) || engine_should_rebuild(e)) {
    atomic_store((_Atomic int *)&e->need_rebuild, 0);
    engine_rebuild(e);
    rebuilt = 1;
  }
  drift_integrate_alloc(e);
  engine_watchdog_before_drift(e);
  int save = 1, tries = 0, rebuilds_here = 0;
  for (;;) {
    const double dt = e->dt;
    int moved = 0;
    double err = 0.0;
    /* the first stage: y0 + dt/2 k1 (rk2), y0 + dt k1 (pc), k1 recorded */
    struct drift_stage a = {dt, 1, {rk2 ? 0.5 : 1.0}, rk->y0, {NULL}, rk->r1, save, 0, 0, {0.0}};
    if (!save) a.r[0] = rk->r1, a.store = NULL;
    drift_integrate_stage(e, &a, &moved);
    save = 0;
    if (!moved) {
      e->time = t0 + (rk2 ? 0.5 : 1.0) * dt;
      drift_integrate_eval(e, rebuilt, 0);
      rebuilt = 0;
      if (rk2) {
        /* y0 + dt (2 k2 - k1) for Kutta's third-order rule, k2 recorded */
        struct drift_stage b = {dt, 2, {-1.0, 2.0}, rk->y0, {rk->r1, NULL}, rk->r2, 0, 0, 0, {0.0}};
        drift_integrate_stage(e, &b, &moved);
        if (!moved) {
          e->time = t0 + dt;
          drift_integrate_eval(e, 0, 0);
        }
      }
    }
    if (!moved) {
      /* the end: y0 + dt k2 (rk2; error dt/6 (k1 - 2 k2 + k3)) or
       * y0 + dt/2 (k1 + k2) (pc) */
      struct drift_stage c = rk2 ? (struct drift_stage){dt,
                                                        3,
                                                        {0.0, 1.0, 0.0},
                                                        rk->y0,
                                                        {rk->r1, rk->r2, NULL},
                                                        NULL,
                                                        0,
                                                        1,
                                                        1,
                                                        {1.0 / 6.0, -2.0 / 6.0, 1.0 / 6.0}}
                                 : (struct drift_stage){dt,   2, {0.5, 0.5}, rk->y0, {rk->r1, NULL},
                                                        NULL, 0, 1,          0,      {0.0}};
      err = drift_integrate_stage(e, &c, &moved);
    }
    if (moved) {
      /* a stage would leave the cells' reach: from the start again, after
       * a rebuild (the step's length stays) */
      drift_integrate_restore(e);
      e->time = t0;
      atomic_store((_Atomic int *)&e->need_rebuild, 0);
      engine_rebuild(e);
      rebuilt = 1;
      drift_integrate_alloc(e);
      engine_watchdog_before_drift(e); /* (the rebuild reordered the particles) */
      save = 1;
      rk->redone++;
      if (rebuilds_here++ > 0)
        error_exit(
            "scheme %s: a stage of the step of %g at t = %g needs a rebuild even right "
            "after one: in one step the particles' kernel supports grow beyond what the "
            "cells allow (in a periodic box: half the box) or the particles move more than "
            "a cell",
            rk2 ? "rk2" : "pc", dt, t0);
      continue;
    }
    if (rk2 && err > rk->tol) {
      /* too large an error: the same step shorter (at least a fifth) */
      double f = 0.9 * cbrt(rk->tol / err);
      if (!(f > 0.2)) f = 0.2;
      e->dt = dt * f;
      rk->rejected++;
      if (e->dt < e->dt_min)
        error_exit(
            "scheme rk2: the step that keeps the error below TimeIntegration:rk2_tolerance "
            "= %g at t = %g is %g, below TimeIntegration:dt_min = %g (error %g at dt %g)",
            rk->tol, t0, e->dt, e->dt_min, err, dt);
      if (++tries > 60)
        error_exit(
            "scheme rk2: no step below the error bound %g at t = %g after 60 tries (error "
            "%g at dt %g)",
            rk->tol, t0, err, dt);
      continue;
    }
    rk->err_last = err;
    break;
  }
  engine_watchdog_after_drift(e);
  e->time = t0 + e->dt;
  if (e->next_out < e->nr_out && fabs(e->time - e->out_times[e->next_out]) <= 1e-12 * fabs(e->time))
    e->time = e->out_times[e->next_out];
  drift_integrate_eval(e, rebuilt, 1);
  if (rk2) {
    /* the next step: dt (tol / err)^(1/3) 0.9, at most twice this one (the
     * Courant step and the others bound it too: cell_dt_min) */
    double f = rk->err_last > 0.0 ? 0.9 * cbrt(rk->tol / rk->err_last) : 2.0;
    if (f > 2.0) f = 2.0;
    const double dt_err = e->dt * f;
    if (e->nr_tcells > 0 && dt_err < e->cell_dt_min[0]) e->cell_dt_min[0] = dt_err;
  }
  return 1;
}

void drift_integrate_log(const struct engine *e) {
  const struct drift_integrator *rk = e->rk;
  if (!rk) return;
  error_log(
      0,
      "time integration %s: %ld evaluations inside the steps (%.2f per step), %ld steps taken "
      "again with a shorter step (error above TimeIntegration:rk2_tolerance), %ld after a "
      "rebuild in their middle",
      e->scheme == ENGINE_SCHEME_RK2 ? "rk2" : "pc", rk->stages,
      e->step > 0 ? (double)rk->stages / (double)e->step : 0.0, rk->rejected, rk->redone);
}
