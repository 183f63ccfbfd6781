#!/usr/bin/env bash
# bolide built with MPI (configure --with-mpi; skips (77) otherwise), issue 22
# item 3:
#  - mpirun -n 1 bolide runs exactly as the serial program: a small impact
#    (2,200 particles, 3 steps, one thread, Scheduler:deterministic) gives a
#    snapshot whose particle datasets are bit for bit those of the serial
#    build's bolide (BOLIDE_SERIAL_BUILDDIR, default: this build's bolide
#    started without mpirun);
#  - mpirun -n 2 and 3 agree with the serial run within round-off (below:
#    an impact with particles moving between the ranks, a Sedov blast in a
#    periodic box, a solid with fracture, a self-gravitating SEA planet, the
#    impact with self-gravity and the domain partitioned again at rebuilds,
#    a porous block crushed);
#  - restart files per rank: resumed on the same number of ranks bit for
#    bit, on another (2 to 3, 2 to 1, 1 to 2, 3 to 2) within the bound;
#  - what multi-rank runs do not support yet (the reuse of gravity's far
#    field) stops with one line, a non-zero status, no hang (60 s limit);
#  - mpirun -n 3 bolide --partition 0 partitions over the 3 ranks and every
#    rank reports its cells.
# With BOLIDE_MPI_GPU=1 (make check-gpu, in a build with MPI and CUDA on a
# machine with a GPU): every run with --gpu, each rank on a GPU (several
# ranks of the node share one where there are fewer), the reference the
# one-rank run on the GPU; the cases 1 to 5c (the impact, the Sedov blast,
# the solid with fracture; with self-gravity the planet, the impact, the
# far bodies, the planet with rebuilds and the solid impact), whose FORCE
# phase the GPU runs in the stages of several ranks (src/gpu/gpu_engine.c),
# self-gravity on the GPU before it, the walks with the other ranks'
# records on the CPU (the one-rank reference: its gravity on the GPU); the
# far bodies once more with gravity's walks and multipoles on the CPU and
# its interactions on the GPU (Scheduler:gpu_walks: host and
# gpu_multipoles: host, on both sides), and the planet with the whole of
# self-gravity on the CPU beside the GPU (Scheduler:gpu lists the
# hydrodynamic families, on both sides); and gpu_multipoles: device with
# gpu_walks: host on 2 ranks stops with one line.
set -u
B=${BOLIDE_BUILDDIR:?}
H=$(cd "$(dirname "$0")/../helpers" && pwd) # restart_compare.py
PY=${PYTHON:-python3}
fail() { echo "FAIL: $*"; exit 1; }
grep -q '^#define HAVE_MPI 1' "$B/config.h" || { echo "not built with MPI: skip"; exit 77; }
gpu="" ref=() gline=""
if [ -n "${BOLIDE_MPI_GPU:-}" ]; then
  grep -q '^#define HAVE_CUDA 1' "$B/config.h" || { echo "not built with CUDA: skip"; exit 77; }
  gpu=--gpu
