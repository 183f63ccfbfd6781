#!/usr/bin/env bash
# `make install` is relocatable (issue 23 item 6): install into a staging
# folder (DESTDIR, prefix /opt/bolide), move the whole prefix to another
# folder and run it from there with no trace of the build in the
# environment (no BOLIDE_SRCDIR, BOLIDE_BUILDDIR, PYTHONPATH):
#   - no installed file names the source or the build folder;
#   - every program's --version is "PROGRAM (Bolide) VERSION (git HASH)"
#     followed by the configure line, the same as the build's;
#   - bolide --check passes on a parameter file of tests/data (SWIFT's Sod
#     shock tube, initial conditions from the installed bolide-ic) and on one
#     that takes its material from the installed library by name;
#   - bolide-eos --plot finds the installed plot_eos.py, the installed
#     plotting scripts import the installed Python package;
#   - a man page per program when configure found help2man;
#   - make uninstall removes every file it installed.
set -u
S=$(cd "${BOLIDE_SRCDIR:?}" && pwd -P)
B=$(cd "${BOLIDE_BUILDDIR:?}" && pwd -P)
PY=${PYTHON:-python3}
MAKE_=${MAKE:-make}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/bolide_install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail=0
FAIL() { echo "FAIL: $*"; fail=1; }
programs="bolide bolide-ic bolide-eos bolide-fof bolide-flaws"

# the sub-make must not join the jobs of the make check that runs this test
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL "$MAKE_" -s -C "$B" "$@" prefix=/opt/bolide; }
mk install DESTDIR="$tmp/stage" >"$tmp/install.log" 2>&1 ||
  { tail -30 "$tmp/install.log"; echo "FAIL: make install"; exit 1; }
[ -d "$tmp/stage/opt/bolide/bin" ] || { echo "FAIL: no bin/ under DESTDIR/prefix"; exit 1; }
mkdir -p "$tmp/elsewhere"
mv "$tmp/stage/opt/bolide" "$tmp/elsewhere/moved"
P="$tmp/elsewhere/moved"
echo "installed and moved to $P: $(find "$P" -type f | wc -l) files"

# run installed programs as a user would: the build and source trees unknown
run() { (cd "$tmp/work" && env -u BOLIDE_SRCDIR -u BOLIDE_BUILDDIR -u PYTHONPATH -u BOLIDE_MATERIALS \
  -u BOLIDE_PLOT_EOS -u BOLIDE_TOOLS_DIR PATH="$P/bin:$PATH" "$@"); }
mkdir -p "$tmp/work"

# 1. no build or source path in any installed file (the configure line is
# printed by --version: a path the user gave configure is theirs)
cfg=$("$B/bolide" --version | sed -n 's/^configured with: //p')
case "$cfg" in
  *"$S"* | *"$B"*) echo "note: the configure line names the source or build folder: path check skipped" ;;
  *)
    for d in "$S" "$B"; do
      hits=$(grep -rlF -- "$d" "$P")
      [ -z "$hits" ] || FAIL "installed files name $d: $(echo "$hits" | sed "s|$P/||" | tr '\n' ' ')"
    done ;;
esac

# 2. --version in one format, the build's
for p in $programs; do
  [ -x "$P/bin/$p" ] || { FAIL "$p not installed"; continue; }
  run "$p" --version >"$tmp/v_$p" 2>&1 || FAIL "$p --version: exit $?"
  head -1 "$tmp/v_$p" | grep -qE "^$p \(Bolide\) [0-9]+\.[0-9]+\.[0-9]+ \(git [0-9a-z-]+\)$" ||
    FAIL "$p --version: first line '$(head -1 "$tmp/v_$p")'"
  sed -n 2p "$tmp/v_$p" | grep -q '^configured with: ' || FAIL "$p --version: no configure line"
  "$B/$p" --version | cmp -s - "$tmp/v_$p" || FAIL "$p --version differs from the build's"
  run "$p" --help >/dev/null 2>&1 || FAIL "$p --help: exit $?"
done

