"""postprocess/tbagspost/check_trends.py on synthetic runs: passes when the paper's trends are there, fails the
right check when one is missing, and compares two speeds' S-u curves."""
import os
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "postprocess"))
from tbagspost import check_trends as ct  # noqa: E402

DT, STEP = 2e-6, 5000
U = np.linspace(0, 7, 71)


def write_csv(run, smax, contraction, dilation, speed=1.0):
    """S rises to smax; w falls by `contraction` by u = 2 mm then rises by `dilation`."""
    w = np.where(U < 2, -contraction * U / 2, -contraction + dilation * (U - 2) / 5)
    s = smax * (1 - np.exp(-U / 0.8 * speed))
    t = U / 1000 / 0.01
    z = 40 + w
    rows = ["%g,%g,%g,%g,%g,0,%g" % r for r in zip(t, U, w - 1.0, s, np.full_like(U, 300), z)]
    (run / "shear.csv").write_text("time_s,u_mm,w_mm,S_N,Fv_N,broken_bonds,zplate_mm\n# comment\n" + "\n".join(rows))


def write_dumps(run, gap_mm, edge_force, centre_force):
    """a top face of 4 bag particles (one with the gap), two sand grains in the middle row and two
    contacts: one at the side, one in the centre."""
    t = STEP * DT
    d = np.genfromtxt(run / "shear.csv", delimiter=",", names=True)
    zplate = np.interp(t, d["time_s"], d["zplate_mm"]) / 1000
    r = 0.0025
    atoms = [  # id type radius x y z vx vy vz dx dy dz
        (1, 1, r, 0.0, 0.05, zplate - r, 0, 0, 0, 0, 0, 0),
        (2, 1, r, 0.1, 0.05, zplate - r - gap_mm / 1000, 0, 0, 0, 0, 0, -gap_mm / 1000),
        (3, 1, r, 0.0, 0.0, 0.0, 0, 0, 0, 0, 0, 0),
        (4, 1, r, 0.1, 0.1, 0.0, 0, 0, 0, 0, 0, 0),
        (5, 2, 0.002, 0.004, 0.05, 0.02, 0, 0, 0, 0, 0, 0),
        (6, 2, 0.002, 0.05, 0.05, 0.02, 0, 0, 0, 0, 0, 0),
        (7, 2, 0.002, 0.054, 0.05, 0.02, 0, 0, 0, 0, 0, 0),
        (8, 1, r, 0.0, 0.054, 0.0, 0, 0, 0, 0, 0, 0),
    ]
    head = "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF %s\n%d\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n"
    (run / ("dump.grains.%d" % STEP)).write_text(
        head % (STEP, "ATOMS", len(atoms)) + "ITEM: ATOMS id type radius x y z vx vy vz dx dy dz\n"
        + "\n".join(" ".join(str(v) for v in a) for a in atoms) + "\n")
    contacts = [(1, 1, 5, 1, 2, 0.004, 0, 0, 0, edge_force, 1e-5), (2, 6, 7, 2, 2, 0.004, 0, 0, 0, centre_force, 1e-5),
                (3, 1, 8, 1, 1, 0.005, 0, 0, 0, 100.0, 1e-5)]    # bag-bag at the side: not counted
    (run / ("dump.contacts.%d" % STEP)).write_text(
        head % (STEP, "ENTRIES", len(contacts)) + "ITEM: ENTRIES index id1 id2 type1 type2 dist ftx fty ftz fn overlap\n"
        + "\n".join(" ".join(str(v) for v in c) for c in contacts) + "\n")
    (run / "log.shear").write_text("TIMESTEP: Rayleigh 1.1e-05 s, bond 7.8e-06 s; using %g s\n" % DT)


def make_trends(tmp_path, peaks=(900, 700, 400), contraction=(0.3, 0.2, 0.1), dilation=(0.1, 0.2, 0.3),
                gap_mm=1.0, edge=(5.0, 1.0), nz=17):
    tmp_path.mkdir(parents=True, exist_ok=True)
    (tmp_path / "log.bag").write_text("BAG 81 x 81 x %d: 17922 particles, 35840 bonds\n" % nz)
    for f, s, c, dl in zip(ct.LOADS, peaks, contraction, dilation):
        run = tmp_path / ("F%d" % f)
        run.mkdir()
        write_csv(run, s, c, dl)
        write_dumps(run, gap_mm, *edge)
    return tmp_path


def failed(results):
    return [name for name, ok in results if not ok]


def test_all_trends_pass(tmp_path, capsys):
    assert failed(ct.check_trends(make_trends(tmp_path))) == []
    out = capsys.readouterr().out
    assert "peak S" in out and "ratio 5.00" in out


