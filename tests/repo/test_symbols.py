"""Every symbol libbolide.a exports carries its module's prefix
(theory/architecture.md, rule 11, "conventions checked by make check"; the
nm check REBOUND does).

A module is a source file; its prefixes are the first word of its name
(engine_graph.c: engine_, gpu_lists.cu: gpu_), that word without or with a
plural s (params.c: param_ and params_, part.c: parts_), and for a file of a
task family tasks/<family>/ the family's name and the cell task types it
owns in the registry (tasks/task_families.h: kick2_ for the kick family,
extra_ghost_ for gradient).  C++ names (the CUDA files) are read demangled,
without their argument lists; the compiler's own symbols (__device_stub_*,
DW.ref.*, names starting with two underscores) are not the code's and are
skipped, and so are the template and inline entities that the CUDA
toolkit's own headers (CCCL: cub, thrust, libcu++; the segmented sort of
tasks/gravity/gpu_gravity.cu) instantiate in an object that uses them:
weak or unique symbols (nm kinds W, V, u; their guard variables, vtables
and typeinfo too) in the namespaces cub::,
thrust:: and cuda::.  Fails with one line per symbol without its prefix.
"""
import os
import re
import subprocess
import sys

B = os.environ.get("BOLIDE_BUILDDIR", "_build")
S = os.environ.get("BOLIDE_SRCDIR") or os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
lib = os.path.join(B, "libbolide.a")
if not os.path.isfile(lib):
    print("FAIL: no %s" % lib)
    sys.exit(1)

# source files by object name (subdir-objects: the archive holds basenames)
sources = {}
for top in ("src", "tasks"):
    for root, _, files in os.walk(os.path.join(S, top)):
        for n in files:
            if n.endswith((".c", ".cu")):
                rel = os.path.relpath(os.path.join(root, n), S)
                sources.setdefault(os.path.splitext(n)[0], []).append(rel)

# the cell task types each family owns (registry rows of shape cell)
with open(os.path.join(S, "tasks/task_families.h"), encoding="utf-8") as f:
    reg = f.read()
owned = {}
for fam, shape, typ in re.findall(r"^\s*X\((\w+),\s*(\w+),\s*(\w+),\s*\w+,\s*\w+\)", reg, re.M):
    owned.setdefault(fam, set())
    if shape == "cell":
        owned[fam].add(typ)


def prefixes(path):
    base = os.path.splitext(os.path.basename(path))[0]
    word = base.split("_")[0]
    p = {word, word.rstrip("s"), word + "s"}
    parts = path.split(os.sep)
    if parts[0] == "tasks" and len(parts) == 3:
        p.add(parts[1])
        p |= owned.get(parts[1], set())
    return p


out = subprocess.run(["nm", "-A", "-C", "-g", "--defined-only", lib], capture_output=True, text=True)
if out.returncode != 0:
    print("FAIL: nm %s: %s" % (lib, out.stderr.strip()))
    sys.exit(1)
fails = 0
count = 0
for line in out.stdout.splitlines():
    m = re.match(r"^[^:]*:([^:]+)\.o:\s*[0-9a-fA-F]*\s+(\w)\s+(.*)$", line)
    if not m:
        continue
    obj, kind, name = m.groups()
    name = re.sub(r"\(.*$", "", name)  # C++: drop the argument list
    name = re.sub(r"<.*$", "", name)   # and template arguments
    if name.startswith(("__", "DW.", "_GLOBAL")) or "." in name:
        continue
    lib_name = re.sub(r"^(guard variable for |typeinfo name for |typeinfo for |vtable for |\w+ )", "", name)
    if kind in "WVu" and re.match(r"(cub|thrust|cuda)::", lib_name):
        continue  # the CUDA toolkit's templates, instantiated here
    count += 1
    paths = sources.get(obj)
    if not paths:
        print("FAIL: object %s.o of libbolide.a has no source in src/ or tasks/" % obj)
        fails += 1
        continue
    allowed = set().union(*(prefixes(p) for p in paths))
    if not any(name.startswith(p + "_") for p in allowed):
        print("FAIL: %s exports %s without its module's prefix (%s)"
              % (paths[0], name, ", ".join(sorted(q + "_" for q in allowed))))
        fails += 1
print("%d exported symbols of libbolide.a: %s" % (count, "%d without their prefix" % fails if fails else "all prefixed"))
sys.exit(1 if fails else 0)
