"""The registry of task families and the layers of the includes.

Fails (one FAIL line per finding) when

  registry   a folder of tasks/ is neither a family of the registry
             (tasks/task_families.h) nor a shared folder (SHARED below:
             tasks/hydro/, the kernels and SPH settings the families share),
             a family has no folder, the families' fragments are not included
             through tasks/families.am, which tools/families_am.sh writes from
             the registry (and which must be current), a shared folder's
             fragment is not included by Makefile.am, a kind of task
             (TASK_FAMILY_TASKS), a hook (TASK_FAMILY_HOOKS), an entry
             point (TASK_FAMILY_ENTRIES) or an interface header
             (TASK_FAMILY_INTERFACES) names a family that is not in the
             registry, an interface header is not a file of its family's
             folder, or a file of a folder
             tasks/<family>/ or tasks/<shared>/ is not listed in its own
             local.am (or listed in another fragment);
  hand list  a C or CUDA line outside the registry lists three or more family
             names as strings (a list kept by hand beside the registry: the
             names of Scheduler:gpu, of timers or of GPU stages);
  layers     a file includes across the layers of theory/architecture.md, "Layers":
               src/ (engine, scheduler, io, gpu) -> tasks/: only the registry,
                 tasks/hydro/ (the SPH settings the engine holds, the
                 kernel whose support sizes its cells) and the interface
                 headers the registry names (TASK_FAMILY_INTERFACES: what the
                 engine holds of a family), never a family's internals
               an interface header -> tasks/: only what src/ may include
               tasks/hydro/ -> only itself and what src/materials/ may
                 include (it sits below the families and the engine)
               src/materials/ -> anything but src/materials/, the portability
                 macros, errors, particles, units, parameters and the paths of
                 shipped files (src/paths.h)
               the scheduler layer (task, queue, scheduler, runner) -> only
                 itself, errors and the registry; the runner (the worker
                 threads) -> not the scheduler: it calls the scheduler back
                 through the function runner_start() was given
             An arrow that exists today and is still to be removed is listed,
             with its reason, in tests/repo/layers.allow; an allowed arrow that no
             longer exists fails too, so that the list only shrinks.

  qualified  every #include "..." names its file from the top of the tree
             ("src/io/params.h", "tasks/force/force_iact.h"): the only -I
             is the top (Makefile.am's AM_CPPFLAGS), so that a file shows
             which layer it reaches into; config.h (the build's) excepted.

Standard-library and system headers (<...>) are not read.  Run with BOLIDE_SRCDIR set (make check), or from the
top of the repository.
"""
import os
import re
import sys

TOP = os.environ.get("BOLIDE_SRCDIR") or os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
os.chdir(TOP)
GENERATED = {"config.h"}  # written by configure into the build folder
SOURCE_EXT = (".c", ".h", ".cu")
fails = []
# folders of tasks/ that are not families: what the families share, each built
# from its own tasks/<name>/local.am, which Makefile.am includes
SHARED = ["hydro"]


def fail(msg):
    fails.append(msg)
    print("FAIL: " + msg)


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


# ------------------------------------------------------------------ registry
reg_text = read("tasks/task_families.h")


def macro_body(name):
    """The lines of #define name(X) ... up to the first line without a
    continuation backslash."""
    lines = reg_text.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("#define %s(X)" % name):
            body = []
            for l in lines[i + 1:]:
                body.append(l)
                if not l.rstrip().endswith("\\"):
                    break
            return body
    fail("tasks/task_families.h: no #define %s(X)" % name)
    return []


families = [m.group(1) for l in macro_body("TASK_FAMILIES") for m in [re.match(r"\s*X\((\w+),", l)] if m]
kinds = [m.group(1) for l in macro_body("TASK_FAMILY_TASKS") for m in [re.match(r"\s*X\((\w+),", l)] if m]
hooks = [m.group(1) for l in macro_body("TASK_FAMILY_HOOKS") for m in [re.match(r"\s*X\((\w+),", l)] if m]
entries = [m.group(1) for l in macro_body("TASK_FAMILY_ENTRIES") for m in [re.match(r"\s*X\((\w+),", l)] if m]
interfaces = [m.groups() for l in macro_body("TASK_FAMILY_INTERFACES")
              for m in [re.match(r'\s*X\((\w+),\s*"([^"]+)"\)', l)] if m]
INTERFACES = {h for _, h in interfaces}  # the family headers src/ may include
if not families:
    fail("the registry lists no family")