fi
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
(cd serial && "$serial" $gpu -n 3 -t 1 p.yml >run.log 2>&1) || { tail -5 serial/run.log; fail "serial run"; }
(cd mpi && timeout 120 "$MPIRUN" -n 1 "$B/bolide" $gpu -n 3 -t 1 p.yml >run.log 2>&1) ||
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
# compare SERIAL_SNAPSHOT MPI_SNAPSHOT: the same particles; every float
# dataset within BOUND of its largest magnitude (max |a - b| / max |a|),
# every integer dataset equal
compare() {
  "$PY" - "$1" "$2" "$BOUND" <<'PY'
import sys
import h5py, numpy as np
a, b, bound = sys.argv[1], sys.argv[2], float(sys.argv[3])
with h5py.File(a, "r") as x, h5py.File(b, "r") as y:
    ia, ib = x["PartType0/ParticleIDs"][...], y["PartType0/ParticleIDs"][...]
    if len(ia) != len(ib):
        sys.exit("%s: %d particles, the serial run %d" % (b, len(ib), len(ia)))
    oa, ob = np.argsort(ia), np.argsort(ib)
    if not np.array_equal(ia[oa], ib[ob]):
        sys.exit("%s: other particle ids than the serial run" % b)
    worst, name = 0.0, ""
    for k in x["PartType0"]:
        u, v = x["PartType0"][k][...][oa], y["PartType0"][k][...][ob]
        if u.dtype.kind == "f":
            s = np.max(np.abs(u))
            d = np.max(np.abs(u - v)) / s if s > 0 else np.max(np.abs(v))
            if not d <= bound:
                sys.exit("%s: %s differs from the serial run by %.3e of its largest value (bound %g)"
                         % (b, k, d, bound))
            if d >= worst:
                worst, name = d, k
        elif not np.array_equal(u, v):
            sys.exit("%s: %s differs from the serial run" % (b, k))
    print("%s: %d particles, largest difference %.2e (%s) of the serial run's" % (b, len(ia), worst, name))
PY
}
# runs RANKS...: the serial run of p.yml in ./serial and mpirun -n R in ./mpiR
# (same parameters, one thread each), the same number of steps, the
# snapshots compared, the budget's energy the same within BOUND
runs() {
  mkdir -p serial && cp p.yml serial/
  (cd serial && "$serial" $gpu "${ref[@]}" -t 1 p.yml >run.log 2>&1) ||
    { tail -5 serial/run.log; fail "$case: serial run"; }
  local steps
  steps=$(sed -n 's/.*done: \([0-9]*\) steps.*/\1/p' serial/run.log)
  for r in "$@"; do
    mkdir -p mpi$r && cp p.yml mpi$r/
    (cd mpi$r && timeout 300 "$MPIRUN" -n "$r" "$B/bolide" $gpu -t 1 p.yml >run.log 2>run.err) ||
      { tail -n 5 mpi$r/run.err mpi$r/run.log; fail "$case: mpirun -n $r"; }
    grep -q "domain decomposition: $r ranks" mpi$r/run.log || fail "$case: no decomposition over $r ranks"
    [ -z "$gpu" ] || grep -q "the foreign copies' records gathered and scattered on the device" \
      mpi$r/run.log || fail "$case: $r ranks did not run their FORCE phases on the GPU"
    [ -z "$gline" ] || grep -q "$gline" mpi$r/run.log ||
      fail "$case: $r ranks: no line on self-gravity with the GPU ($gline)"
    [ "$(sed -n 's/.*done: \([0-9]*\) steps.*/\1/p' mpi$r/run.log)" = "$steps" ] ||
      fail "$case: $r ranks took other than the serial run's $steps steps"
    for f in serial/$snaps; do
      compare "$f" "mpi$r/${f#serial/}" || fail "$case: $r ranks"
    done
    "$PY" "$H/stats_compare.py" serial/$stats mpi$r/$stats "$BOUND" "$box" ||
      fail "$case: $r ranks: the statistics"
  done
  echo "$case: $steps steps on 1 and $* ranks agree"
}
# Several ranks (theory/mpi.md, "Multi-rank runs") against the serial run,
# within BOUND = 1e-10 of each field's largest value: the sums of a particle
# come in another order on another rank (round-off; measured 2e-12 to
# 7e-12 on these cases at 2 to 4 ranks, 2026-12-04).
BOUND=1e-10
# 1. the small impact above, to t = 1000 s (about 60 steps, rebuilds and
#    particles moving between the ranks), on 2 and 3 ranks
case=impact
mkdir -p "$work/impact" && cd "$work/impact"
sed -e 's#\.\./impact.hdf5#../../impact.hdf5#' -e 's/time_end: 4000/time_end: 1000/' \
  -e '/delta_time/s/1e30/500/' "$work/mpi/p.yml" >p.yml
