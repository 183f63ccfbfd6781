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
"""

import os

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


def load(path, fields=None, optional=()):
    """Load a snapshot.

    path:   HDF5 file name.
    fields: iterable of dataset names to read (Bolide's names); None reads
            every dataset of /PartType0.
    optional: dataset names read when present and silently skipped when not
            (with fields given; a large snapshot is then read only in part).
    Returns a dict: one numpy array per dataset (keyed by Bolide's name),
    plus "header" (dict of the /Header attributes, with "Time" as a float and
    "BoxSize" as a length-3 array when present) and "path".
    Raises SnapshotError when the file, a group or a requested field is
    missing or malformed.
    """
    import h5py

    if not os.path.exists(path):
        raise SnapshotError("%s: no such file" % path)
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        raise SnapshotError("%s: not an HDF5 file (%s)" % (path, exc))
    with f:
        if "PartType0" not in f:
            raise SnapshotError("%s: no /PartType0 group" % path)
        group = f["PartType0"]
        available = {}
        for name in group.keys():
            available[ALIASES.get(name, name)] = name
        wanted = list(available) if fields is None else list(fields)
        wanted += [name for name in optional if name in available and name not in wanted]
        data = {}
        for name in wanted:
            if name not in available:
                raise SnapshotError("%s: no dataset /PartType0/%s" % (path, name))
            data[name] = np.asarray(group[available[name]][...])
        header = {}
        if "Header" in f:
            for key, value in f["Header"].attrs.items():
                header[key] = value
        data["header"] = _normalise_header(header, path)
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


def read_stats(path):
    """Read a statistics file.

    The '#' line of Bolide's one-word column names ("# step time dt ...")
    names the columns; without one (another program's file), the last '#'
    line before the first data line (names separated by white space; a
    leading "#" is dropped).  Bolide's files are in SWIFT's layout, whose
    last header line holds SWIFT's names (two blanks apart) for
    swiftsimio.load_statistics.  Returns a dict
    name -> 1D float array.  Raises SnapshotError for a missing file, no
    header line, rows of the wrong length or non-numeric values.
    """
    if not os.path.exists(path):
        raise SnapshotError("%s: no such file" % path)
    names = None
    bolide_names = False
    rows = []
    with open(path) as f:
        for lineno, line in enumerate(f, 1):
            text = line.strip()
            if not text:
                continue
            if text.startswith("#"):
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
    return {name: table[:, i] for i, name in enumerate(names)}
