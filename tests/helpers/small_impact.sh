# Sourced by the partition tests (tests/program/test_partition.sh,
# test_partition_counts.sh): small_impact writes, in the current folder,
# the 22,000-particle granite impact they partition (impact.hdf5, from
# $B/bolide-ic) and its parameter file p.yml; exits 1 with a FAIL line
# when bolide-ic fails.
small_impact() {
  "$B/bolide-ic" impact --target sphere,material=granite,radius=1e6,n=20000,u=237000 \
    --impactor sphere,material=granite,radius=4.642e5,n=2000,u=237000 --v-contact 2000 --angle 45 \
    --separation 1.52e6 --time-end 4000 -o impact.hdf5 >ic.log 2>&1 ||
    { tail -3 ic.log; echo "FAIL: bolide-ic impact"; exit 1; }
  cat >p.yml <<YML
InitialConditions:
  file_name: impact.hdf5
TimeIntegration:
  time_end: 4000
Snapshots:
  subdir: out
  delta_time: 1e30
Materials:
  101: {}
SPH:
  resolution_eta: 1.2348
YML
}
