"""The tiny filled bag of the LAMMPS decks in LIGGGHTS: converted by postprocess/tbagspost/liggghts_fill.py
(the same numbers), modelled by inputs/liggghts/model.lig (contact model tbags, bpm/yarn, plates,
gravity) and run for a few hundred steps pressed between two fixed plates, against the same run
in LAMMPS (pair gran/hertz/rolling, bpm/yarn, fix wall/gran/servo): every particle's force,
torque and position agree to round-off, on 1 and 2 LIGGGHTS ranks. The whole model at once:
bag-bag, bag-sand and sand-sand contacts, bonded neighbours touching, yarn bonds, plates."""
import re

import numpy as np
import pytest

import lmprun
from twoengines import DataFile, bag_deck_lammps, bag_deck_liggghts, convert, top_plate

STEPS = 300
FIELDS = "id x y z fx fy fz tqx tqy tqz"


def last_dump(path):
    """The last snapshot of a dump custom file, sorted by id: {column: array}."""
    cols, data = lmprun.read_dump(path, last=True)
    data = data[np.argsort(data[:, cols.index("id")])]
    return {c: data[:, j] for j, c in enumerate(cols)}


@pytest.fixture(scope="module")
def runs(tiny_filled, tmp_path_factory):
    fill = tiny_filled / "fill.data"
    ztop = top_plate(fill)
    out = {}
    wd = tmp_path_factory.mktemp("lammps")
    (wd / "fill.data").write_bytes(fill.read_bytes())
    lmprun.run(bag_deck_lammps(ztop, STEPS, FIELDS), wd).check()
    out["lammps"] = last_dump(wd / "end.dump")
    for ranks in (1, 2):
        wd = tmp_path_factory.mktemp("liggghts%d" % ranks)
        convert(fill, wd / "fill.liggghts.data")
        # 2 ranks: split across x, through the bag (LIGGGHTS's own grid splits z, above the bag)
        lmprun.run(bag_deck_liggghts(ztop, STEPS, FIELDS), wd, np_ranks=ranks, engine="liggghts",
                   variables={"procs": "%d 1 1" % ranks}).check("liggghts")
        out["liggghts%d" % ranks] = last_dump(wd / "end.dump")
        out["log%d" % ranks] = (wd / "log.lammps").read_text()
    return out


def diff(a, b, cols):
    return max(float(np.max(np.abs(a[c] - b[c])) / np.max(np.abs(b[c]))) for c in cols)


def test_converter_keeps_every_number(tiny_filled, tmp_path):
    fill = tiny_filled / "fill.data"
    convert(fill, tmp_path / "out.data")
    a = DataFile(fill)
    text = (tmp_path / "out.data").read_text()
    assert "3 atom types" in text and "%d bonds" % len(a.bonds) in text
    atoms = [l.split() for l in text.split("Atoms")[1].split("Velocities")[0].splitlines() if l.strip() and not l.startswith("#")][1:]
    rows = np.array(sorted(atoms, key=lambda r: int(r[0])), dtype=float)
    assert (rows[:, 2:5] == a.x).all() and (rows[:, 5] == a.diameter).all() and (rows[:, 6] == a.density).all()


def test_same_bag_same_forces(runs):
    lmp, lig = runs["lammps"], runs["liggghts1"]
    assert (lig["id"] == lmp["id"]).all()
    # the plates press: the top layer pushed down, forces everywhere
    assert np.count_nonzero(lmp["fz"]) == len(lmp["id"])
    for cols in (("fx", "fy", "fz"), ("tqx", "tqy", "tqz"), ("x", "y", "z")):
        d = diff(lig, lmp, cols)
        print("tiny bag after %d steps, %s: LIGGGHTS vs LAMMPS %.2e" % (STEPS, cols[0], d))
        assert d < 1e-8, cols


def test_two_ranks(runs):
    # both ranks own part of the bag
    nmin = re.search(r"Nlocal:\s+\S+ ave \S+ max (\S+) min", runs["log2"])
    assert "2 by 1 by 1 MPI processor grid" in runs["log2"] and float(nmin.group(1)) > 50
    d = max(diff(runs["liggghts2"], runs["liggghts1"], cols) for cols in (("fx", "fy", "fz"), ("x", "y", "z")))
    print("tiny bag: LIGGGHTS 2 ranks vs 1 rank %.2e" % d)
    assert d < 1e-8


