"""Readers of one LAMMPS dump file of a shear run.

- grains (dump custom: id type radius x y z vx vy vz dx dy dz) are read with MDAnalysis's
  LAMMPS dump reader (ids, types, positions, velocities, sorted by id). MDAnalysis 2.4 neither
  reads extra per-atom columns nor keeps the box origin (it shifts positions by the box's lower
  bound), so radius and dx dy dz come from the same file's table (numpy) sorted by id the same
  way, and the shift is undone with the header's lower bounds.
- contacts and bonds (dump local) are tables: read with numpy into named columns.
Before reading, every file is checked to be complete (the entry count of its header, full last
line): a missing, truncated or malformed dump stops with a one-line message naming the file.
"""
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tbagspost import fail

HEADER_LINES = 9
GRAIN_COLUMNS = ("id", "type", "radius", "x", "y", "z", "vx", "vy", "vz", "dx", "dy", "dz")
CONTACT_COLUMNS = ("id1", "id2", "type1", "type2", "ftx", "fty", "ftz", "fn")
BOND_COLUMNS = ("id1", "id2", "tension")


@dataclass
class Header:
    """The header of a single-snapshot dump: step, entry count, box and column names."""
    step: int
    count: int
    lo: np.ndarray
    hi: np.ndarray
    columns: list


def read_header(path):
    """Header of one dump file (the first snapshot); stops clearly on a missing or bad file."""
    path = Path(path)
    if not path.is_file():
        fail("no dump %s" % path)
    with open(path) as f:
        lines = [f.readline() for _ in range(HEADER_LINES)]
    try:
        if not (lines[0].startswith("ITEM: TIMESTEP") and lines[2].startswith("ITEM: NUMBER OF")
                and lines[4].startswith("ITEM: BOX BOUNDS")
                and lines[8].startswith(("ITEM: ATOMS", "ITEM: ENTRIES")) and lines[8].endswith("\n")):
            raise ValueError
        box = np.array([[float(v) for v in lines[k].split()[:2]] for k in (5, 6, 7)])
        return Header(int(lines[1]), int(lines[3]), box[:, 0], box[:, 1], lines[8].split()[2:])
    except (ValueError, IndexError):
        fail("%s is not a LAMMPS dump or its header is truncated" % path)


def check_complete(path, header, needed):
    """Stop unless the file holds header.count full rows and the columns `needed`."""
    missing = [c for c in needed if c not in header.columns]
    if missing:
        fail("%s lacks the columns %s (written by an older inputs/in.shear? rerun the shear stage)"
             % (path, " ".join(missing)))
    rows, last = 0, ""
    with open(path, "rb") as f:
        for k, line in enumerate(f):
            if k >= HEADER_LINES:
                if line.startswith(b"ITEM:"):
                    break
                rows += 1
                last = line
    full = rows == 0 or (last.endswith(b"\n") and len(last.split()) == len(header.columns))
    if rows != header.count or not full:
        fail("%s is truncated: %d of %d rows%s" % (path, rows, header.count,
                                                    "" if full else ", last row cut"))


def _table(path, header):
    """The rows of a checked dump as a 2-D float array (one row per entry)."""
    if header.count == 0:
        return np.zeros((0, len(header.columns)))
    try:
        return np.loadtxt(path, skiprows=HEADER_LINES, max_rows=header.count, ndmin=2)
    except ValueError as e:
        fail("%s is malformed: %s" % (path, e))


def read_local(path, needed):
    """A dump local file (contacts or bonds): dict column name -> array, plus 'step'."""
    header = read_header(path)
    check_complete(path, header, needed)
    data = _table(path, header)
    out = {name: data[:, k] for k, name in enumerate(header.columns)}
    for name in ("id1", "id2", "type1", "type2", "btype"):
        if name in out:
            out[name] = out[name].astype(np.int64)
    out["step"] = header.step
    return out


def read_contacts(path):
    """Contacts of one step (compute pair/local + property/local): ids, types, forces (N)."""
    return read_local(path, CONTACT_COLUMNS)


def read_bonds(path):
    """Bonds of one step (compute bond/local + property/local): ids and tension (N, > 0 pulls)."""
    return read_local(path, BOND_COLUMNS)


@dataclass
class Grains:
    """Particles of one dump step, sorted by id (SI units)."""
    step: int
    ids: np.ndarray
    types: np.ndarray
    radius: np.ndarray
    pos: np.ndarray    # (n, 3) m
    vel: np.ndarray    # (n, 3) m/s
    disp: np.ndarray   # (n, 3) m, from the filled state
    lo: np.ndarray
    hi: np.ndarray

    def index(self, ids):
        """Row of each atom id; stops clearly on an id that is not in this dump."""
        ids = np.asarray(ids)
        k = np.searchsorted(self.ids, ids)
        k = np.clip(k, 0, len(self.ids) - 1)
        if len(ids) and not np.array_equal(self.ids[k], ids):
            fail("step %d: contact or bond atom ids missing from the grains dump" % self.step)
        return k

    @property
    def bag(self):
        """Mask of the bag particles (type 1)."""
        return self.types == 1


def universe(path):
    """The MDAnalysis Universe of one grains dump (topology and coordinates from the dump)."""
    with warnings.catch_warnings():
        # MDAnalysis installs its own 'once' filter for its DeprecationWarnings (xdrlib)
        warnings.simplefilter("ignore")
        warnings.showwarning = lambda *args, **kw: None
        import MDAnalysis
        return MDAnalysis.Universe(str(path), format="LAMMPSDUMP", topology_format="LAMMPSDUMP",
                                   lammps_coordinate_convention="unscaled")


def read_grains(path):
    """Particles of one grains dump: positions, velocities, ids, types through MDAnalysis;
    radius and displacement from the table (see the module note)."""
    path = Path(path)
    header = read_header(path)
    check_complete(path, header, GRAIN_COLUMNS)
    try:
        u = universe(path)
    except (ValueError, IndexError, EOFError, OSError) as e:
        fail("MDAnalysis cannot read %s: %s" % (path, e))
    ts = u.trajectory[0]
    table = _table(path, header)
    col = {name: k for k, name in enumerate(header.columns)}
    order = np.argsort(table[:, col["id"]], kind="stable")
    table = table[order]
    ids = u.atoms.ids.astype(np.int64)
    if not np.array_equal(ids, table[:, col["id"]].astype(np.int64)):
        fail("%s: MDAnalysis and the table disagree on the atom ids" % path)
    pick = lambda names: table[:, [col[c] for c in names]]
    return Grains(step=int(ts.data["step"]), ids=ids, types=u.atoms.types.astype(np.int64),
                  radius=pick(["radius"])[:, 0],
                  pos=ts.positions.astype(np.float64) + header.lo,
                  vel=ts.velocities.astype(np.float64), disp=pick(["dx", "dy", "dz"]),
                  lo=header.lo, hi=header.hi)