# 3. bolide --check on tests/data/swift/sod_shock.yml (SWIFT's -s flag) with
# initial conditions from the installed bolide-ic
cp "$S/tests/data/swift/sod_shock.yml" "$tmp/work/"
run bolide-ic sod -o sod.hdf5 >/dev/null || FAIL "installed bolide-ic sod"
run bolide --check -s sod_shock.yml >"$tmp/check.out" 2>&1 ||
  { FAIL "installed bolide --check -s sod_shock.yml"; cat "$tmp/check.out"; }
# a material by name from the installed library (PREFIX/share/bolide)
run bolide-ic box --n 6 --size 1 --rho 2700 --u 1e5 --mat 0 -o box.hdf5 >/dev/null || FAIL "bolide-ic box"
cat >"$tmp/work/library.yml" <<'EOF'
InitialConditions:
  file_name: box.hdf5
TimeIntegration:
  time_end: 1e-4
Materials:
  0: {name: basalt}
EOF
run bolide --check library.yml >"$tmp/lib.out" 2>&1 ||
  { FAIL "installed bolide --check with a material of the installed library"; cat "$tmp/lib.out"; }
[ -f "$P/share/bolide/materials.yml" ] || FAIL "no share/bolide/materials.yml"

# 4. the plotting: bolide-eos --plot runs the installed plot_eos.py (with
# $PYTHON, which has matplotlib); the installed scripts import the installed
# package (PYTHONPATH unset)
if "$PY" -c 'import matplotlib, numpy, h5py' 2>/dev/null; then
  run env PYTHON="$PY" bolide-eos --nrho 4 --nu 2 --plot eos.png "$P/share/bolide/materials.yml" basalt \
    >"$tmp/eos.out" 2>&1 || { FAIL "installed bolide-eos --plot"; cat "$tmp/eos.out"; }
  [ -s "$tmp/work/eos.png" ] || FAIL "bolide-eos --plot wrote no eos.png"
  for s in plot_impact.py plot_profile.py plot_fragments.py plot_tasks.py plot_stats.py \
    plot_snapshot.py plot_sod.py plot_sedov.py; do
    [ -x "$P/bin/$s" ] || { FAIL "$s not installed in bin"; continue; }
    run "$PY" "$P/bin/$s" --help >"$tmp/s.out" 2>&1 || { FAIL "installed $s --help"; tail -3 "$tmp/s.out"; }
  done
  run "$PY" -c "import sys; sys.path.insert(0, '$P/share/bolide/python'); import bolide
assert bolide.__file__.startswith('$P'), bolide.__file__
print('installed Python package bolide', bolide.__version__)" || FAIL "the installed Python package"
else
  echo "note: $PY has no numpy/matplotlib/h5py: plotting scripts not run"
fi
[ -x "$P/bin/plot_eos.py" ] || FAIL "plot_eos.py not installed in bin"

# 5. man pages, when configure found help2man
if grep -qE '^HELP2MAN = .+' "$B/Makefile"; then
  for p in $programs; do
    m="$P/share/man/man1/$p.1"
    [ -s "$m" ] || { FAIL "no man page $p.1"; continue; }
    grep -q '^\.TH ' "$m" || FAIL "$p.1 is not a man page"
    grep -q -- 'version' "$m" || FAIL "$p.1 lists no options"
  done
  grep -q 'check' "$P/share/man/man1/bolide.1" || FAIL "bolide.1 does not list --check"
  echo "man pages: $(ls "$P/share/man/man1" | tr '\n' ' ')"
else
  echo "note: configure found no help2man: no man pages (checked that none are required)"
fi

# 6. make uninstall removes what make install put there
mk install DESTDIR="$tmp/stage2" >/dev/null 2>&1 || FAIL "second make install"
mk uninstall DESTDIR="$tmp/stage2" >/dev/null 2>&1 || FAIL "make uninstall"
left=$(find "$tmp/stage2" -type f 2>/dev/null)
[ -z "$left" ] || FAIL "make uninstall left: $(echo "$left" | sed "s|$tmp/stage2||" | tr '\n' ' ')"

[ "$fail" = 0 ] && echo "ok: the install runs after being moved"
exit "$fail"
