"""The XDMF file beside a snapshot is well-formed XML and describes exactly
the HDF5 datasets: every DataItem points to an existing dataset of the same
dimensions and number type, and every dataset of /PartType0 is described.
Snapshots of both kinds are checked: an initial condition from bolide-ic and
a full snapshot (with accelerations, gzip) written by tests/helpers/ic_dump.
A run's time series (OUTDIR/BASENAME.xmf, issue 23 item 4) is a temporal
collection of the grids of all its snapshots, in time order, each pointing
to its own snapshot file."""
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py

build = os.environ["BOLIDE_BUILDDIR"]
failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)
        print("FAIL", msg)


def check_pair(h5path):
    xmf = os.path.splitext(h5path)[0] + ".xmf"
    check(os.path.exists(xmf), f"{xmf} missing")
    check(not os.path.exists(xmf + ".tmp") and not os.path.exists(h5path + ".tmp"),
          "temporary file left")
    root = ET.parse(xmf).getroot()  # raises on malformed XML
    check(root.tag == "Xdmf", "root element is not Xdmf")
    grids = root.findall("./Domain/Grid")
    check(len(grids) == 1, f"{len(grids)} grids")
    grid = grids[0]
    with h5py.File(h5path, "r") as f:
        n = f["Header"].attrs["NumPart_ThisFile"][0]
        topo = grid.find("Topology")
        check(topo.get("TopologyType") == "Polyvertex", "topology is not Polyvertex")
        check(int(topo.get("NumberOfElements")) == n, "NumberOfElements != particle count")
        geom = grid.find("Geometry")
        check(geom is not None and geom.get("GeometryType") == "XYZ", "no XYZ geometry")
        described = set()
        items = grid.findall(".//DataItem")
        for item in items:
            fname, dset = item.text.strip().split(":")
            check(fname == os.path.basename(h5path), f"DataItem names file {fname}")
            check(dset in f, f"{dset} not in the HDF5 file")
            if dset not in f:
                continue
            d = f[dset]
            dims = tuple(int(x) for x in item.get("Dimensions").split())
            check(dims == d.shape, f"{dset}: Dimensions {dims} != shape {d.shape}")
            kind = "Float" if d.dtype.kind == "f" else "Int"
            check(item.get("NumberType") == kind, f"{dset}: NumberType {item.get('NumberType')}")
            check(int(item.get("Precision")) == d.dtype.itemsize, f"{dset}: Precision")
            check(item.get("Format") == "HDF", f"{dset}: Format")
            described.add(dset.split("/")[-1])
        for attr in grid.findall("Attribute"):
            d = f["PartType0/" + attr.get("Name")]
            want = {1: "Scalar", 3: "Vector", 6: "Tensor6"}[1 if d.ndim == 1 else d.shape[1]]
            check(attr.get("AttributeType") == want, f"{attr.get('Name')}: {attr.get('AttributeType')}")
        check(geom.find("DataItem").text.strip().endswith("/PartType0/Coordinates"),
              "geometry is not Coordinates")
        # initial conditions also hold GADGET-style singular names as hard
        # links to the same datasets (for SWIFT): those need no description
        aliases = {"SmoothingLength": "SmoothingLengths", "InternalEnergy": "InternalEnergies",
                   "Density": "Densities"}
        for a, target in aliases.items():
            if a in f["PartType0"]:
                check(f["PartType0"][a] == f["PartType0"][target], f"{a} is not a link to {target}")
                described.add(a)
        check(described == set(f["PartType0"].keys()),
              f"described {sorted(described)} != datasets {sorted(f['PartType0'].keys())}")
        time = float(grid.find("Time").get("Value"))
        check(time == f["Header"].attrs["Time"][0], "Time differs")


with tempfile.TemporaryDirectory() as tmp:
    ic = os.path.join(tmp, "box.hdf5")
    snap = os.path.join(tmp, "snap_0000.hdf5")
    subprocess.run([os.path.join(build, "bolide-ic"), "box", "--n", "6", "--lattice", "fcc",
                    "-o", ic], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([os.path.join(build, "tests", "helpers", "ic_dump"), ic, "--write", snap, "--acc",
                    "--gzip", "4"], check=True, stdout=subprocess.DEVNULL)
    check_pair(ic)
    check_pair(snap)
    with h5py.File(snap, "r") as f:
        check("Accelerations" in f["PartType0"], "no Accelerations with --acc")
        check(f["PartType0/Masses"].compression == "gzip", "not compressed")

# the time series of a run
with tempfile.TemporaryDirectory() as tmp:
    ic = os.path.join(tmp, "box.hdf5")
    subprocess.run([os.path.join(build, "bolide-ic"), "box", "--n", "6", "-o", ic], check=True,
                   stdout=subprocess.DEVNULL)
    with open(os.path.join(tmp, "p.yml"), "w") as f:
        f.write("InitialConditions:\n  file_name: box.hdf5\nTimeIntegration:\n  time_end: 0.03\n"
                "Snapshots:\n  subdir: out\n  basename: run\n  delta_time: 0.01\n")
    subprocess.run([os.path.join(build, "bolide"), "p.yml"], cwd=tmp, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    out = os.path.join(tmp, "out")
    snaps = sorted(x for x in os.listdir(out) if x.startswith("run_") and x.endswith(".hdf5"))
    root = ET.parse(os.path.join(out, "run.xmf")).getroot()
    coll = root.find("Domain/Grid")
    check(coll is not None and coll.get("CollectionType") == "Temporal", "run.xmf: no temporal collection")
    grids = coll.findall("Grid") if coll is not None else []
    check(len(grids) == len(snaps) and len(snaps) >= 4,
          "run.xmf: %d grids for %d snapshots" % (len(grids), len(snaps)))
    times = [float(g.find("Time").get("Value")) for g in grids]
    check(times == sorted(times) and times[0] == 0.0, "run.xmf: times %s" % times)
    for g, name in zip(grids, snaps):
        files = {d.text.split(":")[0] for d in g.iter("DataItem")}
        check(files == {name}, "run.xmf: grid of %s points to %s" % (name, files))
    for name in snaps:
        check_pair(os.path.join(out, name))

print("FAIL" if failures else "PASS")
sys.exit(1 if failures else 0)