@pytest.mark.parametrize("kw,which", [
    (dict(peaks=(700, 900, 400)), "1."),
    (dict(dilation=(0.001, 0.2, 0.3)), "2."),
    (dict(contraction=(0.1, 0.2, 0.3)), "3a."),
    (dict(dilation=(0.3, 0.2, 0.1)), "3b."),
    (dict(gap_mm=0.2), "4."),
    (dict(edge=(1.0, 5.0)), "5."),
    # the thresholds: orderings that hold, but too weakly to be a finding
    (dict(peaks=(900, 850, 800)), "1."),         # x 1.06 per load step < 1.1
    (dict(edge=(1.1, 1.0)), "5."),               # edge-to-centre 1.1 < 1.2
    (dict(contraction=(0.3, 0.25, 0.1)), "3a."),  # a step of 0.05 mm < 0.1 % of 75 mm
])
def test_each_check_can_fail(tmp_path, kw, which):
    names = failed(ct.check_trends(make_trends(tmp_path, **kw)))
    assert names and all(n.startswith(which) for n in names), names


def test_speed_check(tmp_path):
    a, b, c = (tmp_path / n for n in "abc")
    for run, speed in ((a, 1.0), (b, 1.05), (c, 3.0)):
        run.mkdir()
        write_csv(run, 500, 0.1, 0.1, speed=speed)
    assert failed(ct.check_speed(a, b, 0.1)) == []
    assert failed(ct.check_speed(a, c, 0.1))


def test_missing_and_truncated(tmp_path):
    with pytest.raises(SystemExit, match="no .*shear.csv"):
        ct.check_trends(tmp_path)
    (tmp_path / "t").mkdir()
    run = make_trends(tmp_path / "t")
    dump = run / "F5500" / ("dump.grains.%d" % STEP)
    dump.write_text(dump.read_text().rsplit("\n", 3)[0] + "\n")
    with pytest.raises(SystemExit, match="truncated"):
        ct.check_trends(run)


def test_every_realization_is_checked(tmp_path, capsys):
    """A folder of realizations (r1, r2): each is checked, the table lists both, one failing
    realization fails the whole check."""
    make_trends(tmp_path / "r1")
    make_trends(tmp_path / "r2", peaks=(700, 900, 400))
    assert [p.name for p in ct.realizations(tmp_path)] == ["r1", "r2"]
    assert ct.main([str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert "11 of 12 checks pass in 2 realization(s)" in out
    assert "1. peak S rises with F_v | PASS | FAIL" in out


def test_sand_height_from_the_bag_log(tmp_path):
    """H comes from the bag's own log (a 9-layer bag: 35 mm), so the thresholds scale with it:
    a 0.05 mm contraction step passes 0.1 % of 35 mm but not of 75 mm."""
    assert ct.sand_height_mm(make_trends(tmp_path / "a", nz=9) / "F5500") == 35.0
    kw = dict(contraction=(0.3, 0.25, 0.1))
    assert failed(ct.check_trends(make_trends(tmp_path / "b", nz=9, **kw))) == []
    assert failed(ct.check_trends(make_trends(tmp_path / "c", nz=17, **kw))) != []
    with pytest.raises(SystemExit, match="no 'BAG nx x ny x nz' line"):
        ct.sand_height_mm(tmp_path / "nowhere" / "F5500")


def test_sand_height_from_the_bag_summary(tmp_path):
    """bag.json (in.bag's summary) gives nz; a run made before it, the BAG line of log.bag."""
    run = tmp_path / "F1960"
    run.mkdir()
    (tmp_path / "bag.json").write_text('{"nx": 25, "ny": 25, "nz": 9, "particles": 1922, "bonds": 3840}')
    (tmp_path / "log.bag").write_text("BAG 25 x 25 x 5: 1 particles, 1 bonds\n")
    assert ct.sand_height_mm(run) == 35.0
    (tmp_path / "bag.json").unlink()
    assert ct.sand_height_mm(run) == 15.0


def test_two_loads(tmp_path, capsys):
    """--loads 5500,1960 (the paper bag before its 3.73 kN load): the two are compared as one step
    spanning two, so the rise must be 1.1 squared and the contraction step 2 x 0.1 % of H; the
    third load's folder is not read, and a load named but not run stops the check."""
    import shutil
    run = make_trends(tmp_path / "a")
    shutil.rmtree(run / "F3730")
    assert failed(ct.check_trends(run, (5500, 1960))) == []
    assert "not run: 3.73 kN" in capsys.readouterr().out
    # x 1.15 passes one step's 1.1 but not two steps' 1.21; 0.1 mm passes 0.075 but not 0.15 mm
    weak = make_trends(tmp_path / "b", peaks=(460, 430, 400), contraction=(0.2, 0.15, 0.1))
    assert sorted(n[:3] for n in failed(ct.check_trends(weak, (5500, 1960)))) == ["1. ", "3a."]
    with pytest.raises(SystemExit, match="no .*F3730.*shear.csv"):
        ct.check_trends(run)
    assert ct.main(["--loads", "1960,5500", str(run)]) == 0


@pytest.mark.parametrize("text", ["5500", "5500,4000", "a,b", "1960,1960"])
def test_bad_loads(text):
    with pytest.raises(SystemExit, match="--loads takes two or three"):
        ct.parse_loads(text)
