"""The simple shear protocol (in.bag, in.fill, in.shear) end to end on a tiny bag: the plate
reaches F_v, shears at constant speed with F_v held, and writes the CSV and dumps; bad -var
values stop with a clear message."""
import numpy as np
import pytest

import lmprun

INPUTS = lmprun.ROOT / "inputs"
SIZE = {"nx": 9, "ny": 9, "nz": 5, "tbags": lmprun.ROOT}


@pytest.fixture(scope="module")
def filled(tmp_path_factory):
    wd = tmp_path_factory.mktemp("tinybag")
    lmprun.run(INPUTS / "in.bag", wd, variables=SIZE).check()
    lmprun.run(INPUTS / "in.fill", wd, variables=SIZE).check()
    return wd


def test_protocol_on_a_tiny_bag(filled):
    res = lmprun.run(INPUTS / "in.shear", filled, variables=dict(SIZE, v=0.02, ufinal=0.0003, du_dump=0.0001)).check()
    out = res.output
    comp = [l for l in out.splitlines() if l.startswith("COMPRESSED")][0]
    fv, target = float(comp.split()[2]), float(comp.split()[5].rstrip("),"))
    print(comp)
    assert abs(fv - target) < 0.005 * target
    assert abs(target - 5500 * 7 * 7 / 79 ** 2) < 1e-9
    d = np.genfromtxt(filled / "shear.csv", delimiter=",", names=True)
    print("CSV rows: u = %s mm, S = %s N, F_v = %s N" % (d["u_mm"], d["S_N"], d["Fv_N"]))
    assert len(d) >= 2 and np.allclose(np.diff(d["u_mm"]), 0.1, atol=1e-3)
    assert (d["S_N"][d["u_mm"] > 0] > 0).all() and np.abs(d["Fv_N"] - target).max() < 0.1 * target
    assert list(filled.glob("dump.grains.*")) and list(filled.glob("dump.contacts.*"))


@pytest.mark.parametrize("var,message", [({"nx": 2}, "nx, ny, nz must be at least 3"),
                                         ({"Fv": -5}, "Fv must be > 0"),
                                         ({"ufinal": 0}, "v and ufinal must be > 0")])
def test_bad_variables(tmp_path, var, message):
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(SIZE, **var))
    assert res.returncode != 0 and message in res.output
