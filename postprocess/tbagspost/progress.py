"""A plain progress bar on stderr for long loops (no dependency)."""
import sys
import time


class Progress:
    """Iterate with a bar: `for x in Progress(items, "writing VTK"): ...`.

    On a terminal the bar is redrawn in place; otherwise (a log file, a pipe) one line is written
    when the loop ends, so logs stay readable.
    """

    def __init__(self, items, label, stream=None, width=30):
        self.items = list(items)
        self.label = label
        self.stream = stream or sys.stderr
        self.width = width
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()

    def _draw(self, done, elapsed, end="\r"):
        n = max(len(self.items), 1)
        fill = int(self.width * done / n)
        self.stream.write("%s [%s%s] %d/%d %.1f s%s" % (self.label, "#" * fill, "." * (self.width - fill),
                                                      done, len(self.items), elapsed, end))
        self.stream.flush()

    def __iter__(self):
        t0 = time.monotonic()
        for k, item in enumerate(self.items):
            if self.tty:
                self._draw(k, time.monotonic() - t0)
            yield item
        self._draw(len(self.items), time.monotonic() - t0, end="\n")
