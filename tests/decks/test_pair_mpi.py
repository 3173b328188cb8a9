"""MPI and newton agreement and restart continuity of pair gran/hertz/rolling (EPSD rolling on):
1, 2 and 4 ranks, newton on and off, and a restart half-way give the same trajectories; a
write_restart between two runs changes nothing, also when atoms cross periodic boundaries. The
same with twisting sds on (its history, its coefficients in the restart file)."""
import numpy as np
import pytest

import lmprun
import packing

DECK = """
units si
atom_style sphere
atom_modify map array
boundary p p p
newton ${newton}
comm_modify vel yes
read_data ${data}
# quasi-static start (settling under gravity from rest): a chaotic granular gas would turn
# round-off into O(1) differences within 1000 steps and prove nothing
velocity all set 0 0 0
set group all omega 0 0 0
${drift}
pair_style gran/hertz/rolling epsd
pair_coeff 1 1 material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2
pair_coeff 2 2 material 0.75e9 0.1 friction 0.26 rolling 0.05 restitution 0.2
pair_coeff 1 2 friction 0.26 rolling 0.05 restitution 0.2
timestep 1e-6
fix 1 all nve/sphere
fix 2 all gravity 9.81 vector 0 0 -1
thermo 100
run ${n1}
${checkpoint}
run ${n2}
write_dump all custom final.dump id x y z vx vy vz omegax omegay omegaz modify sort id format float %.17g
"""

RESTART = """
units si
read_restart half.restart
newton on
comm_modify vel yes
timestep 1e-6
fix 1 all nve/sphere
fix 2 all gravity 9.81 vector 0 0 -1
run ${n2}
write_dump all custom final_restart.dump id x y z vx vy vz omegax omegay omegaz modify sort id format float %.17g
"""

NSTEPS = 1000


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return packing.make(tmp_path_factory.mktemp("packing"))


# the whole packing drifts (contacts unchanged): atoms leave the periodic box between
# reneighborings, so a write_restart's wrapping renumbers ghost atoms
DRIFT = "velocity all set 3.0 2.0 1.0"


# twisting sds on (the coefficients per type; 1-2 mixed)
TWIST = {"pair_style gran/hertz/rolling epsd": "pair_style gran/hertz/rolling epsd twisting sds",
         "restitution 0.2\npair_coeff 2 2": "restitution 0.2 twisting 2e-5 2e-10 2e-6\npair_coeff 2 2",
         "restitution 0.2\npair_coeff 1 2": "restitution 0.2 twisting 5e-6 1e-10 1e-6\npair_coeff 1 2"}


def run_deck(wd, data, ranks=1, newton="on", checkpoint=False, drift=False, twist=False):
    deck = DECK
    for old, new in (TWIST.items() if twist else ()):
        assert old in deck
        deck = deck.replace(old, new)
    lmprun.run(deck, wd, np_ranks=ranks, variables={
        "data": data, "newton": newton, "n1": NSTEPS // 2, "n2": NSTEPS // 2,
        "checkpoint": "write_restart half.restart" if checkpoint else "",
        "drift": DRIFT if drift else ""}).check()
    return wd


@pytest.fixture(scope="module")
def reference(tmp_path_factory, data):
    return run_deck(tmp_path_factory.mktemp("np1"), data, checkpoint=True)


def compare(a_path, b_path):
    cols, a = lmprun.read_dump(a_path)
    _, b = lmprun.read_dump(b_path)
    x = [cols.index(c) for c in ("x", "y", "z")]
    v = [cols.index(c) for c in ("vx", "vy", "vz")]
    return float(np.abs(a[:, x] - b[:, x]).max()), lmprun.max_rel_diff(a[:, v], b[:, v])


@pytest.mark.parametrize("ranks,newton", [(2, "on"), (4, "on"), (1, "off"), (2, "off")])
def test_ranks_and_newton_agree(tmp_path, data, reference, ranks, newton):
    run_deck(tmp_path, data, ranks, newton)
    dx, dv = compare(tmp_path / "final.dump", reference / "final.dump")
    print("ranks=%d newton=%s: max |dx| = %.3e m, max |dv|/max|v| = %.3e" % (ranks, newton, dx, dv))
    assert dx < 1e-12 and dv < 1e-8


@pytest.mark.parametrize("ranks", [1, 2])
def test_write_restart_keeps_history(tmp_path, data, ranks):
    # LAMMPS's fix NEIGH_HISTORY copies the history from the run's neighbor list again after
    # write_restart has wrapped the atoms and rebuilt the ghosts: contacts across a periodic
    # boundary lost it (1.6e-5 m after 500 steps; fix_neigh_history_tbags.h)
    plain = run_deck(tmp_path / "plain", data, ranks, drift=True)
    chk = run_deck(tmp_path / "chk", data, ranks, checkpoint=True, drift=True)
    dx, dv = compare(chk / "final.dump", plain / "final.dump")
    print("ranks=%d write_restart between runs: max |dx| = %.3e m, max |dv|/max|v| = %.3e"
          % (ranks, dx, dv))
    assert dx < 1e-12 and dv < 1e-8
    # and the file holds that history: read back, the run continues as without it
    lmprun.run(RESTART, chk, np_ranks=ranks, variables={"n2": NSTEPS // 2}).check()
    dx, dv = compare(chk / "final_restart.dump", plain / "final.dump")
    print("ranks=%d read_restart: max |dx| = %.3e m, max |dv|/max|v| = %.3e" % (ranks, dx, dv))
    assert dx < 1e-12 and dv < 1e-8


def test_restart_continues(reference):
    lmprun.run(RESTART, reference, variables={"n2": NSTEPS // 2}).check()
    dx, dv = compare(reference / "final_restart.dump", reference / "final.dump")
    print("restart: max |dx| = %.3e m, max |dv|/max|v| = %.3e" % (dx, dv))
    assert dx < 1e-12 and dv < 1e-8


def test_twisting_ranks_newton_and_restart(tmp_path, data):
    """twisting sds: 2 ranks with newton off give the 1-rank trajectories (the twist angle kept,
    not negated, when newton off hands the history from i's view to j's), and read_restart
    continues them (the history of 7 doubles and the coefficients in the file)."""
    ref = run_deck(tmp_path / "np1", data, checkpoint=True, twist=True)
    run_deck(tmp_path / "np2", data, 2, "off", twist=True)
    dx, dv = compare(tmp_path / "np2" / "final.dump", ref / "final.dump")
    print("twisting, 2 ranks newton off: max |dx| = %.3e m, max |dv|/max|v| = %.3e" % (dx, dv))
    assert dx < 1e-12 and dv < 1e-8
    lmprun.run(RESTART, ref, variables={"n2": NSTEPS // 2}).check()
    dx, dv = compare(ref / "final_restart.dump", ref / "final.dump")
    print("twisting, restart: max |dx| = %.3e m, max |dv|/max|v| = %.3e" % (dx, dv))
    assert dx < 1e-12 and dv < 1e-8
    # twisting acted: the run without it ends elsewhere
    plain = run_deck(tmp_path / "plain", data)
    dx, _ = compare(plain / "final.dump", ref / "final.dump")
    print("without twisting: max |dx| = %.3e m" % dx)
    assert dx > 1e-10
