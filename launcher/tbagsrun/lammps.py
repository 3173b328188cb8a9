"""One way to run LAMMPS with the tbags plugin (or LIGGGHTS with our styles compiled in), shared
by the launcher (shear presets), the deck tests, the benchmark and the calibration.

The environment says where things are: TBAGS_LMP (the lmp binary) and LAMMPS_PLUGIN_PATH (the
folder of tbagsplugin.so, which LAMMPS loads at start), as ./tbags sets them from the build's
tbags-env.sh; TBAGS_LIGGGHTS the liggghts binary (engine="liggghts"). More than one rank runs
through mpirun (--oversubscribe; --allow-run-as-root when run as root, as Open MPI requires).
Decks find the repository's files through ${tbags}, which the runner sets to repo_path().
"""
import hashlib
import os
import subprocess
import tempfile
from pathlib import Path

from . import ROOT, LaunchError


def executable():
    """The lmp binary of TBAGS_LMP; stops with what to do when it is missing."""
    lmp = os.environ.get("TBAGS_LMP", "")
    if not lmp:
        raise LaunchError("TBAGS_LMP is not set: run through ./tbags (which reads the build's "
                          "tbags-env.sh), or export TBAGS_LMP=/path/to/lmp and "
                          "LAMMPS_PLUGIN_PATH=/path/to/build/plugin")
    if not (Path(lmp).is_file() and os.access(lmp, os.X_OK)):
        raise LaunchError("TBAGS_LMP=%s is not an executable file" % lmp)
    return lmp


def liggghts_executable():
    """The liggghts binary of TBAGS_LIGGGHTS (built by ./tbags setup); stops when it is missing."""
    exe = os.environ.get("TBAGS_LIGGGHTS", "")
    if not (exe and Path(exe).is_file() and os.access(exe, os.X_OK)):
        raise LaunchError("TBAGS_LIGGGHTS=%r is not the liggghts binary: run './tbags setup' "
                          "(it builds LIGGGHTS with our styles) or run through ./tbags" % exe)
    return exe


def plugin_file():
    """tbagsplugin.so in LAMMPS_PLUGIN_PATH; stops when it is not there."""
    folder = os.environ.get("LAMMPS_PLUGIN_PATH", "")
    plugin = Path(folder) / "tbagsplugin.so"
    if not folder or not plugin.is_file():
        raise LaunchError("LAMMPS_PLUGIN_PATH=%r has no tbagsplugin.so: run './tbags setup'" % folder)
    return plugin


def mpi_prefix(ranks):
    """The mpirun words for `ranks` ranks (none for one)."""
    if ranks <= 1:
        return []
    root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    return ["mpirun"] + root + ["--oversubscribe", "-np", str(ranks)]


def repo_path():
    """The repository as the decks see it (-var tbags). They include its files as
    ${tbags}/inputs/..., and LAMMPS splits a command at white space after substituting (and
    substitutes nothing inside quotes), so a repository whose path has a space is reached through
    a link without one, in the build cache (the same link for the same repository)."""
    if not any(c.isspace() for c in str(ROOT)):
        return ROOT
    cache = Path(os.environ.get("TBAGS_CACHE") or
                 Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "tbags")
    link = cache / ("repo-" + hashlib.sha256(str(ROOT).encode()).hexdigest()[:10])
    if any(c.isspace() for c in str(link)):
        raise LaunchError("the repository's path %r has a space and so has the cache %s: set "
                          "TBAGS_CACHE to a folder without one" % (str(ROOT), cache))
    if not link.is_symlink():
        cache.mkdir(parents=True, exist_ok=True)
        link.symlink_to(ROOT, target_is_directory=True)
    elif link.resolve() != ROOT.resolve():
        raise LaunchError("%s points at %s, not at %s: remove it" % (link, link.resolve(), ROOT))
    return link


