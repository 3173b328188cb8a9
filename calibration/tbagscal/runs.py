"""Running the calibration decks with the plugin, their JSON summaries and the cache of finished runs."""
import hashlib
import json
import os
import subprocess
import threading
import time
from pathlib import Path

from .common import HERE, ROOT, fail


def lmp_command():
    lmp = os.environ.get("TBAGS_LMP", "")
    if not lmp:
        fail("TBAGS_LMP is not set: run through './tbags calibrate ...' (which loads the "
             "environment) or export TBAGS_LMP=/path/to/lmp and LAMMPS_PLUGIN_PATH=/path/to/plugin")
    if not (Path(lmp).is_file() and os.access(lmp, os.X_OK)):
        fail("TBAGS_LMP=%s is not an executable file" % lmp)
    plug = os.environ.get("LAMMPS_PLUGIN_PATH", "")
    if not plug or not (Path(plug) / "tbagsplugin.so").is_file():
        fail("LAMMPS_PLUGIN_PATH=%r has no tbagsplugin.so: run './tbags setup' and use "
             "'./tbags calibrate'" % plug)
    return lmp


def run_deck(deck, workdir, variables):
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    cmd = [lmp_command(), "-nocite", "-log", "log.lammps", "-in", str(HERE / deck),
           "-var", "tbags", str(ROOT)]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    t0 = time.time()
    proc = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True)
    out = proc.stdout + proc.stderr
    (workdir / ("%s.out" % deck)).write_text(out)
    if proc.returncode != 0:
        err = [l for l in out.splitlines() if "ERROR" in l]
        fail("%s failed in %s (rc %d): %s" % (deck, workdir, proc.returncode,
                                              err[0] if err else out[-1500:]))
    return out, time.time() - t0


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
