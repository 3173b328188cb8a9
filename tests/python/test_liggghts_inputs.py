"""What --engine liggghts does with -var values. The LIGGGHTS shear gets -var sand's parameters
(its deck has no sand.lmp): none for paper (model.lig's defaults), those of
calibration/results/sand_calibrated.lmp for calibrated, passed to the deck's run; a file without
them or another set name stops with a message. A value only LAMMPS's shear decks take stops the
launcher before anything runs (the LIGGGHTS run would go on without it)."""
import re
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "launcher"))
from tbagsrun import LaunchError, liggghts_stage, variables  # noqa: E402


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


@pytest.mark.parametrize("name", ["Fv", "damping", "film_mu", "du_dump", "compress_to"])
def test_values_only_lammps_takes_are_refused(name):
    with pytest.raises(LaunchError, match="-var %s: the LIGGGHTS shear" % name):
        variables.check_liggghts({name: "1"})


def test_values_the_liggghts_run_takes_pass():
    variables.check_liggghts({"bag_mur": "0", "yarn_bendE": "1e9", "sand": "calibrated", "v": "0.01",
                              "ufinal": "0.002", "seed": "5", "nx": "9", "Fpaper": "1960", "trace": "1",
                              "fabric": "words", "yarn_shear": "0", "dt": "1e-6"})
