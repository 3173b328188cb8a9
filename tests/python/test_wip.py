"""launcher/tbagsrun/wip.py: an unfinished run packed for the next machine and unpacked there:
the newer checkpoint kept with its time, the older one, the products of committed states, the
compression's own checkpoints and the estimate left out; refused over the size limit, from a
folder ./tbags did not make, and into a folder that holds files; files left out by name (--drop); a run whose older checkpoint is gone."""
import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "launcher"))
from tbagsrun import LaunchError, states, wip  # noqa: E402
from tbagsrun.stages import MARKER  # noqa: E402


def run_folder(root):
    f = root / "paper"
    (f / "F1960").mkdir(parents=True)
    (f / "estimate" / "state").mkdir(parents=True)
    (f / "compress").mkdir()
    (f / MARKER).touch()
    (f / ".fill.vars").write_text("{}")
    (f / "fill.data").write_bytes(b"the committed fill\n" * 50)
    (f / "compress" / "compress.part.1").write_bytes(b"x" * 100)
    (f / "estimate" / "state" / "state.data").write_bytes(b"y" * 100)
    (f / "F1960" / ".shear.vars").write_text('{"Fpaper": "1960"}')
    (f / "F1960" / "shear.csv").write_text("u_mm,S_N\n0.1,5\n")
    (f / "F1960" / "shear.restart.1").write_bytes(b"older" * 20)
    (f / "F1960" / "shear.restart.2").write_bytes(b"newer" * 20)
    os.utime(f / "F1960" / "shear.restart.1", (1e9, 1e9))
    os.utime(f / "F1960" / "shear.restart.2", (2e9, 2e9))
    # a committed state holding that fill
    st = root / "states"
    states.keep(f, "fill", "fill.data", "paper-fill", "test", root=st)
    return f, st


def test_pack_keeps_what_the_resume_needs(tmp_path):
    f, st = run_folder(tmp_path)
    got = {str(p) for p in wip.members(f, st)}
    assert got == {MARKER, ".fill.vars", "F1960/.shear.vars", "F1960/shear.csv", "F1960/shear.restart.2"}
    target, size = wip.pack(f, "paper-F1960", root=tmp_path / "wip", states_root=st)
    assert target.name == "paper-F1960.tar.xz" and size == target.stat().st_size
    new = wip.unpack("paper-F1960", tmp_path / "new", root=tmp_path / "wip")
    assert (new / "F1960" / "shear.restart.2").read_bytes() == b"newer" * 20
    assert (new / "F1960" / "shear.restart.2").stat().st_mtime == 2e9
    assert not (new / "fill.data").exists() and not (new / "estimate").exists()
    with pytest.raises(LaunchError, match="not empty"):
        wip.unpack("paper-F1960", new, root=tmp_path / "wip")


def test_refusals(tmp_path):
    f, st = run_folder(tmp_path)
    with pytest.raises(LaunchError, match="over the"):
        wip.pack(f, "big", root=tmp_path / "wip", limit=10, states_root=st)
    assert not (tmp_path / "wip" / "big.tar.xz").exists()
    (f / MARKER).unlink()
    with pytest.raises(LaunchError, match="not a run folder"):
        wip.pack(f, "x", root=tmp_path / "wip", states_root=st)
    with pytest.raises(LaunchError, match="no "):
        wip.unpack("missing", tmp_path / "n", root=tmp_path / "wip")


def test_drop_patterns_and_a_run_with_only_its_second_checkpoint(tmp_path):
    f, st = run_folder(tmp_path)
    for step in (353000, 519670):
        (f / "F1960" / ("dump.grains.%d" % step)).write_text("dump")
    (f / "F1960" / "shear.restart.1").unlink()    # the newer one alone: kept
    got = {str(p) for p in wip.members(f, st, drop=["dump.*.519670"])}
    assert got == {MARKER, ".fill.vars", "F1960/.shear.vars", "F1960/shear.csv", "F1960/shear.restart.2",
                   "F1960/dump.grains.353000"}


def test_dropped_contact_dumps_need_their_load_path_kept(tmp_path):
    """--drop of a contact dump is refused until tbagspost.loadpath keep has kept its load path
    (loadpath.kept.json beside it): the finished run's load path needs every dump step."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
    from tbagspost import loadpath
    assert wip.KEPT == loadpath.KEPT
    f, st = run_folder(tmp_path)
    for step in (353000, 519670):
        (f / "F1960" / ("dump.contacts.%d" % step)).write_text("dump")
    drop = ["dump.*.353000", "dump.*.519670"]
    with pytest.raises(LaunchError, match="tbagspost.loadpath keep .*F1960"):
        wip.pack(f, "p", root=tmp_path / "wip", states_root=st, drop=drop)
    (f / "F1960" / wip.KEPT).write_text('{"353000": []}')
    with pytest.raises(LaunchError, match="519670"):
        wip.pack(f, "p", root=tmp_path / "wip", states_root=st, drop=drop)
    (f / "F1960" / wip.KEPT).write_text('{"353000": [], "519670": []}')
    target, _ = wip.pack(f, "p", root=tmp_path / "wip", states_root=st, drop=drop)
    assert target.is_file()
    assert wip.pack(f, "q", root=tmp_path / "wip", states_root=st, drop=["dump.grains.*"])[0].is_file()
