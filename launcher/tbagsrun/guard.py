"""What a preset call would do to its output folder, decided before any stage runs.

Every stage of a call is planned first (shear.plan: folder, deck, variables, product). A stage
made once (bag, fill, the shared compression) is reused when an earlier call made its product
with the same variables; a run is new when its folder holds none of its files. Anything else
would remove or rewrite a file of an earlier run: without --resume a run that is there, with
--resume a stage made with other variables. check() refuses such a call with what to do
(--resume, --overwrite, or another --out) before it touches anything; with --overwrite the
folder is emptied first (never a folder of the user's: the marker rule of stages.fresh_dir).
"""
from dataclasses import dataclass
from pathlib import Path

from . import LaunchError, resume as resumed
from .stages import MARKER, fresh_dir, vars_key


@dataclass
class Stage:
    folder: Path
    deck: str
    variables: dict
    product: str = ""    # made once (stage_once): the file it makes; "" for a run (stage_run)


def run_files(folder, deck):
    """The files of a run of `deck` in folder: its stamp, output, checkpoints, log and dumps."""
    folder = Path(folder)
    names = [".%s.vars" % deck, resumed.CSV.get(deck, deck + ".csv"), "log." + deck,
             resumed.screen_file(folder, deck).name]
    found = [folder / n for n in names if (folder / n).exists()]
    found += [folder / n for n, _ in resumed.checkpoints(folder, deck)]
    return found + sorted(folder.glob("dump.*"))


def conflicts(stages, resume, origin=""):
    """[(stage, why)]: the stages that would remove or rewrite an earlier call's files."""
    out = []
    for s in stages:
        stamp = Path(s.folder) / (".%s.vars" % s.deck)
        said = stamp.read_text() if stamp.is_file() else None
        if s.product:
            if (Path(s.folder) / s.product).is_file() and said != vars_key(s.variables):
                out.append((s, "%s was made with other -var values" % (Path(s.folder) / s.product)))
            continue
        files = run_files(s.folder, s.deck)
        if not files:
            continue
        if not resume:
            out.append((s, "%s holds an earlier %s run (%s)" % (s.folder, s.deck,
                                                              ", ".join(f.name for f in files[:4]))))
        elif said != vars_key(s.variables) + origin:
            out.append((s, "%s was run with other -var values or another fill" % s.folder))
    return out


def check(out, groups, resume, overwrite):
    """Decide before anything runs: refuse a call that would remove or rewrite an earlier run's
    files (LaunchError naming them and the way on), or with overwrite empty `out` first.
    groups: [(stages, origin)], a realization's stages and its fill's stamp each."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise LaunchError("shear: --out %s is a file, not a folder; choose another --out" % out)
    if overwrite:
        make(out, empty=True)
        return
    found = [c for stages, origin in groups for c in conflicts(stages, resume, origin)]
    if found:
        lines = "\n".join("  " + why for _, why in found[:6])
        way = ("--overwrite to start again from nothing (it removes %s's contents), or another --out"
               % out) if resume else ("--resume to continue or keep it (same preset and -var values), "
                                      "--overwrite to start again (it removes %s's contents), or "
                                      "another --out" % out)
        raise LaunchError("shear: %s holds an earlier call's runs that this call would %s:\n%s\n"
                          "Nothing was changed. Give %s." % (out, "rewrite" if resume else "remove",
                                                              lines, way))
    if out.is_dir() and any(out.iterdir()) and not (out / MARKER).exists():
        raise LaunchError("shear: %s is not empty and was not made by ./tbags shear; choose another "
                          "--out" % out)
    make(out)


def make(out, empty=False):
    """The output folder and its marker (empty: emptied first, stages.fresh_dir); one line naming
    the path and the reason if it cannot be made (a path under /proc, a read-only disk, a file in
    the way)."""
    out = Path(out)
    try:
        if empty:
            fresh_dir(out)
        else:
            out.mkdir(parents=True, exist_ok=True)
            (out / MARKER).touch()
    except OSError as e:
        raise LaunchError("shear: cannot write the outputs to %s: %s; choose another --out"
                          % (out, e.strerror or e))
