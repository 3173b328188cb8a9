"""postprocess/tbagspost/loadpath on a made-up bag: a wall column of bag particles and a column of
sand between a bottom and a top layer; the forces the contacts pass across the mid-height plane,
split by contact class, against a hand count."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from tbagspost import loadpath  # noqa: E402
from tbagspost.dumps import Grains  # noqa: E402

S = 0.005


def bag_and_contacts(wall_force=9.0, sand_force=3.0, shear=0.5):
    # bag: a wall column at x = 0 of 5 layers (z = 0..20 mm); sand: a column at x = 10 mm
    pos = [(0.0, 0.0, k * S) for k in range(5)] + [(0.01, 0.0, 0.0025 + k * 0.004) for k in range(5)]
    types = [1] * 5 + [2] * 5
    n = len(pos)
    g = Grains(step=0, ids=np.arange(1, n + 1), types=np.array(types), radius=np.full(n, 0.0025),
               pos=np.array(pos), vel=np.zeros((n, 3)), disp=np.zeros((n, 3)), lo=np.zeros(3), hi=np.ones(3))
    rows = []
    for col, f in ((0, wall_force), (5, sand_force)):
        for k in range(4):       # contacts between consecutive particles of a column, upper = id1
            a, b = col + k + 2, col + k + 1
            t = types[a - 1], types[b - 1]
            # on the upper particle: pushed up by fn along n (from lower to upper); friction -x
            rows.append((a, b, t[0], t[1], -shear, 0.0, 0.0, f))
    cols = ("id1", "id2", "type1", "type2", "ftx", "fty", "ftz", "fn")
    c = {k: np.array([r[i] for r in rows], dtype=float) for i, k in enumerate(cols)}
    for k in ("id1", "id2", "type1", "type2"):
        c[k] = c[k].astype(int)
    return g, c


def test_plane_between_the_middle_layers():
    g, _ = bag_and_contacts()
    assert loadpath.mid_plane(g) == pytest.approx(0.0075)    # layers 0..4: between 1 and 2


def test_forces_through_the_plane_by_class():
    g, c = bag_and_contacts()
    r = loadpath.through_plane(g, c)
    # one wall contact (layers 1-2) and one sand contact (z 6.5-10.5 mm) cross z = 7.5 mm
    assert r["bag-bag"] == (pytest.approx(9.0), pytest.approx(0.5), 1)
    assert r["sand-sand"] == (pytest.approx(3.0), pytest.approx(0.5), 1)
    assert r["bag-sand"] == (0.0, 0.0, 0)
    assert r["Fz"] == pytest.approx(12.0) and r["Fx"] == pytest.approx(1.0)
    line = loadpath.describe(r, S=10.0)
    assert "sand-sand 25 %" in line and "bag-bag 75 %" in line and "horizontal 1 N" in line


def test_kept_rows_stand_for_dropped_dumps(tmp_path, monkeypatch):
    """keep() writes the load path of every dump step; once some dumps are dropped (a run carried
    between machines), by_step() still gives their rows, equal to what the dumps gave, and a dump
    that exists wins over its kept row."""
    from types import SimpleNamespace
    g, c = bag_and_contacts()
    dumps = {0: (g, c), 10: bag_and_contacts(wall_force=5.0)}
    run = SimpleNamespace(path=tmp_path, steps=lambda kind: sorted(dumps))
    monkeypatch.setattr(loadpath, "at_step", lambda r, step: loadpath.through_plane(*dumps[step]))
    before = loadpath.by_step(run)
    assert loadpath.keep(run) == [0, 10]
    del dumps[0]                                    # its dumps dropped
    after = loadpath.by_step(run)
    assert list(after) == [0, 10] and after[0] == before[0] and after[10] == before[10]
    dumps[20] = bag_and_contacts(sand_force=7.0)    # a later dump, not kept: computed
    dumps[10] = bag_and_contacts(wall_force=1.0)    # a dump present wins over its kept row
    again = loadpath.by_step(run)
    assert list(again) == [0, 10, 20] and again[10]["bag-bag"][0] == pytest.approx(1.0)
    assert loadpath.keep(run) == [0, 10, 20]        # kept rows stay kept
