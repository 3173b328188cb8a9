"""calibration/tbagscal/search.py's order of evaluations on a known misfit (no decks run): the
start, the grid, the star (--star: the start +- the step along each fitted parameter, E in log
scale, within the budget), then Nelder-Mead, which reaches the quadratic's minimum."""
import sys
import types
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "calibration"))
from tbagscal import confidence, search  # noqa: E402

CENTRE = {"mu": 0.40, "mur": 0.30, "E": 5e9}


def misfit(prm):
    d = [confidence.to_x(k, prm[k]) - confidence.to_x(k, CENTRE[k]) for k in ("mu", "mur", "E")]
    return 0.1 + sum(x * x for x in d)


@pytest.fixture
def run(monkeypatch):
    monkeypatch.setattr(search, "summarise", lambda prm, res, data: dict(prm, J=misfit(prm)))

    def go(**opts):
        a = types.SimpleNamespace(mu=0.3, mur=0.2, E=4e9, fit=["mu", "mur", "E"], grid_mu=[],
                                  grid_mur=[], star=0.0, budget=8, jobs=1)
        vars(a).update(opts)
        cal = types.SimpleNamespace(a=a, evaluate=lambda prm, pool: None)
        return search.search(cal, data=None)
    return go


def test_star_follows_the_start_on_both_sides_of_each_parameter(run):
    rows = run(star=0.5, budget=7)
    got = [(r["mu"], r["mur"], r["E"]) for r in rows]
    assert got == [(0.3, 0.2, 4e9),
                   (0.25, 0.2, 4e9), (0.35, 0.2, 4e9),
                   (0.3, 0.175, 4e9), (0.3, 0.225, 4e9),
                   (0.3, 0.2, float("%.3g" % (4e9 / 10 ** 0.075))), (0.3, 0.2, float("%.3g" % (4e9 * 10 ** 0.075)))]


def test_without_star_nelder_mead_comes_second_and_reaches_the_minimum(run):
    rows = run(budget=60)
    assert rows[1]["mu"] != 0.25 or rows[1]["mur"] != 0.2     # no star point
    best = min(rows, key=lambda r: r["J"])
    assert abs(best["mu"] - 0.40) < 0.02 and abs(best["mur"] - 0.30) < 0.01
    assert abs(best["E"] / 5e9 - 1) < 0.05


def test_the_budget_bounds_the_star(run):
    assert len(run(star=0.5, budget=3)) == 3
