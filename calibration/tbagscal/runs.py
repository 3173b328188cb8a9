"""Running the calibration decks with the plugin, their JSON summaries and the cache of finished runs."""
import hashlib
import json
import sys
import threading
import time
from pathlib import Path

from .common import HERE, ROOT, fail

sys.path.insert(0, str(ROOT / "launcher"))
from tbagsrun import LaunchError, lammps  # noqa: E402  (the launcher's runner)


def lmp_command():
    """The lmp binary, with the plugin beside it; stops clearly when either is missing."""
    try:
        lammps.plugin_file()
        return lammps.executable()
    except LaunchError as e:
        fail("%s (./tbags calibrate ... loads both)" % e)


def run_deck(deck, workdir, variables):
    """calibration/<deck> in workdir (screen output in <deck>.out); (output, seconds)."""
    lmp_command()
    t0 = time.time()
    res = lammps.run(HERE / deck, workdir, variables=variables, screen="%s.out" % deck)
    if res.returncode != 0:
        fail("%s failed in %s (rc %d): %s" % (deck, workdir, res.returncode,
                                              res.error_line() or res.output[-1500:]))
    return res.output, time.time() - t0


def summary(workdir, name):
    """A deck's machine-readable summary (name.json, written by its print ... file)."""
    path = Path(workdir) / (name + ".json")
    if not path.is_file():
        fail("the deck wrote no %s in %s" % (path.name, workdir))
    return json.loads(path.read_text())


# restart files of the plugin: 2 since the pair's contact history is in fix NEIGH_HISTORY/TBAGS
# (samples prepared before carry it under NEIGH_HISTORY, which read_restart no longer restores)
RESTART_FORMAT = 2


def deck_hash(*names):
    """Short hash of the decks a run depends on: an edited deck is not served from the cache."""
    h = hashlib.sha256()
    for n in names:
        h.update((HERE / n).read_bytes())
    return h.hexdigest()[:10]


class Cache:
    """JSON file of finished runs, keyed by their inputs; written atomically (resumable)."""

    def __init__(self, path):
        self.path = Path(path)
        self.lock = threading.Lock()
        self.data = json.loads(self.path.read_text()) if self.path.is_file() else {}

    def get(self, key):
        with self.lock:
            return self.data.get(key)

    def put(self, key, value):
        with self.lock:
            self.data[key] = value
            self.path.parent.mkdir(parents=True, exist_ok=True)
            tmp = self.path.with_suffix(".tmp")
            tmp.write_text(json.dumps(self.data, indent=1, sort_keys=True))
            tmp.replace(self.path)
