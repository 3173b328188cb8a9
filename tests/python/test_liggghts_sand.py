"""The LIGGGHTS shear gets -var sand's parameters (its deck has no sand.lmp): none for paper
(model.lig's defaults), calibration/results/sand_calibrated.lmp's for calibrated, passed to the
deck's run; a file without them or another set name stops with a message."""
import re
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "launcher"))
from tbagsrun import LaunchError, liggghts_stage  # noqa: E402


def test_paper_and_calibrated_sets(tmp_path):
    assert liggghts_stage.sand_variables({}) == {}
    assert liggghts_stage.sand_variables({"sand": "paper"}) == {}
    got = liggghts_stage.sand_variables({"sand": "calibrated"})
    text = liggghts_stage.SAND_CALIBRATED.read_text()
    for name, value in got.items():
        assert re.search(r"^variable\s+%s\s+equal\s+%s\s*$" % (name, re.escape(value)), text, re.M)
    assert set(got) == {"sand_E", "sand_nu", "sand_mu", "sand_mur"}
    f = tmp_path / "s.lmp"
    f.write_text("variable sand_E equal 7.2e9\nvariable sand_nu equal 0.1\n"
                 "variable sand_mu equal 0.325\nvariable sand_mur equal 0.381\n")
    assert liggghts_stage.sand_variables({"sand": "calibrated"}, f) == {
        "sand_E": "7.2e9", "sand_nu": "0.1", "sand_mu": "0.325", "sand_mur": "0.381"}


def test_missing_or_unknown(tmp_path):
    f = tmp_path / "s.lmp"
    f.write_text("variable sand_E equal 7.2e9\n")
    with pytest.raises(LaunchError, match="no sand_nu, sand_mu, sand_mur"):
        liggghts_stage.sand_variables({"sand": "calibrated"}, f)
    with pytest.raises(LaunchError, match="paper or calibrated"):
        liggghts_stage.sand_variables({"sand": "toyoura"})


def test_the_run_gets_them(tmp_path, monkeypatch):
    seen = {}

    class Done(Exception):
        pass

    def fake_run(deck, folder, ranks, variables, **kw):
        seen.update(variables)
        raise Done

    monkeypatch.setattr(liggghts_stage, "run_python", lambda *a, **k: (True, ""))
    monkeypatch.setattr(liggghts_stage.lammps, "run", fake_run)
    with pytest.raises(Done):
        liggghts_stage.stage_liggghts(tmp_path, 1, {"sand": "calibrated"}, print)
    assert seen["sand_mu"] == liggghts_stage.sand_variables({"sand": "calibrated"})["sand_mu"]
