"""Set-up paths that must fail with a one-line explanation, not a stack trace: a tarball with
the wrong sha256, a LAMMPS binary without a needed package, launcher misuse."""
import os
import re
import stat
import subprocess
from pathlib import Path

import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
BUILD = Path(os.environ.get("TBAGS_BUILD", ROOT / "build"))


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600, **kw)


@pytest.mark.parametrize("script,tarball,var", [
    ("fetch-lammps.sh", "lammps_20250204+dfsg.1.orig.tar.xz", "LAMMPS_TARBALL"),
    ("fetch-liggghts.sh", "liggghts_3.8.0+repack1.orig.tar.xz", "LIGGGHTS_TARBALL")])
def test_wrong_sha256_is_refused(tmp_path, script, tarball, var):
    bogus = tmp_path / tarball
    bogus.write_bytes(b"not the source")
    env = dict(os.environ, **{var: str(bogus)})
    r = run(["bash", str(ROOT / "cmake" / script), str(tmp_path / "cache")], env=env)
    assert r.returncode != 0
    assert "sha256 mismatch" in r.stderr and "refusing to build" in r.stderr
    assert not (tmp_path / "cache" / bogus.name).exists()    # the bad file is not kept


def lammps_source_dir():
    env_file = BUILD / "tbags-env.sh"
    if not env_file.exists():
        pytest.skip("no configured build")
    for line in env_file.read_text().splitlines():
        if line.startswith("LAMMPS_SOURCE_DIR="):
            return line.split("=", 1)[1].strip("'")
    pytest.skip("no LAMMPS_SOURCE_DIR in tbags-env.sh")


@pytest.mark.parametrize("packages,missing", [("GRANULAR MOLECULE BPM", "PLUGIN"),
                                               ("PLUGIN GRANULAR MOLECULE", "BPM")])
def test_lammps_without_package_is_refused(tmp_path, packages, missing):
    fake = tmp_path / "lmp"
    fake.write_text("#!/bin/sh\nprintf 'Large-scale Atomic/Molecular Massively Parallel Simulator\\n\\n"
                    "Installed packages:\\n\\n%s\\n\\nList of individual style options\\n'\n" % packages)
    fake.chmod(fake.stat().st_mode | stat.S_IEXEC)
    r = run(["cmake", "-S", str(ROOT), "-B", str(tmp_path / "b"), "-DTBAGS_TESTS=OFF",
             "-DLAMMPS_SOURCE_DIR=" + lammps_source_dir(), "-DLAMMPS_EXECUTABLE=" + str(fake)])
    assert r.returncode != 0
    # CMake wraps a long message (a long temporary path moves the break): compare words
    assert "was built without the %s package" % missing in " ".join(r.stderr.split())


def test_source_tree_that_is_not_lammps(tmp_path):
    r = run(["cmake", "-S", str(ROOT), "-B", str(tmp_path / "b"), "-DTBAGS_TESTS=OFF",
             "-DLAMMPS_SOURCE_DIR=" + str(tmp_path)])
    assert r.returncode != 0 and "is not a LAMMPS source tree" in r.stderr


def test_launcher_help_and_unknown_command():
    r = run([str(ROOT / "tbags"), "help"])
    assert r.returncode == 0 and "shear" in r.stdout and "test" in r.stdout
    r = run([str(ROOT / "tbags"), "frobnicate"])
    assert r.returncode != 0 and "unknown command 'frobnicate'" in r.stderr


def test_launcher_run_missing_deck():
    r = run([str(ROOT / "tbags"), "run", "/nonexistent/in.deck"])
    assert r.returncode != 0 and "no deck" in r.stderr


def test_launcher_runs_a_deck_with_the_plugin(tmp_path):
    if not (BUILD / "tbags-env.sh").exists():
        pytest.skip("no configured build")
    deck = tmp_path / "in.list"
    deck.write_text("plugin list\nregion box block 0 1 0 1 0 1\ncreate_box 1 box\n")
    r = run([str(ROOT / "tbags"), "run", str(deck)], env=dict(os.environ, TBAGS_BUILD_DIR=str(BUILD)))
    assert r.returncode == 0 and "gran/hertz/rolling" in r.stdout
    r = run([str(ROOT / "tbags"), "run", str(deck), "-np", "2"], env=dict(os.environ, TBAGS_BUILD_DIR=str(BUILD)))
    grid = re.search(r"(\d+) by (\d+) by (\d+) MPI processor grid", r.stdout)
    assert r.returncode == 0 and grid and eval("*".join(grid.groups())) == 2


def test_launcher_shear_presets_and_bad_arguments():
    """Unknown presets and bad -np stop before any set-up, with a message naming the choices."""
    r = run([str(ROOT / "tbags"), "shear", "papr"])
    assert r.returncode != 0 and "unknown preset 'papr'" in r.stderr and "trends" in r.stderr
    r = run([str(ROOT / "tbags"), "shear", "demo", "-np", "zero"])
    assert r.returncode != 0 and "-np needs a positive number" in r.stderr
    r = run([str(ROOT / "tbags"), "shear", "trends", "--estimate"])
    assert r.returncode != 0 and "--estimate is for the paper preset" in r.stderr
    r = run([str(ROOT / "tbags"), "shear", "--help"])
    assert r.returncode == 0 and all(p in r.stdout for p in ("demo", "trends", "quasistatic", "paper"))


@pytest.mark.parametrize("sizes", ["BIGBIG", "SMALLSMALL", "SMALLBIG"])
def test_plugin_takes_the_integer_sizes_of_lammps(tmp_path, sizes):
    """A bigbig (or smallsmall) LAMMPS gets a plugin built for it, not LAMMPS's default smallbig:
    the sizes come from the binary's own -h (its -DLAMMPS_<SIZES> line)."""
    fake = tmp_path / "lmp"
    fake.write_text("#!/bin/sh\nprintf 'Large-scale Atomic/Molecular Massively Parallel Simulator\\n\\n"
                    "-DLAMMPS_GZIP\\n-DLAMMPS_%s\\n\\nInstalled packages:\\n\\nBPM GRANULAR MOLECULE PLUGIN\\n\\n"
                    "List of individual style options\\n'\n" % sizes)
    fake.chmod(fake.stat().st_mode | stat.S_IEXEC)
    r = run(["cmake", "-S", str(ROOT), "-B", str(tmp_path / "b"), "-DTBAGS_TESTS=OFF",
             "-DLAMMPS_SOURCE_DIR=" + lammps_source_dir(), "-DLAMMPS_EXECUTABLE=" + str(fake)])
    assert r.returncode == 0, r.stderr
    assert "integer sizes %s" % sizes.lower() in r.stdout
    flags = (tmp_path / "b" / "CMakeFiles" / "tbagsplugin.dir" / "flags.make").read_text()
    defines = set(re.findall(r"-DLAMMPS_(SMALLBIG|BIGBIG|SMALLSMALL)\b", flags))
    assert defines == {sizes}
