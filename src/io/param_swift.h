/* SWIFT's parameter keys and sections that Bolide accepts without an effect.
 *
 * A parameter file written for SWIFT (its examples/parameter_example.yml and
 * its planetary and hydro-test examples) runs as it is: every key SWIFT has
 * for the same thing is a key of BOLIDE_PARAMS (param_list.h) with SWIFT's
 * name and meaning; the keys and sections below are SWIFT's for things that
 * Bolide does not do or does another way.  They are accepted whatever their
 * value, and each one given gets one line, "FILE:LINE: note: ... has no
 * effect in Bolide: REASON" (a warning where ignoring it changes what is
 * simulated, as an external potential does).  The reference parameter file
 * lists them (params_write_reference).
 *
 * X(name, level, reason)
 *   name: "Section:key", or "Section" for every key of a section, or
 *         "Prefix*" for every section whose name starts with Prefix;
 *   level: PARAM_SWIFT_NOTE or PARAM_SWIFT_WARN. */
#ifndef BOLIDE_PARAM_SWIFT_H
#define BOLIDE_PARAM_SWIFT_H

#define PARAM_SWIFT_NOTE 0
#define PARAM_SWIFT_WARN 1

/* clang-format off */
#define BOLIDE_SWIFT_IGNORED(X)                                                                          \
  X("PhysicalConstants:mu_0", PARAM_SWIFT_NOTE, "Bolide has no magnetic fields")                        \
  X("SPH:delta_neighbours", PARAM_SWIFT_NOTE, "the neighbour tolerance follows from SPH:h_tolerance (as in SWIFT, which no longer reads this key)") \
  X("SPH:use_mass_weighted_num_ngb", PARAM_SWIFT_NOTE, "neighbours are counted by number")             \
  X("SPH:particle_splitting", PARAM_SWIFT_NOTE, "Bolide does not split particles")                     \
  X("SPH:particle_splitting_mass_threshold", PARAM_SWIFT_NOTE, "Bolide does not split particles")      \
  X("SPH:particle_splitting_log_extra_splits", PARAM_SWIFT_NOTE, "Bolide does not split particles")    \
  X("SPH:generate_random_ids", PARAM_SWIFT_NOTE, "Bolide does not create particles")                   \
  X("SPH:initial_temperature", PARAM_SWIFT_WARN, "the internal energies of the initial conditions are used as they are") \
  X("SPH:minimal_temperature", PARAM_SWIFT_NOTE, "the floors of the equations of state apply (P_min, cs_min, u >= 0 where the EOS needs it)") \
  X("SPH:H_mass_fraction", PARAM_SWIFT_NOTE, "Bolide has no cooling or chemistry")                     \
  X("SPH:H_ionization_temperature", PARAM_SWIFT_NOTE, "Bolide has no cooling or chemistry")            \
  X("SPH:viscosity_alpha_max", PARAM_SWIFT_NOTE, "the viscosity alpha is fixed (SPH:viscosity_alpha)") \
  X("SPH:viscosity_alpha_min", PARAM_SWIFT_NOTE, "the viscosity alpha is fixed (SPH:viscosity_alpha)") \
  X("SPH:viscosity_length", PARAM_SWIFT_NOTE, "the viscosity alpha is fixed (SPH:viscosity_alpha)")    \
  X("SPH:diffusion_alpha", PARAM_SWIFT_NOTE, "Bolide's artificial conduction is SPH:conductivity_alpha") \
  X("SPH:diffusion_beta", PARAM_SWIFT_NOTE, "Bolide's artificial conduction is SPH:conductivity_alpha") \
  X("SPH:diffusion_alpha_max", PARAM_SWIFT_NOTE, "Bolide's artificial conduction is SPH:conductivity_alpha") \
  X("SPH:diffusion_alpha_min", PARAM_SWIFT_NOTE, "Bolide's artificial conduction is SPH:conductivity_alpha") \
  X("Gravity:mesh_side_length", PARAM_SWIFT_NOTE, "Bolide has no particle mesh: the tree covers the whole box") \
  X("Gravity:distributed_mesh", PARAM_SWIFT_NOTE, "Bolide has no particle mesh")                       \
  X("Gravity:mesh_uses_local_patches", PARAM_SWIFT_NOTE, "Bolide has no particle mesh")                \
  X("Gravity:use_tree_below_softening", PARAM_SWIFT_NOTE, "the opening criteria are Gravity:theta_cr and Gravity:epsilon_fmm") \
  X("Gravity:allow_truncation_in_MAC", PARAM_SWIFT_NOTE, "Bolide has no truncated long-range force")   \
  X("Gravity:comoving_DM_softening", PARAM_SWIFT_NOTE, "Bolide has no cosmology and no dark matter")   \
  X("Gravity:max_physical_DM_softening", PARAM_SWIFT_NOTE, "Bolide has no dark matter")                \
  X("Gravity:comoving_baryon_softening", PARAM_SWIFT_NOTE, "Bolide has no cosmology (the softening is Gravity:max_physical_baryon_softening)") \
  X("Gravity:comoving_nu_softening", PARAM_SWIFT_NOTE, "Bolide has no neutrinos")                      \
  X("Gravity:max_physical_nu_softening", PARAM_SWIFT_NOTE, "Bolide has no neutrinos")                  \
  X("Gravity:softening_ratio_background", PARAM_SWIFT_NOTE, "Bolide has no background particles")     \
  X("Gravity:max_adaptive_softening", PARAM_SWIFT_NOTE, "adaptive softening is Gravity:softening_h_factor") \
  X("Gravity:min_adaptive_softening", PARAM_SWIFT_NOTE, "adaptive softening is Gravity:softening_h_factor") \
  X("Gravity:rebuild_frequency", PARAM_SWIFT_NOTE, "the tree is rebuilt with the cells (Scheduler:rebuild_fraction)") \
  X("Gravity:rebuild_active_fraction", PARAM_SWIFT_NOTE, "every particle is active every step")        \
  X("Gravity:a_smooth", PARAM_SWIFT_NOTE, "Bolide has no long-range mesh force")                        \
  X("Gravity:r_cut_max", PARAM_SWIFT_NOTE, "Bolide has no long-range mesh force")                       \
  X("Gravity:r_cut_min", PARAM_SWIFT_NOTE, "Bolide has no long-range mesh force")                       \
  X("Scheduler:nr_queues", PARAM_SWIFT_NOTE, "one queue per worker thread")                            \
  X("Scheduler:cell_max_size", PARAM_SWIFT_NOTE, "task sizes are Scheduler:cell_task_size and gravity_task_size") \
  X("Scheduler:cell_sub_size_pair_hydro", PARAM_SWIFT_NOTE, "task sizes are Scheduler:cell_task_size") \
  X("Scheduler:cell_sub_size_self_hydro", PARAM_SWIFT_NOTE, "task sizes are Scheduler:cell_task_size") \
  X("Scheduler:cell_sub_size_pair_stars", PARAM_SWIFT_NOTE, "Bolide has no stars")                     \
  X("Scheduler:cell_sub_size_self_stars", PARAM_SWIFT_NOTE, "Bolide has no stars")                     \
  X("Scheduler:cell_sub_size_pair_grav", PARAM_SWIFT_NOTE, "gravity task sizes are Scheduler:gravity_task_size") \
  X("Scheduler:cell_sub_size_self_grav", PARAM_SWIFT_NOTE, "gravity task sizes are Scheduler:gravity_task_size") \
  X("Scheduler:grid_split_threshold", PARAM_SWIFT_NOTE, "Bolide has no Voronoi grid")                  \
  X("Scheduler:cell_subdepth_diff_grav", PARAM_SWIFT_NOTE, "gravity task sizes are Scheduler:gravity_task_size") \
  X("Scheduler:cell_extra_parts", PARAM_SWIFT_NOTE, "Bolide does not create particles")                \
  X("Scheduler:cell_extra_gparts", PARAM_SWIFT_NOTE, "Bolide does not create particles")               \
  X("Scheduler:cell_extra_sparts", PARAM_SWIFT_NOTE, "Bolide does not create particles")               \
  X("Scheduler:cell_extra_bparts", PARAM_SWIFT_NOTE, "Bolide does not create particles")               \
  X("Scheduler:cell_extra_sinks", PARAM_SWIFT_NOTE, "Bolide does not create particles")                \
  X("Scheduler:tasks_per_cell", PARAM_SWIFT_NOTE, "the task arrays grow as needed")                     \
  X("Scheduler:links_per_tasks", PARAM_SWIFT_NOTE, "the task arrays grow as needed")                    \
  X("Scheduler:mpi_message_limit", PARAM_SWIFT_NOTE, "Bolide has no MPI yet")                          \
  X("Scheduler:engine_max_parts_per_ghost", PARAM_SWIFT_NOTE, "ghost tasks follow Scheduler:cell_task_size") \
  X("Scheduler:engine_max_sparts_per_ghost", PARAM_SWIFT_NOTE, "Bolide has no stars")                  \
  X("Scheduler:engine_max_parts_per_cooling", PARAM_SWIFT_NOTE, "Bolide has no cooling")               \
  X("Scheduler:engine_redist_alloc_margin", PARAM_SWIFT_NOTE, "Bolide has no MPI yet")                 \
  X("Scheduler:engine_foreign_alloc_margin", PARAM_SWIFT_NOTE, "Bolide has no MPI yet")                \
  X("Scheduler:dependency_graph_frequency", PARAM_SWIFT_NOTE, "task timelines are Scheduler:dump_tasks (-y N)") \
  X("Scheduler:dependency_graph_cell", PARAM_SWIFT_NOTE, "task timelines are Scheduler:dump_tasks (-y N)") \
  X("Scheduler:task_level_output_frequency", PARAM_SWIFT_NOTE, "task timelines are Scheduler:dump_tasks (-y N)") \
  X("Scheduler:free_foreign_during_restart", PARAM_SWIFT_NOTE, "Bolide has no MPI yet")                \
  X("Scheduler:free_foreign_during_rebuild", PARAM_SWIFT_NOTE, "Bolide has no MPI yet")                \
  X("Scheduler:deadlock_waiting_time_s", PARAM_SWIFT_NOTE, "the watchdog of --enable-debug-checks detects deadlocks") \
  X("TimeIntegration:max_dt_RMS_factor", PARAM_SWIFT_NOTE, "the time step follows the Courant, acceleration and change limits") \
  X("TimeIntegration:dt_RMS_use_gas_only", PARAM_SWIFT_NOTE, "the time step follows the Courant, acceleration and change limits") \
  X("TimeIntegration:max_nr_rt_subcycles", PARAM_SWIFT_NOTE, "Bolide has no radiative transfer")       \
  X("Snapshots:scale_factor_first", PARAM_SWIFT_NOTE, "Bolide has no cosmology (Snapshots:time_first)") \
  X("Snapshots:int_time_label_on", PARAM_SWIFT_NOTE, "snapshots are numbered BASENAME_NNNN.hdf5")      \
  X("Snapshots:invoke_stf", PARAM_SWIFT_NOTE, "Bolide runs no structure finder (bolide-fof runs on snapshots)") \
  X("Snapshots:invoke_fof", PARAM_SWIFT_NOTE, "run bolide-fof on the snapshots")                       \
  X("Snapshots:invoke_ps", PARAM_SWIFT_NOTE, "Bolide computes no power spectra")                       \
  X("Snapshots:distributed", PARAM_SWIFT_NOTE, "snapshots are one file each")                          \
  X("Snapshots:lustre_OST_checks", PARAM_SWIFT_NOTE, "Bolide does no Lustre striping checks")          \
  X("Snapshots:lustre_OST_free", PARAM_SWIFT_NOTE, "Bolide does no Lustre striping checks")            \
  X("Snapshots:lustre_OST_test", PARAM_SWIFT_NOTE, "Bolide does no Lustre striping checks")            \
  X("Snapshots:use_delta_from_edge", PARAM_SWIFT_NOTE, "snapshots are not lossy-compressed")           \
  X("Snapshots:delta_from_edge", PARAM_SWIFT_NOTE, "snapshots are not lossy-compressed")               \
  X("Snapshots:UnitMass_in_cgs", PARAM_SWIFT_NOTE, "snapshots are in the internal units, recorded in their /Units group") \
  X("Snapshots:UnitLength_in_cgs", PARAM_SWIFT_NOTE, "snapshots are in the internal units, recorded in their /Units group") \
  X("Snapshots:UnitVelocity_in_cgs", PARAM_SWIFT_NOTE, "snapshots are in the internal units, recorded in their /Units group") \
  X("Snapshots:UnitCurrent_in_cgs", PARAM_SWIFT_NOTE, "snapshots are in the internal units, recorded in their /Units group") \
  X("Snapshots:UnitTemp_in_cgs", PARAM_SWIFT_NOTE, "snapshots are in the internal units, recorded in their /Units group") \
  X("Snapshots:select_output_on", PARAM_SWIFT_NOTE, "every snapshot holds every field (Snapshots:accelerations adds more)") \
  X("Snapshots:select_output", PARAM_SWIFT_NOTE, "every snapshot holds every field (Snapshots:accelerations adds more)") \
  X("Snapshots:run_on_dump", PARAM_SWIFT_NOTE, "Bolide runs no command after a snapshot")              \
  X("Snapshots:dump_command", PARAM_SWIFT_NOTE, "Bolide runs no command after a snapshot")             \
  X("Snapshots:recording_triggers_part", PARAM_SWIFT_NOTE, "Bolide has no tracers")                    \
  X("Snapshots:recording_triggers_spart", PARAM_SWIFT_NOTE, "Bolide has no tracers")                   \
  X("Snapshots:recording_triggers_bpart", PARAM_SWIFT_NOTE, "Bolide has no tracers")                   \
  X("Snapshots:recording_triggers_sink", PARAM_SWIFT_NOTE, "Bolide has no tracers")                    \
  X("Statistics:scale_factor_first", PARAM_SWIFT_NOTE, "Bolide has no cosmology (Statistics:time_first)") \
  X("Statistics:rt_subcycles_file_name", PARAM_SWIFT_NOTE, "Bolide has no radiative transfer")         \
  X("Statistics:output_list_on", PARAM_SWIFT_NOTE, "statistics are written every Statistics:delta_time") \
  X("Statistics:output_list", PARAM_SWIFT_NOTE, "statistics are written every Statistics:delta_time")  \
  X("InitialConditions:generate_gas_in_ics", PARAM_SWIFT_WARN, "Bolide does not create particles")     \
  X("InitialConditions:cleanup_h_factors", PARAM_SWIFT_NOTE, "the smoothing lengths are read as stored (no Gadget h-factors)") \
  X("InitialConditions:cleanup_velocity_factors", PARAM_SWIFT_NOTE, "the velocities are read as stored (no cosmology)") \
  X("InitialConditions:cleanup_smoothing_lengths", PARAM_SWIFT_NOTE, "the smoothing lengths are iterated to SPH:resolution_eta at start-up whatever their value") \
  X("InitialConditions:stars_smoothing_length", PARAM_SWIFT_NOTE, "Bolide has no stars")               \
  X("InitialConditions:black_holes_smoothing_length", PARAM_SWIFT_NOTE, "Bolide has no black holes")   \
  X("InitialConditions:replicate", PARAM_SWIFT_WARN, "the initial conditions are used once (replicate a box with bolide-ic)") \
  X("InitialConditions:remap_ids", PARAM_SWIFT_NOTE, "the particle ids are kept")                      \
  X("InitialConditions:metadata_group_name", PARAM_SWIFT_NOTE, "Bolide copies no metadata group")      \
  X("Restarts:resubmit_on_exit", PARAM_SWIFT_NOTE, "Bolide runs no command at exit (Restarts:max_run_time stops with status 0)") \
  X("Restarts:resubmit_command", PARAM_SWIFT_NOTE, "Bolide runs no command at exit")                   \
  X("Restarts:lustre_OST_checks", PARAM_SWIFT_NOTE, "Bolide does no Lustre striping checks")           \
  X("Restarts:lustre_OST_free", PARAM_SWIFT_NOTE, "Bolide does no Lustre striping checks")             \
  X("Restarts:lustre_OST_test", PARAM_SWIFT_NOTE, "Bolide does no Lustre striping checks")             \
  X("Cosmology", PARAM_SWIFT_WARN, "Bolide has no cosmology")                                          \
  X("Stars", PARAM_SWIFT_NOTE, "Bolide has no stars")                                                  \
  X("BlackHoles", PARAM_SWIFT_NOTE, "Bolide has no black holes")                                       \
  X("Sinks", PARAM_SWIFT_NOTE, "Bolide has no sinks")                                                  \
  X("DefaultSink", PARAM_SWIFT_NOTE, "Bolide has no sinks")                                            \
  X("BasicSink", PARAM_SWIFT_NOTE, "Bolide has no sinks")                                              \
  X("GEARSink", PARAM_SWIFT_NOTE, "Bolide has no sinks")                                               \
  X("ForceChecks", PARAM_SWIFT_NOTE, "gravity accuracy is checked by make check (test_gravity_accuracy)") \
  X("FOF", PARAM_SWIFT_NOTE, "run bolide-fof on the snapshots")                                        \
  X("CSDS", PARAM_SWIFT_NOTE, "Bolide has no continuous simulation data stream")                       \
  X("DomainDecomposition:initial_type", PARAM_SWIFT_NOTE, "the first partition is METIS on the estimated costs (Morton ranges without METIS)") \
  X("DomainDecomposition:initial_grid", PARAM_SWIFT_NOTE, "the first partition is METIS on the estimated costs (Morton ranges without METIS)") \
  X("DomainDecomposition:repartition_type", PARAM_SWIFT_NOTE, "a new partition weighs the cells by the measured task times (DomainDecomposition:trigger)") \
  X("DomainDecomposition:minfrac", PARAM_SWIFT_NOTE, "every rank takes part in every partition") \
  X("DomainDecomposition:usemetis", PARAM_SWIFT_NOTE, "METIS is used when configure found it") \
  X("DomainDecomposition:adaptive", PARAM_SWIFT_NOTE, "a new partition is made from scratch, its parts numbered to keep most cells in place") \
  X("DomainDecomposition:itr", PARAM_SWIFT_NOTE, "a new partition is made from scratch, its parts numbered to keep most cells in place") \
  X("DomainDecomposition:use_fixed_costs", PARAM_SWIFT_NOTE, "a new partition weighs the cells by the measured task times") \
  X("DomainDecomposition:synchronous", PARAM_SWIFT_NOTE, "the exchanges are collective") \
  X("StructureFinding", PARAM_SWIFT_NOTE, "Bolide runs no structure finder")                           \
  X("LineOfSight", PARAM_SWIFT_NOTE, "Bolide writes no lines of sight")                                \
  X("PowerSpectrum", PARAM_SWIFT_NOTE, "Bolide computes no power spectra")                             \
  X("Lightcone*", PARAM_SWIFT_NOTE, "Bolide writes no lightcones")                                     \
  X("Neutrino", PARAM_SWIFT_NOTE, "Bolide has no neutrinos")                                           \
  X("XrayEmissivity", PARAM_SWIFT_NOTE, "Bolide has no X-ray emission")                                \
  X("MHD", PARAM_SWIFT_NOTE, "Bolide has no magnetic fields")                                          \
  X("PointMassPotential", PARAM_SWIFT_WARN, "Bolide has no external potentials")                       \
  X("IsothermalPotential", PARAM_SWIFT_WARN, "Bolide has no external potentials")                      \
  X("HernquistPotential", PARAM_SWIFT_WARN, "Bolide has no external potentials")                       \
  X("NFWPotential", PARAM_SWIFT_WARN, "Bolide has no external potentials")                             \
  X("NFW_MNPotential", PARAM_SWIFT_WARN, "Bolide has no external potentials")                          \
  X("DiscPatchPotential", PARAM_SWIFT_WARN, "Bolide has no external potentials")                       \
  X("SineWavePotential", PARAM_SWIFT_WARN, "Bolide has no external potentials")                        \
  X("MWPotential2014Potential", PARAM_SWIFT_WARN, "Bolide has no external potentials")                 \
  X("BoundaryParticles", PARAM_SWIFT_WARN, "Bolide's fixed boundary particles are those of a material with boundary: true (theory/boundaries.md)") \
  X("RobertsFlowForcing", PARAM_SWIFT_WARN, "Bolide has no forcing")                                   \
  X("RobertsFlowAccelerationForcing", PARAM_SWIFT_WARN, "Bolide has no forcing")                       \
  X("ABC_Flow_Forcing", PARAM_SWIFT_WARN, "Bolide has no forcing")                                     \
  X("BalsaraKimForcing", PARAM_SWIFT_WARN, "Bolide has no forcing")                                    \
  X("EAGLEEntropyFloor", PARAM_SWIFT_NOTE, "Bolide has no galaxy-formation physics")                   \
  X("QLAEntropyFloor", PARAM_SWIFT_NOTE, "Bolide has no galaxy-formation physics")                     \
  X("GEARPressureFloor", PARAM_SWIFT_NOTE, "Bolide has no galaxy-formation physics")                   \
  X("ConstCooling", PARAM_SWIFT_NOTE, "Bolide has no cooling")                                         \
  X("LambdaCooling", PARAM_SWIFT_NOTE, "Bolide has no cooling")                                        \
  X("EAGLECooling", PARAM_SWIFT_NOTE, "Bolide has no cooling")                                         \
  X("QLACooling", PARAM_SWIFT_NOTE, "Bolide has no cooling")                                           \
  X("PS2020Cooling", PARAM_SWIFT_NOTE, "Bolide has no cooling")                                        \
  X("GrackleCooling", PARAM_SWIFT_NOTE, "Bolide has no cooling")                                       \
  X("EAGLEChemistry", PARAM_SWIFT_NOTE, "Bolide has no chemistry")                                     \
  X("GEARChemistry", PARAM_SWIFT_NOTE, "Bolide has no chemistry")                                      \
  X("AGORAChemistry", PARAM_SWIFT_NOTE, "Bolide has no chemistry")                                     \
  X("EAGLEStarFormation", PARAM_SWIFT_NOTE, "Bolide has no star formation")                            \
  X("QLAStarFormation", PARAM_SWIFT_NOTE, "Bolide has no star formation")                              \
  X("GEARStarFormation", PARAM_SWIFT_NOTE, "Bolide has no star formation")                             \
  X("EAGLEFeedback", PARAM_SWIFT_NOTE, "Bolide has no feedback")                                       \
  X("GEARFeedback", PARAM_SWIFT_NOTE, "Bolide has no feedback")                                        \
  X("GEARSupernovaeII", PARAM_SWIFT_NOTE, "Bolide has no feedback")                                    \
  X("GEARStellarWind", PARAM_SWIFT_NOTE, "Bolide has no feedback")                                     \
  X("AGORAFeedback", PARAM_SWIFT_NOTE, "Bolide has no feedback")                                       \
  X("EAGLEAGN", PARAM_SWIFT_NOTE, "Bolide has no black holes")                                         \
  X("SPINJETAGN", PARAM_SWIFT_NOTE, "Bolide has no black holes")                                       \
  X("GEARRT", PARAM_SWIFT_NOTE, "Bolide has no radiative transfer")                                    \
  X("SPHM1RT", PARAM_SWIFT_NOTE, "Bolide has no radiative transfer")
/* clang-format on */

#endif
