"""One shear run directory (written by inputs/in.shear): the CSV, the time step, the dump steps
and the shear displacement u of each dump step.

u at a dump step: LAMMPS time is step * dt (dt is constant through in.shear and a resumed run
keeps step and time), so the dump step is put on the CSV's time axis and u (and w, S, the top
plate position) is interpolated linearly between the CSV rows (every 0.1 mm of u). dt is read
from the log line "TIMESTEP: ... using DT s" that in.shear prints (log.* or screen.*.txt), or
given with --dt. This holds for dumps written at any step, also after a restart.
"""
import json
import re
from pathlib import Path

import numpy as np

from tbagspost import dumps, fail, read_columns

CSV_COLUMNS = ("time_s", "u_mm", "w_mm", "S_N", "Fv_N")
KINDS = ("grains", "contacts", "bonds")
DT_LINE = re.compile(r"^TIMESTEP:.*using\s+(\S+)\s+s", re.M)
BAG_LINE = re.compile(r"^BAG (\d+) x (\d+) x (\d+):", re.M)


def log_timestep(path):
    """The time step of a log's 'TIMESTEP: ... using DT s' line (in.shear, in.cyclic), or None."""
    path = Path(path)
    m = DT_LINE.search(path.read_text(errors="replace")) if path.is_file() else None
    return float(m.group(1)) if m else None


def shear_timestep(run):
    """The time step of a shear run's log.shear; stops with one line when it has none."""
    dt = log_timestep(Path(run) / "log.shear")
    if dt is None:
        fail("no TIMESTEP line in %s/log.shear (the run's log)" % run)
    return dt


LOOP_LINE = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", re.M)
SECTION_LINE = re.compile(r"^(Pair|Bond|Neigh|Comm|Output|Modify|Other)\s*\|([^|]*)\|([^|]*)\|([^|]*)\|", re.M)
# LIGGGHTS (the LAMMPS of 2013) prints "Pair  time (%) = T (P)", the average over the ranks
OLD_SECTION_LINE = re.compile(r"^(Pair|Bond|Neigh|Comm|Outpt|Modfy|Modify|Other)\s+time \(%\) = (\S+) \(", re.M)
OLD_NAMES = {"Outpt": "Output", "Modfy": "Modify"}
HISTO_LINE = re.compile(r"^(Nlocal|Nghost|Neighs):\s*(\S+) ave\s+(\S+) max\s+(\S+) min", re.M)
GRID_LINE = re.compile(r"^\s*(\d+) by (\d+) by (\d+) MPI processor grid", re.M)


def loops(text):
    """Every completed run of a LAMMPS log or screen output, in order: dicts of loop (s), ranks,
    steps, atoms, sections (name -> (min, avg, max) seconds over the ranks; Other has its avg
    only; LIGGGHTS's logs: the average as all three), stats (Nlocal, Nghost, Neighs -> dict ave,
    max, min; when LAMMPS printed them) and grid (the last processor grid printed before the
    run, or None)."""
    found = []
    heads = list(LOOP_LINE.finditer(text))
    grids = [(g.start(), tuple(int(v) for v in g.groups())) for g in GRID_LINE.finditer(text)]
    for k, m in enumerate(heads):
        end = heads[k + 1].start() if k + 1 < len(heads) else len(text)
        body = text[m.end():end]
        sections = {}
        for name, *cols in SECTION_LINE.findall(body):
            vals = [float(c) if c.strip() else None for c in cols]
            sections[name] = tuple(v if v is not None else vals[1] for v in vals)
        for name, t in OLD_SECTION_LINE.findall(body):
            sections[OLD_NAMES.get(name, name)] = (float(t),) * 3
        stats = {name: dict(ave=float(a), max=float(b), min=float(c))
                 for name, a, b, c in HISTO_LINE.findall(body)}
        before = [g for at, g in grids if at < m.start()]
        found.append(dict(loop=float(m.group(1)), ranks=int(m.group(2)), steps=int(m.group(3)),
                          atoms=int(m.group(4)), sections=sections, stats=stats,
                          grid=before[-1] if before else None))
    return found


def bag_size(*folders):
    """(nx, ny, nz) of the bag made in the first of `folders` that has it: in.bag's summary
    bag.json, else the 'BAG nx x ny x nz' line of log.bag (runs made before bag.json); None."""
    for folder in map(Path, folders):
        if (folder / "bag.json").is_file():
            bag = json.loads((folder / "bag.json").read_text())
            return int(bag["nx"]), int(bag["ny"]), int(bag["nz"])
        if (folder / "log.bag").is_file():
            m = BAG_LINE.search((folder / "log.bag").read_text(errors="replace"))
            if m:
                return tuple(int(g) for g in m.groups())
    return None


