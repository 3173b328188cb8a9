"""./tbags shear --resume without LAMMPS: the CSV merge, the checkpoint order, and stage_run's
decisions with a stand-in for the LAMMPS stage (the deck test test_launcher.py resumes a real
interrupted run)."""
import os
import sys
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "launcher"))
from tbagsrun import LaunchError, resume, stages  # noqa: E402

HEAD = ["time_s,u_mm,S_N", "# means over each row's interval"]


def test_rows_written_last_win():
    # checkpoint after 0.2; the interrupted run wrote 0.3 and 0.4 (0.3's time printed 1e-7 early)
    rows = HEAD + ["0.0000000,0,1", "0.1000000,1,2", "0.2000000,2,3", "0.2999999,3,4", "0.4000000,4,5",
                   HEAD[1], "0.3000001,3,40", "0.4000000,4,50", "0.5000000,5,60"]
    assert resume.merge_rows(rows) == HEAD + ["0.0000000,0,1", "0.1000000,1,2", "0.2000000,2,3",
                                              "0.3000001,3,40", "0.4000000,4,50", "0.5000000,5,60"]
    # resumed twice, the second time from an earlier checkpoint than the first's last rows
    twice = rows + ["0.2000000,2,300", "0.3000000,3,400"]
    assert resume.merge_rows(twice)[-3:] == ["0.1000000,1,2", "0.2000000,2,300", "0.3000000,3,400"]
    # nothing past the checkpoint: unchanged
    clean = HEAD + ["0.0,0,1", "0.1,1,2", "0.2,2,3"]
    assert resume.merge_rows(clean) == clean


def touch(path, age=0.0):
    path.write_text("x")
    t = time.time() - age
    os.utime(path, (t, t))


def test_checkpoints_newest_first(tmp_path):
    touch(tmp_path / "shear.restart.1", age=10)
    touch(tmp_path / "shear.restart.2", age=20)
    assert resume.checkpoints(tmp_path, "shear") == [
        ("shear.restart.1", {"restart": "shear.restart.1", "checkpoint_first": 2}),    # writes .2 first
        ("shear.restart.2", {"restart": "shear.restart.2", "checkpoint_first": 1})]
    for k in (1, 2, 10):
        touch(tmp_path / ("cyclic.restart.a%d" % k))
    touch(tmp_path / "cyclic.restart.a3.bak")
    assert resume.checkpoints(tmp_path, "cyclic") == [
        ("cyclic.restart.a10", {"restart": "cyclic.restart.a10", "start": 11}),
        ("cyclic.restart.a2", {"restart": "cyclic.restart.a2", "start": 3}),
        ("cyclic.restart.a1", {"restart": "cyclic.restart.a1", "start": 2})]


class FakeStage:
    """stages.stage's stand-in: records the -var values; fails when the restart named is in `bad`;
    else writes a checkpoint, a CSV row and, if `finish`, the closing line."""

    def __init__(self, bad=(), finish=True):
        self.calls, self.bad, self.finish = [], set(bad), finish

    def __call__(self, folder, deck, ranks, variables, say):
        self.calls.append(dict(variables))
        folder = Path(folder)
        if variables.get("restart") in self.bad:
            raise LaunchError("ERROR: cannot read %s" % variables["restart"])
        touch(folder / "shear.restart.1")
        with open(folder / "shear.csv", "a") as fh:
            fh.write("%s\n" % ("time_s,S_N\n0.0,1" if "restart" not in variables else "0.5,9"))
        (folder / "log.shear").write_text("log")
        (folder / "screen.shear.txt").write_text("SHEARED: u 1 mm\n" if self.finish else "Step\n")


def test_stage_run_resumes_keeps_and_refuses(tmp_path, monkeypatch):
    run = tmp_path / "F5500"
    said = []
    fake = FakeStage(finish=False)
    monkeypatch.setattr(stages, "stage", fake)
    v = {"Fpaper": 5500, "fill": "../fill.data"}
    stages.stage_run(run, "shear", 2, v, said.append, resume=True, origin="fill A")   # nothing yet: from the start
    assert fake.calls == [v] and (run / ".shear.vars").is_file()
    with open(run / "shear.csv", "a") as fh:    # rows past the checkpoint, then interrupted
        fh.write("0.6,7\n")
    fake.finish = True
    stages.stage_run(run, "shear", 2, v, said.append, resume=True, origin="fill A")
    assert fake.calls[-1] == dict(v, restart="shear.restart.1", checkpoint_first=2)
    assert (run / "shear.csv").read_text() == "time_s,S_N\n0.0,1\n0.5,9\n"
    assert (run / "log.shear.1").is_file() and (run / "screen.shear.txt.1").is_file()
    stages.stage_run(run, "shear", 2, v, said.append, resume=True, origin="fill A")
    assert len(fake.calls) == 2 and "finished before, kept" in said[-1]
    with pytest.raises(LaunchError, match="run with other -var values or another fill"):
        stages.stage_run(run, "shear", 2, dict(v, Fpaper=3730), said.append, resume=True, origin="fill A")
    with pytest.raises(LaunchError, match="another fill"):
        stages.stage_run(run, "shear", 2, v, said.append, resume=True, origin="fill B")
    # without --resume: refused while the run's checkpoints are there (hours of work)
    with pytest.raises(LaunchError, match=r"holds an earlier run's checkpoints \(shear.restart.1\): --resume"):
        stages.stage_run(run, "shear", 2, v, said.append, origin="fill A")
    # removed by the user: from the start, the old CSV and dumps gone first
    (run / "shear.restart.1").unlink()
    touch(run / "dump.grains.100")
    stages.stage_run(run, "shear", 2, v, said.append, origin="fill A")
    assert "restart" not in fake.calls[-1] and len(fake.calls) == 3
    assert not (run / "dump.grains.100").exists() and (run / "shear.csv").read_text() == "time_s,S_N\n0.0,1\n"
    # checkpoints without a stamp (an older launcher's run): not removed on --resume either
    (run / ".shear.vars").unlink()
    with pytest.raises(LaunchError, match="no stamp of their -var values"):
        stages.stage_run(run, "shear", 2, v, said.append, resume=True, origin="fill A")


