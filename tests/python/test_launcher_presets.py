"""The shear presets as data (launcher/tbagsrun/presets.py) and the launcher's argument parsing:
every run's deck exists, the user's -var values win over the preset's, bad arguments stop with a
message naming the fix."""
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "launcher"))
from tbagsrun import LaunchError  # noqa: E402
from tbagsrun.presets import LOADS, PRESETS, Run  # noqa: E402
from tbagsrun.shear import means_to_csv, run_variables  # noqa: E402
from tbagspost.run import read_csv  # noqa: E402
from tbagsrun.cli import parse, usage  # noqa: E402


def test_every_preset_runs_existing_decks_in_distinct_folders():
    for p in PRESETS.values():
        assert p.help and p.post in ("figures", "cyclic", "stack")
        folders = [r.folder for r in p.runs]
        assert len(set(folders)) == len(folders), p.name
        for r in p.runs:
            assert (ROOT / "inputs" / ("in." + r.deck)).is_file(), (p.name, r.deck)
    assert [r.variables["Fpaper"] for r in PRESETS["trends"].runs] == list(LOADS)
    assert all(name in usage() for name in PRESETS)


def test_user_variables_win_and_subfolder_runs_read_the_fill_above():
    trends = PRESETS["trends"]
    v = run_variables(trends, trends.runs[0], {"v": "0.02", "nz": "9"})
    assert v["v"] == "0.02" and v["nz"] == "9" and v["nx"] == 28 and v["Fpaper"] == 5500
    assert v["fill"] == "../fill.data"
    demo = PRESETS["demo"]
    assert "fill" not in run_variables(demo, demo.runs[0], {})
    assert run_variables(demo, Run("", "shear", {"v": 1}), {})["v"] == 1


def test_parse_options_variables_and_seed():
    preset, ranks, out, nreal, estimate, seed, variables, extra, engine = parse(
        ["trends", "-np", "3", "--realizations", "2", "-var", "seed", "7", "-var", "amps", "0.25", "1",
         "-var", "v", "0.01"])
    assert (preset.name, ranks, nreal, seed, engine) == ("trends", 3, 2, 7, "lammps")
    assert variables == {"amps": ["0.25", "1"], "v": "0.01"} and not extra and out is None
    assert parse([])[0].name == "demo"
    assert parse(["--engine", "liggghts"])[-1] == "liggghts"


@pytest.mark.parametrize("argv, message", [
    (["papr"], "unknown preset 'papr'"),
    (["-np", "0"], "-np needs a positive number"),
    (["--realizations"], "--realizations needs a positive number"),
    (["stack", "--realizations", "2"], "not for the stack preset"),
    (["demo", "--estimate"], "--estimate is for the paper preset"),
    (["-var", "seed", "x"], "-var seed needs a positive integer"),
    (["-var", "v"], "-var v needs a value"),
    (["--outt", "x"], "unknown option --outt"),
    (["--engine", "lampps"], "--engine must be lammps or liggghts"),
    (["cyclic", "--engine", "liggghts"], "LIGGGHTS has no decks for cyclic yet"),
    (["paper", "--engine", "liggghts"], "LIGGGHTS has no decks for paper yet"),
])
def test_bad_arguments_say_what_is_wrong(argv, message):
    with pytest.raises(LaunchError, match=message):
        parse(argv)


def test_liggghts_means_become_the_shear_csv(tmp_path):
    """fix ave/time's output of inputs/liggghts/in.shear (SI) as the CSV's columns (mm, N)."""
    (tmp_path / "m.txt").write_text("# Time-averaged data for fix means\n# TimeStep v_t v_u v_w v_S v_F v_zp\n"
                                    "4444 0.0033 5e-05 -0.00138 29.95 43.19 0.02245\n"
                                    "8888 0.0100 0.00015 -0.00137 43.41 43.18 0.02246\n")
    (tmp_path / "s.txt").write_text("0 0.0 0 -0.00139 19.9 43.18 0.02244\n")
    means_to_csv(tmp_path / "m.txt", tmp_path / "shear.csv", tmp_path / "s.txt")
    d = read_csv(tmp_path / "shear.csv")
    assert list(d["u_mm"]) == [0, 0.05, 0.15] and list(d["w_mm"]) == [-1.39, -1.38, -1.37]
    assert list(d["S_N"]) == [19.9, 29.95, 43.41] and list(d["steps"]) == [1, 4444, 4444]
