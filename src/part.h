/* Particles: one structure of arrays.
 *
 * Every per-particle field is declared once, in BOLIDE_PART_FIELDS below.
 * From that one list come the struct members, allocation, reordering on
 * rebuild, the HDF5 dataset names of initial conditions and snapshots, their
 * units and the XDMF description (theory/architecture.md, rule 5: "one list,
 * many uses").
 *
 * Vectors and tensors are stored one array per component (x, y, z each a
 * contiguous array) so that CPU loops vectorise and GPU loads coalesce; the
 * I/O layer gathers the components sharing an HDF5 name into an N x ncomp
 * dataset.
 *
 * X(type, name, h5name, comp, ncomp, uM, uL, uT, flags, description)
 *   type        C type of the array (double, int64_t, int32_t)
 *   name        struct member
 *   h5name      dataset in /PartType0 (NULL: internal, never in files)
 *   comp,ncomp  component index and component count of that dataset
 *   uM,uL,uT    unit exponents of mass, length and time
 *   flags       PART_IC_REQ  must be present in initial conditions
 *               PART_IC_OPT  read from initial conditions when present
 *               PART_SNAP    written to every snapshot
 *               PART_SNAP_ACC written when Snapshots:accelerations is true
 *
 * "Hot" fields (read by neighbour loops) come first; "cold" fields (kick,
 * drift, bookkeeping) after.  The GPU runner moves only the hot fields a loop
 * needs. */
#ifndef BOLIDE_PART_H
#define BOLIDE_PART_H

#include <stddef.h>
#include <stdint.h>

enum part_flags {
  PART_IC_REQ = 1,
  PART_IC_OPT = 2,
  PART_SNAP = 4,
  PART_SNAP_ACC = 8,
};