snaps='out/snapshot_000[0-2].hdf5'
stats=out/statistics.txt box=3.5e7
runs 2 3
# 2. the Sedov blast in a periodic box (16^3), on 3 ranks
case=sedov
mkdir -p "$work/sedov" && cd "$work/sedov"
"$B/bolide-ic" sedov --n 16 --energy 1 --rho 1 -o sedov.hdf5 >ic.log 2>&1 || fail "bolide-ic sedov"
cat >p.yml <<YML
InitialConditions:
  file_name: ../sedov.hdf5
  periodic: true
TimeIntegration:
  time_end: 0.05
  dt_min: 1e-10
Snapshots:
  basename: sedov
  delta_time: 0.025
SPH:
  resolution_eta: 1.2348
  CFL_condition: 0.2
  viscosity_alpha: 1.5
  gamma: 1.6666666666666667
YML
snaps='sedov_000[0-2].hdf5'
stats=statistics.txt box=1
runs 3
# 3. a basalt sphere with strength, fracture and Weibull flaws in tension
#    (tests/physics/test_damage_run.sh, 1,400 particles), on 2 ranks
case=damage
mkdir -p "$work/damage" && cd "$work/damage"
"$PY" "$H/tension_sphere.py" sphere.hdf5 14 >/dev/null || fail "damage: initial conditions"
cat >p.yml <<'YML'
InitialConditions:
  file_name: ../sphere.hdf5
TimeIntegration:
  time_end: 3e-6
Snapshots:
  delta_time: 1.5e-6
Materials:
  0: {name: basalt, weibull_k: 5e34, weibull_m: 8}
SPH:
  viscosity_alpha: 1.0
Damage:
  seed: 7
YML
snaps='snapshot_000[0-2].hdf5'
stats=statistics.txt box=0.2
runs 2
"$PY" -c "
import h5py, numpy as np, sys
d = h5py.File('mpi2/snapshot_0002.hdf5', 'r')['PartType0/Damage'][...]
print('damage: %d of %d particles damaged, largest %.3f' % ((d > 0).sum(), len(d), d.max()))
sys.exit(0 if (d > 0).sum() > 0 else 'damage: no particle damaged: the case tests no fracture')
" || fail "damage"
if [ -n "$gpu" ]; then
  grep -m1 "GPU runner" mpi2/run.log
  echo "several ranks on the GPU: the cases without self-gravity agree with one rank"
  gline="self-gravity on the GPU (Scheduler:gpu_walks: device: multipoles, walks, M2L, L2L, L2P, M2P and P2P; several MPI ranks"
fi
# 4. a self-gravitating SEA planet (VALIDATION "SEA planet": Earth-mass
#    Tillotson granite on stretched equal-area shells, here 3,000
#    particles), hydrodynamics and self-gravity (adaptive criterion) to
#    1000 s, on 2 and 3 ranks: every rank holds the whole tree (theory/mpi.md)
case=planet
mkdir -p "$work/planet" && cd "$work/planet"
"$B/bolide-ic" planet --materials granite --mass 5.972e24 --n 3000 -o planet.hdf5 >ic.log 2>&1 ||
  { tail -3 ic.log; fail "bolide-ic planet"; }
cat >p.yml <<'YML'
InitialConditions:
  file_name: ../planet.hdf5
TimeIntegration:
  time_end: 1000
Snapshots:
  delta_time: 500
Materials:
  101: {}
Gravity:
  enabled: true
  softening: 2e4
YML
snaps='snapshot_000[0-2].hdf5'
stats=statistics.txt box=2e7
runs 2 3
if [ -n "$gpu" ]; then
  # the planet with the whole of self-gravity on the CPU workers beside the
  # GPU's hydrodynamics, on one rank and on two
  case=planet-cpu-gravity
  mkdir -p cpug && cd cpug
  sed -e 's#\.\./planet.hdf5#../../planet.hdf5#' ../p.yml >p.yml
  printf 'Scheduler:\n  gpu: [density, gradient, force, damage, drift, kick]\n' >>p.yml
  savedg=$gline gline="self-gravity entirely on the CPU workers (several MPI ranks"
  runs 2
  gline=$savedg
  cd ..