def read_csv(path):
    """The shear CSV as a numpy structured array; stops clearly if missing or truncated."""
    data = read_columns(path, CSV_COLUMNS, "inputs/in.shear")
    if len(data) < 2:
        fail("%s has fewer than two rows (truncated run?)" % path)
    if np.isnan(data[-1]["S_N"]):
        fail("%s: its last row is cut (truncated run?)" % path)
    return data


class Run:
    """A shear run directory: lazy CSV, dt, dump steps; u and plate position at a step."""

    def __init__(self, path, dt=None):
        self.path = Path(path)
        if not self.path.is_dir():
            fail("no run directory %s" % self.path)
        self._dt = dt
        self._csv = None
        # the last grains and contacts dumps read (the figures, load path and VTK of one step
        # share them)
        self._grains = {}
        self._contacts = {}

    @property
    def name(self):
        return self.path.resolve().name

    @property
    def csv(self):
        if self._csv is None:
            self._csv = read_csv(self.path / "shear.csv")
        return self._csv

    @property
    def fv_kN(self):
        """The vertical force held while shearing (median of the CSV), kN."""
        return float(np.median(self.csv["Fv_N"])) / 1000

    @property
    def label(self):
        return "$F_v$ = %.2f kN" % self.fv_kN

    @property
    def model(self):
        """The run's sand and fabric names, from its log's SAND: and FABRIC: lines (paper and
        solid when a log has none: runs made before the names)."""
        text = "".join(p.read_text(errors="replace") for p in
                       sorted(self.path.glob("log.*")) + sorted(self.path.glob("screen.*")))
        sand = re.search(r"^SAND: (\w+) parameters", text, re.M)
        fabric = re.search(r"^FABRIC: (\w+):", text, re.M)
        return dict(sand=sand.group(1) if sand else "paper", fabric=fabric.group(1) if fabric else "solid")

    @property
    def dt(self):
        """Time step (s): --dt, else the TIMESTEP line of the run's log."""
        if self._dt is None:
            logs = sorted(self.path.glob("log.*")) + sorted(self.path.glob("screen.*"))
            self._dt = next((dt for dt in map(log_timestep, logs) if dt is not None), None)
            if self._dt is None:
                fail("%s: no 'TIMESTEP: ... using DT s' line in its log.* or screen.* files; "
                     "give the time step with --dt" % self.path)
        return self._dt

    def steps(self, kind="grains"):
        """Sorted steps of the dumps dump.<kind>.<step>."""
        steps = []
        for p in self.path.glob("dump.%s.*" % kind):
            tail = p.name.rsplit(".", 1)[1]
            if tail.isdigit():
                steps.append(int(tail))
        return sorted(steps)

    def dump(self, kind, step):
        return self.path / ("dump.%s.%d" % (kind, step))

    def at_step(self, step, column="u_mm"):
        """A CSV column interpolated at a dump step (time = step * dt); stops if the step lies
        more than one CSV interval outside the CSV's time range."""
        t, y = self.csv["time_s"], self.csv[column]
        time = step * self.dt
        gap = np.median(np.diff(t))
        if time < t[0] - gap or time > t[-1] + gap:
            fail("%s: step %d (t = %.6g s with dt = %g s) is outside shear.csv's times "
                 "%.6g-%.6g s (wrong --dt?)" % (self.path, step, time, self.dt, t[0], t[-1]))
        k = np.clip(np.searchsorted(t, time), 1, len(t) - 1)
        return float(y[k - 1] + (y[k] - y[k - 1]) * (time - t[k - 1]) / (t[k] - t[k - 1]))

    def step_near(self, u_mm, kind="grains"):
        """The dump step whose u is closest to u_mm; stops if there is no dump."""
        steps = self.steps(kind)
        if not steps:
            fail("%s: no dump.%s.* files" % (self.path, kind))
        us = np.array([self.at_step(s) for s in steps])
        return steps[int(np.argmin(np.abs(us - u_mm)))]

    def grains(self, step):
        """Particles of a dump step (the last one read is kept: treat it as read-only)."""
        if step not in self._grains:
            self._grains = {step: dumps.read_grains(self.dump("grains", step))}
        return self._grains[step]

    def contacts(self, step):
        """Contacts of a dump step (the last one read is kept: treat it as read-only)."""
        if step not in self._contacts:
            self._contacts = {step: dumps.read_contacts(self.dump("contacts", step))}
        return self._contacts[step]

    def bonds(self, step):
        return dumps.read_bonds(self.dump("bonds", step))