/* clang-format off */
#define BOLIDE_PART_FIELDS(X)                                                                     \
  /* hot: positions, predicted velocities, masses, smoothing lengths */                           \
  X(double,  x,   "Coordinates",      0, 3, 0,  1,  0, PART_IC_REQ | PART_SNAP, "position")       \
  X(double,  y,   "Coordinates",      1, 3, 0,  1,  0, PART_IC_REQ | PART_SNAP, "position")       \
  X(double,  z,   "Coordinates",      2, 3, 0,  1,  0, PART_IC_REQ | PART_SNAP, "position")       \
  X(double,  vpx, NULL,               0, 3, 0,  1, -1, 0, "predicted velocity used in interactions") \
  X(double,  vpy, NULL,               1, 3, 0,  1, -1, 0, "predicted velocity used in interactions") \
  X(double,  vpz, NULL,               2, 3, 0,  1, -1, 0, "predicted velocity used in interactions") \
  X(double,  m,   "Masses",           0, 1, 1,  0,  0, PART_IC_REQ | PART_SNAP, "mass")           \
  X(double,  h,   "SmoothingLengths", 0, 1, 0,  1,  0, PART_IC_OPT | PART_SNAP, "smoothing length (kernel support = kernel_gamma * h)") \
  X(double,  rho, "Densities",        0, 1, 1, -3,  0, PART_IC_OPT | PART_SNAP, "density")        \
  X(double,  up,  NULL,               0, 1, 0,  2, -2, 0, "predicted specific internal energy")   \
  X(double,  P,   "Pressures",        0, 1, 1, -1, -2, PART_SNAP, "pressure")                     \
  X(double,  cs,  "SoundSpeeds",      0, 1, 0,  1, -1, PART_SNAP, "sound speed")                  \
  X(double,  cl,  NULL,               0, 1, 0,  1, -1, 0, "longitudinal wave speed sqrt(c_s^2 + 4 (1-D) G / (3 rho)) of a solid, the time step's signal speed (set only in runs with strength)") \
  X(double,  balsara, NULL,           0, 1, 0,  0,  0, 0, "Balsara switch")                       \
  X(double,  f_gradh, NULL,           0, 1, 0,  0,  0, 0, "grad-h correction factor")             \
  X(int32_t, mat, "MaterialIDs",      0, 1, 0,  0,  0, PART_IC_OPT | PART_SNAP, "material id")    \
  /* hot, solids: predicted deviatoric stress (xx, xy, xz, yy, yz, zz) and artificial stress */    \
  X(double,  Spxx, NULL,              0, 6, 1, -1, -2, 0, "predicted deviatoric stress xx")       \
  X(double,  Spxy, NULL,              1, 6, 1, -1, -2, 0, "predicted deviatoric stress xy")       \
  X(double,  Spxz, NULL,              2, 6, 1, -1, -2, 0, "predicted deviatoric stress xz")       \
  X(double,  Spyy, NULL,              3, 6, 1, -1, -2, 0, "predicted deviatoric stress yy")       \
  X(double,  Spyz, NULL,              4, 6, 1, -1, -2, 0, "predicted deviatoric stress yz")       \
  X(double,  Spzz, NULL,              5, 6, 1, -1, -2, 0, "predicted deviatoric stress zz")       \
  X(double,  Rxx,  NULL,              0, 6, -1, 5, -2, 0, "artificial stress R/rho^2 xx (Monaghan 2000)") \
  X(double,  Rxy,  NULL,              1, 6, -1, 5, -2, 0, "artificial stress R/rho^2 xy")         \
  X(double,  Rxz,  NULL,              2, 6, -1, 5, -2, 0, "artificial stress R/rho^2 xz")         \
  X(double,  Ryy,  NULL,              3, 6, -1, 5, -2, 0, "artificial stress R/rho^2 yy")         \
  X(double,  Ryz,  NULL,              4, 6, -1, 5, -2, 0, "artificial stress R/rho^2 yz")         \
  X(double,  Rzz,  NULL,              5, 6, -1, 5, -2, 0, "artificial stress R/rho^2 zz")         \
  /* density loop accumulators */                                                                 \
  X(double,  wcount,    NULL,         0, 1, 0,  0,  0, 0, "kernel-weighted neighbour count")      \
  X(double,  wcount_dh, NULL,         0, 1, 0, -1,  0, 0, "d wcount / dh")                        \
  X(double,  rho_dh,    NULL,         0, 1, 1, -4,  0, 0, "d rho / dh")                           \
  X(double,  div_v,     NULL,         0, 1, 0,  0, -1, 0, "velocity divergence")                  \
  X(double,  curl_vx,   NULL,         0, 3, 0,  0, -1, 0, "velocity curl")                        \
  X(double,  curl_vy,   NULL,         1, 3, 0,  0, -1, 0, "velocity curl")                        \
  X(double,  curl_vz,   NULL,         2, 3, 0,  0, -1, 0, "velocity curl")                        \
  /* gradient loop accumulators (solids): M = sum V_j (x_j - x_i) (x) grad W (symmetric) and      \
   * G = sum V_j (v_j - v_i) (x) grad W; after the extra ghost gv holds dv^a/dx^b */              \
  X(double,  gmxx, NULL,              0, 6, 0,  0,  0, 0, "correction-tensor sum xx")             \
  X(double,  gmxy, NULL,              1, 6, 0,  0,  0, 0, "correction-tensor sum xy")             \
  X(double,  gmxz, NULL,              2, 6, 0,  0,  0, 0, "correction-tensor sum xz")             \
  X(double,  gmyy, NULL,              3, 6, 0,  0,  0, 0, "correction-tensor sum yy")             \
  X(double,  gmyz, NULL,              4, 6, 0,  0,  0, 0, "correction-tensor sum yz")             \
  X(double,  gmzz, NULL,              5, 6, 0,  0,  0, 0, "correction-tensor sum zz")             \
  X(double,  gvxx, NULL,              0, 9, 0,  0, -1, 0, "velocity gradient dvx/dx")             \
  X(double,  gvxy, NULL,              1, 9, 0,  0, -1, 0, "velocity gradient dvx/dy")             \
  X(double,  gvxz, NULL,              2, 9, 0,  0, -1, 0, "velocity gradient dvx/dz")             \
  X(double,  gvyx, NULL,              3, 9, 0,  0, -1, 0, "velocity gradient dvy/dx")             \
  X(double,  gvyy, NULL,              4, 9, 0,  0, -1, 0, "velocity gradient dvy/dy")             \
  X(double,  gvyz, NULL,              5, 9, 0,  0, -1, 0, "velocity gradient dvy/dz")             \
  X(double,  gvzx, NULL,              6, 9, 0,  0, -1, 0, "velocity gradient dvz/dx")             \
  X(double,  gvzy, NULL,              7, 9, 0,  0, -1, 0, "velocity gradient dvz/dy")             \
  X(double,  gvzz, NULL,              8, 9, 0,  0, -1, 0, "velocity gradient dvz/dz")             \
  X(double,  wvol, NULL,              0, 1, 0,  0,  0, 0, "kernel sum sum_j m_j/rho_j W_ij (gradient loop; the extra ghost adds the self term): the free-surface detection's") \
  /* force loop accumulators */                                                                   \
  X(double,  ax,  "Accelerations",    0, 3, 0,  1, -2, PART_SNAP_ACC, "acceleration")             \
  X(double,  ay,  "Accelerations",    1, 3, 0,  1, -2, PART_SNAP_ACC, "acceleration")             \
  X(double,  az,  "Accelerations",    2, 3, 0,  1, -2, PART_SNAP_ACC, "acceleration")             \
  X(double,  du_dt,  NULL,            0, 1, 0,  2, -3, 0, "rate of change of specific internal energy") \
  X(double,  drho_dt, NULL,           0, 1, 1, -3, -1, 0, "rate of change of density")           \
  X(double,  v_sig,  NULL,            0, 1, 0,  1, -1, 0, "maximum signal velocity")              \
  X(double,  pot,  "Potentials",      0, 1, 0,  2, -2, PART_SNAP_ACC, "gravitational potential")  \
  X(double,  gax, NULL,               0, 3, 0,  1, -2, 0, "gravitational acceleration (gravity tasks' accumulator, added to ax by the kick; kept as the scale of the next adaptive opening criterion)") \
  X(double,  gay, NULL,               1, 3, 0,  1, -2, 0, "gravitational acceleration") \
  X(double,  gaz, NULL,               2, 3, 0,  1, -2, 0, "gravitational acceleration") \
  X(double,  xsphx, NULL,             0, 3, 0,  1, -1, 0, "XSPH velocity correction (Monaghan 1989)") \
  X(double,  xsphy, NULL,             1, 3, 0,  1, -1, 0, "XSPH velocity correction")            \
  X(double,  xsphz, NULL,             2, 3, 0,  1, -1, 0, "XSPH velocity correction")            \
  /* cold: integrated state, bookkeeping */                                                       \
  X(double,  vx,  "Velocities",       0, 3, 0,  1, -1, PART_IC_REQ | PART_SNAP, "velocity")       \
  X(double,  vy,  "Velocities",       1, 3, 0,  1, -1, PART_IC_REQ | PART_SNAP, "velocity")       \
  X(double,  vz,  "Velocities",       2, 3, 0,  1, -1, PART_IC_REQ | PART_SNAP, "velocity")       \
  X(double,  u,   "InternalEnergies", 0, 1, 0,  2, -2, PART_IC_OPT | PART_SNAP, "specific internal energy") \
  X(double,  Sxx, "DeviatoricStress", 0, 6, 1, -1, -2, PART_IC_OPT | PART_SNAP, "deviatoric stress xx (components xx xy xz yy yz zz)") \
  X(double,  Sxy, "DeviatoricStress", 1, 6, 1, -1, -2, PART_IC_OPT | PART_SNAP, "deviatoric stress xy") \
  X(double,  Sxz, "DeviatoricStress", 2, 6, 1, -1, -2, PART_IC_OPT | PART_SNAP, "deviatoric stress xz") \
  X(double,  Syy, "DeviatoricStress", 3, 6, 1, -1, -2, PART_IC_OPT | PART_SNAP, "deviatoric stress yy") \
  X(double,  Syz, "DeviatoricStress", 4, 6, 1, -1, -2, PART_IC_OPT | PART_SNAP, "deviatoric stress yz") \
  X(double,  Szz, "DeviatoricStress", 5, 6, 1, -1, -2, PART_IC_OPT | PART_SNAP, "deviatoric stress zz") \
  X(double,  dSxx, NULL,              0, 6, 1, -1, -3, 0, "dS/dt xx (Hooke + Jaumann)")          \
  X(double,  dSxy, NULL,              1, 6, 1, -1, -3, 0, "dS/dt xy")                            \
  X(double,  dSxz, NULL,              2, 6, 1, -1, -3, 0, "dS/dt xz")                            \
  X(double,  dSyy, NULL,              3, 6, 1, -1, -3, 0, "dS/dt yy")                            \
  X(double,  dSyz, NULL,              4, 6, 1, -1, -3, 0, "dS/dt yz")                            \
  X(double,  dSzz, NULL,              5, 6, 1, -1, -3, 0, "dS/dt zz")                            \
  X(double,  eps_p, "PlasticStrains", 0, 1, 0,  0,  0, PART_IC_OPT | PART_SNAP, "accumulated equivalent plastic strain") \
  X(double,  w_plastic, NULL,          0, 1, 0,  2, -2, 0, "specific plastic work sum Y d eps_p / rho of the radial returns (statistics: W_plastic)") \
  X(double,  e_clamp, NULL,            0, 1, 0,  2, -2, 0, "specific energy added by the kick's floor on u, which halves an energy that would go negative (statistics: E_clamp)") \
  /* fracture (tasks/damage): Grady-Kipp damage with Weibull flaws */                              \
  X(double,  dmg, "Damage",           0, 1, 0,  0,  0, PART_IC_OPT | PART_SNAP, "tensile damage d in [0, 1] (Grady & Kipp 1980; Benz & Asphaug 1995)") \
  X(double,  dcbrt, "DamageCubeRoot", 0, 1, 0,  0,  0, PART_IC_OPT | PART_SNAP, "d^(1/3), the integrated variable of the damage model") \
  X(double,  dmg_shear, "ShearDamage", 0, 1, 0,  0,  0, PART_IC_OPT | PART_SNAP, "shear (compressive) damage D_s in [0, 1] from the plastic strain (Collins et al. 2004)") \
  X(int32_t, n_act, "ActiveFlaws",    0, 1, 0,  0,  0, PART_SNAP, "number of activated flaws") \
  X(int32_t, n_flaws, "NumberOfFlaws", 0, 1, 0, 0,  0, PART_SNAP, "number of flaws of the particle") \
  X(int64_t, flaw_first, NULL,        0, 1, 0,  0,  0, 0, "index of the particle's first flaw threshold in the engine's flat array") \
  X(double,  dmg_rate, NULL,          0, 1, 0,  0, -1, 0, "growth rate of d^(1/3) in the last step") \
  /* porosity (src/materials/porosity_eos.h): P-alpha distention */                                \
  X(double,  alpha, "Distentions",    0, 1, 0,  0,  0, PART_IC_OPT | PART_SNAP, "distention alpha = rho_matrix / rho of porous materials (Jutzi et al. 2008; 1: not porous; 0 or absent in ICs: alpha_0 of the material)") \
  X(double,  alpha_p, NULL,           0, 1, 0,  0,  0, 0, "predicted distention (the EOS of the ghost uses it)") \
  X(double,  dalpha_dt, NULL,         0, 1, 0,  0, -1, 0, "rate of change of the distention") \
  X(double,  rho_full, NULL,          0, 1, 1, -3,  0, 0, "density integrated by the continuity equation") \
  X(double,  rho_fp, NULL,            0, 1, 1, -3,  0, 0, "predicted continuity density")        \
  X(double,  h_lo, NULL,              0, 1, 0,  1,  0, 0, "lower bracket of the h iteration; once converged, the ratio of the root estimated from the sums to h, applied by the drift at the start of the next step (ghost_part_step, drift_h_root; 0: none)") \
  X(double,  h_hi, NULL,              0, 1, 0,  1,  0, 0, "upper bracket of the h iteration")     \
  X(double,  x0,  NULL,               0, 3, 0,  1,  0, 0, "position at the last rebuild")         \
  X(double,  y0,  NULL,               1, 3, 0,  1,  0, 0, "position at the last rebuild")         \
  X(double,  z0,  NULL,               2, 3, 0,  1,  0, 0, "position at the last rebuild")         \
  X(int64_t, id,  "ParticleIDs",      0, 1, 0,  0,  0, PART_IC_REQ | PART_SNAP, "unique particle id") \
  X(int32_t, flags, NULL,             0, 1, 0,  0,  0, 0, "internal state bits (enum part_state)") \
  X(int64_t, msrc, NULL,              0, 1, 0,  0,  0, 0, "mirror ghost (PART_MIRROR): the index of the particle it mirrors, and (msrc_plane) the plane; unused by the others (theory/boundaries.md)") \
  X(int32_t, msrc_plane, NULL,        0, 1, 0,  0,  0, 0, "mirror ghost: the plane of Boundaries:planes it is the image through") \
  X(int32_t, ngb_bin_min, NULL,       0, 1, 0,  0,  0, 0, "time bins: the shortest bin among the particle's neighbours in the last force loop (the limiter's bound on its next bin)") \
  X(int32_t, wake, NULL,              0, 1, 0,  0,  0, 0, "time bins: TIMELINE_NR_BINS + 1 - the bin a neighbour asks a particle in the middle of a longer step to take at once (the limiter's wake-up; 0: none)") \
  X(int32_t, time_bin, NULL,          0, 1, 0,  0,  0, 0, "time bin: with individual time steps (TimeIntegration:global_step: false) the particle steps by 2^time_bin ticks of the run's time line (src/timeline.h); 0 with the global step")
