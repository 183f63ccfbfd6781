"""Read Bolide's output files.

`load` reads an HDF5 snapshot in the layout planetary SPH users know
(SWIFT's): /Header attributes (Time, BoxSize, ...) and the particle datasets
under /PartType0 (Coordinates (N,3), Velocities (N,3), Masses,
SmoothingLengths, InternalEnergies, Densities, Pressures, SoundSpeeds,
ParticleIDs, MaterialIDs, and optional fields such as DeviatoricStress or
Damage).  SWIFT's singular dataset names (SmoothingLength, InternalEnergy,
Density, ...) are accepted and returned under Bolide's plural names, so a
SWIFT snapshot can be compared with a Bolide one by the same scripts.

`read_stats` reads the statistics file: whitespace-separated columns under a
'#' header line that names them.  Columns are found by name, never by
position.

`read_fragments` reads a fragment table of bolide-fof (its columns by the
names of the last '#' line, its total mass and time from the header).
"""

import os
import re

import numpy as np

#: Alternative dataset names (SWIFT's singular forms) -> Bolide's names.
ALIASES = {
    "SmoothingLength": "SmoothingLengths",
    "InternalEnergy": "InternalEnergies",
    "Density": "Densities",
    "Pressure": "Pressures",
    "SoundSpeed": "SoundSpeeds",
    "MaterialID": "MaterialIDs",
    "Mass": "Masses",
    "Acceleration": "Accelerations",
    "Potential": "Potentials",
}


class SnapshotError(Exception):
    """A snapshot or statistics file that cannot be read; the message names
    the file and what is wrong with it."""


#: Dimension (mass, length, time exponents) of the datasets, for files whose
#: datasets carry no "U_M exponent" attributes (SWIFT's and Bolide's do).
DIMENSIONS = {
    "Coordinates": (0, 1, 0), "Velocities": (0, 1, -1), "Masses": (1, 0, 0),
    "SmoothingLengths": (0, 1, 0), "InternalEnergies": (0, 2, -2), "Densities": (1, -3, 0),
    "Pressures": (1, -1, -2), "SoundSpeeds": (0, 1, -1), "Accelerations": (0, 1, -2),
    "Potentials": (0, 2, -2), "DeviatoricStress": (1, -1, -2), "Entropies": (1, -1, -2),
    "ParticleIDs": (0, 0, 0), "MaterialIDs": (0, 0, 0), "Damage": (0, 0, 0),
}

#: One cgs base unit in SI: g -> kg, cm -> m, s -> s.
CGS_TO_SI = (1e-3, 1e-2, 1.0)


def _file_units(f):
    """The file's unit of mass, length and time in cgs (/Units: U_M, U_L,
    U_t, as SWIFT, woma and Bolide write it); cgs (1, 1, 1) without one."""
    if "Units" not in f:
        return None
    a = f["Units"].attrs
    try:
        return tuple(float(np.ravel(a[k])[0]) for k in
                     ("Unit mass in cgs (U_M)", "Unit length in cgs (U_L)", "Unit time in cgs (U_t)"))
    except KeyError:
        return None


def _dimension(dset, name):
    """(a, b, c) exponents of mass, length and time of a dataset: its own
    attributes when present, else DIMENSIONS, else dimensionless."""
    at = dset.attrs
    if all(k in at for k in ("U_M exponent", "U_L exponent", "U_t exponent")):
        return tuple(float(np.ravel(at[k])[0]) for k in ("U_M exponent", "U_L exponent", "U_t exponent"))
    return DIMENSIONS.get(name, (0, 0, 0))


def si_factor(units, dim):
    """Factor from a file's units (mass, length, time in cgs) to SI for a
    quantity of dimension dim = (a, b, c)."""
    f = 1.0
    for u, e, c in zip(units, dim, CGS_TO_SI):
        f *= (u * c) ** e
    return f


def _open(path):
    """The snapshot or initial-conditions file at path, open for reading
    (an h5py.File), with its /PartType0 group; SnapshotError when the file
    is missing, not HDF5, or has no such group."""
    import h5py

    if not os.path.exists(path):
        raise SnapshotError("%s: no such file" % path)
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        raise SnapshotError("%s: not an HDF5 file (%s)" % (path, exc))
    if "PartType0" not in f:
        f.close()
        raise SnapshotError("%s: no /PartType0 group" % path)
    return f


