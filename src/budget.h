/* The conservation budget of a run (theory/sph.md, "Conservation budget"):
 * what particles removed from an open box took with them, and the totals
 * of the start that the statistics file and the end-of-run summary compare
 * against.  Kept in the restart files, so that a resumed run reports the
 * budget of the whole run. */
#ifndef BOLIDE_BUDGET_H
#define BOLIDE_BUDGET_H

/** What the particles removed from an open box carried when they left
 *  (space_rebuild accumulates it; internal units). */
struct budget_removed {
  double m;         /**< mass */
  double E;         /**< kinetic + internal + their share m phi of the potential energy */
  double p[3];      /**< momentum */
  double L[3];      /**< angular momentum about the origin */
  double E_clamp;   /**< their e_clamp: energy the kick's floor on u had added to them */
  double W_plastic; /**< their plastic work */
};

/** Totals of the run's first statistics line. */
struct budget_start {
  double E_tot;  /**< E_kin + E_int + E_pot */
  double E_pot;  /**< potential energy (0 without self-gravity) */
  double E_abs;  /**< |E_kin| + |E_int| + |E_pot| */
  double p[3];   /**< momentum */
  double L[3];   /**< angular momentum */
  double p_abs;  /**< sum of m |v|, the scale of momentum errors */
  double set;    /**< 1 once measured */
  double com[3]; /**< centre of mass: the fixed point of the angular-momentum budget, so that
                      a momentum error does not show as one of angular momentum at the lever
                      arm of the origin (theory/sph.md, "Conservation budget"; since restart
                      format 7) */
};

#endif