fi
# 5. the impact of 1. with self-gravity: particles move between the ranks
#    and between the two kinds of copies at the rebuilds; the domain
#    partitioned again at the rebuilds (DomainDecomposition:trigger 1e-6,
#    the measured task times rather than Scheduler:deterministic's fixed
#    costs: any imbalance triggers it), which moves particles between ranks
#    by the thousand; compressed snapshots (Snapshots:compression 4: with
#    parallel HDF5, chunks written collectively)
case=impact-gravity
mkdir -p "$work/impactg" && cd "$work/impactg"
sed -e 's#\.\./impact.hdf5#../../impact.hdf5#' -e 's/time_end: 4000/time_end: 1000/' \
  -e '/delta_time/s/1e30/500/' -e '/delta_time/a\  compression: 4' -e '/^Scheduler:/,$d' \
  "$work/mpi/p.yml" >p.yml
printf 'Gravity:\n  enabled: true\n  softening: 2e4\nDomainDecomposition:\n  trigger: 1e-6\n' >>p.yml
printf 'Scheduler:\n  max_top_level_cells: 8\n' >>p.yml
snaps='out/snapshot_000[0-2].hdf5'
stats=out/statistics.txt box=3.5e7
runs 2 3
grep "domain decomposition again" mpi3/run.log | head -3
grep -m1 "snapshot .*hdf5 at t" mpi3/run.log
grep -q "domain decomposition again at step" mpi3/run.log || fail "$case: never partitioned again"
# 5a. two bodies far apart with self-gravity (the impact of 1. at a
#    separation of 25 target radii, rebuilds every few steps): gravity's far
#    field between the ranks goes by the top-level cells' records, so each
#    rank holds only the particles its walks may open (theory/mpi.md,
#    "Self-gravity on several ranks"); and the SEA planet of 4. with
#    rebuilds, whose top-level grid changes from the decomposition's (8^3 to
#    7^3: cells holding particles of two ranks, whose copies the drift must
#    leave to their owners)
case=far
mkdir -p "$work/far" && cd "$work/far"
"$B/bolide-ic" impact --target sphere,material=granite,radius=1e6,n=2000,u=237000 \
  --impactor sphere,material=granite,radius=4.642e5,n=200,u=237000 --v-contact 2000 --angle 45 \
  --separation 2.5e7 --time-end 4000 -o far.hdf5 >ic.log 2>&1 || { tail -3 ic.log; fail "far: bolide-ic impact"; }
cat >p.yml <<'YML'
InitialConditions:
  file_name: ../far.hdf5
TimeIntegration:
  time_end: 300
Snapshots:
  delta_time: 150
Materials:
  101: {}
Gravity:
  enabled: true
  softening: 2e4
Scheduler:
  rebuild_fraction: 0.02
YML
snaps='snapshot_000[0-2].hdf5'
stats=statistics.txt box=9.2e7
runs 2 3
for r in 2 3; do
  line=$(grep "far field by the top-level cells' records" mpi$r/run.log) ||
    fail "far: $r ranks: no line on gravity's records"
  echo "far, $r ranks: ${line#*records: }" | cut -c1-200
  "$PY" - "$line" <<'PY' || fail "far: $r ranks: the records did not replace copies, or a walk missed"
import re, sys
m = re.search(r"(\d+) of (\d+) rebuilds chose the cells to copy from them, ([\d.]+)% of the other "
              r"ranks' non-empty cells on average; (\d+) misses", sys.argv[1])
