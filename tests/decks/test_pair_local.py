"""compute pair/local through single(): the tangential force and normal force of every contact,
summed per atom, give the per-atom forces of compute() (the contact dump is a faithful record).
compute pair/local builds its own neighbor list, which may name a pair the other way round
from the pair's list; single() then finds the history under the other atom. (With newton off
on several ranks a pair across ranks is listed on both, so 2 ranks run with newton on.)"""
import numpy as np
import pytest

import lmprun
import packing

DECK = lmprun.packing_head("NEWTON") + """pair_style gran/hertz/rolling ROLL
pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
velocity all create 1e-9 4928 loop geom
velocity all set NULL NULL NULL sum yes
timestep 1e-6
fix 1 all nve/sphere
run 200
""" + lmprun.CONTACT_DUMP


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return packing.make(tmp_path_factory.mktemp("packing"))


@pytest.mark.parametrize("roll,newton,ranks", [("epsd", "on", 1), ("cdt", "off", 1), ("epsd", "on", 2)])
def test_contact_dump_sums_to_the_forces(data, tmp_path, roll, newton, ranks):
    deck = tmp_path / "in.local"
    deck.write_text(DECK.replace("ROLL", roll).replace("NEWTON", newton))
    lmprun.run(deck, tmp_path, np_ranks=ranks, variables={"data": data}).check()
    c, ids, forces, sums = lmprun.contact_force_sums(tmp_path)
    fmax, tangential = np.abs(c[:, 3:6]).max(), np.abs(c[:, 6:9]).max()
    err = np.abs(sums - forces).max() / fmax
    print("%d contacts, largest normal force %.3g N, tangential %.3g N; per-atom force error %.2e of it"
          % (len(c), fmax, tangential, err))
    assert tangential > 1e-2 * fmax
    assert err < 1e-12