/* clang-format on */

/** The number of fields, as a compile-time constant (for fixed arrays
 *  indexed by field). */
#define PART_COUNT_FIELD(...) +1
enum { PART_NR_FIELDS = 0 BOLIDE_PART_FIELDS(PART_COUNT_FIELD) };

/** Bits of parts.flags. */
enum part_state {
  PART_ACTIVE = 1,        /**< updated in the current step */
  PART_H_CONVERGED = 2,   /**< smoothing length iteration converged */
  PART_RHO_FLOOR = 4,     /**< continuity density held at its floor (continuity_floor.h) */
  PART_U_FLOOR = 8,       /**< its material's EOS needs u >= 0: the kick halves a u that would go
                               negative (material.u_floor, set by the ghost; drift.h) */
  PART_FREE_SURFACE = 16, /**< a fluid particle on the free surface (SPH:free_surface): P = 0
                              (extra_ghost_part.h) */
  PART_INACTIVE = 32,     /**< with individual time steps, in the middle of its step at the end
                               of the step being taken: the FORCE phase leaves it as it is (its
                               sums, rates and equation of state), its neighbours read its
                               predicted state (drift_part_bins); never set with the global step */
  PART_SOLID = 64,        /**< a particle of a material with strength (set by the extra ghost): the
                               fluid-solid interface's phase (force_iact.h) */
  PART_MIRROR = 128,      /**< a mirror ghost of a plane of Boundaries:planes: its sums are
                               computed, its h is its source's, it is never kicked, written or
                               counted (tasks/drift/drift_mirror.c) */
  PART_FOREIGN = 256,     /**< a copy of a particle another MPI rank owns (src/mpi/halo.c): before
                               every FORCE phase and between its stages it takes its owner's
                               state; its own sums are not computed (its h is not iterated), it
                               is never kicked, written or counted */
  PART_WOKEN = 512,       /**< with TimeIntegration:limiter_wake: density, a sleeping particle the
                               density phase woke: its ghost made it active (PART_INACTIVE cleared)
                               for the rest of the step, and the kick closes its truncated step
                               (kick2_part_bins) */
};