used, rebuilds, frac, misses = int(m[1]), int(m[2]), float(m[3]), int(m[4])
sys.exit(0 if used >= 1 and frac < 100.0 and misses == 0 else 1)
PY
done
if [ -n "$gpu" ]; then
  # the far bodies with gravity's walks and multipoles on the CPU workers,
  # its interactions on the GPU, the records' far field added on the host
  case=far-host-walks
  mkdir -p hw && cd hw
  sed -e 's#\.\./far.hdf5#../../far.hdf5#' ../p.yml >p.yml
  printf '  gpu_walks: host\n  gpu_multipoles: host\n' >>p.yml
  savedg=$gline
  gline="self-gravity: multipoles and walks on the CPU workers, M2L, L2L, L2P, M2P and P2P on the GPU (several MPI ranks"
  runs 2
  gline=$savedg
  grep "far field by the top-level cells' records" mpi2/run.log | cut -c1-200
  cd ..
fi
case=planet-rebuilds
cd "$work/planet" && mkdir -p rb && cd rb
sed -e 's#\.\./planet.hdf5#../../planet.hdf5#' ../p.yml >p.yml
printf 'Scheduler:\n  rebuild_fraction: 0.01\n' >>p.yml
snaps='snapshot_000[0-2].hdf5'
stats=statistics.txt box=2e7
runs 2 3
(cd serial && "$serial" -v -t 1 -n 25 p.yml 2>&1) | grep -q "7 x 7 x 7 top-level cells" ||
  fail "planet-rebuilds: the top-level grid did not change (the case tests no mixed cells)"
# 5c. a solid impact with self-gravity: basalt with strength and Weibull
#    flaws (a 10 km target, 2,000 + 200 particles, 3 km/s at 45 degrees,
#    to 4 s, 400 steps, a rebuild every few steps) on 3 ranks: the stage
#    of the gradient, gravity's records and the cells that hold particles
#    of two ranks (a rank that owns some particles of a cell holds all of
#    them; without that, a rank held 315 of a cell's 316 particles)
case=solid-gravity
mkdir -p "$work/solidg" && cd "$work/solidg"
"$B/bolide-ic" impact --target sphere,material=basalt,radius=1e4,n=2000 \
  --impactor sphere,material=basalt,radius=2e3,n=200 --v-contact 3000 --angle 45 \
  --separation 1.3e4 --time-end 10 -o solid.hdf5 >ic.log 2>&1 || { tail -3 ic.log; fail "solid-gravity: bolide-ic impact"; }
cat >p.yml <<'YML'
InitialConditions:
  file_name: ../solid.hdf5
TimeIntegration:
  time_end: 4
Snapshots:
  delta_time: 2
Materials:
  103: {name: basalt, weibull_k: 5e34, weibull_m: 8}
Gravity:
  enabled: true
  softening: 100
Damage:
  seed: 3
Scheduler:
  rebuild_fraction: 0.02
  max_top_level_cells: 32
YML
snaps='snapshot_000[0-2].hdf5'
stats=statistics.txt box=1.43e5
runs 3
if [ -n "$gpu" ]; then
  grep -m1 "self-gravity on the GPU" mpi3/run.log | cut -c1-240
  # the multipoles on the device for walks on the CPU: one line, non-zero, no hang
  cd "$work/impactg/mpi2"
  timeout 60 "$MPIRUN" -n 2 "$B/bolide" --gpu -n 3 -t 1 -P Scheduler:gpu_walks:host \
    -P Scheduler:gpu_multipoles:device p.yml >walks.out 2>walks.err
  rc=$?
  [ $rc = 124 ] && fail "mpirun -n 2 --gpu with Scheduler:gpu_multipoles: device hung"
  [ $rc != 0 ] || fail "mpirun -n 2 --gpu with Scheduler:gpu_multipoles: device exited 0"
  grep -q "bolide: error: p.yml: Scheduler:gpu_multipoles: device needs Scheduler:gpu_walks: device on 2 MPI ranks" \
    walks.err || { cat walks.err; fail "mpirun -n 2 --gpu with Scheduler:gpu_multipoles: device: no error line"; }
  cd "$work/solidg"
  echo "several ranks on the GPU: the cases with self-gravity agree with one rank"
  exit 0
