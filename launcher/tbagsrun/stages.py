"""One stage of a preset: a LAMMPS deck run in its folder under mpirun, its summary lines said,
its progress on the console (progress.py); a stage made once and reused (stage_once), a preset's
run stamped with its variables and continued on --resume (stage_run, resume.py); the folders the
launcher makes (fresh_dir) and the Python it runs (run_python, run_module).
"""
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from . import ROOT, LaunchError, lammps, progress, resume as resumed, states

# the lines of a stage's screen output that the launcher repeats (the decks' summaries)
SUMMARY = re.compile(r"^(BAG|FILL|FABRIC|PRESSED|TIMESTEP|INERTIAL|COMPRESSION PART|COMPRESSED|SHEARED|CYCLIC|CYCLED|AMPLITUDE [0-9]+ DONE)")
MARKER = ".tbags-run"    # in every output folder the launcher made (so --out never clears a user's)
PROGRESS_DEFAULT = 30    # s between a stage's progress lines at least (--progress; 0: none; progress.py)
PROGRESS_EVERY = PROGRESS_DEFAULT


def post_env():
    """The environment with postprocess/ (tbagspost) first on PYTHONPATH."""
    return dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT / "postprocess")] + ([os.environ["PYTHONPATH"]] if os.environ.get("PYTHONPATH") else [])))


def run_python(args, stdout=None):
    """Debian's Python on a module or script of the repository, postprocess/ on its path."""
    proc = subprocess.run([sys.executable] + [str(a) for a in args], env=post_env(), stdout=stdout,
                          stderr=subprocess.PIPE, text=True)
    return proc.returncode == 0, proc.stderr


def run_module(name, args, say):
    """tbagspost.<name> (a check or a projection) on args; says its output; (succeeded, stdout)."""
    proc = subprocess.run([sys.executable, "-m", "tbagspost." + name] + [str(a) for a in args],
                          env=post_env(), capture_output=True, text=True)
    for line in (proc.stdout + proc.stderr).splitlines():
        say(line)
    return proc.returncode == 0, proc.stdout


def stage(folder, deck, ranks, variables, say):
    """inputs/in.<deck> in folder with `ranks` ranks; says its summary lines; stops if it fails.
    Its progress goes to the console every PROGRESS_EVERY seconds (progress.py)."""
    say("tbags shear: %s in %s ..." % (deck, folder))
    screen = resumed.screen_file(folder, deck)
    with progress.Watch(screen, "%s in %s" % (deck, folder), PROGRESS_EVERY,
                        lambda line: print(line, flush=True)):
        res = lammps.run(ROOT / "inputs" / ("in." + deck), folder, ranks, variables,
                         log="log." + deck, screen=screen.name)
    report(res, "the %s stage" % deck, Path(folder) / ("log." + deck), say)


def report(res, what, log, say):
    """A finished stage: its summary lines said, or LaunchError with its ERROR lines (else its
    output's end) when it failed."""
    lines = res.output.splitlines()
    if res.returncode != 0:
        errors = [line for line in lines if "ERROR" in line] or lines[-20:]
        raise LaunchError("\n".join(errors) + "\nshear: %s failed (see %s)" % (what, log))
    for line in lines:
        if SUMMARY.match(line):
            say("  " + shear_w(line, Path(log).parent))


def shear_w(line, folder):
    """A SHEARED line with w from the start of shear too (the figures' w: the CSV's u = 0 row's
    w subtracted; the deck's w counts from the start of compression)."""
    m = re.search(r" w (\S+) mm from the start of compression", line)
    csv = Path(folder) / "shear.csv"
    if not (line.startswith("SHEARED") and m and csv.is_file()):
        return line
    lines = csv.read_text().splitlines()
    rows = [r for r in lines if r[:1].isdigit()]
    head = next((r for r in lines if r.startswith("time_s")), "").split(",")
    if not rows or "w_mm" not in head:
        return line
    w0 = float(rows[0].split(",")[head.index("w_mm")])
    return line.replace(m.group(0), "%s, %.3f mm from the start of shear" % (m.group(0), float(m.group(1)) - w0))


def fresh_dir(folder):
    """An empty folder for a run's outputs. A non-empty folder outside runs/ must be one the
    launcher made (its marker), so that --out never clears a folder of the user's."""
    folder = Path(folder)
    if folder.is_dir() and any(folder.iterdir()) and not (folder / MARKER).exists() and \
            (ROOT / "runs") not in folder.resolve().parents:
        raise LaunchError("shear: %s is not empty and was not made by ./tbags shear; choose another "
                          "--out" % folder)
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    (folder / MARKER).touch()