/** The flags of particles a rank holds but does not own (no kick, no output,
 *  not in the budget): mirror ghosts and foreign copies. */
#define PART_NOT_OWNED (PART_MIRROR | PART_FOREIGN)
/** Whether particle i is held but not owned (PART_NOT_OWNED): the ghost
 *  keeps its h, the kick and the time step leave it out. */
#define PART_IS_NOT_OWNED(p, i) ((p)->flags[i] & PART_NOT_OWNED)

/** Whether particle i sits out the FORCE phase of this step (time bins). */
#define PART_IS_INACTIVE(p, i) ((p)->flags[i] & PART_INACTIVE)

/** All particles, one array per field. */
struct parts {
  size_t count;    /**< number of particles */
  size_t capacity; /**< allocated length of every array */
#define PART_MEMBER(type, name, ...) type *name;
  BOLIDE_PART_FIELDS(PART_MEMBER)
#undef PART_MEMBER
  /** 1: the run never uses field k, whose array is not held (NULL; parts_drop) */
  unsigned char absent[PART_NR_FIELDS];
};

/** Description of one field, generated from BOLIDE_PART_FIELDS. */
struct part_field {
  const char *name;   /**< struct member name */
  const char *h5name; /**< HDF5 dataset name, NULL if internal */
  int comp, ncomp;    /**< component of the dataset */
  int uM, uL, uT;     /**< unit exponents */
  int flags;          /**< enum part_flags */
  int type;           /**< enum part_field_type */
  size_t size;        /**< bytes per element */
  size_t offset;      /**< offset of the array pointer in struct parts */
  const char *description;
};