fi
# 5b. a porous basalt block crushed (P-alpha, continuity density; the
#    distentions and the solid state through the refreshes between stages,
#    which send only the fields the stage before wrote), on 2 ranks
case=porous
mkdir -p "$work/porous" && cd "$work/porous"
"$PY" "$H/porous_cube.py" block.hdf5 1500 3000 || fail "porous: initial conditions"
cat >p.yml <<'YML'
InitialConditions:
  file_name: ../block.hdf5
TimeIntegration:
  time_end: 3e-5
Snapshots:
  delta_time: 1.5e-5
SPH:
  density: continuity
Materials:
  0: {name: basalt, porosity: {model: palpha, alpha_0: 1.8, alpha_t: 1.3, p_e: 1e6, p_t: 5e7, p_s: 2e8, n1: 6, n2: 3}}
YML
snaps='snapshot_000[0-2].hdf5'
stats=statistics.txt box=4
runs 2
# 6. restart files per rank (Restarts:enable; src/mpi/halo.h): a run stopped
#    at step 30 (-n 30) and resumed with --restart takes the steps of the
#    uninterrupted run, bit for bit (tests/helpers/restart_compare.py; one
#    thread and Scheduler:deterministic, so that the uninterrupted run
#    repeats bit for bit too): the
#    basalt sphere of 3. on 2 ranks (the Weibull flaws of particles that
#    change rank after the resumption) and the impact with self-gravity of 5.
#    on 3 ranks
restart_case() { # DIR RANKS
  cd "$work/$1" || fail "restart: no $1"
  sed -e '/^Snapshots:/,/^[A-Z]/{/subdir/d}' p.yml >rp.yml
  printf 'Restarts:\n  enable: true\n  subdir: restart\n' >>rp.yml
  for d in A B; do mkdir -p r$d && cp rp.yml r$d/p.yml; done
  (cd rA && timeout 300 "$MPIRUN" -n "$2" "$B/bolide" -t 1 -P Scheduler:deterministic:true p.yml >a.log 2>&1) ||
    { tail -5 rA/a.log; fail "restart $1: uninterrupted run on $2 ranks"; }
  (cd rB && timeout 300 "$MPIRUN" -n "$2" "$B/bolide" -t 1 -P Scheduler:deterministic:true -n 30 p.yml >b0.log 2>&1) ||
    { tail -5 rB/b0.log; fail "restart $1: first part on $2 ranks"; }
  (cd rB && timeout 300 "$MPIRUN" -n "$2" "$B/bolide" -t 1 -P Scheduler:deterministic:true --restart p.yml >b1.log 2>&1) ||
    { tail -5 rB/b1.log; fail "restart $1: resumed on $2 ranks"; }
  "$PY" "$H/restart_compare.py" rA rB || fail "restart $1: the resumed run differs from the uninterrupted one"
  # resumed again from the file written at the end (a run killed before it
  # exited): nothing more to do, no line added
  (cd rB && timeout 300 "$MPIRUN" -n "$2" "$B/bolide" -t 1 -P Scheduler:deterministic:true --restart p.yml >b2.log 2>&1) ||
    { tail -5 rB/b2.log; fail "restart $1: resumed at the end on $2 ranks"; }
  "$PY" "$H/restart_compare.py" rA rB || fail "restart $1: resumed at the end, the outputs changed"
  echo "restart $1: stopped at step 30 and resumed on $2 ranks, the same as the uninterrupted run"
}
restart_case damage 2
restart_case impactg 3
# 7. resumed on another number of ranks (restart_read_ranks): the files of
#    the stop at step 30 read by every rank, each rank's own particles
#    gathered, partitioned anew; the run then agrees with the uninterrupted
#    one within BOUND, as runs on different numbers of ranks do (snapshots
#    and statistics, restart_compare.py --tol): the basalt sphere's files
#    of 2 ranks resumed on 3 and on 1 (the serial build), a one-rank run's
#    file resumed on 2, the impact with self-gravity's files of 3 resumed
#    on 2; the files of the other layout are removed once the resumed run
#    has written its own
regroup() { # DIR RANKS_BEFORE RANKS_AFTER (0: the serial build)
  cd "$work/$1" || fail "regroup: no $1"
  local d=g$2to$3 run0 run1
  rm -rf "$d" && mkdir "$d" && cp rp.yml "$d/p.yml"
  run0=("$MPIRUN" -n "$2" "$B/bolide")
  [ "$2" = 0 ] && run0=("$serial")
  run1=("$MPIRUN" -n "$3" "$B/bolide")
  [ "$3" = 0 ] && run1=("$serial")
  (cd "$d" && timeout 300 "${run0[@]}" -t 1 -P Scheduler:deterministic:true -n 30 p.yml >g0.log 2>&1) ||
    { tail -5 "$d/g0.log"; fail "regroup $1: first part on $2 ranks"; }
  (cd "$d" && timeout 300 "${run1[@]}" -t 1 -P Scheduler:deterministic:true --restart p.yml >g1.log 2>&1) ||
    { tail -5 "$d/g1.log"; fail "regroup $1: resumed on $3 ranks"; }
  grep -q "resuming the files of a run on" "$d/g1.log" || fail "regroup $1: $2 to $3 ranks: no line on the files"
  "$PY" "$H/restart_compare.py" --tol "$BOUND" rA "$d" ||
    fail "regroup $1: stopped on $2 ranks and resumed on $3, the run differs from the uninterrupted one"
  local left
  left=$(cd "$d/restart" && ls)
  case "$3" in
    0) [ "$left" = restart.bin ] || fail "regroup $1: files left after resuming on one rank: $left" ;;
    *) [ "$(echo "$left" | grep -c '^restart_rank.*[0-9]\.bin$')" = "$3" ] && ! echo "$left" | grep -q '^restart\.\|prev' ||
         fail "regroup $1: files left after resuming on $3 ranks: $left" ;;
  esac
  echo "regroup $1: stopped at step 30 on $2 ranks, resumed on $3, within $BOUND of the uninterrupted run"
}
regroup damage 2 3
regroup damage 2 0
regroup damage 0 2
regroup impactg 3 2
# files of two steps (rank 1's written at the end of the run, rank 0's at
# step 30) are refused with one line, a non-zero status, no hang
cd "$work/damage" && rm -rf mix && mkdir mix && cp rp.yml mix/p.yml
(cd mix && timeout 300 "$MPIRUN" -n 2 "$B/bolide" -t 1 -P Scheduler:deterministic:true -n 30 p.yml >m0.log 2>&1) ||
  { tail -5 mix/m0.log; fail "regroup: files of two steps: first part"; }