def load(path, fields=None, optional=(), si=False):
    """Load a snapshot.

    path:   HDF5 file name.
    fields: iterable of dataset names to read (Bolide's names); None reads
            every dataset of /PartType0.
    optional: dataset names read when present and silently skipped when not
            (with fields given; a large snapshot is then read only in part).
    si:     convert every dataset and the header's Time and BoxSize from
            the file's units (its /Units group: a Bolide snapshot is in the
            run's internal units, SWIFT's and woma's often in Earth masses
            and radii) to SI; a file without /Units is taken as cgs.
    Returns a dict: one numpy array per dataset (keyed by Bolide's name),
    plus "header" (dict of the /Header attributes, with "Time" as a float and
    "BoxSize" as a length-3 array when present), "dimensions" (name ->
    (mass, length, time) exponents), "units" ("SI" or "file") and "path".
    Raises SnapshotError when the file, a group or a requested field is
    missing or malformed.
    """
    f = _open(path)
    with f:
        group = f["PartType0"]
        available = {}
        for name in group.keys():
            available[ALIASES.get(name, name)] = name
        wanted = list(available) if fields is None else list(fields)
        wanted += [name for name in optional if name in available and name not in wanted]
        data = {}
        dims = {}
        units = _file_units(f) or (1.0, 1.0, 1.0)
        for name in wanted:
            if name not in available:
                raise SnapshotError("%s: no dataset /PartType0/%s" % (path, name))
            dset = group[available[name]]
            data[name] = np.asarray(dset[...])
            dims[name] = _dimension(dset, name)
            if si and dims[name] != (0, 0, 0):
                data[name] = data[name] * si_factor(units, dims[name])
        header = {}
        if "Header" in f:
            for key, value in f["Header"].attrs.items():
                header[key] = value
        data["header"] = _normalise_header(header, path)
        if si:
            if "Time" in data["header"]:
                data["header"]["Time"] *= si_factor(units, (0, 0, 1))
            if "BoxSize" in data["header"]:
                data["header"]["BoxSize"] = data["header"]["BoxSize"] * si_factor(units, (0, 1, 0))
        data["dimensions"] = dims
        data["units"] = "SI" if si else "file"
        data["path"] = path
    n = None
    for name in wanted:
        if n is None:
            n = data[name].shape[0]
        elif data[name].shape[0] != n:
            raise SnapshotError(
                "%s: /PartType0/%s has %d rows, expected %d"
                % (path, name, data[name].shape[0], n))
    for name in ("Coordinates", "Velocities"):
        if name in data and (data[name].ndim != 2 or data[name].shape[1] != 3):
            raise SnapshotError("%s: /PartType0/%s is not an (N,3) array" % (path, name))
    return data


def iter_chunks(path, name, size=1 << 20):
    """Yield one dataset of /PartType0 (Bolide's name or SWIFT's alias) in
    blocks of at most size rows, as float64 arrays in the file's units: for
    files too large to load at once (tools/bench/impact_counts.py).  Raises
    SnapshotError as load does."""
    f = _open(path)
    with f:
        group = f["PartType0"]
        found = [k for k in group.keys() if ALIASES.get(k, k) == name]
        if not found:
            raise SnapshotError("%s: no dataset /PartType0/%s" % (path, name))
        dset = group[found[0]]
        for start in range(0, dset.shape[0], size):
            yield np.asarray(dset[start:start + size], dtype=np.float64)


def _normalise_header(header, path):
    """Time as a float, BoxSize as a length-3 float array (a scalar BoxSize,
    as older SWIFT files have, means a cube)."""
    if "Time" in header:
        header["Time"] = float(np.ravel(header["Time"])[0])
    if "BoxSize" in header:
        box = np.ravel(np.asarray(header["BoxSize"], dtype=float))
        if box.size == 1:
            box = np.repeat(box, 3)
        if box.size != 3:
            raise SnapshotError("%s: /Header BoxSize has %d values, expected 1 or 3"
                                % (path, box.size))
        header["BoxSize"] = box
    return header


def snapshot_time(snap, override=None):
    """The snapshot's time (header Time) unless OVERRIDE is given."""
    if override is not None:
        return float(override)
    if "Time" not in snap["header"]:
        raise SnapshotError("%s: /Header has no Time attribute (give the time as an option)"
                            % snap["path"])
    return snap["header"]["Time"]


#: cgs symbols of the statistics file's units: (SI value, (mass, length, time) exponents).
_CGS_SYMBOLS = {"gram": (1e-3, (1, 0, 0)), "g": (1e-3, (1, 0, 0)), "cm": (1e-2, (0, 1, 0)),
                "s": (1.0, (0, 0, 1)), "erg": (1e-7, (1, 2, -2))}


def _cgs_unit(factor, unit):
    """SI value of FACTOR x UNIT and its (mass, length, time) exponents,
    UNIT as the statistics file writes it ("gram * cm**2 * s**-2", "s",
    "dimensionless")."""
    f, dim = factor, [0.0, 0.0, 0.0]
    if unit.strip() in ("", "dimensionless"):
        return f, tuple(dim)
    for term in re.split(r"\s+\*\s+", unit.strip()):
        term = term.strip()
        if not term:
            continue
        sym, _, exp = term.partition("**") if "**" in term else (term, "", "1")
        if sym.strip() not in _CGS_SYMBOLS:
            raise ValueError("unknown unit %r" % sym)
        si, d = _CGS_SYMBOLS[sym.strip()]
        f *= si ** float(exp)
        dim = [a + b * float(exp) for a, b in zip(dim, d)]
    return f, tuple(dim)


def read_stats(path, si=False):
    """Read a statistics file: read_stats_units without the units."""
    return read_stats_units(path, si)[0]


