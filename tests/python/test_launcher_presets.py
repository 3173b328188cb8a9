"""The shear presets as data (launcher/tbagsrun/presets.py) and the launcher's argument parsing:
every run's deck exists, the user's -var values win over the preset's, bad arguments stop with a
message naming the fix."""
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "launcher"))
from tbagsrun import LaunchError  # noqa: E402
from tbagsrun.presets import COMPRESS_SHARED, LOADS, PRESETS, Run  # noqa: E402
from tbagsrun.liggghts_stage import means_to_csv  # noqa: E402
from tbagsrun.shear import run_variables, shared_compression  # noqa: E402
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


def test_loads_of_one_fill_share_their_compression():
    """Runs that differ only in their load compress once to the shared fraction of the smallest
    (folder compress); runs that differ otherwise, one run, LIGGGHTS and resumed runs do not."""
    for name in ("trends", "paper", "cyclic"):
        part = shared_compression(PRESETS[name], {}, "lammps")
        assert part.folder == "compress" and part.deck == PRESETS[name].runs[0].deck, name
        assert part.variables["Fpaper"] == min(LOADS) and part.variables["compress_to"] == COMPRESS_SHARED
        assert 0 < COMPRESS_SHARED < 0.98    # below it, every load's servo runs at its speed limit
        assert shared_compression(PRESETS[name], {}, "liggghts") is None
        assert shared_compression(PRESETS[name], {"restart": "x"}, "lammps") is None
        assert shared_compression(PRESETS[name], {"compress_to": "0"}, "lammps") is None
        assert shared_compression(PRESETS[name], {"compress_to": "0.5"}, "lammps").variables["compress_to"] == 0.5
    for name in ("demo", "quasistatic", "stack", "protocol"):
        assert shared_compression(PRESETS[name], {}, "lammps") is None, name


def test_the_protocol_study_compresses_each_run_at_its_own_speed_limit(monkeypatch):
    """./tbags shear protocol: one run per approach speed (V<mm/s>), the deck's default first (the
    study's reference), each at the highest load, and tbagspost.protocol compares them."""
    from tbagsrun import shear
    p = PRESETS["protocol"]
    assert [r.folder for r in p.runs] == ["V20", "V50", "V100", "V200"]
    assert {r.variables["Fpaper"] for r in p.runs} == {max(LOADS)}
    assert [r.variables["vmax_compress"] for r in p.runs] == [0.02, 0.05, 0.1, 0.2]
    deck = (ROOT / "inputs" / "between_plates.lmp").read_text()
    assert "variable        vmax_compress index 0.02" in deck
    called = []
    monkeypatch.setattr(shear, "run_module", lambda name, args, say: called.append((name, args)) or (True, ""))
    shear.check(p, Path("out"), print, in_realizations=False)
    assert called == [("protocol", [Path("out")])]



def test_the_shared_part_does_not_depend_on_the_motion():
    """The part's variables (its stamp, and so its committed state) leave out the shear's and the
    cycles' -var values, which it does not read: a run at another speed reuses it."""
    from tbagsrun.shear import part_variables
    paper = PRESETS["paper"]
    part = shared_compression(paper, {}, "lammps")
    assert not {"v", "ufinal"} & set(part_variables(paper, part, {}))
    assert part_variables(paper, part, {"v": "0.016"}) == part_variables(paper, part, {})
    assert {k: v for k, v in run_variables(paper, part, {}).items() if k not in ("v", "ufinal")} == \
        part_variables(paper, part, {})
    assert part_variables(paper, part, {"sand": "calibrated"})["sand"] == "calibrated"
    cyclic = PRESETS["cyclic"]
    assert not {"amps", "vpeak", "cycles"} & set(part_variables(cyclic, shared_compression(cyclic, {}, "lammps"),
                                                                 {"amps": "0.25 1", "vpeak": "0.01"}))


def test_loads_run_some_loads_from_the_compression_of_all(tmp_path):
    """--loads: the paper preset with one load plans that load only, from the same shared
    compression (same folder, deck and stamp: the committed state serves it) as the whole preset."""
    from tbagsrun.shear import part_variables, plan
    paper = PRESETS["paper"]
    one = parse(["paper", "--loads", "F3730"]).preset
    assert [r.folder for r in one.runs] == ["F3730"] and one.compress_runs == paper.runs
    two = parse(["paper", "--loads", "F1960,F5500"]).preset
    assert [r.folder for r in two.runs] == ["F5500", "F1960"]    # the preset's order
    full, part = shared_compression(paper, {}, "lammps"), shared_compression(one, {}, "lammps")
    assert part == full and part.variables["Fpaper"] == 1960
    assert part_variables(one, part, {"seed": 4821}) == part_variables(paper, full, {"seed": 4821})
    stages = plan(one, tmp_path, {"seed": 4821})
    assert [s.folder.name for s in stages] == [tmp_path.name, tmp_path.name, "compress", "F3730"]
    assert stages[3].variables["compress_from"] == "../compress/compress.restart"
    assert stages[2].variables == plan(paper, tmp_path, {"seed": 4821})[2].variables
    # the estimate times the load that runs (it compressed the bag on to 5.50 kN before)
    from tbagsrun.shear import estimate_load
    assert estimate_load(parse(["paper", "--loads", "F1960"]).preset, {}) == {"Fpaper": 1960}
    assert estimate_load(paper, {}) == {"Fpaper": 5500}
    assert estimate_load(one, {"Fpaper": 3000}) == {}


