"""A long LAMMPS stage's progress on the console (./tbags shear --progress SECONDS): the last
thermo row of its screen output in one line, at least SECONDS apart and, once a % is known, at
least 10 % of the stage apart (whichever is later), or 10 min apart when the stage is slower: the
shear's % done (in.shear's v_done), the cycles' % (in.cyclic's v_pct), or the compression's force
(v_Fmeas). The time left is measured:
the stage's own rate since its % first showed; before there is a rate, LAMMPS's estimate
(CPULeft, in.cyclic's v_eta) if it has one, else "estimating" (LAMMPS's first row says 0)."""
import threading
import time
from pathlib import Path

TAIL = 65536    # bytes of the screen output read (a thermo block's header and its last rows)


def last_row(lines):
    """{column: value} of the last thermo row in the lines (under the last 'Step ...' header),
    or None."""
    for k in range(len(lines) - 1, -1, -1):
        cols = lines[k].split()
        if cols[:1] != ["Step"]:
            continue
        for line in reversed(lines[k + 1:]):
            words = line.split()
            if len(words) == len(cols):
                try:
                    return dict(zip(cols, map(float, words)))
                except ValueError:
                    pass
        return None
    return None


def duration(seconds):
    if seconds >= 3600:
        return "%.1f h" % (seconds / 3600)
    return "%.0f min" % (seconds / 60) if seconds >= 120 else "%.0f s" % seconds


def percent(row):
    """The % done of a thermo row (shear or cycles), or None (compression, other decks)."""
    if "v_done" in row and "CPULeft" in row:
        return row["v_done"]
    if "v_pct" in row and "v_eta" in row:
        return row["v_pct"]
    return None


def lammps_left(row):
    """LAMMPS's (or in.cyclic's) own estimate of the seconds left, 0 when it has none yet."""
    return row["CPULeft"] if "CPULeft" in row else 60 * row.get("v_eta", 0.0)


def describe(row, left=None):
    """A thermo row in words; left: seconds to go (None: LAMMPS's estimate, if any)."""
    pct = percent(row)
    if pct is not None:
        left = lammps_left(row) if left is None else left
        when = "about %s left" % duration(left) if left > 0 or pct >= 100 else "time left: estimating"
        if "v_done" in row:
            return "%.0f %% of the shear (u %.2f mm), %s" % (pct, row.get("v_u", 0.0) * 1e3, when)
        return "%.0f %% of the cycles, %s" % (pct, when)
    if "v_Fmeas" in row:
        return "compressing: F_v %.0f N at step %d" % (row["v_Fmeas"], row["Step"])
    return "step %d" % row["Step"]


def status(lines):
    """The progress line of a screen output's last thermo row, or None."""
    row = last_row(lines)
    return None if row is None else describe(row)


def tail_lines(path):
    try:
        with open(path, "rb") as fh:
            fh.seek(0, 2)
            fh.seek(max(0, fh.tell() - TAIL))
            return fh.read().decode(errors="replace").splitlines()
    except OSError:
        return []


STEP_PCT = 10    # % of a stage between two lines at least ...
QUIET_MAX = 600  # ... unless this many seconds have passed without one (a stage of hours)


class Watch:
    """with Watch(screen, label, every, say): while the block runs, says '  label: <status>'
    when its status changed, at least `every` seconds after the block began or the last line
    and at least STEP_PCT % of the stage after the last line, or QUIET_MAX seconds after it when
    the stage moves slower (the paper run: a line per 10 min, not per 40); none if every is 0."""

    def __init__(self, screen, label, every, say, clock=time.monotonic):
        self.screen, self.label, self.every, self.say = Path(screen), label, every, say
        self.clock = clock
        self.stop = threading.Event()
        self.thread = None

    def loop(self):
        said, said_at, said_pct, first = None, self.clock(), None, None
        while not self.stop.wait(min(self.every, 2.0)):
            row = last_row(tail_lines(self.screen))
            if row is None:
                continue
            now, pct = self.clock(), percent(row)
            if pct is not None and (first is None or pct < first[1]):
                first = (now, pct)    # where this stage's % began (a new stage: again)
            if now - said_at < self.every or (pct is not None and said_pct is not None and
                                               0 <= pct - said_pct < STEP_PCT and
                                               now - said_at < QUIET_MAX):
                continue
            left = None
            if pct is not None and pct - first[1] >= 1:    # the stage's own rate since then
                left = (now - first[0]) * (100 - pct) / (pct - first[1])
            line = describe(row, left)
            if line != said:
                self.say("  %s: %s" % (self.label, line))
                said, said_at, said_pct = line, now, pct

    def __enter__(self):
        if self.every > 0:
            self.thread = threading.Thread(target=self.loop, daemon=True)
            self.thread.start()
        return self

    def __exit__(self, *exc):
        self.stop.set()
        if self.thread:
            self.thread.join()
        return False
