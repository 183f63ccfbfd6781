/* What the engine may know of self-gravity: the gravity family's interface
 * (tasks/task_families.h, TASK_FAMILY_INTERFACES; theory/architecture.md,
 * "Layers").  Its settings, read from the Gravity section, which the engine,
 * the kick's time step and the GPU runner read; and its state (the cells'
 * multipoles and local expansions, the interaction lists and the far field
 * that steps reuse), which the engine holds behind a pointer and drives
 * through the registry's hooks and entry points.  Nothing here includes the
 * family's internals. */
#ifndef BOLIDE_GRAVITY_PROPS_H
#define BOLIDE_GRAVITY_PROPS_H

#include <stdint.h>

struct params;
struct unit_system;

/** Default of Gravity:epsilon_fmm (the same value as in src/io/param_list.h). */
#define GRAVITY_EPSILON_FMM_DEFAULT 5e-5

/** Parameters of self-gravity (section Gravity of the parameter file). */
struct gravity_props {
  int enabled;           /**< Gravity:enabled */
  int direct;            /**< Gravity:direct: exact O(N^2) summation instead of the tree */
  double G;              /**< gravitational constant in internal units */
  double theta;          /**< Gravity:theta_cr, opening angle of the acceptance criterion */
  double eps;            /**< Plummer-equivalent softening length (Gravity:softening) */
  int softening;         /**< enum gravity_softening (Gravity:softening_kernel) */
  int order;             /**< expansion order p (Gravity:multipole_order), 1..GRAVITY_ORDER_MAX */
  double eta;            /**< Gravity:eta, time-step factor: dt = sqrt(2 eta eps / |a|) */
  double epsilon_fmm;    /**< Gravity:epsilon_fmm, tolerance of the adaptive criterion (0: off) */
  double h_support;      /**< distance beyond which the pair force is Newtonian (3 eps for the
                              spline, 0 for Plummer whose expansions are softened) */
  double eps2_expansion; /**< softening squared inside the expansions (eps^2 for Plummer, else 0) */
  double h_factor;       /**< Gravity:softening_h_factor: > 0: eps_i = h_factor h_i, a pair's
                              softening max(eps_i, eps_j), spline only (0: the constant eps) */
  int active_only;       /**< Gravity:active_only: with time bins, gravity for the cells with
                              particles that end their step only (gravity_active_decide) */
  int reuse_steps;       /**< Gravity:reuse_steps: most steps in a row that reuse the far field */
  double reuse_tol;      /**< Gravity:reuse_tolerance: largest displacement since the last full
                              evaluation, in units of the shortest far-field distance */
  int replay;            /**< set by the engine for one step: 1 = reuse the far field
                              (gravity_reuse_decide) */
  int active_step;       /**< set by the engine for one step (gravity_active_decide): 1 = only
                              the cells with particles that end their step receive (on the CPU
                              through `active`, on the GPU through gpu_grav_set_active) */
  unsigned char *active; /**< set by the engine for one step (gravity_active_decide): with time
                              bins, per cell index, whether the cell holds a particle that ends
                              its step (the upward pass fills it); only those cells receive
                              (walks, local expansions, L2P); NULL: every cell receives */
  int64_t active_ti;     /**< with `active`: the step's end on the time line (integertime_t:
                              the particles whose bin's step divides it end their step) */
  const int *remote_idx; /**< several MPI ranks (gravity_top_records_use): per top-level cell,
                              its entry of remote, -1 for a cell of this rank's own particles
                              and an empty one; NULL: one rank */
  const struct gravity_remote *remote; /**< the other ranks' top-level cells (gravity_cpu.h) */
  int remote_only;      /**< several MPI ranks with the walks on the GPU: the long-range walks
                             read only the other ranks' cells whose particles are not all here
                             (by their records; the GPU walks the rest) */
  const int *tops_used; /**< the top-level cells the long-range walks visit (set by the
                             engine at each rebuild and exchange of records): those with
                             particles here or a record, increasing; NULL: every one */
  int nr_tops_used;     /**< their number */
  const struct cell *tops_base; /**< the top-level cells tops_used refers to (nr_tops of them):
                                     other arrays are walked in full */
  int nr_tops;
  const int *remote_partial;        /**< those cells (top-level indices, increasing), the only ones
                                         the walks visit with remote_only */
  int nr_remote_partial;            /**< their number */
  const unsigned char *top_partial; /**< several MPI ranks, per top-level cell of the last
                                         rebuild: 1 for another rank's cell of which only some
                                         particles are here (copies for the hydrodynamics); the
                                         long-range walks read it by its record; NULL: none */
};

/** The family's state in a run (tasks/gravity/gravity_state.h), opaque to
 *  the engine: made by the hook gravity_engine_init, freed by
 *  gravity_engine_clean. */
struct gravity_state;
struct gravity_remote;

/** Fill gp from the Gravity section of params; G from the unit system. */
void gravity_props_init(struct gravity_props *gp, const struct params *params,
                        const struct unit_system *us);

/** Fill gp directly (tests, tools): softening eps with kernel `softening`,
 *  opening angle theta, expansion order p.  Out-of-range p stops with an
 *  error line. */
void gravity_props_set(struct gravity_props *gp, double G, double theta, double eps, int softening,
                       int order);

#endif
