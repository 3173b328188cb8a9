"""A long LAMMPS stage's progress on the console (./tbags shear --progress SECONDS): every so
often, the last thermo row of its screen output in one line: the shear's % done (in.shear's
v_done) with LAMMPS's estimate of the time left (CPULeft), the cycles' % (in.cyclic's v_pct)
with their minutes left (v_eta), or the compression's force (v_Fmeas)."""
import threading
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
    return "%.1f h" % (seconds / 3600) if seconds >= 3600 else "%.0f min" % (seconds / 60)


def status(lines):
    """The progress line of a screen output's last thermo row, or None."""
    row = last_row(lines)
    if row is None:
        return None
    if "v_done" in row and "CPULeft" in row:
        return "%.0f %% of the shear (u %.2f mm), about %s left" % (
            row["v_done"], row.get("v_u", 0.0) * 1e3, duration(row["CPULeft"]))
    if "v_pct" in row and "v_eta" in row:
        return "%.0f %% of the cycles, about %s left" % (row["v_pct"], duration(60 * row["v_eta"]))
    if "v_Fmeas" in row:
        return "compressing: F_v %.0f N at step %d" % (row["v_Fmeas"], row["Step"])
    return "step %d" % row["Step"]


def tail_lines(path):
    try:
        with open(path, "rb") as fh:
            fh.seek(0, 2)
            fh.seek(max(0, fh.tell() - TAIL))
            return fh.read().decode(errors="replace").splitlines()
    except OSError:
        return []


class Watch:
    """with Watch(screen, label, every, say): while the block runs, says '  label: <status>'
    every `every` seconds (none if 0) when the status changed."""

    def __init__(self, screen, label, every, say):
        self.screen, self.label, self.every, self.say = Path(screen), label, every, say
        self.stop = threading.Event()
        self.thread = None

    def loop(self):
        said = None
        while not self.stop.wait(self.every):
            line = status(tail_lines(self.screen))
            if line and line != said:
                self.say("  %s: %s" % (self.label, line))
                said = line

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
