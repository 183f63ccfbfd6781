"""Snapshots and statistics with units (unyt, as swiftsimio gives them).

load_snapshot(path) and load_statistics(path) return objects whose
attributes are unyt arrays in SI, converted from the units the file records
(a snapshot's /Units group and the dimension of each dataset; the
statistics file's "Unit =" line of each column), so that a run in SWIFT's
planetary units (Earth masses and radii) and a run in SI give the same
numbers.  Names are Bolide's: snapshot fields by their dataset names in
snake case (coordinates, velocities, masses, ...), statistics columns by
Bolide's column names (time, E_kin, E_tot, px, Lz, ...)."""
import re

import numpy as np

from . import snapshot as _snapshot


def _si_unit(dim):
    """The unyt unit of dimension (mass, length, time) exponents in SI."""
    import unyt
    parts = ["%s**%g" % (base, e) if e != 1 else base
             for base, e in (("kg", dim[0]), ("m", dim[1]), ("s", dim[2])) if e]
    return unyt.Unit("*".join(parts)) if parts else unyt.dimensionless


def _snake(name):
    """SmoothingLengths -> smoothing_lengths."""
    return re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower().replace("_i_ds", "_ids")


class Fields:
    """Attributes holding unyt arrays; `names` lists them."""

    def __init__(self):
        self.names = []

    def _set(self, name, value):
        setattr(self, name, value)
        self.names.append(name)

    def __repr__(self):
        return "<bolide %s: %s>" % (type(self).__name__, ", ".join(self.names))


class Snapshot(Fields):
    """A snapshot: particle fields, time, box_size (unyt, SI), path."""


class Statistics(Fields):
    """A statistics file: one unyt array per column (SI), path."""


def load_snapshot(path):
    """Every dataset of /PartType0 of a Bolide or SWIFT snapshot as unyt
    arrays in SI (ids and material ids dimensionless integers)."""
    import unyt
    d = _snapshot.load(path, si=True)
    snap = Snapshot()
    snap.path = path
    for name, dim in d["dimensions"].items():
        arr = d[name]
        unit = _si_unit(dim) if arr.dtype.kind == "f" else unyt.dimensionless
        snap._set(_snake(name), unyt.unyt_array(arr, unit))
    h = d["header"]
    if "Time" in h:
        snap.time = unyt.unyt_quantity(h["Time"], "s")
    if "BoxSize" in h:
        snap.box_size = unyt.unyt_array(h["BoxSize"], "m")
    return snap


def load_statistics(path):
    """Every column of a Bolide statistics file as a unyt array in SI, of
    the dimension the file's "Unit =" line of the column gives
    (dimensionless without one)."""
    import unyt
    cols, dims = _snapshot.read_stats_units(path, si=True)
    st = Statistics()
    st.path = path
    for name, values in cols.items():
        st._set(name, unyt.unyt_array(np.asarray(values), _si_unit(dims.get(name, (0, 0, 0)))))
    return st
