"""inputs/project_time.py: the projection of the paper-size run from measured loop times, checked
against a hand computation on synthetic logs; missing or truncated logs give a clear message."""
import importlib.util
import os
import re
from pathlib import Path

import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
spec = importlib.util.spec_from_file_location("project_time", ROOT / "inputs" / "project_time.py")
pt = importlib.util.module_from_spec(spec)
spec.loader.exec_module(pt)

LOOP = "Loop time of %g on %d procs for %d steps with %d atoms\n"


def make(tmp_path, costs={1: 1e-6, 2: 0.6e-6}):
    (tmp_path / "log.bag").write_text("BAG 21 x 21 x 7: 1282 particles, 2560 bonds (formula: 1282, 2560)\n")
    (tmp_path / "log.fill").write_text(LOOP % (1, 2, 2000, 3156) * 10 + LOOP % (10, 2, 40000, 3156))
    for p, c in costs.items():
        d = tmp_path / ("np%d" % p)
        d.mkdir()
        (d / "log.shear").write_text(LOOP % (c * 39000 * 3156, p, 39000, 3156) + LOOP % (c * 25000 * 3156, p, 25000, 3156))
    return tmp_path


def test_counts_match_the_decks():
    assert pt.bag_particles(81, 81, 17) == 17922 and pt.sand_grains(81, 81, 17) == 97130
    assert pt.bag_particles(21, 21, 7) == 1282 and pt.sand_grains(21, 21, 7) == 1874


def test_timestep_from_the_run_else_the_deck(tmp_path):
    r = pt.project(make(tmp_path), ranks=1)
    deck = float(re.search(r"^variable\s+dt\s+index\s+(\S+)", (ROOT / "inputs" / "in.shear").read_text(), re.M).group(1))
    assert r["dt"] == deck
    log = tmp_path / "np1" / "log.shear"
    log.write_text("TIMESTEP: Rayleigh 1.141e-05 s, bond 7.777e-06 s; using 1e-6 s\n" + log.read_text())
    r = pt.project(tmp_path, ranks=1)
    assert r["dt"] == 1e-6 and r["shear_steps"] == pytest.approx(0.015 / (0.004 * 1e-6))


def test_projection_by_hand(tmp_path):
    make(tmp_path)
    for p in (1, 2):
        log = tmp_path / ("np%d" % p) / "log.shear"
        log.write_text("TIMESTEP: Rayleigh 1.1e-05 s, bond 7.8e-06 s; using 2e-6 s\n" + log.read_text())
    r = pt.project(tmp_path, ranks=4)
    atoms = 17922 + 97130
    assert r["atoms"] == atoms and r["fill_steps"] == 60000 and r["comp_steps"] == 39000
    steps_load = 39000 * 15 / 5 + 0.015 / (0.004 * 2e-6)
    rows = {p: row for p, *row in r["rows"]}
    assert rows[1][0] == pytest.approx(1e-6) and rows[2][0] == pytest.approx(0.6e-6)
    assert rows[2][2] == pytest.approx(60000 * atoms * 0.6e-6 / 3600)
    assert rows[2][3] == pytest.approx(steps_load * atoms * 0.6e-6 / 3600)
    assert rows[4][1] and rows[4][0] == pytest.approx(0.3e-6)     # extrapolated, ideal from 2
    assert not rows[2][1]
    text = pt.report(r)
    assert "* extrapolated" in text and "97130" not in text and "115052 particles" in text


def test_missing_and_truncated(tmp_path):
    with pytest.raises(SystemExit, match="no bag.json and no BAG line"):
        pt.project(tmp_path, 1)
    make(tmp_path)
    (tmp_path / "np2" / "log.shear").write_text("LAMMPS (4 Feb 2025)\n")
    with pytest.raises(SystemExit, match="no completed run"):
        pt.project(tmp_path, 1)