def command(deck, ranks=1, variables=None, args=(), log="log.lammps", engine="lammps"):
    """The command line: [mpirun ...] lmp -nocite -log LOG -in DECK -var tbags REPO -var k v ...
    (engine "liggghts": the liggghts binary, which has no -nocite). A variable's value may be a
    list (an index variable of several values)."""
    if engine == "liggghts":
        head = [liggghts_executable()]
    elif engine == "lammps":
        head = [executable(), "-nocite"]
    else:
        raise LaunchError("unknown engine %r: lammps or liggghts" % engine)
    cmd = mpi_prefix(ranks) + head + ["-log", str(log), "-in", str(deck)]
    variables = dict(variables or {})
    variables.setdefault("tbags", repo_path())
    for name, value in variables.items():
        values = value if isinstance(value, (list, tuple)) else [value]
        cmd += ["-var", str(name)] + [str(v) for v in values]
    return cmd + [str(a) for a in args]


class Result:
    """A finished run: return code, its screen output, the folder it ran in."""

    def __init__(self, returncode, output, workdir):
        self.returncode = returncode
        self.output = output
        self.workdir = Path(workdir)

    def error_line(self):
        """The first line with 'ERROR' LAMMPS printed, or ''."""
        return next((line for line in self.output.splitlines() if "ERROR" in line), "")

    def check(self, what="LAMMPS"):
        """The result itself, or LaunchError with the first ERROR line (else the output's end)."""
        if self.returncode != 0:
            raise LaunchError("%s failed in %s (rc %d):\n%s" % (
                what, self.workdir, self.returncode, self.error_line() or self.output[-4000:]))
        return self


# Open MPI's start-up, set unless the user's environment says otherwise: a rank started without
# mpirun needs no daemon (ess_singleton_isolated), and the shared-memory transport (pml ob1) needs
# no UCX, whose start-up measures the CPU's clock by sleeping. Measured on 2 cores: a LAMMPS start
# takes 0.09 s instead of 0.64 s (a deck test's bad-input case is mostly start-up)
OPEN_MPI_START = {"OMPI_MCA_ess_singleton_isolated": "1", "OMPI_MCA_pml": "ob1"}


def quick_start(env):
    """env with one OpenMP thread and OPEN_MPI_START, where env does not set them already."""
    for name, value in dict(OPEN_MPI_START, OMP_NUM_THREADS="1").items():
        env.setdefault(name, value)
    return env


# Open MPI 4.1's isolated singletons are all job [0,1] and share one session directory
# (<tmp>/ompi.<host>.<uid>/jf.0): one that ends removes it while another starts, which then stops
# in orte_init ("A call to mkdir was unable to create the desired directory", session_dir.c line
# 107). Measured: 4 of 300 staggered 1-rank starts failed so, 0 of 300 with a directory each.
SESSION_BASE = "OMPI_MCA_orte_tmpdir_base"


def run(deck, workdir, ranks=1, variables=None, args=(), log="log.lammps", screen=None,
        timeout=None, plugin=True, engine="lammps"):
    """Run `deck` (a path) in `workdir` (made if missing) and return its Result, unchecked.
    screen: a file for the screen output, written as the run goes (the output is read back from
    it); else kept in memory. plugin=False: without LAMMPS_PLUGIN_PATH (stock LAMMPS alone); a
    folder: the plugin built there (another build, for benchmarks). engine: as command()."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    cmd = command(deck, ranks, variables, args, log, engine)
    env = quick_start(dict(os.environ))
    if plugin is False:
        env.pop("LAMMPS_PLUGIN_PATH", None)
    elif plugin is not True:
        env["LAMMPS_PLUGIN_PATH"] = str(plugin)
    with tempfile.TemporaryDirectory(prefix="tbags-mpi.") as session:
        env.setdefault(SESSION_BASE, session)    # the run's own Open MPI session directory
        if screen is None:
            # (an engine may print stray bytes, e.g. LIGGGHTS after some errors: never a decode error)
            proc = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True,
                                  errors="replace", timeout=timeout)
            return Result(proc.returncode, proc.stdout + proc.stderr, workdir)
        screen = workdir / screen
        with open(screen, "w") as out:
            proc = subprocess.run(cmd, cwd=workdir, env=env, stdout=out, stderr=subprocess.STDOUT,
                                  timeout=timeout)
    return Result(proc.returncode, screen.read_text(errors="replace"), workdir)
