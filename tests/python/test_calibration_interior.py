"""calibration/tbagscal/interior.py on lattices of known solid fraction: simple cubic (pi/6) in a
periodic box and inside a walled block (the inset box on cell boundaries), and a face-centred
cubic of touching spheres (pi/(3 sqrt 2)); within the Monte Carlo noise (0.5 %)."""
import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "calibration"))
from tbagscal import interior  # noqa: E402

A = 0.005     # m, lattice spacing


def cubic(n, basis):
    cells = np.array([[i, j, k] for i in range(n) for j in range(n) for k in range(n)], float)
    return np.concatenate([(cells + b) * A for b in basis])


def test_simple_cubic_periodic_and_walled():
    x = cubic(6, [np.array([0.5, 0.5, 0.5])])
    d = np.full(len(x), A)                                  # touching spheres
    box = np.array([[0, 6 * A]] * 3)
    e = 6 / math.pi - 1
    assert interior.void_ratio(d, x, box, periodic=True) == pytest.approx(e, rel=5e-3)
    assert interior.void_ratio(d, x, box, inset=2 * A) == pytest.approx(e, rel=5e-3)
    # a sparser lattice (spheres of half the spacing): eight times the voids per solid
    assert interior.void_ratio(d / 2, x, box, periodic=True) == pytest.approx(8 * (e + 1) - 1, rel=5e-3)


def test_face_centred_cubic():
    basis = [np.array(b) for b in ([0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5])]
    x = cubic(4, basis)
    d = np.full(len(x), A / math.sqrt(2))
    box = np.array([[0, 4 * A]] * 3)
    assert interior.void_ratio(d, x, box, periodic=True) == pytest.approx(3 * math.sqrt(2) / math.pi - 1, rel=5e-3)


def test_reads_the_calibrations_data_files(tmp_path):
    """write_data's atom style sphere (id type diameter density x y z ix iy iz) through tbagspost's
    DataFile: diameters, positions (by id) and the box; bpm/sphere keeps its molecule column."""
    head = ("LAMMPS data file\n\n2 atoms\n1 atom types\n\n0 0.05 xlo xhi\n0 0.05 ylo yhi\n"
            "-0.01 0.1 zlo zhi\n\n")
    (tmp_path / "s.data").write_text(head + "Atoms # sphere\n\n2 1 0.004 2650 0.03 0.02 0.01 0 0 0\n"
                                     "1 1 0.003 2650 0.01 0.02 0.03 0 0 0\n")
    d, x, box = interior.read_data(tmp_path / "s.data")
    assert list(d) == [0.003, 0.004] and x.tolist() == [[0.01, 0.02, 0.03], [0.03, 0.02, 0.01]]
    assert box.tolist() == [[0, 0.05], [0, 0.05], [-0.01, 0.1]]
    from tbagspost.datafile import DataFile
    (tmp_path / "b.data").write_text(head + "Atoms # bpm/sphere\n\n1 7 2 0.005 450 0.01 0.02 0.03 0 0 0\n"
                                     "2 7 1 0.004 2650 0.03 0.02 0.01 0 0 0\n")
    b = DataFile(tmp_path / "b.data")
    assert b.mol.tolist() == [7, 7] and b.type.tolist() == [2, 1] and b.diameter.tolist() == [0.005, 0.004]
    assert DataFile(tmp_path / "s.data").mol.tolist() == [0, 0]