cp rA/restart/restart_rank0001.bin mix/restart/
(cd mix && timeout 60 "$MPIRUN" -n 3 "$B/bolide" -t 1 -P Scheduler:deterministic:true --restart p.yml >c.log 2>&1)
rc=$?
[ $rc = 124 ] && fail "restart with 3 ranks from files of two steps hung"
[ $rc != 0 ] || fail "restart with 3 ranks from files of two steps exited 0"
grep -m1 "bolide: error: .*restart_rank0001.bin: of step .*resume from the files of one run" mix/c.log ||
  { cat mix/c.log; fail "restart from files of two steps: no error line naming rank 1's file"; }
# what multi-rank runs do not do yet: one line, non-zero, no hang
cd "$work/mpi"
timeout 60 "$MPIRUN" -n 2 "$B/bolide" -n 3 -t 1 -P Gravity:enabled:true -P Gravity:reuse_steps:2 \
  p.yml >two.out 2>two.err
rc=$?
[ $rc = 124 ] && fail "mpirun -n 2 with Gravity:reuse_steps hung"
[ $rc != 0 ] || fail "mpirun -n 2 with Gravity:reuse_steps exited 0"
grep -q "bolide: error: 2 MPI ranks: multi-rank runs cannot reuse gravity's far field" two.err ||
  { cat two.err; fail "mpirun -n 2 with Gravity:reuse_steps: no error line"; }