if len(set(families)) != len(families):
    fail("a family is listed twice in the registry: %s" % families)
for k in sorted(set(kinds) - set(families)):
    fail("TASK_FAMILY_TASKS: '%s' is not a family of the registry" % k)
for k in sorted(set(hooks) - set(families)):
    fail("TASK_FAMILY_HOOKS: '%s' is not a family of the registry" % k)
for k in sorted(set(entries) - set(families)):
    fail("TASK_FAMILY_ENTRIES: '%s' is not a family of the registry" % k)
for k, h in interfaces:
    if k not in families:
        fail("TASK_FAMILY_INTERFACES: '%s' is not a family of the registry" % k)
    elif not h.startswith("tasks/%s/" % k) or not os.path.isfile(h):
        fail("TASK_FAMILY_INTERFACES: %s is not a header of tasks/%s/" % (h, k))
for f in families:
    if f not in kinds:
        fail("family %s makes no kind of task (TASK_FAMILY_TASKS)" % f)

folders = sorted(d for d in os.listdir("tasks") if os.path.isdir(os.path.join("tasks", d)))
for d in folders:
    if d not in families and d not in SHARED:
        fail("tasks/%s/ is not a family of the registry (tasks/task_families.h)" % d)
for d in SHARED:
    if d in families:
        fail("tasks/%s/ is a family of the registry and a shared folder (SHARED)" % d)
    if d not in folders:
        fail("the shared folder tasks/%s/ does not exist" % d)
for f in families:
    if f not in folders:
        fail("family %s of the registry has no folder tasks/%s/" % (f, f))

makefile = read("Makefile.am")
for d, frag in re.findall(r"^include \$\(top_srcdir\)/tasks/(\w+)/(\S+)$", makefile, re.M):
    if d in SHARED and frag == "local.am":
        continue
    fail("Makefile.am includes tasks/%s/%s: the families' fragments come from tasks/families.am" % (d, frag))
if not re.search(r"^include \$\(top_srcdir\)/tasks/families\.am$", makefile, re.M):
    fail("Makefile.am does not include tasks/families.am (the registry's fragments)")
for d in SHARED:
    if not re.search(r"^include \$\(top_srcdir\)/tasks/%s/local\.am$" % d, makefile, re.M):
        fail("Makefile.am does not include tasks/%s/local.am (the shared folder's fragment)" % d)
expected = ["include $(top_srcdir)/tasks/%s/local.am" % f for f in families]
if not os.path.isfile("tasks/families.am"):
    fail("no tasks/families.am: run ./autogen.sh (tools/families_am.sh writes it from the registry)")
else:
    got = [l for l in read("tasks/families.am").splitlines() if not l.startswith("#")]
    if got != expected:
        fail("tasks/families.am is not the registry's (%s): run tools/families_am.sh" % ", ".join(families))

# every file of a family's (or shared) folder listed in its own fragment, and in no other
fragments = {}
for root, _, files in os.walk("."):
    if root.startswith(("./.git", "./_build", "./_dbuild", "./build", "./.venv", "./autom4te")):
        continue
    for n in files:
        if n.endswith(".am") or n == "Makefile.am":
            p = os.path.normpath(os.path.join(root, n))
            fragments[p] = read(p)
for f in families + [d for d in SHARED if d in folders]:
    own = "tasks/%s/local.am" % f
    if own not in fragments:
        fail("folder tasks/%s/ has no fragment %s" % (f, own))
        continue
    for n in sorted(os.listdir("tasks/" + f)):
        p = "tasks/%s/%s" % (f, n)
        if not n.endswith(SOURCE_EXT):
            continue
        if not re.search(r"(^|\s)%s(\s|$)" % re.escape(p), fragments[own]):
            fail("%s is not listed in %s" % (p, own))
        for frag, text in fragments.items():
            if frag != own and re.search(r"(^|\s)%s(\s|$)" % re.escape(p), text):
                fail("%s is listed in %s, outside its family's fragment %s" % (p, frag, own))

# ------------------------------------------------------------------ hand lists
quoted = re.compile(r'"(%s)"' % "|".join(map(re.escape, families))) if families else None
sources = []
for top in ("src", "tasks", "tests", "tools"):
    for root, _, files in os.walk(top):
        for n in files:
            if n.endswith(SOURCE_EXT):
                sources.append(os.path.normpath(os.path.join(root, n)))
