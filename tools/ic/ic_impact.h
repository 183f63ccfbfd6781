/* bolide-ic impact: the two-body trajectory back from first contact. */
#ifndef BOLIDE_IC_IMPACT_H
#define BOLIDE_IC_IMPACT_H

/** Relative state s = (x, y, z, vx, vy, vz) of the impactor with respect to
 *  the target at the start, for gravitational parameter mu = G (M_t + M_i),
 *  contact distance d_c, speed v_c and angle theta (radians, 0 head-on) at
 *  contact; followed back to separation d0 (> 0) or, if d0 <= 0, to time t0
 *  before contact.  At contact the impactor is at d_c (-cos theta, sin
 *  theta, 0) moving along +x.  Returns the time from the start to contact. */
double ic_impact_start(double mu, double d_c, double v_c, double theta, double d0, double t0,
                       double s[6]);

/** The planet and impact subcommands (argv[0] is the subcommand). */
int icgen_planet_main(int argc, char **argv);
int icgen_impact_main(int argc, char **argv);
/** import-miluphcuda: a miluphcuda ASCII input file (ic_miluphcuda.c). */
int icgen_miluphcuda_main(int argc, char **argv);
/** import-mesh: the nodes of a finite-element mesh (ic_mesh.c). */
int icgen_mesh_main(int argc, char **argv);
/** bolide-ic miluphcuda-materials: a miluphcuda material.cfg as a Materials
 *  section (ic_miluphcuda_cfg.c; needs libconfig). */
int icgen_miluphcuda_cfg_main(int argc, char **argv);

#endif
