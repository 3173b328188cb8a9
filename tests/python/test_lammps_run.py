"""tbagsrun.lammps.run gives every run its own Open MPI session directory: Open MPI 4.1's isolated
singletons share one (<tmp>/ompi.<host>.<uid>/jf.0), and one that ends removes it under another
that starts (4 of 300 staggered 1-rank starts failed in orte_init on this machine)."""
import os
import stat
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "launcher"))
from tbagsrun import lammps  # noqa: E402

FAKE = """#!/bin/sh
# stands for lmp: reports the session base it was given and whether it exists
echo "base=$OMPI_MCA_orte_tmpdir_base"
test -d "$OMPI_MCA_orte_tmpdir_base" && echo exists
"""


@pytest.fixture
def fake_lmp(tmp_path, monkeypatch):
    exe = tmp_path / "lmp"
    exe.write_text(FAKE)
    exe.chmod(exe.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setenv("TBAGS_LMP", str(exe))
    monkeypatch.delenv(lammps.SESSION_BASE, raising=False)
    return exe


def base(result):
    return next(line[5:] for line in result.output.splitlines() if line.startswith("base="))


def test_each_run_has_its_own_session_directory_removed_after(tmp_path, fake_lmp):
    a = lammps.run(tmp_path / "in.x", tmp_path / "a")
    b = lammps.run(tmp_path / "in.x", tmp_path / "b", screen="screen.txt")
    assert "exists" in a.output and "exists" in b.output
    assert base(a) and base(b) and base(a) != base(b)
    assert not os.path.exists(base(a)) and not os.path.exists(base(b))


def test_the_users_session_base_wins(tmp_path, fake_lmp, monkeypatch):
    mine = tmp_path / "mine"
    mine.mkdir()
    monkeypatch.setenv(lammps.SESSION_BASE, str(mine))
    assert base(lammps.run(tmp_path / "in.x", tmp_path / "a")) == str(mine)
    assert mine.is_dir()