sources.sort()
for p in sources:
    if p == "tasks/task_families.h" or quoted is None:
        continue
    for i, line in enumerate(read(p).splitlines(), 1):
        if len(set(quoted.findall(line))) >= 3:
            fail("%s:%d: a list of family names outside the registry: %s" % (p, i, line.strip()))

# ------------------------------------------------------------------ layers
include_re = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def resolve(src, name):
    """The file an include names: from the top of the tree (the one -I)."""
    p = os.path.normpath(name)
    return p if os.path.isfile(p) else None


for p in sources:
    for i, line in enumerate(read(p).splitlines(), 1):
        m = include_re.match(line)
        if not m or m.group(1) in GENERATED:
            continue
        if resolve(p, m.group(1)) is None or m.group(1) != os.path.normpath(m.group(1)):
            fail('%s:%d: #include "%s" does not name a file from the top of the tree '
                 '(write its folder: "src/...", "tasks/<family>/...")' % (p, i, m.group(1)))


SCHED = {"src/task.h", "src/task.c", "src/queue.h", "src/queue.c", "src/scheduler.h",
         "src/scheduler.c", "src/runner.h", "src/runner.c"}
MATERIALS_OK = ("src/materials/", "src/inline.h", "src/error.h", "src/part.h", "src/io/units.h",
                "src/io/params.h", "src/paths.h")  # paths.h: a leaf (the C library only)
ENGINE_OK = ("tasks/task_families.h", "tasks/hydro/")  # what src/ may include of tasks/
HYDRO_OK = ("tasks/hydro/",) + MATERIALS_OK  # what tasks/hydro/ may include


def violation(src, dst):
    """The rule that src including dst breaks, or None.  Programs (main_*.c)
    sit on top of every layer."""
    if os.path.basename(src).startswith("main_"):
        return None
    if src.startswith("src/") and dst.startswith("tasks/") and not dst.startswith(ENGINE_OK) \
            and dst not in INTERFACES:
        return ("src/ reaches into a family's internals (only tasks/task_families.h, tasks/hydro/ "
                "and the interface headers of TASK_FAMILY_INTERFACES)")
    if src in INTERFACES and dst.startswith("tasks/") and not dst.startswith(ENGINE_OK) \
            and dst not in INTERFACES:
        return "a family's interface header includes what src/ may not (its family's internals)"
    if src.startswith("tasks/hydro/") and not dst.startswith(HYDRO_OK):
        return "tasks/hydro/ includes above its layer (families, engine)"
    if src.startswith("src/materials/") and not dst.startswith(MATERIALS_OK):
        return "src/materials/ includes above its layer"
    if src.startswith("src/runner.") and dst in SCHED and not dst.startswith("src/runner."):
        return "the runner calls the scheduler back, never includes it (no runner <-> scheduler circle)"
    if src in SCHED and dst not in SCHED and dst not in ("src/error.h", "tasks/task_families.h"):
        return "the scheduler layer includes above its layer"
    return None


arrows = {}
for p in sources:
    if not p.startswith(("src/", "tasks/hydro/")) and p not in INTERFACES:
        continue
    for name in include_re.findall(read(p)):
        dst = resolve(p, name)
        if dst is None:
            continue  # config.h, generated or system headers
        why = violation(p, dst)
        if why:
            arrows[(p, dst)] = why

allowed = {}
for i, line in enumerate(read("tests/repo/layers.allow").splitlines(), 1):
    line = line.split("#", 1)[0].strip()
    if not line:
        continue
    parts = line.split()
    if len(parts) != 2:
        fail("tests/repo/layers.allow:%d: expected 'FILE INCLUDED-FILE  # reason'" % i)
        continue
    allowed[tuple(parts)] = i
for (src, dst), why in sorted(arrows.items()):
    if (src, dst) not in allowed:
        fail("%s includes %s: %s" % (src, dst, why))
for (src, dst), i in sorted(allowed.items(), key=lambda kv: kv[1]):
    if (src, dst) not in arrows:
        fail("tests/repo/layers.allow:%d: %s no longer includes %s across the layers: remove the line"
             % (i, src, dst))

print("%d families (%s), %d kinds of task, %d files read, %d arrows across the layers (all in "
      "tests/repo/layers.allow)" % (len(families), ", ".join(families), len(kinds), len(sources), len(arrows))
      if not fails else "%d findings" % len(fails))
sys.exit(1 if fails else 0)
