"""compute pair/local through single(): the tangential force and normal force of every contact,
summed per atom, give the per-atom forces of compute() (the contact dump is a faithful record).
compute pair/local builds its own neighbor list, which may name a pair the other way round
from the pair's list; single() then finds the history under the other atom. (With newton off
on several ranks a pair across ranks is listed on both, so 2 ranks run with newton on.)"""
import numpy as np
import pytest

import lmprun
import packing

DECK = """
units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
newton NEWTON
read_data ${data}
pair_style gran/hertz/rolling ROLL
pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
velocity all create 1e-9 4928 loop geom
velocity all set NULL NULL NULL sum yes
timestep 1e-6
fix 1 all nve/sphere
run 200
compute pl all pair/local dist fx fy fz p1 p2 p3 cutoff radius
compute pid all property/local patom1 patom2 cutoff radius
dump c all local 1 contacts.dump c_pid[*] c_pl[*]
dump_modify c format float %.17g
run 0
write_dump all custom forces.dump id fx fy fz modify sort id format float %.17g
"""


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return packing.make(tmp_path_factory.mktemp("packing"))


@pytest.mark.parametrize("roll,newton,ranks", [("epsd", "on", 1), ("cdt", "off", 1), ("epsd", "on", 2)])
def test_contact_dump_sums_to_the_forces(data, tmp_path, roll, newton, ranks):
    deck = tmp_path / "in.local"
    deck.write_text(DECK.replace("ROLL", roll).replace("NEWTON", newton))
    lmprun.run(deck, tmp_path, np_ranks=ranks, variables={"data": data}).check()
    lines = (tmp_path / "contacts.dump").read_text().splitlines()
    k = max(i for i, l in enumerate(lines) if l.startswith("ITEM: ENTRIES"))
    c = np.array([[float(x) for x in l.split()] for l in lines[k + 1:] if l.strip()])
    _, rows = lmprun.read_dump(tmp_path / "forces.dump")
    ids = rows[:, 0].astype(int)
    F = np.zeros((ids.max() + 1, 3))
    # columns: id1 id2 dist fx fy fz (normal force on id1) p1 p2 p3 (tangential force on id1)
    fij = c[:, 3:6] + c[:, 6:9]
    np.add.at(F, c[:, 0].astype(int), fij)
    np.add.at(F, c[:, 1].astype(int), -fij)
    fmax, tangential = np.abs(c[:, 3:6]).max(), np.abs(c[:, 6:9]).max()
    err = np.abs(F[ids] - rows[:, 1:4]).max() / fmax
    print("%d contacts, largest normal force %.3g N, tangential %.3g N; per-atom force error %.2e of it"
          % (len(c), fmax, tangential, err))
    assert tangential > 1e-2 * fmax
    assert err < 1e-12
