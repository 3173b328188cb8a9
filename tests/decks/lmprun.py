"""Run LAMMPS decks for the tests: serial or through mpirun, with the tbags plugin path set.

Every deck test imports this module. The environment comes from ctest (TBAGS_LMP,
LAMMPS_PLUGIN_PATH); run through `./tbags test` or `ctest` rather than by hand.
"""
import os
import subprocess
import textwrap
from pathlib import Path

import numpy as np

LMP = os.environ.get("TBAGS_LMP", "")
ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
PLUGIN = Path(os.environ.get("LAMMPS_PLUGIN_PATH", "")) / "tbagsplugin.so"


class LammpsResult:
    def __init__(self, proc, workdir):
        self.returncode = proc.returncode
        self.output = proc.stdout + proc.stderr
        self.workdir = Path(workdir)

    def check(self):
        if self.returncode != 0:
            raise AssertionError("LAMMPS failed (rc=%d):\n%s" % (self.returncode, self.output[-4000:]))
        return self

    def error_line(self):
        """The first 'ERROR' line LAMMPS printed, or ''."""
        for line in self.output.splitlines():
            if "ERROR" in line:
                return line
        return ""


def run(deck, workdir, np_ranks=1, variables=None, args=(), plugin_path=True, timeout=1200):
    """Run `deck` (text or path) in workdir; returns a LammpsResult (not checked)."""
    if not LMP:
        raise RuntimeError("TBAGS_LMP is not set: run the tests with ./tbags test or ctest")
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    if isinstance(deck, Path):
        deck_file = deck
    else:
        deck_file = workdir / "in.test"
        deck_file.write_text(textwrap.dedent(deck))
    cmd = [LMP, "-nocite", "-log", str(workdir / "log.lammps"), "-in", str(deck_file)]
    for k, v in (variables or {}).items():
        cmd += ["-var", str(k), str(v)]
    cmd += list(args)
    if np_ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_ranks)] + cmd
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", "1")
    if not plugin_path:
        env.pop("LAMMPS_PLUGIN_PATH", None)
    proc = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True, timeout=timeout)
    return LammpsResult(proc, workdir)


def read_dump(path):
    """Read a sorted 'write_dump ... custom' text file: returns (columns, array)."""
    lines = Path(path).read_text().splitlines()
    for k, line in enumerate(lines):
        if line.startswith("ITEM: ATOMS"):
            cols = line.split()[2:]
            data = np.array([[float(x) for x in l.split()] for l in lines[k + 1:] if l.strip()])
            return cols, data
    raise ValueError("no ITEM: ATOMS in %s" % path)


def column(path, name):
    cols, data = read_dump(path)
    return data[:, cols.index(name)]


def max_rel_diff(a, b):
    """Largest component difference relative to the largest magnitude in b."""
    a, b = np.asarray(a), np.asarray(b)
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))