def stage_once(folder, deck, ranks, variables, say, product):
    """stage(), unless an earlier call made `product` in folder with the same variables (a stamp
    beside it) or a committed state (states.py) holds it, so that a long stage that finished is
    not run again. A stage stopped before its product continues from its own checkpoints (the
    shared compression's, resume.once_checkpoints) when its stamp, written before it ran, is
    this call's."""
    folder = Path(folder)
    stamp = folder / (".%s.vars" % deck)
    key = vars_key(variables)
    if not (folder / product).is_file():
        states.restore(folder, deck, key, product, say)
    stamped = stamp.is_file() and stamp.read_text() == key
    if (folder / product).is_file() and stamped:
        say("tbags shear: %s in %s: done before, reused" % (deck, folder))
        return
    tries = resumed.once_checkpoints(folder, product) if stamped else []
    if from_checkpoints(folder, deck, ranks, variables, say, tries, "continuing from its checkpoint"):
        resumed.drop_once_checkpoints(folder, product)
        return
    (folder / product).unlink(missing_ok=True)
    resumed.drop_once_checkpoints(folder, product)
    folder.mkdir(parents=True, exist_ok=True)
    stamp.write_text(key)    # before the run: its checkpoints belong to these variables
    stage(folder, deck, ranks, variables, say)
    resumed.drop_once_checkpoints(folder, product)


def from_checkpoints(folder, deck, ranks, variables, say, tries, doing):
    """stage() continued from the first of tries [(checkpoint, its -var values)] that works (the
    interrupted run's log and screen set aside first); False when there is none. The last one's
    failure stops the launcher."""
    for k, (name, extra) in enumerate(tries):
        say("tbags shear: %s in %s: %s %s" % (deck, folder, doing, name))
        resumed.set_aside(folder, deck)
        try:
            stage(folder, deck, ranks, dict(variables, **extra), say)
        except LaunchError as e:
            if k + 1 == len(tries):
                raise
            say("%s\n  (from %s it failed; the older checkpoint next)" % (e, name))
            continue
        return True
    return False


def vars_key(variables):
    return json.dumps({k: str(v) for k, v in variables.items()}, sort_keys=True)


def stage_run(folder, deck, ranks, variables, say, resume=False, origin=""):
    """One of a preset's runs (stage()), its variables stamped beside it. resume: a run that
    finished before with the same variables is kept, an interrupted one continues from its
    checkpoint (resume.py; the older checkpoint if the newer does not read), else it starts
    again; a run made with other variables (or another origin: its fill's) is not resumed. A
    run's checkpoints are never removed to start it again: that stops with what to do."""
    folder = Path(folder)
    stamp = folder / (".%s.vars" % deck)
    key = vars_key(variables) + origin
    if resume and stamp.is_file():
        if stamp.read_text() != key:
            raise LaunchError("shear: --resume: %s was run with other -var values or another fill "
                              "(%s); run without --resume to start it again" % (folder, stamp))
        if resumed.finished(folder, deck):
            say("tbags shear: %s in %s: finished before, kept" % (deck, folder))
            return
        if from_checkpoints(folder, deck, ranks, variables, say, resumed.checkpoints(folder, deck), "resuming from"):
            resumed.merge_csv(folder / resumed.CSV[deck])
            return
    kept = [name for name, _ in resumed.checkpoints(folder, deck)]
    if kept:    # hours of a run are not removed unasked
        raise LaunchError("shear: %s holds an earlier run's checkpoints (%s): %s, or remove them to "
                          "run it again" % (folder, ", ".join(kept), "they have no stamp of their "
                          "-var values to resume from" if resume else "--resume continues or keeps it"))
    resumed.forget(folder, deck)
    folder.mkdir(parents=True, exist_ok=True)
    stamp.write_text(key)    # before the run: its checkpoints belong to these variables
    stage(folder, deck, ranks, variables, say)


def made_part(part_stage, where):
    """The loads' shared part of the compression made once (stage_once's arguments, part_stage);
    its checkpoint's path from the folder `where` (a run's, for -var compress_from)."""
    stage_once(*part_stage)
    return os.path.relpath(Path(part_stage[0]) / part_stage[-1], where)