def test_unreadable_checkpoint_falls_back_to_the_older(tmp_path, monkeypatch):
    run = tmp_path / "F1960"
    fake = FakeStage(bad={"shear.restart.2"})
    monkeypatch.setattr(stages, "stage", fake)
    v = {"Fpaper": 1960}
    stages.stage_run(run, "shear", 1, v, lambda s: None, resume=True)
    (run / "screen.shear.txt").write_text("Step\n")    # interrupted
    touch(run / "shear.restart.1", age=100)
    touch(run / "shear.restart.2")                      # newer, half written
    said = []
    stages.stage_run(run, "shear", 1, v, said.append, resume=True)
    assert [c.get("restart") for c in fake.calls[1:]] == ["shear.restart.2", "shear.restart.1"]
    assert any("the older checkpoint next" in s for s in said)


def test_once_made_stage_continues_or_starts_clean(tmp_path, monkeypatch):
    """stage_once of the shared compression: stopped with checkpoints and its stamp, it continues
    from the newer (the older when that fails) and drops them once compress.restart is made; with
    another stamp (other -var values) it starts clean, the other run's checkpoints removed."""
    calls = []

    def fake(folder, deck, ranks, variables, say):
        calls.append(variables.get("compress_from"))
        if variables.get("compress_from") == "compress.part.2":
            raise LaunchError("unreadable checkpoint")
        (Path(folder) / "compress.restart").write_text("made")
    monkeypatch.setattr(stages, "stage", fake)
    part = {"nx": 9, "compress_to": 0.9}
    folder = tmp_path / "compress"
    folder.mkdir()
    (folder / ".shear.vars").write_text(stages.vars_key(part))
    for k, name in enumerate(("compress.part.1", "compress.part.2")):
        (folder / name).write_text(name)
        os.utime(folder / name, (1000 + k, 1000 + k))    # .2 the newer
    said = []
    stages.stage_once(folder, "shear", 1, part, said.append, "compress.restart")
    assert calls == ["compress.part.2", "compress.part.1"]
    assert "(from compress.part.2 it failed; the older checkpoint next)" in "\n".join(said)
    assert (folder / "compress.restart").is_file() and not list(folder.glob("compress.part.*"))
    # another stamp: a clean start, the other run's checkpoints not used
    calls.clear()
    (folder / "compress.restart").unlink()
    (folder / "compress.part.1").write_text("of another run")
    stages.stage_once(folder, "shear", 1, dict(part, nx=11), said.append, "compress.restart")
    assert calls == [None] and not list(folder.glob("compress.part.*"))
    assert (folder / ".shear.vars").read_text() == stages.vars_key(dict(part, nx=11))


def test_past_start_when_every_run_finished_or_has_a_checkpoint(tmp_path):
    """./tbags shear paper --resume skips the cost estimate (15 min on the paper bag) only when every
    load it runs finished or has a checkpoint."""
    from types import SimpleNamespace
    runs = [SimpleNamespace(folder=tmp_path / f, deck="shear") for f in ("F1960", "F3730")]
    for r in runs:
        r.folder.mkdir()
    assert not resume.past_start(runs) and not resume.past_start([])
    touch(runs[0].folder / "shear.restart.1")
    assert not resume.past_start(runs)    # F3730 has neither
    (runs[1].folder / "screen.shear.txt").write_text("SHEARED: u 15 mm\n")
    assert resume.past_start(runs)


def test_paper_loads_one_per_job_make_no_estimate(tmp_path):
    """The paper preset's estimate (its own compression and timing, about 30 min on the paper bag)
    is made by the whole preset and by --estimate, not by each --loads job, and not by a --resume
    that finds every run past its start."""
    from types import SimpleNamespace
    from tbagsrun.presets import PRESETS
    from tbagsrun.shear import skip_estimate
    paper = PRESETS["paper"]
    runs = [SimpleNamespace(folder=tmp_path / "F5500", deck="shear")]
    runs[0].folder.mkdir()
    assert skip_estimate(paper, runs, False, False) == ""
    assert skip_estimate(paper.only({"F5500"}), runs, False, False) == "--loads F5500"
    assert skip_estimate(paper.only({"F5500"}), runs, False, True) == ""    # --estimate --loads F5500
    assert skip_estimate(paper, runs, True, False) == ""                    # resumed, not past its start
    touch(runs[0].folder / "shear.restart.2")
    assert "checkpoint" in skip_estimate(paper, runs, True, False)
    assert skip_estimate(PRESETS["trends"], runs, False, False) == ""        # no estimate to skip
