"""A LAMMPS data file of the decks (write_data, atom style bpm/sphere): the box, the atoms
(id, type, diameter, position) and the bonds (first and second atom id).

bpm/sphere's Atoms lines are: id molecule type diameter density x y z [ix iy iz].
"""
from pathlib import Path

import numpy as np

from tbagspost import fail

SECTIONS = ("Atoms", "Velocities", "Bonds", "Masses", "Pair Coeffs", "Bond Coeffs", "PairIJ Coeffs")


class DataFile:
    """box: 3 x 2 (lo, hi) in m; id, type (int), diameter, x (n x 3) of the atoms; bonds
    (m x 2 atom ids)."""

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
        atoms = self._section(lines, "Atoms")
        if atoms is None or atoms.shape[1] < 8:
            fail("%s has no Atoms section of atom style bpm/sphere" % path)
        order = np.argsort(atoms[:, 0])
        atoms = atoms[order]
        self.id = atoms[:, 0].astype(np.int64)
        self.type = atoms[:, 2].astype(int)
        self.diameter = atoms[:, 3]
        self.x = atoms[:, 5:8]
        bonds = self._section(lines, "Bonds")
        self.bonds = np.zeros((0, 2), dtype=np.int64) if bonds is None else bonds[:, 2:4].astype(np.int64)

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
