"""A fresh machine: /usr/bin/python3 is there, Debian's numpy and the rest are not. Every ./tbags
command installs its packages before any Python of ours runs, and the launcher's modules import
with the standard library alone (they are what runs before and around the set-up)."""
import os
import stat
import subprocess
from pathlib import Path

import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
LAUNCHER = ROOT / "launcher"


def launcher_modules():
    """Every module of launcher/tbagsrun (its __main__ only runs cli.main)."""
    return sorted("tbagsrun." + p.stem for p in (LAUNCHER / "tbagsrun").glob("*.py")
                  if p.stem not in ("__init__", "__main__"))


def test_launcher_modules_import_without_debian_packages():
    """-I -S: no site-packages, no dist-packages (where Debian's numpy lives), no PYTHONPATH.
    Failed on be13c81: estimate.py imported tbagspost.run, hence numpy, at import time."""
    code = ("import importlib, sys\nsys.path[:0] = [%r]\nfor m in %r:\n    importlib.import_module(m)\n"
            "print('imported', len(%r))" % (str(LAUNCHER), launcher_modules(), launcher_modules()))
    r = subprocess.run(["/usr/bin/python3", "-I", "-S", "-c", code], capture_output=True, text=True,
                       timeout=60)
    assert r.returncode == 0, "a launcher module needs a package at import time:\n" + r.stderr
    assert "imported %d" % len(launcher_modules()) in r.stdout


def test_the_check_itself_sees_a_missing_package():
    """The same -I -S run refuses numpy: the test above would catch a module that imports it."""
    r = subprocess.run(["/usr/bin/python3", "-I", "-S", "-c", "import numpy"], capture_output=True,
                       text=True, timeout=60)
    assert r.returncode != 0 and "No module named 'numpy'" in r.stderr


def stand_ins(tmp_path):
    """dpkg/dpkg-query that know no package, an apt-get that records its calls and fails to
    install, a sudo that runs its command: a bare machine whose installation fails."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    calls = tmp_path / "apt-calls.txt"
    scripts = {
        "dpkg": "#!/bin/sh\nexit 1\n",
        "dpkg-query": "#!/bin/sh\necho \"dpkg-query: no packages found matching $*\" >&2\nexit 1\n",
        "apt-get": "#!/bin/sh\necho \"apt-get $*\" >> %s\n"
                   "case \"$1\" in update) exit 0 ;; *) echo 'E: stand-in: no network' >&2; exit 100 ;; esac\n"
                   % calls,
        "sudo": "#!/bin/sh\nexec \"$@\"\n",
    }
    for name, text in scripts.items():
        f = bin_dir / name
        f.write_text(text)
        f.chmod(f.stat().st_mode | stat.S_IEXEC)
    return bin_dir, calls


COMMANDS = [["shear"], ["shear", "trends", "--out", "OUT"], ["run", str(ROOT / "inputs" / "in.bag")],
            ["plot", "OUT"], ["calibrate"], ["bench"], ["setup"], ["test"]]


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: "-".join(c[:2]).replace("/", "_")[:30])
def test_every_command_installs_before_any_python(tmp_path, command):
    """With every package missing and apt-get failing, each command asks apt-get to install and
    stops on its failure with one line, before any Python runs (PYTHONVERBOSE would print every
    import of a Python that started). Failed on be13c81: shear, plot, run and calibrate started
    Python first (shear: ModuleNotFoundError: numpy on a fresh machine)."""
    bin_dir, calls = stand_ins(tmp_path)
    out = tmp_path / "out"
    env = dict(os.environ, PATH="%s:%s" % (bin_dir, os.environ["PATH"]), PYTHONVERBOSE="1",
               TBAGS_CACHE=str(tmp_path / "cache"), TBAGS_BUILD_DIR=str(tmp_path / "build"))
    env.pop("TBAGS_CMAKE_ARGS", None)
    cmd = [str(ROOT / "tbags")] + [str(out) if w == "OUT" else w for w in command]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=120, env=env, cwd=tmp_path)
    recorded = calls.read_text() if calls.exists() else ""
    assert "apt-get install" in recorded, "no installation asked for:\n" + r.stderr[-2000:]
    assert "installing Debian packages" in r.stderr and "python3-numpy" in r.stderr
    assert r.returncode != 0 and "apt-get install failed" in r.stderr
    assert "import " not in r.stderr and "Traceback" not in r.stderr, \
        "Python ran before the packages were installed:\n" + r.stderr[-2000:]
    assert not out.exists() and not (tmp_path / "build").exists()    # nothing made


@pytest.mark.parametrize("command", [["shear", "--help"], ["help"]])
def test_help_needs_no_packages(tmp_path, command):
    """The help texts come from the standard library: no installation for them."""
    bin_dir, calls = stand_ins(tmp_path)
    env = dict(os.environ, PATH="%s:%s" % (bin_dir, os.environ["PATH"]))
    r = subprocess.run([str(ROOT / "tbags")] + command, capture_output=True, text=True, timeout=60, env=env)
    assert r.returncode == 0 and "shear" in r.stdout and not calls.exists()
