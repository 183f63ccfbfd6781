# SWIFT's parameter file for the planetary reference impact of the benchmark
# set (theory/validation.md, "Benchmarks"): SWIFT's settings (cubic spline
# eta 1.2348, CFL 0.2, alpha 1.5, adaptive MAC epsilon_fmm 1e-3, theta 0.5,
# Tillotson granite) in the units of make_impact_ic.py's file (1e24 kg,
# 1e6 m, 1 s).  Sourced by tools/bench/energy.sh and tools/bench/mpi.sh.
#
#   swift_params IC TIME_END DT_MAX STATS_DT EPS CELLS [H_MAX]  > swift.yml
#     EPS: the softening in the file's units (1e6 m); CELLS: the top-level
#     grid; STATS_DT: the statistics' interval; H_MAX: SPH:h_max, if given
swift_params() {
  local hmax=""
  [ -z "${7:-}" ] || hmax="
  h_max: $7"
  cat <<YML
InternalUnitSystem:
  UnitMass_in_cgs: 1e27
  UnitLength_in_cgs: 1e8
  UnitVelocity_in_cgs: 1e8
  UnitCurrent_in_cgs: 1
  UnitTemp_in_cgs: 1
InitialConditions:
  file_name: $1
  periodic: 0
TimeIntegration:
  time_begin: 0
  time_end: $2
  dt_min: 1e-10
  dt_max: $3
Snapshots:
  basename: swift_out
  time_first: 0
  delta_time: 1e10
Statistics:
  time_first: 0
  delta_time: $4
Restarts:
  enable: 0
SPH:
  resolution_eta: 1.2348
  delta_neighbours: 0.1
  CFL_condition: 0.2$hmax
  viscosity_alpha: 1.5
Gravity:
  eta: 0.025
  MAC: adaptive
  epsilon_fmm: 0.001
  theta_cr: 0.5
  comoving_DM_softening: $5
  max_physical_DM_softening: $5
  comoving_baryon_softening: $5
  max_physical_baryon_softening: $5
Scheduler:
  max_top_level_cells: $6
EoS:
  planetary_use_Til_granite: 1
YML
}
