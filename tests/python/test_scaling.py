"""postprocess/tbagspost/scaling.py: LAMMPS's processor grid, the per-rank counts of a decomposition and the
model's step time, against hand counts on a lattice of touching spheres; the data-file reader."""
import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "postprocess"))
from tbagspost.datafile import DataFile  # noqa: E402

from tbagspost import scaling as sc  # noqa: E402

A = 0.005    # lattice spacing = diameter: neighbours touch, diagonals (7.07 mm) are beyond r_i + r_j + skin


def lattice(tmp_path, nx=8, ny=8, nz=2):
    """nx x ny x nz spheres on a cubic lattice filling the box [0, n A]; bonds: every vertical pair
    (first atom the lower one)."""
    ids = np.arange(nx * ny * nz).reshape(nz, ny, nx) + 1
    lines = ["LAMMPS data file", "", "%d atoms" % ids.size, "2 atom types", "%d bonds" % (nx * ny * (nz - 1)),
             "1 bond types", "", "0 %g xlo xhi" % (nx * A), "0 %g ylo yhi" % (ny * A), "0 %g zlo zhi" % (nz * A),
             "", "Atoms # bpm/sphere", ""]
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                lines.append("%d 0 2 %g 2650 %g %g %g 0 0 0" % (ids[k, j, i], A, (i + .5) * A, (j + .5) * A, (k + .5) * A))
    lines += ["", "Bonds", ""]
    b = 0
    for k in range(nz - 1):
        for j in range(ny):
            for i in range(nx):
                b += 1
                lines.append("%d 1 %d %d" % (b, ids[k, j, i], ids[k + 1, j, i]))
    (tmp_path / "lattice.data").write_text("\n".join(lines) + "\n")
    return DataFile(tmp_path / "lattice.data")


def test_grid_is_lammps_rule():
    # the paper bag's box (in.bag: 88 x 88 x 28 spacings): 4 x 8 x 2 has less surface (0.0176 m^2)
    # than 8 x 8 x 1 (0.0184)
    assert sc.grid(64, (0.44, 0.44, 0.14)) == (4, 8, 2)
    assert sc.grid(1, (1, 1, 1)) == (1, 1, 1)
    assert sc.grid(2, (0.44, 0.44, 0.14)) == (1, 2, 1)     # a tie: the first of least surface
    assert sc.grid(4, (0.04, 0.04, 0.01)) == (2, 2, 1)
    assert sc.grid(8, (1.0, 1.0, 1.0)) == (2, 2, 2)
    assert sc.grid(7, (1.0, 1.0, 1.0)) in ((7, 1, 1), (1, 7, 1), (1, 1, 7))


def test_data_file_reader(tmp_path):
    d = lattice(tmp_path)
    assert d.x.shape == (128, 3) and np.allclose(d.box[:, 1], (0.04, 0.04, 0.01))
    assert d.diameter[0] == A and d.type[0] == 2 and d.bonds.shape == (64, 2)
    assert np.allclose(d.x[d.index(d.bonds[0])], [[.5 * A, .5 * A, .5 * A], [.5 * A, .5 * A, 1.5 * A]])


def test_counts_by_hand(tmp_path):
    n = sc.counts(lattice(tmp_path), 4, plates=(0.0, 0.012))
    assert n["grid"] == (2, 2, 1)
    assert list(n["owned"]) == [32] * 4
    # the brick grown by 10 mm (two spacings) holds 6 x 6 x 2 atoms, 32 of them its own
    assert list(n["ghosts"]) == [40] * 4
    # 64 touching pairs inside a brick (bonded ones too, as in LAMMPS's list); the 8 pairs across
    # each of the 4 inner faces go to the brick with the lower x (or y): 16, 8, 8 and 0
    assert sorted(n["neigh"]) == [64, 72, 72, 80] and n["neigh"].sum() == 7 * 8 * 2 * 2 + 8 * 8
    assert list(n["bonds"]) == [16] * 4
    # the bottom layer touches the plate at z = 0; the top layer is 2 mm from the one at 12 mm
    assert list(n["plate"]) == [16] * 4
    assert list(sc.counts(lattice(tmp_path), 4, plates=(0.0, 0.011))["plate"]) == [32] * 4


def test_one_rank_holds_everything(tmp_path):
    n = sc.counts(lattice(tmp_path), 1, plates=(0.0, 0.012))
    assert n["owned"][0] == 128 and n["ghosts"][0] == 0 and n["neigh"][0] == 288 and n["bonds"][0] == 64


def test_step_time_by_hand(tmp_path):
    n = sc.counts(lattice(tmp_path), 4, plates=(0.0, 0.012))
    c = dict(c_pair=1.0, c_bond=10.0, c_atom=100.0, c_ghost=1000.0)
    net = dict(alpha=1e4, beta=2.0, bytes_per_ghost=120, sums_per_step=4)
    expect = 80 + 160 + 3200 + (1000 + 240) * 40 + 4 * 2 * 1e4 + 4 * math.log2(4) * 1e4
    assert sc.step_time(c, n, 4, net) == pytest.approx(expect)
    one = sc.counts(lattice(tmp_path), 1, plates=(0.0, 0.012))
    assert sc.step_time(c, one, 1, net) == pytest.approx(288 + 640 + 12800)    # no communication


def test_costs_from_sections():
    one = dict(total=10.0, Pair=4.0, Bond=2.0, Comm=0.5)
    c = sc.costs(one, dict(Comm_min=0.3), dict(neigh=400, bonds=100, owned=350, ghosts2=30))
    assert c == dict(c_pair=0.01, c_bond=0.02, c_atom=3.5 / 350, c_ghost=0.01)


def test_check_names_what_differs(tmp_path):
    n = sc.counts(lattice(tmp_path), 4, plates=(0.0, 0.012))
    stats = dict(grid=(2, 2, 1), Nlocal=dict(ave=32, max=32), Nghost=dict(ave=40, max=40), Neighs=dict(ave=72, max=80))
    assert sc.check(n, stats) == []
    bad = sc.check(n, dict(stats, grid=(4, 1, 1), Nghost=dict(ave=40, max=50)))
    assert len(bad) == 2 and "grid" in bad[0] and "ghosts max 40" in bad[1]
