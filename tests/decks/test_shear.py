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


def test_resume_from_checkpoint(filled, tmp_path):
    """A checkpoint written while shearing resumes the shear stage: the plate continues from its
    state and the CSV is appended up to u_final. The resumed run starts with a fresh force
    evaluation (LAMMPS setup uses full-step velocities), so it is close, not bit-identical."""
    import shutil
    shutil.copy(filled / "fill.data", tmp_path)
    v = dict(SIZE, v=0.02, ufinal=0.0006, du_dump=0.0002)
    lmprun.run(INPUTS / "in.shear", tmp_path, variables=v).check()
    straight = np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True)
    older = min(tmp_path.glob("shear.restart.*"), key=lambda p: p.stat().st_mtime_ns)
    res = lmprun.run(INPUTS / "in.shear", tmp_path, variables=dict(v, restart=older.name)).check()
    rows = np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True)[len(straight):]
    first = rows[0]
    same = straight[np.isclose(straight["u_mm"], first["u_mm"])][0]
    print("resumed at u = %.2f mm: S %.3f N (straight %.3f), w %.4f mm (straight %.4f); last u %.2f mm"
          % (first["u_mm"], first["S_N"], same["S_N"], first["w_mm"], same["w_mm"], rows["u_mm"][-1]))
    assert 0.0 < first["u_mm"] < 0.6 and rows["u_mm"][-1] == pytest.approx(0.6, abs=1e-3)
    assert abs(first["S_N"] - same["S_N"]) < 0.01 * abs(same["S_N"])
    assert abs(first["w_mm"] - same["w_mm"]) < 1e-3
    assert "SHEARED: u 0.600 mm" in res.output


def test_same_on_one_and_two_ranks(filled, tmp_path):
    """The whole shear stage (compression and the first 0.2 mm of shear) on 1 and 2 ranks gives
    the same CSV, digit for digit (forces agree to round-off, which the CSV's 4 decimals hide)."""
    import shutil
    v = dict(SIZE, v=0.02, ufinal=0.0002, du_dump=0.001)
    csv = {}
    for ranks in (1, 2):
        wd = tmp_path / str(ranks)
        wd.mkdir()
        shutil.copy(filled / "fill.data", wd)
        lmprun.run(INPUTS / "in.shear", wd, np_ranks=ranks, variables=v).check()
        csv[ranks] = (wd / "shear.csv").read_text()
    print(csv[2])
    assert csv[1] == csv[2] and len(csv[1].splitlines()) >= 4
