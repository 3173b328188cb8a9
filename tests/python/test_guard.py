"""./tbags shear decides before it touches anything: a call that would remove or rewrite an earlier
call's files is refused (every file as it was), a bad -var name or value stops with one line
before any stage (no folder made), and --overwrite is the one way to start again."""
import hashlib
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "launcher"))
from tbagsrun import LaunchError, guard  # noqa: E402
from tbagsrun.cli import parse  # noqa: E402
from tbagsrun.presets import PRESETS  # noqa: E402
from tbagsrun.shear import decide, plan  # noqa: E402
from tbagsrun.stages import vars_key  # noqa: E402

TINY = {"nx": "9", "ny": "9", "nz": "5"}


def checksums(folder):
    return {str(f.relative_to(folder)): hashlib.sha256(f.read_bytes()).hexdigest()
            for f in sorted(Path(folder).rglob("*")) if f.is_file()}


def earlier_call(out, preset, user, seed=4821, checkpoint=True):
    """The files an earlier call of `preset` left in out: its bag, fill and stamps, and in every
    run's folder its stamp, CSV and a checkpoint (as an interrupted call leaves them)."""
    stages = plan(preset, out, dict(user, seed=seed))
    origin = vars_key(dict(preset.bag, **dict(user, seed=seed)))
    guard.make(Path(out))
    for s in stages:
        s.folder.mkdir(parents=True, exist_ok=True)
        if s.product:
            (s.folder / s.product).write_text("made by an earlier call\n")
            (s.folder / (".%s.vars" % s.deck)).write_text(vars_key(s.variables))
            continue
        (s.folder / (".%s.vars" % s.deck)).write_text(vars_key(s.variables) + origin)
        (s.folder / ("%s.csv" % s.deck)).write_text("time_s,u_mm\n0,0\n")
        if checkpoint:
            (s.folder / ("cyclic.restart.a3" if s.deck == "cyclic" else "shear.restart.1")).write_bytes(b"\0" * 64)


def tbags(*args):
    return subprocess.run([str(ROOT / "tbags"), "shear"] + [str(a) for a in args], capture_output=True,
                          text=True, timeout=120)


@pytest.mark.parametrize("name", ["demo", "cyclic", "trends"])
def test_a_plain_rerun_is_refused_and_touches_nothing(tmp_path, name):
    """be13c81 emptied the folder (fresh_dir) before stage_run's refusal: a cyclic folder with
    F5500/cyclic.restart.a3 was gone within 6 s."""
    out = tmp_path / "out"
    preset = PRESETS[name]
    for f in preset.fabrics or [None]:    # a design preset: once per fabric, in out/FABRIC
        earlier_call(out / f if f else out, preset, dict(TINY, fabric=f) if f else TINY)
    before = checksums(out)
    r = tbags(name, "--out", out, *[w for k, v in TINY.items() for w in ("-var", k, v)])
    assert r.returncode != 0 and "holds an earlier" in r.stderr and "Nothing was changed" in r.stderr, r.stderr
    assert "--resume to continue or keep it" in r.stderr and "--overwrite" in r.stderr
    assert checksums(out) == before


def test_resume_with_other_variables_is_refused_before_the_fill(tmp_path):
    """be13c81 re-made the bag and rewrote fill.data (the fill behind the checkpoints) before it
    refused. Now the bag, the fill and each run are compared with their stamps first."""
    out = tmp_path / "out"
    earlier_call(out, PRESETS["demo"], TINY)
    before = checksums(out)
    for var, value in (("e0", "0.70"), ("v", "0.03"), ("seed", "9")):
        with pytest.raises(LaunchError, match="other -var values") as e:
            decide(PRESETS["demo"], out, dict(TINY, **{var: value}), resume=True)
        assert "Nothing was changed" in str(e.value) and "--overwrite" in str(e.value)
        assert checksums(out) == before
    decide(PRESETS["demo"], out, dict(TINY), resume=True)    # the same values: it may continue
    assert checksums(out) == before


def test_a_new_run_reuses_what_matches_and_overwrite_starts_again(tmp_path):
    """Runs not made yet may be added (the fill is reused: paper --estimate, then paper);
    --overwrite empties the folder; a user's folder is never emptied."""
    out = tmp_path / "out"
    earlier_call(out, PRESETS["demo"], TINY)
    for f in out.glob("shear*"):
        f.unlink()
    (out / ".shear.vars").unlink()
    decide(PRESETS["demo"], out, dict(TINY))    # bag and fill only, with the same values
    assert (out / "fill.data").is_file()
    earlier_call(out, PRESETS["demo"], TINY)
    decide(PRESETS["demo"], out, dict(TINY), overwrite=True)
    assert [p.name for p in out.iterdir()] == [".tbags-run"]
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "thesis.tex").write_text("keep")
    for overwrite in (False, True):
        with pytest.raises(LaunchError, match="not made by ./tbags shear"):
            decide(PRESETS["demo"], mine, dict(TINY), overwrite=overwrite)
    assert (mine / "thesis.tex").read_text() == "keep"


@pytest.mark.parametrize("argv, message", [
    (["-var", "ufinall", "0.001"], "-var ufinall is not a variable of the demo preset's decks .*did you mean ufinal"),
    (["-var", "v", "-1"], "-var v -1: must be positive"),
    (["-var", "Fv", "abc"], "-var Fv abc: a number is needed"),
    (["-var", "Fv", "0"], "-var Fv 0: must be positive"),
    (["-var", "dt", "1e-5"], "-var dt 1e-5: the plates' contacts are stable below about 1.75e-06 s"),
    (["-var", "nx", "2.5"], "-var nx 2.5: must be a whole number"),
    (["-var", "damping", "soft"], "-var damping soft: must be explicit or implicit"),
    (["-var", "yarn_shear", "-2"], "-var yarn_shear -2: must be 0 or more, or -1"),
    (["-var", "fabric", "knitted"], "-var fabric knitted: must be solid or words or woven"),
    (["-var", "yarn_bendE", "-5e9"], "-var yarn_bendE -5e9: must be positive"),
    (["-var", "bag_mur", "-0.5"], "-var bag_mur -0.5: must be 0 or more, or -1"),
    (["cyclic", "-var", "amps", "1 0.5"], "-var amps 1 0.5: positive amplitudes in mm, increasing"),
    (["-var", "tbags", "/x"], "-var tbags is set by the launcher"),
    (["--out", "/proc/x"], "cannot write the outputs to /proc/x"),
    (["--out", "README.md"], "README.md is a file, not a folder"),
    (["--resume", "--overwrite"], "give one"),
])
def test_bad_arguments_stop_before_any_stage(tmp_path, argv, message):
    """One line, rc 1, nothing made (be13c81: -var ufinall ran the 5 mm run, -var Fv abc failed
    after the bag and fill, -var dt 1e-5 at the plate, --out a file ended in a traceback)."""
    out = tmp_path / "out"
    args = argv if "--out" in argv else argv + ["--out", out]
    r = subprocess.run([str(ROOT / "tbags"), "shear"] + [str(a) for a in args], capture_output=True,
                       text=True, timeout=120, cwd=ROOT)
    import re
    assert r.returncode != 0 and re.search(message, r.stderr), r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr
    assert not out.exists()


def test_negative_values_reach_the_checks():
    """be13c81 answered '-var v needs a value' for -var v -1."""
    o = parse(["-var", "yarn_shear", "-1", "-var", "Fv", "-1", "-np", "2"])
    assert o.variables == {"yarn_shear": "-1", "Fv": "-1"} and o.ranks == 2