def test_parse_options_variables_and_seed():
    o = parse(["trends", "-np", "3", "--realizations", "2", "-var", "seed", "7", "-var", "amps", "0.25", "1",
               "-var", "v", "0.01"])
    assert (o.preset.name, o.ranks, o.nreal, o.seed, o.engine, o.resume, o.progress_every) == \
        ("trends", 3, 2, 7, "lammps", False, 30)
    assert o.variables == {"amps": ["0.25", "1"], "v": "0.01"} and not o.extra and o.out is None
    assert parse([]).preset.name == "demo"
    assert parse(["--engine", "liggghts"]).engine == "liggghts"
    o = parse(["paper", "--resume", "--progress", "60"])
    assert o.resume is True and o.progress_every == 60


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
    (["paper", "--estimate", "--resume"], "--resume continues LAMMPS runs"),
    (["trends", "--engine", "liggghts", "--resume"], "--resume continues LAMMPS runs"),
    (["--progress", "-1"], "--progress needs a whole number of seconds"),
    (["paper", "--loads", "F1961"], r"--loads needs some of F5500, F3730, F1960, comma-separated \(not F1961\)"),
    (["paper", "--loads"], "--loads needs some of"),
    (["demo", "--loads", "F1960"], "--loads is for presets of several runs"),
])
def test_bad_arguments_say_what_is_wrong(argv, message):
    with pytest.raises(LaunchError, match=message):
        parse(argv)


def liggghts_outputs(folder, trace_rows):
    """fix ave/time's means of inputs/liggghts/in.shear (two rows of 2 steps), its u = 0 row and
    a per-step trace (step w S F_v z_plate broken, SI)"""
    (folder / "m.txt").write_text("# Time-averaged data for fix means\n# TimeStep v_t v_u v_w v_S v_F v_zp\n"
                                  "2 0.0033 5e-05 -0.00138 29.95 43.19 0.02245\n"
                                  "4 0.0100 0.00015 -0.00137 43.41 43.18 0.02246\n")
    (folder / "s.txt").write_text("0 0.0 0 -0.00139 19.9 43.18 0.02244\n")
    (folder / "t.txt").write_text("".join(" ".join(str(x) for x in r) + "\n" for r in trace_rows))


TRACE = [(1, -0.00139, 28.0, 43.0, 0.02244, 0), (2, -0.00137, 31.9, 43.38, 0.02246, 0),
         (3, -0.00138, 40.0, 43.1, 0.02245, 1), (4, -0.00136, 46.82, 43.26, 0.02247, 2)]


def test_liggghts_means_become_the_shear_csv(tmp_path):
    """The LIGGGHTS run's outputs (SI) as inputs/in.shear's CSV (mm, N): the means as they are,
    min and max over each row's steps and the broken bonds at its last step from the trace."""
    liggghts_outputs(tmp_path, TRACE)
    means_to_csv(tmp_path / "m.txt", tmp_path / "shear.csv", tmp_path / "s.txt", tmp_path / "t.txt")
    d = read_csv(tmp_path / "shear.csv")
    assert list(d["u_mm"]) == [0, 0.05, 0.15] and list(d["w_mm"]) == [-1.39, -1.38, -1.37]
    assert list(d["S_N"]) == [19.9, 29.95, 43.41] and list(d["steps"]) == [1, 2, 2]
    assert list(d["S_min_N"]) == [19.9, 28.0, 40.0] and list(d["S_max_N"]) == [19.9, 31.9, 46.82]
    assert list(d["w_min_mm"]) == [-1.39, -1.39, -1.38] and list(d["w_max_mm"]) == [-1.39, -1.37, -1.36]
    assert list(d["Fv_min_N"]) == [43.18, 43.0, 43.1] and list(d["Fv_max_N"]) == [43.18, 43.38, 43.26]
    assert list(d["zplate_min_mm"]) == [22.44, 22.44, 22.45] and list(d["zplate_max_mm"]) == [22.44, 22.46, 22.47]
    assert list(d["broken_bonds"]) == [0, 0, 2]
    # the same columns as LAMMPS's in.shear
    lammps_header = [line for line in (ROOT / "inputs" / "in.shear").read_text().splitlines()
                     if "print time_s," in line][0].split("print ")[1].split()[0]
    assert (tmp_path / "shear.csv").read_text().splitlines()[0] == lammps_header


def test_liggghts_trace_must_cover_every_step(tmp_path):
    liggghts_outputs(tmp_path, TRACE[:2] + TRACE[3:])
    with pytest.raises(LaunchError, match="has 1 of the 2 steps 3-4"):
        means_to_csv(tmp_path / "m.txt", tmp_path / "shear.csv", tmp_path / "s.txt", tmp_path / "t.txt")

def test_sheared_line_gives_w_from_both_starts(tmp_path):
    """The deck's w counts from the start of compression, the figures' from the start of shear:
    the console says both, labelled (be13c81 said 'w -1.427 mm' where the figures say -0.147)."""
    from tbagsrun.stages import shear_w
    (tmp_path / "shear.csv").write_text("time_s,u_mm,w_mm,S_N\n# means\n0.1,0.0,-1.2800,10\n0.2,0.01,-1.2810,12\n")
    line = "SHEARED: u 5.000 mm, S 572.519 N, F_v 317.958 N, w -1.427 mm from the start of compression, broken bonds 0"
    assert shear_w(line, tmp_path) == line.replace(
        "compression,", "compression, -0.147 mm from the start of shear,")
    assert shear_w("COMPRESSED: F_v 1 N", tmp_path) == "COMPRESSED: F_v 1 N"
