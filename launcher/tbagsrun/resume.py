"""Continuing a preset's interrupted runs (./tbags shear PRESET --resume).

A run that finished is kept; a run with a checkpoint continues from it (in.shear: shear.restart.1
and .2, alternating every du_dump of u, the newer first; in.cyclic: cyclic.restart.aK after
amplitude K, the highest first, resumed at amplitude K + 1); any other run starts again. The
resumed deck appends to the run's CSV, after rows the interrupted run may have written past its
checkpoint: merge_rows() keeps, for every stretch of time, the rows written last.
"""
import re
from pathlib import Path

from . import use_postprocess

use_postprocess()
from tbagspost import superseded  # noqa: E402  (the rule the CSV readers apply too)

FINISHED = {"shear": "SHEARED:", "cyclic": "CYCLED:"}    # the deck's last summary line
CSV = {"shear": "shear.csv", "cyclic": "cyclic.csv"}
# s: two rows of the same stretch of steps (their times printed to 1e-7 s) are at the same time;
# rows of different stretches are at least a row's steps apart (over 1e-5 s)
TIME_TOL = 1e-6


def screen_file(folder, deck):
    return Path(folder) / ("screen.%s.txt" % deck)


def finished(folder, deck):
    """Whether the run in folder printed its deck's closing summary line."""
    screen = screen_file(folder, deck)
    return screen.is_file() and any(line.startswith(FINISHED[deck])
                                    for line in screen.read_text(errors="replace").splitlines())


def checkpoints(folder, deck):
    """The run's checkpoints as [(file name, the deck's -var values to resume from it)], the one to
    try first first."""
    folder = Path(folder)
    if deck == "shear":
        files = sorted(folder.glob("shear.restart.[12]"), key=lambda f: f.stat().st_mtime, reverse=True)
        # the resumed run writes its first checkpoint into the other file: a stop while it writes
        # leaves the one it resumed from (after ./tbags wip unpack, the only one)
        return [(f.name, {"restart": f.name, "checkpoint_first": 3 - int(f.name[-1])}) for f in files]
    if deck == "cyclic":
        amps = [(int(m.group(1)), f) for f in folder.glob("cyclic.restart.a*")
                if (m := re.fullmatch(r"cyclic\.restart\.a(\d+)", f.name))]
        return [(f.name, {"restart": f.name, "start": k + 1}) for k, f in sorted(amps, reverse=True)]
    return []


def past_start(runs):
    """Whether every run (objects with .folder and .deck) finished or has a checkpoint: a --resume
    of them needs no new estimate of their cost (./tbags shear paper)."""
    return bool(runs) and all(finished(r.folder, r.deck) or checkpoints(r.folder, r.deck) for r in runs)


# a once-made stage's own checkpoints while it runs (stages.stage_once), by its product: the
# shared compression's (inputs/between_plates.lmp, every compress_every steps), continued with
# -var compress_from
ONCE_CHECKPOINTS = {"compress.restart": ("compress.part.1", "compress.part.2")}


def once_checkpoints(folder, product):
    """[(file name, -var values to continue from it)] of a once-made stage stopped before its
    product, the newer first."""
    files = [Path(folder) / n for n in ONCE_CHECKPOINTS.get(product, ())]
    files = sorted((f for f in files if f.is_file()), key=lambda f: f.stat().st_mtime, reverse=True)
    return [(f.name, {"compress_from": f.name}) for f in files]


def drop_once_checkpoints(folder, product):
    """A once-made stage's checkpoints removed (its product made, or a fresh start)."""
    for n in ONCE_CHECKPOINTS.get(product, ()):
        (Path(folder) / n).unlink(missing_ok=True)


def set_aside(folder, deck):
    """The interrupted run's log and screen output kept as log.<deck>.N and screen.<deck>.txt.N
    (N the first number free for both), for the resumed run's own."""
    folder = Path(folder)
    files = [folder / ("log." + deck), screen_file(folder, deck)]
    n = 1
    while any(Path("%s.%d" % (f, n)).exists() for f in files):
        n += 1
    for f in files:
        if f.is_file():
            f.rename("%s.%d" % (f, n))


def forget(folder, deck):
    """A run starting again (with no checkpoint): its earlier CSV and dumps removed (the figures
    must not read them)."""
    folder = Path(folder)
    for f in [folder / CSV[deck]] + list(folder.glob("dump.*")):
        f.unlink(missing_ok=True)


def merge_rows(lines):
    """A CSV's lines (a header, comment lines, rows whose first field is the time) with the rows
    of every resumed stretch in place of those the interrupted run wrote for the same times
    (tbagspost.superseded: a row is dropped when a later row is at its time or earlier). A
    comment line repeated (the resumed deck's title) is kept once."""
    out, seen, times = [], set(), []
    for line in lines:
        if not line.strip():
            continue
        try:
            times.append(float(line.split(",", 1)[0]))
        except ValueError:    # the header or a comment
            if line not in seen:
                seen.add(line)
                out.append((False, line))
            continue
        out.append((True, line))
    drop = iter(superseded(times, TIME_TOL))
    return [line for row, line in out if not (row and next(drop))]


def merge_csv(path):
    path = Path(path)
    if path.is_file():
        path.write_text("\n".join(merge_rows(path.read_text().splitlines())) + "\n")
