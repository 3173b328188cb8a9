"""An unfinished run carried to the next machine: a preset's output folder packed into one
xz-compressed tar under states/wip/ (committed; the issue's limit 50 MB), unpacked into an empty
folder that `./tbags shear PRESET --resume` then continues.

Packed: everything the resume needs and nothing it can make again. Left out: the products a
committed state restores (states/*/manifest.json: the fill, the shared compression), the older
of a run's two checkpoints (resume.checkpoints tries the newer first), the shared compression's
own checkpoints, the estimate's folder (a --resume whose loads all have a checkpoint makes
none), and the files whose names match a --drop pattern (e.g. the dumps between the ones a study
needs, when the package would pass the limit: --drop 'dump.*.519670'; refused while a dropped
contact dump's load path is not kept in loadpath.kept.json: tbagspost.loadpath keep RUN). Tar
keeps the files' modification times, which resume.checkpoints orders by.

  /usr/bin/python3 -m tbagsrun.wip pack FOLDER NAME [--drop PATTERN ...]   (states/wip/NAME.tar.xz)
  /usr/bin/python3 -m tbagsrun.wip unpack NAME FOLDER
"""
import fnmatch
import json
import sys
import tarfile
from pathlib import Path

from . import LaunchError, resume, states
from .stages import MARKER

WIP = states.STATES / "wip"
LIMIT = 50e6
SKIP_DIRS = ("estimate",)
KEPT = "loadpath.kept.json"    # tbagspost.loadpath.KEPT: the load path of the dumps, by step


def restorable(folder, states_root=None):
    """Paths (relative to folder) of the products a committed state restores there."""
    out = set()
    for _, m in states.manifests(states_root):
        for f in Path(folder).rglob(m["product"]):
            if f.is_file() and f.stat().st_size == m["size"] and states.sha256(f) == m["sha256"]:
                out.add(f.relative_to(folder))
    return out


def members(folder, states_root=None, drop=()):
    """The files of folder to pack (relative paths), by the rules above; drop: fnmatch patterns of
    file names left out."""
    folder = Path(folder)
    skip = restorable(folder, states_root)
    for run in {ck.parent for ck in folder.rglob("shear.restart.[12]")}:
        older = resume.checkpoints(run, "shear")[1:]
        skip |= {(run / name).relative_to(folder) for name, _ in older}
    keep = []
    for f in sorted(p for p in folder.rglob("*") if p.is_file()):
        rel = f.relative_to(folder)
        if rel in skip or rel.parts[0] in SKIP_DIRS or f.name.startswith("compress.part.") \
                or any(fnmatch.fnmatchcase(f.name, d) for d in drop):
            continue
        keep.append(rel)
    return keep


def unkept(folder, drop):
    """The contact dumps a --drop pattern leaves out whose load path is not kept beside them
    (tbagspost.loadpath keep: loadpath.kept.json), as paths; a run's load path needs every dump."""
    dropped = [f for f in sorted(Path(folder).rglob("dump.contacts.*"))
               if any(fnmatch.fnmatchcase(f.name, d) for d in drop)]
    kept = {}    # run folder -> its kept steps, read once
    for run in {f.parent for f in dropped}:
        kept[run] = json.loads((run / KEPT).read_text()) if (run / KEPT).is_file() else {}
    return [f for f in dropped if f.suffix[1:] not in kept[f.parent]]


def pack(folder, name, root=None, limit=LIMIT, states_root=None, drop=()):
    """states/wip/NAME.tar.xz of folder's members; refused over `limit` bytes (removed), and when
    it would drop contact dumps whose load path is not kept."""
    folder = Path(folder)
    if not (folder / MARKER).is_file():
        raise LaunchError("wip: %s is not a run folder of ./tbags (no .tbags-run)" % folder)
    lost = unkept(folder, drop)
    if lost:
        raise LaunchError("wip: --drop would lose the load path of %s (and %d more): keep it first: "
                          "cd postprocess && /usr/bin/python3 -m tbagspost.loadpath keep %s"
                          % (lost[0], len(lost) - 1, " ".join(sorted({str(p.parent.resolve()) for p in lost}))))
    target = Path(root or WIP) / (name + ".tar.xz")
    target.parent.mkdir(parents=True, exist_ok=True)
    with tarfile.open(target, "w:xz", preset=9) as tar:
        for rel in members(folder, states_root, drop):
            tar.add(folder / rel, arcname=str(rel))
    size = target.stat().st_size
    if size > limit:
        target.unlink()
        raise LaunchError("wip: %s would be %.1f MB, over the %.0f MB a commit may carry"
                          % (target.name, size / 1e6, limit / 1e6))
    return target, size


def unpack(name, folder, root=None):
    """states/wip/NAME.tar.xz into folder (new or empty: never over a run's files)."""
    source = Path(root or WIP) / (name + ".tar.xz")
    folder = Path(folder)
    if not source.is_file():
        raise LaunchError("wip: no %s" % source)
    if folder.exists() and any(folder.iterdir()):
        raise LaunchError("wip: %s is not empty; unpack into a new folder" % folder)
    folder.mkdir(parents=True, exist_ok=True)
    with tarfile.open(source, "r:xz") as tar:
        for m in tar.getmembers():
            if not m.isfile() or m.name.startswith(("/", "..")) or "/../" in m.name:
                raise LaunchError("wip: %s holds %s, not a file of a run folder" % (source, m.name))
        tar.extractall(folder)
    return folder


def main(argv):
    rest = argv[3:]    # pack's --drop PATTERN pairs
    if len(argv) >= 3 and argv[0] == "pack" and len(rest) % 2 == 0 and set(rest[::2]) <= {"--drop"}:
        t, n = pack(argv[1], argv[2], drop=rest[1::2])
        print("%s: %.1f MB" % (t, n / 1e6))
    elif len(argv) == 3 and argv[0] == "unpack":
        print(unpack(argv[1], argv[2]))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    try:
        main(sys.argv[1:])
    except LaunchError as e:
        sys.exit(str(e))