@pytest.mark.parametrize("fabric", ["words", "woven"])
def test_fabric_in_liggghts(tiny_filled, tmp_path, fabric):
    """inputs/liggghts/model.lig offers the fabric words (the yarn bond without its shear spring)
    and stops on woven, which needs bonded particles that do not touch, naming LAMMPS."""
    fill = tiny_filled / "fill.data"
    convert(fill, tmp_path / "fill.liggghts.data")
    res = lmprun.run(bag_deck_liggghts(top_plate(fill), 10, FIELDS), tmp_path, engine="liggghts",
                     variables={"fabric": fabric})
    if fabric == "words":
        res.check("liggghts")
        log = (tmp_path / "log.lammps").read_text().splitlines()
        coeff = [l for l in log if l.lstrip().startswith("bond_coeff") and "YARN_PP_TAPE" in l]
        assert coeff and coeff[-1].rstrip().endswith("r0 0.005 shear 0 E -1"), coeff    # (echoed, substituted)
    else:
        assert res.returncode != 0 and "woven: run LAMMPS" in res.output


def test_bag_rolling_and_bending_modulus_in_both_engines(runs, tiny_filled, tmp_path):
    """-var bag_mur and -var yarn_bendE reach model.lig as they reach fabric.lmp: the same run
    with both changed agrees between the engines to round-off, and differs from the default
    run (the values acted; before, LIGGGHTS ignored both and kept 0.05 and the rod's modulus)."""
    fill = tiny_filled / "fill.data"
    ztop = top_plate(fill)
    v = {"bag_mur": 0, "yarn_bendE": 1e9}
    (tmp_path / "lammps").mkdir()
    (tmp_path / "lammps" / "fill.data").write_bytes(fill.read_bytes())
    lmprun.run(bag_deck_lammps(ztop, STEPS, FIELDS), tmp_path / "lammps", variables=v).check()
    (tmp_path / "liggghts").mkdir()
    convert(fill, tmp_path / "liggghts" / "fill.liggghts.data")
    res = lmprun.run(bag_deck_liggghts(ztop, STEPS, FIELDS), tmp_path / "liggghts", engine="liggghts",
                     variables=dict(v, procs="1 1 1"))
    res.check("liggghts")
    assert "bending modulus 1000000000.0 Pa" in res.output and "bag rolling 0\n" in res.output
    lmp, lig = last_dump(tmp_path / "lammps" / "end.dump"), last_dump(tmp_path / "liggghts" / "end.dump")
    for cols in (("fx", "fy", "fz"), ("tqx", "tqy", "tqz")):
        d, moved = diff(lig, lmp, cols), diff(lmp, runs["lammps"], cols)
        print("bag_mur 0, yarn_bendE 1e9, %s: LIGGGHTS vs LAMMPS %.2e; against the defaults %.2e" % (cols[0], d, moved))
        assert d < 1e-8 and moved > 1e-4


@pytest.mark.parametrize("E, given, want", [("1.8e9", None, 1.5e-6), ("7.2e9", None, 0.75e-6),
                                            ("7.2e9", "1e-6", 1e-6)])
def test_time_step_follows_the_grains_modulus(tmp_path, E, given, want):
    """model.lig's time step lines, run in LIGGGHTS: sand.lmp's rule (dt0 times sqrt(1.8 GPa / E)
    for stiffer grains; -var dt overrides), printed on the SAND line."""
    text = (lmprun.ROOT / "inputs" / "liggghts" / "model.lig").read_text()
    block = text[text.index("variable        sand_E index"):text.index("# the bag's fabric")]
    variables = {"sand_E": E} if given is None else {"sand_E": E, "dt": given}
    lmprun.run(block, tmp_path, engine="liggghts", variables=variables).check("liggghts")
    line = [l for l in (tmp_path / "log.lammps").read_text().splitlines() if l.startswith("SAND:")][-1]
    assert float(re.search(r"time step (\S+) s", line).group(1)) == pytest.approx(want, rel=1e-9)
