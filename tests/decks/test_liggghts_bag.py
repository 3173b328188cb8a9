"""The tiny filled bag of the LAMMPS decks in LIGGGHTS: converted by inputs/liggghts/convert_fill.py
(the same numbers), modelled by inputs/liggghts/model.lig (contact model tbags, bpm/yarn, plates,
gravity) and run for a few hundred steps pressed between two fixed plates, against the same run
in LAMMPS (pair gran/hertz/rolling, bpm/yarn, fix wall/gran/servo): every particle's force,
torque and position agree to round-off, on 1 and 2 LIGGGHTS ranks. The whole model at once:
bag-bag, bag-sand and sand-sand contacts, bonded neighbours touching, yarn bonds, plates."""
import re
import subprocess
import sys

import numpy as np
import pytest

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
from tbagspost.datafile import DataFile  # noqa: E402

STEPS = 300
FIELDS = "id x y z fx fy fz tqx tqy tqz"


def last_dump(path):
    """The last snapshot of a dump custom file, sorted by id: {column: array}."""
    lines = path.read_text().splitlines()
    k = max(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[k].split()[2:]
    data = np.array([[float(x) for x in l.split()] for l in lines[k + 1:] if l.strip()])
    data = data[np.argsort(data[:, 0])]
    return {c: data[:, j] for j, c in enumerate(cols)}


def top_plate(fill):
    """A top plate 20 um into the highest particle, so that both plates press."""
    d = DataFile(fill)
    return float(np.max(d.x[:, 2] + 0.5 * d.diameter)) - 2e-5


def lammps_deck(ztop):
    plate = "material 200e9 0.1 coeff 1 friction 1e10 rolling 0.05 restitution 0.2 " \
            "coeff 2 friction 1e10 rolling 0.05 restitution 0.2"
    return f"""
units si
atom_style bpm/sphere
boundary f f f
comm_modify vel yes cutoff 0.010
newton on off
read_data fill.data
special_bonds lj 1 1 1 coul 1 1 1
include ${{tbags}}/inputs/sand.lmp
pair_style gran/hertz/rolling epsd
pair_coeff 1 1 material 0.75e9 0.1 friction 0.26 rolling 0.05 restitution 0.2
pair_coeff 2 2 material ${{sand_E}} ${{sand_nu}} friction ${{sand_mu}} rolling ${{sand_mur}} restitution 0.2
pair_coeff 1 2 friction 0.26 rolling 0.05 restitution 0.2
include ${{tbags}}/inputs/yarn.lmp
timestep 1.5e-6
fix bottom all wall/gran/servo zplane -0.0025 +1 {plate}
fix top all wall/gran/servo zplane {ztop!r} -1 {plate}
fix integrate all nve/sphere
fix gravity all gravity 9.81 vector 0 0 -1
run {STEPS}
write_dump all custom end.dump {FIELDS} modify sort id format float %.17g
"""


def liggghts_deck(ztop):
    return f"""
variable fill string fill.liggghts.data
include ${{tbags}}/inputs/liggghts/model.lig
fix top all wall/gran model tbags primitive type 3 zplane {ztop!r}
dump end all custom {STEPS} end.dump {FIELDS}
dump_modify end sort id format "%d{' %.17g' * 9}"
run {STEPS}
"""


@pytest.fixture(scope="module")
def runs(tiny_filled, tmp_path_factory):
    fill = tiny_filled / "fill.data"
    ztop = top_plate(fill)
    out = {}
    wd = tmp_path_factory.mktemp("lammps")
    (wd / "fill.data").write_bytes(fill.read_bytes())
    lmprun.run(lammps_deck(ztop), wd).check()
    out["lammps"] = last_dump(wd / "end.dump")
    for ranks in (1, 2):
        wd = tmp_path_factory.mktemp("liggghts%d" % ranks)
        subprocess.run([sys.executable, str(lmprun.ROOT / "inputs" / "liggghts" / "convert_fill.py"),
                        str(fill), str(wd / "fill.liggghts.data")], check=True, capture_output=True)
        # 2 ranks: split across x, through the bag (LIGGGHTS's own grid splits z, above the bag)
        lmprun.run(liggghts_deck(ztop), wd, np_ranks=ranks, engine="liggghts",
                   variables={"procs": "%d 1 1" % ranks}).check("liggghts")
        out["liggghts%d" % ranks] = last_dump(wd / "end.dump")
        out["log%d" % ranks] = (wd / "log.lammps").read_text()
    return out


def diff(a, b, cols):
    return max(float(np.max(np.abs(a[c] - b[c])) / np.max(np.abs(b[c]))) for c in cols)


def test_converter_keeps_every_number(tiny_filled, tmp_path):
    fill = tiny_filled / "fill.data"
    subprocess.run([sys.executable, str(lmprun.ROOT / "inputs" / "liggghts" / "convert_fill.py"),
                    str(fill), str(tmp_path / "out.data")], check=True, capture_output=True)
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
