"""A LAMMPS data file of the decks (write_data, atom style bpm/sphere, or sphere: the
calibration's grains): the box, the atoms (id, molecule, type, diameter, density, position,
velocities) and the bonds (first and second atom id); write_liggghts() writes the same particles
as a LIGGGHTS data file.

bpm/sphere's Atoms lines are: id molecule type diameter density x y z [ix iy iz]; sphere's the
same without the molecule (0 here); Velocities: id vx vy vz wx wy wz. The style is the one the
Atoms line names (write_data writes "Atoms # style"); without a name, bpm/sphere.
"""
from pathlib import Path

import numpy as np

from tbagspost import fail

# the Atoms columns of each style: molecule (None: none), type, diameter, density, x
COLUMNS = {"bpm/sphere": (1, 2, 3, 4, 5), "sphere": (None, 1, 2, 3, 4)}
SECTIONS = ("Atoms", "Velocities", "Bonds", "Masses", "Pair Coeffs", "Bond Coeffs", "PairIJ Coeffs")


class DataFile:
    """box: 3 x 2 (lo, hi) in m; id, mol, type (int), diameter, density, x (n x 3), v and omega
    (n x 3, zero when the file has no Velocities) of the atoms; bonds (m x 2 atom ids) and
    bond_type."""

    def __init__(self, path):
        path = Path(path)
        if not path.is_file():
            fail("no data file %s" % path)
        lines = path.read_text().splitlines()
        self.path = path
        self.box = np.zeros((3, 2))
        for line in lines[:40]:
            words = line.split()
            for k, axis in enumerate("xyz"):
                if words[2:4] == [axis + "lo", axis + "hi"]:
                    self.box[k] = float(words[0]), float(words[1])
        head = next((line for line in lines if line.split("#")[0].strip() == "Atoms"), "")
        style = head.split("#")[1].strip() if "#" in head else "bpm/sphere"
        if style not in COLUMNS:
            fail("%s: atom style %s; this reader knows %s" % (path, style, ", ".join(COLUMNS)))
        mol, typ, dia, rho, x = COLUMNS[style]
        atoms = self._section(lines, "Atoms")
        if atoms is None or atoms.shape[1] < x + 3:
            fail("%s has no Atoms section of atom style %s" % (path, style))
        atoms = atoms[np.argsort(atoms[:, 0])]
        self.id = atoms[:, 0].astype(np.int64)
        self.mol = np.zeros(len(atoms), dtype=np.int64) if mol is None else atoms[:, mol].astype(np.int64)
        self.type = atoms[:, typ].astype(int)
        self.diameter = atoms[:, dia]
        self.density = atoms[:, rho]
        self.x = atoms[:, x:x + 3]
        self.v = np.zeros_like(self.x)
        self.omega = np.zeros_like(self.x)
        vel = self._section(lines, "Velocities")
        if vel is not None:
            vel = vel[np.argsort(vel[:, 0])]
            if vel.shape[0] != len(self.id) or (vel[:, 0] != self.id).any():
                fail("%s: its Velocities do not list the same atoms as its Atoms" % path)
            self.v, self.omega = vel[:, 1:4], vel[:, 4:7]
        bonds = self._section(lines, "Bonds")
        self.bonds = np.zeros((0, 2), dtype=np.int64) if bonds is None else bonds[:, 2:4].astype(np.int64)
        self.bond_type = np.zeros(0, dtype=int) if bonds is None else bonds[:, 1].astype(int)

    def _section(self, lines, name):
        """The numbers of a section as a float array (rows of its lines), or None."""
        try:
            start = next(i for i, line in enumerate(lines) if line.split("#")[0].strip() == name) + 2
        except StopIteration:
            return None
        end = start
        while end < len(lines) and lines[end].strip() and lines[end].split("#")[0].strip() not in SECTIONS:
            end += 1
        try:
            return np.array([line.split() for line in lines[start:end]], dtype=float)
        except ValueError:
            fail("%s: a malformed line in its %s section" % (self.path, name))

    def index(self, ids):
        """Row indices of atom ids."""
        return np.searchsorted(self.id, ids)

    def write_liggghts(self, path, ntypes=None):
        """The particles and bonds as a LIGGGHTS data file (atom_style hybrid granular molecular:
        Atoms id type x y z diameter density molecule; Velocities id vx vy vz wx wy wz), every
        number as written here (%.17g: the same bits). ntypes: atom types to declare (more than
        the file's, e.g. one for the plates, which LIGGGHTS gives a type of their own)."""
        ntypes = ntypes or int(self.type.max())
        out = ["LIGGGHTS data from %s (tbagspost.datafile)" % self.path.name, "",
               "%d atoms" % len(self.id), "%d atom types" % ntypes]
        if len(self.bonds):
            out += ["%d bonds" % len(self.bonds), "%d bond types" % self.bond_type.max()]
        out.append("")
        out += ["%.17g %.17g %slo %shi" % (lo, hi, a, a) for (lo, hi), a in zip(self.box, "xyz")]
        out += ["", "Atoms  # id type x y z diameter density molecule", ""]
        out += ["%d %d %.17g %.17g %.17g %.17g %.17g %d" % (i, t, x[0], x[1], x[2], d, rho, m)
                for i, t, x, d, rho, m in zip(self.id, self.type, self.x, self.diameter, self.density, self.mol)]
        out += ["", "Velocities", ""]
        out += ["%d %.17g %.17g %.17g %.17g %.17g %.17g" % ((i,) + tuple(v) + tuple(w))
                for i, v, w in zip(self.id, self.v, self.omega)]
        if len(self.bonds):
            out += ["", "Bonds", ""]
            out += ["%d %d %d %d" % (k + 1, t, a, b) for k, (t, (a, b)) in enumerate(zip(self.bond_type, self.bonds))]
        Path(path).write_text("\n".join(out) + "\n")
