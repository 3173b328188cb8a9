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
