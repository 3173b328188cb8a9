"""The film sheet of fix wall/gran/servo (side 'both', free motion) between two bonded blocks
(tests/decks/in.film): a block slides on it at mu N, monotonically and cyclically; the film stays
with the block its lower face grips; a film between two blocks that move together moves with them;
its motion is Newton's law on its own mass, gravity included, to round-off; 1 and 2 ranks agree."""
import sys

import numpy as np
import pytest

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
from tbagspost import hysteresis  # noqa: E402

DECK = lmprun.ROOT / "tests" / "decks" / "in.film"
DT = 1.5e-6
MASS = 950 * 0.001 * 0.035 ** 2    # density x thickness x the bounds' area (in.film)
N = 90.0


def film_run(tmp_path, np_ranks=1, **variables):
    res = lmprun.run(DECK, tmp_path, np_ranks=np_ranks, variables=dict(variables, tbags=lmprun.ROOT)).check()
    assert "FILM DONE" in res.output
    rows = np.genfromtxt(tmp_path / "film.csv", delimiter=",", names=True, comments="#")
    steps = np.genfromtxt(tmp_path / "film.steps", delimiter=",", names=True, comments="#")
    return rows, steps


@pytest.mark.parametrize("mu", [0.1, 0.3])
def test_block_slides_on_the_film_at_mu_N_cyclically(tmp_path, mu):
    """Cycled at 2 mm under N = 90 N: the loop's half peak-to-peak force is mu N within 1 %, h_eq
    is 2/pi within 2 % (a rigid-plastic loop; the contacts' elastic slip lowers it slightly), and
    the film, gripped by the lower block (friction 1e10 below), does not move with the upper
    block: it stays within 20 um, 1 % of u_a (the elastic give of the contacts below it, 16 um
    at mu 0.3, reversing with the force)."""
    rows, _ = film_run(tmp_path, mode="cyclic", mu=mu, ua=2e-3)
    last = rows[rows["cycle"] == 2]
    m = hysteresis.measure(last["u_mm"], last["S_N"])
    print("mu %.1f: S_a %.4f N (mu N %.4f), h_eq %.4f (2/pi %.4f), film |x| max %.4f mm"
          % (mu, m.S_a, mu * N, m.h_eq, 2 / np.pi, np.abs(rows["film_mm"]).max()))
    assert last["Fv_N"].mean() == pytest.approx(N, rel=0.01)
    assert m.S_a == pytest.approx(mu * N, rel=0.01)
    assert m.h_eq == pytest.approx(2 / np.pi, rel=0.02)
    assert np.abs(rows["film_mm"]).max() < 0.02
    # the upper block slides with the plate, over the whole amplitude
    assert np.abs(last["upper_mm"]).max() == pytest.approx(2.0, abs=0.02)


def test_block_slides_on_the_film_at_mu_N_monotonically(tmp_path):
    """At 10 mm/s for 0.9 mm: once sliding (u > 0.1 mm) every row's S is mu N within 1 %."""
    rows, _ = film_run(tmp_path, mode="monotonic", mu=0.2)
    sliding = rows[rows["u_mm"] > 0.1]
    assert len(sliding) > 100
    print("S %.5f to %.5f N, mu N %.4f" % (sliding["S_N"].min(), sliding["S_N"].max(), 0.2 * N))
    assert np.allclose(sliding["S_N"], 0.2 * N, rtol=0.01)
    assert np.abs(sliding["upper_mm"] - sliding["u_mm"]).max() < 0.01


@pytest.fixture(scope="module")
def together(tmp_path_factory):
    """Both plates at 10 mm/s, gravity on: the two blocks and the film between move together."""
    wd = tmp_path_factory.mktemp("together")
    return film_run(wd, mode="together", g=9.81)


def test_film_between_bodies_moving_together_does_not_slip(together):
    rows, _ = together
    end = rows[-1]
    print("end: plate %.5f, film %.5f, lower %.5f, upper %.5f mm, S %.4f N"
          % (end["u_mm"], end["film_mm"], end["lower_mm"], end["upper_mm"], end["S_N"]))
    assert end["u_mm"] == pytest.approx(0.9, abs=0.01)
    for body in ("film_mm", "lower_mm", "upper_mm"):
        assert abs(end[body] - end["u_mm"]) < 1e-4    # 0.1 um: no slip anywhere
    assert np.abs(rows["S_N"]).max() < 0.01 * 0.1 * N


def test_film_moves_by_newtons_law(together):
    """m (v_n+1 - v_n) / dt = F + m g on each component at every step of the start (the film is
    accelerated by the blocks), to round-off; the forces are not trivially zero."""
    _, steps = together
    g = {"x": 0.0, "y": 0.0, "z": -9.81}
    fmax = max(np.abs(steps["fx"]).max(), np.abs(steps["fz"]).max())
    assert np.abs(steps["fx"]).max() > 0.1 and np.abs(steps["vx"]).max() > 1e-3
    for c in "xyz":
        ma = MASS * np.diff(steps["v" + c]) / DT
        F = steps["f" + c][1:] + MASS * g[c]
        assert np.abs(ma - F).max() < 1e-9 * fmax, c


def test_film_on_two_ranks(tmp_path):
    """The cyclic run on 2 ranks (the film's forces summed over ranks) gives the 1-rank rows to
    round-off over a short run."""
    short = dict(mode="cyclic", mu=0.1, ua=5e-4, cycles=1, nrow=50)
    one, _ = film_run(tmp_path / "np1", **short)
    two, _ = film_run(tmp_path / "np2", np_ranks=2, **short)
    assert len(one) == len(two) == 200
    for col in ("S_N", "Fv_N", "film_mm", "upper_mm"):
        assert np.allclose(one[col], two[col], rtol=1e-6, atol=1e-6), col
