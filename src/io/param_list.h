/* Every parameter key Bolide knows: the one list from which validation,
 * defaults, the reference file examples/parameters.yml (bolide
 * --param-reference) and the parameters echoed into snapshots come.
 *
 * X(name, type, default, min, max, choices, unit, doc)
 *   default NULL means the key is required.  Ranges are inclusive; use
 *   PARAM_INF for no bound.  For PARAM_STRING, min and max bound the length
 *   of the text in bytes (max 0: no bound); for PARAM_REAL_ARRAY, choices is
 *   the '|'-separated list of the allowed numbers of values (NULL: any).  Keys follow SWIFT's
 * sections and names where SWIFT has the same thing. */
#ifndef BOLIDE_PARAM_LIST_H
#define BOLIDE_PARAM_LIST_H

#include "tasks/hydro/kernel.h" /* KERNEL_ETA_DEFAULT_STR: the default resolution_eta of the kernel */

#define PARAM_INF 1e308

/* clang-format off */
#define BOLIDE_PARAMS(X)                                                                                 \
  X("MetaData:run_name", PARAM_STRING, "bolide", 0, 1023, NULL, "-", "name of the run, recorded in every output") \
                                                                                                         \
  X("InternalUnitSystem:UnitMass_in_cgs", PARAM_REAL, "1000", 1e-300, PARAM_INF, NULL, "g", "internal mass unit (default: 1 kg)") \
  X("InternalUnitSystem:UnitLength_in_cgs", PARAM_REAL, "100", 1e-300, PARAM_INF, NULL, "cm", "internal length unit (default: 1 m)") \
  X("InternalUnitSystem:UnitVelocity_in_cgs", PARAM_REAL, "100", 1e-300, PARAM_INF, NULL, "cm/s", "internal velocity unit (default: 1 m/s); the time unit is length/velocity") \
  X("InternalUnitSystem:UnitCurrent_in_cgs", PARAM_REAL, "1", 1e-300, PARAM_INF, NULL, "A", "internal current unit") \
  X("InternalUnitSystem:UnitTemp_in_cgs", PARAM_REAL, "1", 1e-300, PARAM_INF, NULL, "K", "internal temperature unit") \
                                                                                                         \
  X("PhysicalConstants:G", PARAM_REAL, "0", 0, PARAM_INF, NULL, "internal units", "Newton's constant in internal units, as SWIFT's key (0: 6.67430e-11 m^3 kg^-1 s^-2 converted to the internal units)") \
                                                                                                         \
  X("InitialConditions:file_name", PARAM_STRING, NULL, 1, 1023, NULL, "-", "HDF5 initial conditions (relative paths: to the parameter file's folder)") \
  X("InitialConditions:periodic", PARAM_BOOL, "false", 0, 0, NULL, "-", "periodic box (true) or open box (false)") \
  X("InitialConditions:box_size", PARAM_REAL_ARRAY, "[]", 0, PARAM_INF, "0|1|3", "internal length", "box size overriding /Header/BoxSize (1 or 3 values)") \
  X("InitialConditions:shift", PARAM_REAL_ARRAY, "[0, 0, 0]", -PARAM_INF, PARAM_INF, "3", "internal length", "shift added to every position on reading") \
  X("InitialConditions:smoothing_length_scaling", PARAM_REAL, "1", 1e-6, 1e6, NULL, "-", "factor applied to the smoothing lengths read") \
                                                                                                         \
  X("TimeIntegration:time_begin", PARAM_REAL, "0", -PARAM_INF, PARAM_INF, NULL, "internal time", "simulation time at the start") \
  X("TimeIntegration:time_end", PARAM_REAL, NULL, -PARAM_INF, PARAM_INF, NULL, "internal time", "simulation time at which the run stops") \
  X("TimeIntegration:dt_min", PARAM_REAL, "1e-12", 0, PARAM_INF, NULL, "internal time", "smallest allowed time step; a smaller one stops the run with an error") \
  X("TimeIntegration:dt_max", PARAM_REAL, "1e30", 0, PARAM_INF, NULL, "internal time", "largest allowed time step") \
  X("TimeIntegration:max_bin_ratio", PARAM_INT, "1", 1, 56, NULL, "-", "with individual time steps, the time-step limiter (Saitoh & Makino 2009; Durier & Dalla Vecchia 2012): a particle's bin is at most this many bins (a factor 2^n in time step) longer than the shortest of its neighbours', and a particle in the middle of a longer step is woken (its step ended at once) when a neighbour that ends its step has a bin more than this many shorter; default 1 (a factor 2): with 2 the Sedov blast of tests/physics/test_time_bins.py changes its energy by 0.9%, with 1 by 0.2% (0.03% with the global step); 56: no limiter; theory/sph.md section 8") \
  X("TimeIntegration:global_step", PARAM_BOOL, "true", 0, 0, NULL, "-", "every particle steps with the smallest time step of all (true; the timesteps file shows the bins the particles' own limits would take and the fraction of updates they would do), or each with its own step in power-of-two time bins on an integer time line (false; theory/sph.md section 8; CPU and GPU; only the particles that end their step are computed (self-gravity too: Gravity:active_only); neighbours' bins kept within TimeIntegration:max_bin_ratio; issue 20)") \
  X("TimeIntegration:scheme", PARAM_ENUM, "kdk", 0, 0, "kdk|rk2|pc", "-", "time integrator: kdk (kick-drift-kick leapfrog, one derivative evaluation per step, symplectic; every task family, CPU and GPU, global step or time bins), rk2 (Runge-Kutta 2 with an adaptive step: the midpoint rule, its error estimated against the third-order rule of Kutta sharing its stages and held below TimeIntegration:rk2_tolerance, three evaluations per step, like miluphcuda's default) or pc (predictor-corrector: Euler predictor, trapezoidal corrector (Heun), two evaluations per step); rk2 and pc run with the global step, on the CPU and the GPU; theory/integrators.md") \
  X("TimeIntegration:rk2_tolerance", PARAM_REAL, "1e-3", 1e-12, PARAM_INF, NULL, "-", "with scheme: rk2, the largest accepted error of a step: the largest over the particles of the difference between the second- and third-order results, positions in units of h, velocities of the larger of |v| and the sound speed, energies of |u| + 1e-2 c_s^2, densities and distentions relative, deviatoric stresses of |S| + 1e-3 rho c_s^2; a step above it is taken again with a shorter step, and the next step is dt (tolerance/error)^(1/3) times 0.9, at most twice the last and never above the Courant step; theory/integrators.md") \
                                                                                                         \
  X("Snapshots:basename", PARAM_STRING, "snapshot", 1, 255, NULL, "-", "snapshot file prefix (files are BASENAME_NNNN.hdf5; relative to the output folder)") \
  X("Snapshots:subdir", PARAM_STRING, ".", 1, 1023, NULL, "-", "folder for snapshots and statistics, created if missing") \
  X("Snapshots:time_first", PARAM_REAL, "0", -PARAM_INF, PARAM_INF, NULL, "internal time", "time of the first snapshot") \
  X("Snapshots:delta_time", PARAM_REAL, "0", 0, PARAM_INF, NULL, "internal time", "time between snapshots (0: only the first and last)") \
  X("Snapshots:output_list", PARAM_STRING, "", 0, 1023, NULL, "-", "file with one output time per line (overrides time_first/delta_time)") \
  X("Snapshots:output_list_on", PARAM_BOOL, "true", 0, 0, NULL, "-", "use Snapshots:output_list when it names a file (SWIFT's switch: false ignores the list)") \
  X("Snapshots:accelerations", PARAM_BOOL, "false", 0, 0, NULL, "-", "write Accelerations (and Potentials with gravity) in every snapshot") \
  X("Snapshots:compression", PARAM_INT, "0", 0, 9, NULL, "-", "gzip level of the datasets (0: none)") \
  X("Snapshots:enabled", PARAM_BOOL, "true", 0, 0, NULL, "-", "write snapshots (false: none, not even the first and last: benchmarks of large runs; the statistics, restart files and crash snapshots are still written)") \
                                                                                                         \
  X("Statistics:delta_time", PARAM_REAL, "0", 0, PARAM_INF, NULL, "internal time", "time between lines of the statistics file (0: every step)") \
  X("Statistics:time_first", PARAM_REAL, "0", -PARAM_INF, PARAM_INF, NULL, "internal time", "time of the first line of the statistics file (the start of the run when earlier); the lines follow every delta_time") \
  X("Statistics:energy_file_name", PARAM_STRING, "statistics", 1, 255, NULL, "-", "statistics file name (a .txt suffix is added)") \
  X("Statistics:timestep_file_name", PARAM_STRING, "timesteps", 1, 255, NULL, "-", "file with one line per step (step, time, dt, active particles, wall time; a .txt suffix is added), as SWIFT's") \
  X("Statistics:max_angular_momentum_change", PARAM_REAL, "0", 0, PARAM_INF, NULL, "-", "angular-momentum check, at every line of the statistics file: the run stops with exit status 3 when |L - L(0)| / |L(0)| (about the centre of mass of the start; the particles that left an open box counted) exceeds this (0: off; open boxes only; theory/sph.md, \"Conservation budget\")") \
                                                                                                         \
  X("SPH:resolution_eta", PARAM_REAL, KERNEL_ETA_DEFAULT_STR, 0.1, 10, NULL, "-", "target h in units of the mean inter-particle spacing; the default depends on the kernel: 1.7 with the Wendland C2 kernel (the default kernel, 149 neighbours; theory/sph.md, section 1), 1.2348 with the others (48 neighbours with the cubic spline)") \
  X("SPH:h_tolerance", PARAM_REAL, "1e-4", 1e-10, 0.1, NULL, "-", "relative tolerance of the smoothing length iteration") \
  X("SPH:h_taylor", PARAM_BOOL, "true", 0, 0, NULL, "-", "a Newton step of the smoothing length iteration of at most sqrt(h_tolerance / 6) relative is taken with the density sums corrected to first order in the step (rho + h-derivative times the step, the neighbour number likewise) instead of summing again; the neglected second-order term is below h_tolerance (theory/sph.md section 2); false: every such particle sums again") \
  X("SPH:h_max", PARAM_REAL, "1e30", 0, PARAM_INF, NULL, "internal length", "largest allowed smoothing length") \
  X("SPH:h_min_ratio", PARAM_REAL, "0", 0, 1, NULL, "-", "smallest allowed h in units of the softening (0: no limit)") \
  X("SPH:h_evolution", PARAM_ENUM, "iterate", 0, 0, "iterate|continuity", "-", "smoothing length: iterate (solve n(h) h^3 = resolution_eta^3 at every step, the neighbour number; the drift's dh/dt = h div v / 3 is its first guess) or continuity (integrate dh/dt = -h/(3 rho) drho/dt in the drift, with the drho/dt of the force loop, and take it as it is: h keeps the ratio to (m/rho)^(1/3) of the initial conditions, e.g. a graded body from bolide-ic import-mesh; theory/sph.md section 2)") \
  X("SPH:max_ghost_iterations", PARAM_INT, "30", 1, 1000, NULL, "-", "iterations of the smoothing length before the run stops with an error") \
  X("SPH:CFL_condition", PARAM_REAL, "0.2", 1e-4, 1, NULL, "-", "Courant factor of the time step") \
  X("SPH:max_volume_change", PARAM_REAL, "1.4", 1.01, 10, NULL, "-", "largest allowed change of kernel volume in one step") \
  X("SPH:viscosity_alpha", PARAM_REAL, "1.5", 0, 10, NULL, "-", "Monaghan artificial viscosity alpha") \
  X("SPH:viscosity_beta", PARAM_REAL, "3", 0, 20, NULL, "-", "Monaghan artificial viscosity beta (in units of alpha: beta = 2 alpha when 2)") \
  X("SPH:balsara", PARAM_BOOL, "true", 0, 0, NULL, "-", "Balsara switch on the artificial viscosity") \
  X("SPH:conductivity_alpha", PARAM_REAL, "0", 0, 10, NULL, "-", "artificial conduction of internal energy (Price 2008); 0 switches it off") \
  X("SPH:density", PARAM_ENUM, "summation", 0, 0, "summation|continuity", "-", "density from kernel summation or from the continuity equation") \
  X("SPH:continuity_correction", PARAM_BOOL, "false", 0, 0, NULL, "-", "with density: continuity, take div v in drho/dt = -rho div v from the velocity gradient corrected by the correction tensor (CSPM; Eghtesad & Knezevic 2018), exact for linear velocity fields") \
  X("SPH:continuity_min_density_ratio", PARAM_REAL, "0.01", 0, 1, NULL, "-", "with density: continuity, the integrated density never falls below this fraction of the material's reference density rho0 (nor below its density_floor); a particle on the floor keeps its density while its neighbours diverge (theory/sph.md section 6; 0: no floor)") \
  X("SPH:xsph_epsilon", PARAM_REAL, "0", 0, 1, NULL, "-", "XSPH velocity smoothing factor (0: off)") \
  X("SPH:free_surface", PARAM_BOOL, "false", 0, 0, NULL, "-", "free-surface detection: a fluid particle (a material without strength) whose kernel sum sum_j m_j/rho_j W_ij falls below free_surface_threshold is on the free surface and its pressure is set to 0 (theory/fluids.md); needs density: continuity; runs the gradient tasks") \
  X("SPH:free_surface_threshold", PARAM_REAL, "0.9", 0.01, 0.99, NULL, "-", "with free_surface, the kernel sum sum_j m_j/rho_j W_ij below which a fluid particle is on the free surface (1 inside a fluid; on a cubic lattice 0.75-0.8 on a face, 0.66 on an edge, 0.53 at a corner: theory/fluids.md)") \
  X("SPH:fluid_solid_interface", PARAM_BOOL, "false", 0, 0, NULL, "-", "fluid-solid interface treatment (Eghtesad & Knezevic 2018): a pair of a fluid and a solid particle takes the solid's pressure and deviatoric stress against the fluid's pressure and viscous stress in the form (sigma_i + sigma_j)/(rho_i rho_j) and carries no tension (pressures below 0 taken as 0); no penalty force (theory/fluids.md F6-F8); needs density: continuity and continuity_correction: true (CSPM continuity for both phases)") \
  X("SPH:momentum_form", PARAM_ENUM, "standard", 0, 0, "standard|symmetric", "-", "momentum equation: sigma_i/rho_i^2 + sigma_j/rho_j^2 (standard, Gray et al. 2001) or (sigma_i + sigma_j)/(rho_i rho_j) (symmetric)") \
  X("SPH:velocity_gradient_correction", PARAM_BOOL, "true", 0, 0, NULL, "-", "linear-consistency correction tensor on the velocity gradient of solids (Randles & Libersky 1996)") \
  X("SPH:artificial_stress_epsilon", PARAM_REAL, "0", 0, 1, NULL, "-", "artificial stress factor epsilon_s against the tensile instability (Monaghan 2000; 0: off)") \
  X("SPH:artificial_stress_n", PARAM_REAL, "4", 1, 20, NULL, "-", "artificial stress exponent n (Monaghan 2000)") \
  X("SPH:max_relative_change", PARAM_REAL, "0", 0, 1, NULL, "-", "time-step limit: largest relative change of density, energy and deviatoric stress in one step (0: off)") \
  X("SPH:hydro", PARAM_BOOL, "true", 0, 0, NULL, "-", "compute hydrodynamics (false: gravity-only run)") \
  X("SPH:gamma", PARAM_REAL, "1.6666666666666667", 1.0001, 10, NULL, "-", "adiabatic index of the default ideal-gas material (id 0) when no Materials section is given") \
                                                                                                         \
  X("ConstantPotential:g_cgs", PARAM_REAL_ARRAY, "[0, 0, 0]", -PARAM_INF, PARAM_INF, "3", "cm/s^2", "uniform external acceleration g acting on every particle but the fixed boundary particles (the potential -g.x, counted in the statistics' E_pot), as SWIFT's key of the same name: [0, 0, -981] is the Earth's surface gravity along -z (theory/boundaries.md)") \
                                                                                                         \
  X("Boundaries:planes", PARAM_REAL_ARRAY, "[]", -PARAM_INF, PARAM_INF, "0|6|12|18|24|30|36|42|48", "internal length", "plane walls made of mirror ghost particles, six numbers per plane: a point on the plane and its normal, pointing into the domain (x, y, z, nx, ny, nz; the normal need not be unit length); each particle in front of a plane and within (2 + Scheduler:rebuild_fraction) top-level cell widths of it has a ghost behind it, its mirror image with the mirrored velocity (Boundaries:slip) and stress and the same mass, h, density and energy, refreshed before every force computation, computed as a particle in it but never kicked, written or counted (Monaghan 1994; miluphcuda's ghost boundaries; theory/boundaries.md); the ghosts must lie inside the box; CPU only, global time step, no self-gravity, no restart files (a run with them stops with one line)") \
  X("Boundaries:slip", PARAM_ENUM, "free_slip", 0, 0, "free_slip|no_slip", "-", "velocity of the mirror ghosts: free_slip (the normal component reversed, the tangential kept: no friction) or no_slip (the whole velocity reversed, 2 v_wall - v with the wall at rest: the viscous stress holds the fluid at the wall; Takeda et al. 1994, Morris et al. 1997)") \
                                                                                                         \
  X("Gravity:enabled", PARAM_BOOL, "false", 0, 0, NULL, "-", "self-gravity on or off") \
  X("Gravity:direct", PARAM_BOOL, "false", 0, 0, NULL, "-", "exact O(N^2) summation instead of multipoles") \
  X("Gravity:theta_cr", PARAM_REAL, "0.5", 0, 1, NULL, "-", "opening angle of the multipole acceptance criterion") \
  X("Gravity:MAC", PARAM_ENUM, "adaptive", 0, 0, "adaptive|geometric|gadget", "-", "multipole acceptance criterion, as SWIFT's key: adaptive (Gravity:epsilon_fmm besides theta_cr), geometric (theta_cr alone: epsilon_fmm is taken as 0), gadget (read as adaptive)") \
  X("Gravity:eta", PARAM_REAL, "0.025", 1e-6, 10, NULL, "-", "gravitational time-step factor: dt = sqrt(2 eta eps / |a|)") \
  X("Gravity:softening", PARAM_REAL, "0", 0, PARAM_INF, NULL, "internal length", "Plummer-equivalent softening length (absolute)") \
  X("Gravity:softening_h_factor", PARAM_REAL, "0", 0, PARAM_INF, NULL, "-", "softening tied to h: eps_i = factor * h_i, pairs use max(eps_i, eps_j); 0 = off (absolute Gravity:softening); spline kernel only") \
  X("Gravity:max_physical_baryon_softening", PARAM_REAL, "0", 0, PARAM_INF, NULL, "internal length", "SWIFT's name for the softening; used when Gravity:softening is 0") \
  X("Gravity:softening_kernel", PARAM_ENUM, "spline", 0, 0, "spline|plummer", "-", "pair softening: spline (Wendland C2 mass, Newtonian beyond 3 eps) or plummer (1/sqrt(r^2+eps^2)); theory/gravity.md") \
  X("Gravity:epsilon_fmm", PARAM_REAL, "5e-5", 0, 1, NULL, "-", "tolerance of the adaptive opening criterion (Dehnen 2014): a cell-cell interaction is accepted only if its acceleration error, estimated from the source's multipole power at the expansion order, is below epsilon_fmm times the smallest gravitational acceleration in the receiving cell (the previous evaluation's; on a run's first step a cheaper geometric pass's), besides theta_cr; a particle's total error sums its ~10-30 interactions: the defaults give median 2.4e-5, p99 1.0e-4 on the reference impact (SWIFT's 3.3e-5, 1.7e-4 at its epsilon_fmm 1e-3); 0: the geometric criterion alone; theory/gravity.md, BENCHMARKS.md") \
  X("Gravity:multipole_order", PARAM_INT, "5", 1, 5, NULL, "-", "order p of the multipole and local expansions (potential to order p, forces to p-1); 5 reaches a given accuracy at less cost than 4 with the adaptive criterion (BENCHMARKS.md); theory/gravity.md") \
  X("Gravity:reuse_steps", PARAM_INT, "0", 0, 1000000, NULL, "-", "reuse the far field (multipoles and local expansions) for at most this many steps after a full evaluation, recomputing only the particle-level interactions (0: every step is full); theory/gravity.md") \
  X("Gravity:active_only", PARAM_BOOL, "true", 0, 0, NULL, "-", "with individual time steps (TimeIntegration:global_step: false) on the CPU: compute self-gravity only for the cells that hold a particle ending its step (the others keep the acceleration of their last evaluation, which nothing reads before their step ends; steps with statistics or snapshots compute every particle's); on the GPU too when its walks run on the device (Scheduler:gpu_walks: device); false: every particle at every step; theory/gravity.md") \
  X("Gravity:gpu_reproducible", PARAM_BOOL, "false", 0, 0, NULL, "-", "self-gravity on the GPU: sort the interactions of each cell, whose order the device's atomics change from run to run, so that a GPU run repeats bit for bit (tests/gpu/test_gpu_run.sh); costs about 14 ms per evaluation (+16%) and 364 bytes per particle at 1.1e6 on the H200 (BENCHMARKS.md); false: runs agree to round-off") \
  X("Gravity:reuse_tolerance", PARAM_REAL, "0.01", 0, 1, NULL, "-", "a step reuses the far field only while every particle has moved less than this fraction of the shortest far-field interaction distance since the full evaluation") \
                                                                                                         \
  X("Scheduler:cell_split_size", PARAM_INT, "400", 8, 1000000, NULL, "-", "largest number of particles in a leaf cell (default 400; 32 when self-gravity is on and the key is not given)") \
  X("Scheduler:cell_task_size", PARAM_INT, "1000", 8, 100000000, NULL, "-", "tasks work on octree cells of at most this many particles (smaller: more, finer tasks); 8000 when the GPU runs the whole phase and this is not set") \
  X("Scheduler:gravity_task_size", PARAM_INT, "2000", 8, 1000000000, NULL, "-", "the self-gravity task of a top-level cell with more particles is split into tasks on its octants (and theirs, up to 3 levels down) so that a concentrated body keeps every worker busy") \
  X("Scheduler:max_top_level_cells", PARAM_INT, "16", 1, 1024, NULL, "-", "largest number of top-level cells along one side") \
  X("Scheduler:dump_tasks", PARAM_INT, "0", 0, PARAM_INF, NULL, "-", "write a task timeline (thread, start, end, type, cell) every this many steps (0: never)") \
  X("Scheduler:rebuild_fraction", PARAM_REAL, "0.25", 0.01, 1, NULL, "-", "rebuild the cells once a particle drifted this fraction of its cell's width") \
  X("Scheduler:deterministic", PARAM_BOOL, "false", 0, 0, NULL, "-", "keep the task priorities fixed instead of learning them from measured task times: with one thread (-t 1) every run, and every run resumed from a restart file, then repeats bit for bit (for tests; slightly slower)") \
  X("Scheduler:gpu", PARAM_WORDS, "auto", 0, 0, NULL, "-", "where the tasks run (CUDA builds with a GPU): off (every task on the CPU); all (everything the GPU can do, one family after the other: self-gravity's CPU part (multipoles, walks), its device part, then the hydrodynamics); a list of the task families on the GPU, the others on the CPU workers at the same time: the hydrodynamic families density, gradient, force, damage, drift, kick run on it as one phase and are named together (ghost goes with density), with gravity: the walks run on the CPU beside the GPU's hydrodynamics, then gravity's device part, then the kick (hybrid), without it: the whole of self-gravity on the CPU beside the GPU's hydrodynamics; auto: the measured best, the hybrid list [density, gradient, force, damage, drift, kick, gravity] where gravity's walks run on the CPU (Scheduler:gpu_walks: host), else all (BENCHMARKS.md)") \
  X("Scheduler:cpu_leaf_size", PARAM_INT, "400", 0, 1000000, NULL, "-", "the CPU's hydro loops (density, gradient, force) treat an octree cell of at most this many particles as a leaf and loop over all its pairs (coarser than the tree's leaves when larger than Scheduler:cell_split_size, as with self-gravity's leaves of 32; 0: the tree's leaves)") \
  X("Scheduler:gpu_leaf_size", PARAM_INT, "0", 0, 1000000, NULL, "-", "the GPU runner's hydro neighbour lists join cells of at most this many particles (coarser than the tree's leaves when larger than Scheduler:cell_split_size: fewer list entries, more pairs tested per entry; 0: the tree's leaves)") \
  X("Scheduler:gpu_lists", PARAM_ENUM, "device", 0, 0, "device|host", "-", "where the GPU runner builds its hydro neighbour lists: device (kernels; the lists stay on the GPU) or host (threads walking the trees, the lists uploaded; the same lists, for comparison)") \
  X("Scheduler:gpu_rebuild", PARAM_ENUM, "device", 0, 0, "device|host", "-", "how a rebuild treats particles resident on the GPU: device (the host sorts the cells from the positions and smoothing lengths it holds, with the few fields it reads downloaded; the device reorders its own copy of every field, with no full copy over the bus) or host (every field back to the host, reordered there and uploaded again; for comparison); host is used anyway where the rebuild removes particles (open box) and with mirror planes") \
  X("Scheduler:gpu_multipoles", PARAM_ENUM, "device", 0, 0, "host|device", "-", "where the GPU runner computes gravity's multipoles (P2M, M2M) when gravity runs on the GPU: device (kernels with the same inline functions, equal to the CPU's bit for bit) or host (the CPU workers' grav_up tasks, uploaded; then the walks are on the host too unless Scheduler:gpu_walks says device)") \
  X("Scheduler:gpu_walks", PARAM_ENUM, "device", 0, 0, "host|device", "-", "where the GPU runner walks gravity's trees when gravity runs on the GPU: device (kernels with the CPU's decisions, gravity_walk.h; needs the multipoles on the device) or host (the CPU workers' tasks record the interactions while the GPU computes the hydrodynamics, uploaded; the default with Gravity:reuse_steps > 0, which the device walks do not support yet)") \
                                                                                                         \
  X("DomainDecomposition:method", PARAM_ENUM, "auto", 0, 0, "auto|metis|morton|slabs", "-", "several MPI ranks: how the top-level cells are split over the ranks, at the start and at each repartition (DomainDecomposition:trigger): auto (METIS when the build has it, else Morton ranges), metis (METIS_PartGraphKway on the graph of the cells weighted by their estimated or measured costs, or the Morton ranges where those balance 5% better, as on a few heavy cells; a build without METIS stops with an error), morton (contiguous ranges of the cells' Morton order of equal cost: compact domains without a library), slabs (slabs along x of equal width: the naive split, for comparison); theory/mpi.md, \"Domain decomposition\"") \
  X("DomainDecomposition:trigger", PARAM_REAL, "0", 0, PARAM_INF, NULL, "-", "several MPI ranks: at a rebuild, when the busiest rank's measured task time of the last step exceeds the ranks' mean by more than this fraction, rank 0 partitions the top-level cells again with the measured costs (the split of DomainDecomposition:method), keeps the new partition if its imbalance is lower by at least half the trigger, numbers its parts so that most cells stay where they are, and the particles move to their new ranks (SWIFT's key; theory/mpi.md, \"Repartitioning\"); 0 (the default until it is measured on machines whose ranks each have their own cores: the task times of ranks sharing cores vary by tens of percent from step to step): never") \
                                                                                                         \
  X("Damage:seed", PARAM_INT, "1", 0, 9.2e18, NULL, "-", "seed of the Weibull flaws drawn at start-up for brittle materials (materials with weibull_k > 0 and a shear modulus)") \
  X("Damage:start_time", PARAM_REAL, "0", 0, 1e300, NULL, "internal time", "no flaw activation and no damage growth before this time (lets bodies settle under self-gravity first: their settling oscillation can exceed the weakest flaws' thresholds; 0: damage from the start)") \
  X("Damage:max_change", PARAM_REAL, "0.1", 1e-6, 1, NULL, "-", "time-step limit: damage d grows by at most this much per step (d^(1/3) is integrated exactly and capped, so saturation takes about 1/max_change steps)") \
                                                                                                         \
  X("Porosity:ic_tolerance", PARAM_REAL, "0.01", 0, 1, NULL, "-", "start-up check of porous bodies: the IC density times the distention must be the matrix density rho0 of the material within this relative difference") \
                                                                                                         \
  X("Restarts:enable", PARAM_BOOL, "false", 0, 0, NULL, "-", "write restart files") \
  X("Restarts:delta_hours", PARAM_REAL, "1", 0, PARAM_INF, NULL, "h", "wall-clock hours between restart files") \
  X("Restarts:subdir", PARAM_STRING, "restart", 1, 1023, NULL, "-", "folder of the restart files") \
  X("Restarts:delta_steps", PARAM_INT, "0", 0, 1000000000, NULL, "-", "steps between restart files, besides delta_hours (0: none)") \
  X("Restarts:max_run_time", PARAM_REAL, "0", 0, PARAM_INF, NULL, "h", "wall-clock hours after which the run writes a restart file and stops with status 0, for the time limit of a batch queue (0: no limit)") \
  X("Restarts:save", PARAM_BOOL, "true", 0, 0, NULL, "-", "keep the previous restart file as restart.prev.bin (as SWIFT's key; Bolide always keeps it, false gets a note)") \
  X("Restarts:onexit", PARAM_BOOL, "true", 0, 0, NULL, "-", "write a restart file when the run ends (with Restarts:enable; as SWIFT's key; Bolide always does, false gets a note)") \
  X("Restarts:basename", PARAM_STRING, "restart", 1, 255, NULL, "-", "name of the restart files in Restarts:subdir: BASENAME.bin and BASENAME.prev.bin (SWIFT's key)") \
  X("Restarts:stop_steps", PARAM_INT, "1", 1, 1000000000, NULL, "-", "steps between looks for the stop file Restarts:subdir/stop, whose presence makes the run write a restart file and stop (as SWIFT's key; SWIFT's default is 100)") \
                                                                                                         \
  X("Materials", PARAM_SECTION, "", 0, 0, NULL, "-", "material table: see examples/parameters.yml") \
  X("EoS", PARAM_SECTION, "", 0, 0, NULL, "-", "SWIFT's planetary equation-of-state section, read as entries of Materials: see examples/parameters.yml")
/* clang-format on */

#endif