# DomainDecomposition:method: the split the first partition's log line names
for m in "morton:Morton ranges" "slabs:slabs along x"; do
  timeout 120 "$MPIRUN" -n 2 "$B/bolide" -n 2 -t 1 -P "DomainDecomposition:method:${m%%:*}" p.yml \
    >dd.out 2>dd.err || { cat dd.err; fail "mpirun -n 2 with DomainDecomposition:method ${m%%:*}"; }
  grep -q "domain decomposition: 2 ranks over .* (${m#*:})" dd.out ||
    { grep "domain decomposition" dd.out; fail "DomainDecomposition:method ${m%%:*}: not ${m#*:}"; }
done
# metis in a build without METIS: one error line naming the key
if ! "$B/bolide" --version | grep -q "^METIS: yes"; then
  timeout 60 "$MPIRUN" -n 2 "$B/bolide" -n 2 -t 1 -P DomainDecomposition:method:metis p.yml \
    >dd.out 2>dd.err && fail "DomainDecomposition:method metis without METIS exited 0"
  grep -q "bolide: error: .*DomainDecomposition:method: metis, but this build has no METIS" dd.err ||
    { cat dd.err; fail "DomainDecomposition:method metis without METIS: no error line"; }
fi
# a mistake in the parameter file, read by every rank: one error line (rank
# 0's; before, each of the 3 ranks printed it), non-zero, no hang
timeout 60 "$MPIRUN" -n 3 "$B/bolide" -t 1 -P SPH:no_such_key:1 p.yml >bad.out 2>bad.err
rc=$?
[ $rc = 124 ] && fail "mpirun -n 3 with an unknown key hung"
[ $rc != 0 ] || fail "mpirun -n 3 with an unknown key exited 0"
nerr=$(grep -c "bolide: error: .*unknown key 'SPH:no_such_key'" bad.err)
[ "$nerr" = 1 ] || { cat bad.err; fail "mpirun -n 3 with an unknown key: $nerr error lines, not 1"; }
# a problem with the initial conditions, read by every rank: one error line
# (rank 0 reads them first), non-zero, no hang: a missing file
sed 's/^  file_name: .*/  file_name: no_such_ic.hdf5/' p.yml >noic.yml
grep -q "no_such_ic.hdf5" noic.yml || fail "test set-up: no file_name in p.yml"
timeout 60 "$MPIRUN" -n 3 "$B/bolide" -t 1 noic.yml >noic.out 2>noic.err
rc=$?
[ $rc = 124 ] && fail "mpirun -n 3 with a missing IC file hung"
[ $rc != 0 ] || fail "mpirun -n 3 with a missing IC file exited 0"
nerr=$(grep -c "bolide: error: .*no_such_ic.hdf5" noic.err)
[ "$nerr" = 1 ] || { cat noic.err; fail "mpirun -n 3 with a missing IC file: $nerr error lines, not 1"; }
# the partition over the ranks of mpirun
timeout 120 "$MPIRUN" -n 3 "$B/bolide" --partition 0 -t 1 p.yml >part.out 2>part.err ||
  { cat part.err; fail "mpirun -n 3 bolide --partition 0"; }
grep "^partition" part.out
grep -q "^partition: method .* ranks 3 .* unassigned 0" part.out || fail "no partition over 3 ranks"
[ "$(grep -c '^partition: rank [0-2] of 3 holds' part.out)" = 3 ] || fail "not every rank reported"
echo "test_mpi: PASS"