enum part_field_type { PART_DOUBLE, PART_INT64, PART_INT32 };

/** The table of all fields, in declaration order. */
extern const struct part_field part_fields[];
extern const int part_nr_fields;

/** Pointer to the array of field f in p. */
void *part_field_array(const struct parts *p, const struct part_field *f);
/** 1 if the elements [lo, hi) of field k (index in part_fields) are all
 *  bits zero. */
int part_field_zero(const struct parts *p, int k, size_t lo, size_t hi);

/** Allocate every array for n particles (zero-filled). */
void parts_alloc(struct parts *p, size_t n);
/** Allocate for n particles (zero-filled) the arrays that like holds. */
void parts_alloc_like(struct parts *p, size_t n, const struct parts *like);
/** Free the arrays of the named fields and mark them absent: part_field_array
 *  returns NULL for them, and parts_reserve, parts_permute, parts_copy_one,
 *  the snapshots (zeros), the restart files (zeros) and the MPI records
 *  (left out) skip them.  Returns the bytes per particle freed. */
size_t parts_drop(struct parts *p, const char *const *names, int n);
/** The solid state (deviatoric stress, its prediction and rate, the
 *  artificial stress, the correction tensor and velocity gradient sums, the
 *  kernel sum of the free-surface detection, the plastic strain and work,
 *  the shear damage) and the fracture fields (Grady-Kipp damage, its cube
 *  root and rate, the flaws): the fields that a run without stress, without
 *  damage and with the kick-drift-kick scheme never reads or writes. */
extern const char *const part_solid_fields[];
extern const int part_nr_solid_fields;
extern const char *const part_damage_fields[];
extern const int part_nr_damage_fields;
/** Grow the arrays to at least n particles, keeping the contents. */
void parts_reserve(struct parts *p, size_t n);
/** Free every array. */
void parts_free(struct parts *p);
/** Reorder every array: new[i] = old[perm[i]]. */
void parts_permute(struct parts *p, const size_t *perm);
/** Copy particle src to position dst (every field). */
void parts_copy_one(struct parts *p, size_t dst, size_t src);
/** Bytes of memory per particle for all arrays. */
size_t parts_bytes_per_particle(void);
/** Bytes of memory per particle for the arrays p holds (not absent). */
size_t parts_bytes_held(const struct parts *p);

#endif