def read_stats_units(path, si=False):
    """Read a statistics file and the units of its columns.

    The '#' line of Bolide's one-word column names ("# step time dt ...")
    names the columns; without one (another program's file), the last '#'
    line before the first data line (names separated by white space; a
    leading "#" is dropped).  Bolide's files are in SWIFT's layout, whose
    last header line holds SWIFT's names (two blanks apart) for
    swiftsimio.load_statistics.  Returns a dict
    name -> 1D float array.  With si, every column with a "Unit = F UNIT"
    line in the header (Bolide's files: one per numbered column) is
    converted to SI.  Returns (columns, dimensions): dimensions maps the
    name of each column with a "Unit =" line to its (mass, length, time)
    exponents, as that line gives them.  Raises SnapshotError for a
    missing file, no header line, rows of the wrong length or non-numeric
    values.
    """
    if not os.path.exists(path):
        raise SnapshotError("%s: no such file" % path)
    names = None
    bolide_names = False
    rows = []
    units = {}  # column number -> (factor to SI, dimension)
    column = None
    with open(path) as f:
        for lineno, line in enumerate(f, 1):
            text = line.strip()
            if not text:
                continue
            if text.startswith("#"):
                w = text.lstrip("#").split()
                if w and w[0].startswith("(") and w[0].endswith(")") and w[0][1:-1].isdigit():
                    column = int(w[0][1:-1])
                elif (len(w) >= 3 and w[0] == "Unit" and w[1] == "=" and column is not None
                      and column not in units):
                    try:
                        units[column] = (1.0, (0.0, 0.0, 0.0)) if w[2] == "dimensionless" else \
                            _cgs_unit(float(w[2]), " ".join(w[3:]))
                    except ValueError as exc:
                        raise SnapshotError("%s:%d: %s" % (path, lineno, exc))
                if not rows:
                    tokens = text.lstrip("#").split()
                    if tokens and not bolide_names:
                        names = tokens
                    if tokens and tokens[0] == "step" and len(tokens) > 1:
                        bolide_names = True
                continue
            if names is None:
                raise SnapshotError("%s:%d: data before a '#' header line naming the columns"
                                    % (path, lineno))
            tokens = text.split()
            if len(tokens) != len(names):
                raise SnapshotError("%s:%d: %d columns, the header names %d"
                                    % (path, lineno, len(tokens), len(names)))
            try:
                rows.append([float(t) for t in tokens])
            except ValueError:
                raise SnapshotError("%s:%d: non-numeric value" % (path, lineno))
    if names is None:
        raise SnapshotError("%s: no '#' header line naming the columns" % path)
    if len(set(names)) != len(names):
        raise SnapshotError("%s: repeated column name in the header" % path)
    table = np.array(rows, dtype=float).reshape(len(rows), len(names))
    if si:
        for i in range(len(names)):
            table[:, i] *= units[i][0] if i in units else 1.0
    dims = {name: units[i][1] for i, name in enumerate(names) if i in units}
    return {name: table[:, i] for i, name in enumerate(names)}, dims


def read_fragments(path):
    """Read a fragment table written by bolide-fof (--out).

    Returns (columns, info): columns a dict name -> 1D float array, by the
    names of the last '#' header line ("# rank mass count x y z ...",
    frac_matN per material), one entry per fragment; info a dict with
    "total_mass" (kg: the header's "total mass M kg", else the sum of the
    fragments' masses) and "time" (s: the header's "time T s", None without
    one).  bolide-fof writes SI whatever the snapshot's units.  Raises
    SnapshotError for a missing file, no header naming a mass column, or
    rows of the wrong length.
    """
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except OSError as exc:
        raise SnapshotError("%s: cannot read: %s" % (path, exc.strerror))
    header = [ln for ln in lines if ln.startswith("#")]
    names = header[-1].lstrip("#").split() if header else []
    if "mass" not in names:
        raise SnapshotError("%s: no '# rank mass ...' header line (not a bolide-fof table?)" % path)
    info = {"total_mass": None, "time": None}
    for ln in header:
        m = re.search(r"total mass ([0-9.eE+-]+) kg", ln)
        if m:
            info["total_mass"] = float(m.group(1))
        m = re.match(r"#\s*time ([0-9.eE+-]+) s\b", ln)
        if m:
            info["time"] = float(m.group(1))
    rows = [ln.split() for ln in lines if ln.strip() and not ln.startswith("#")]
    for k, r in enumerate(rows):
        if len(r) != len(names):
            raise SnapshotError("%s: fragment %d has %d columns, the header names %d"
                                % (path, k + 1, len(r), len(names)))
    try:
        data = np.array(rows, dtype=float).reshape(-1, len(names))
    except ValueError:
        raise SnapshotError("%s: non-numeric value in a fragment row" % path)
    cols = {n: data[:, i] for i, n in enumerate(names)}
    if info["total_mass"] is None:
        info["total_mass"] = float(cols["mass"].sum())
    return cols, info
