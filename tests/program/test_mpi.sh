#!/usr/bin/env bash
# bolide built with MPI (configure --with-mpi; skips (77) otherwise), issue 22
# item 3:
#  - mpirun -n 1 bolide runs exactly as the serial program: a small impact
#    (2,200 particles, 3 steps, one thread, Scheduler:deterministic) gives a
#    snapshot whose particle datasets are bit for bit those of the serial
#    build's bolide (BOLIDE_SERIAL_BUILDDIR, default: this build's bolide
#    started without mpirun);
#  - mpirun -n 2 bolide stops: one line from rank 0 that multi-rank runs are
#    not implemented yet, a non-zero status, no hang (60 s limit);
#  - mpirun -n 3 bolide --partition 0 partitions over the 3 ranks and every
#    rank reports its cells.
set -u
B=${BOLIDE_BUILDDIR:?}
PY=${PYTHON:-python3}
fail() { echo "FAIL: $*"; exit 1; }
grep -q '^#define HAVE_MPI 1' "$B/config.h" || { echo "not built with MPI: skip"; exit 77; }
MPIRUN=$(sed -n 's/^MPIRUN = //p' "$B/Makefile")
[ -n "$MPIRUN" ] || MPIRUN=mpirun
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
serial=${BOLIDE_SERIAL_BUILDDIR:-$B}/bolide
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" impact --target sphere,material=granite,radius=1e6,n=2000,u=237000 \
  --impactor sphere,material=granite,radius=4.642e5,n=200,u=237000 --v-contact 2000 --angle 45 \
  --separation 1.52e6 --time-end 4000 -o impact.hdf5 >ic.log 2>&1 || { tail -3 ic.log; fail "bolide-ic impact"; }
for d in serial mpi; do
  mkdir -p $d
  cat >$d/p.yml <<YML
InitialConditions:
  file_name: ../impact.hdf5
TimeIntegration:
  time_end: 4000
Snapshots:
  subdir: out
  delta_time: 1e30
Materials:
  101: {}
SPH:
  resolution_eta: 1.2348
Scheduler:
  deterministic: true
YML
done
(cd serial && "$serial" -n 3 -t 1 p.yml >run.log 2>&1) || { tail -5 serial/run.log; fail "serial run"; }
(cd mpi && timeout 120 "$MPIRUN" -n 1 "$B/bolide" -n 3 -t 1 p.yml >run.log 2>&1) ||
  { tail -5 mpi/run.log; fail "mpirun -n 1 bolide"; }
"$PY" - <<'PY' || fail "mpirun -n 1 and the serial run differ"
import glob, sys
import h5py, numpy as np
a = sorted(glob.glob("serial/out/*.hdf5")); b = sorted(glob.glob("mpi/out/*.hdf5"))
assert a and [x.split("/")[-1] for x in a] == [x.split("/")[-1] for x in b], (a, b)
n = 0
for fa, fb in zip(a, b):
    with h5py.File(fa, "r") as x, h5py.File(fb, "r") as y:
        for k in x["PartType0"]:
            if not np.array_equal(x["PartType0"][k][...], y["PartType0"][k][...]):
                sys.exit("%s: %s differs" % (fb, k))
            n += 1
print("mpirun -n 1: %d snapshots, %d datasets identical to the serial run" % (len(a), n))
PY
grep -E '^ +3 ' serial/run.log | head -1
grep -E '^ +3 ' mpi/run.log | head -1
# two ranks: one line, non-zero, no hang
cd mpi
timeout 60 "$MPIRUN" -n 2 "$B/bolide" -n 3 -t 1 p.yml >two.out 2>two.err
rc=$?
[ $rc = 124 ] && fail "mpirun -n 2 hung"
[ $rc != 0 ] || fail "mpirun -n 2 exited 0"
[ "$(grep -c 'bolide: error: multi-rank runs are not implemented yet (2 ranks)' two.err)" = 1 ] ||
  { cat two.err; fail "mpirun -n 2: not one error line"; }
# the partition over the ranks of mpirun
timeout 120 "$MPIRUN" -n 3 "$B/bolide" --partition 0 -t 1 p.yml >part.out 2>part.err ||
  { cat part.err; fail "mpirun -n 3 bolide --partition 0"; }
grep "^partition" part.out
grep -q "^partition: method .* ranks 3 .* unassigned 0" part.out || fail "no partition over 3 ranks"
[ "$(grep -c '^partition: rank [0-2] of 3 holds' part.out)" = 3 ] || fail "not every rank reported"
echo "test_mpi: PASS"
