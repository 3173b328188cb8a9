"""inputs/in.bag: the bag shell has exactly the formula's particle and bond counts for several
sizes (the paper's 81 x 81 x 17: 17,922 and 35,840), every particle has 2 to 4 bonds at one
spacing, and a size below 3 stops with a clear message."""
import json

import numpy as np
import pytest

import lmprun

BAG = lmprun.ROOT / "inputs" / "in.bag"


def counts(nx, ny, nz):
    atoms = nx * ny * nz - (nx - 2) * (ny - 2) * (nz - 2)
    bonds = ((nx - 1) * (ny * nz - (ny - 2) * (nz - 2)) + (ny - 1) * (nx * nz - (nx - 2) * (nz - 2))
             + (nz - 1) * (nx * ny - (nx - 2) * (ny - 2)))
    return atoms, bonds


def test_paper_counts():
    assert counts(81, 81, 17) == (17922, 35840)


@pytest.mark.parametrize("size", [(3, 3, 3), (5, 4, 3), (11, 11, 5), (81, 81, 17)])
def test_bag_counts(tmp_path, size):
    nx, ny, nz = size
    res = lmprun.run(BAG, tmp_path, variables={"nx": nx, "ny": ny, "nz": nz}).check()
    line = [l for l in res.output.splitlines() if l.startswith("BAG")][0]
    atoms, bonds = counts(*size)
    print(line)
    assert "%d particles, %d bonds" % (atoms, bonds) in line
    # the summary for the tools (check_trends, project_time)
    assert json.loads((tmp_path / "bag.json").read_text()) == {
        "nx": nx, "ny": ny, "nz": nz, "particles": atoms, "bonds": bonds}
    data = (tmp_path / "bag.data").read_text()
    assert "%d atoms" % atoms in data and "%d bonds" % bonds in data
    # bonds per particle: 2 (corners of a 3-high edge) to 4 (faces)
    sec = data[data.index("Bonds\n"):].split("\n")[2:2 + bonds]
    ends = np.array([[int(w) for w in l.split()[2:4]] for l in sec]).ravel()
    ids, per = np.unique(ends, return_counts=True)
    assert len(ids) == atoms and per.min() >= 2 and per.max() <= 4 and per.sum() == 2 * bonds


@pytest.mark.parametrize("size", [(2, 5, 5), (5, 5, 1)])
def test_bag_too_small(tmp_path, size):
    nx, ny, nz = size
    res = lmprun.run(BAG, tmp_path, variables={"nx": nx, "ny": ny, "nz": nz})
    assert res.returncode != 0 and "nx, ny, nz must be at least 3" in res.output
