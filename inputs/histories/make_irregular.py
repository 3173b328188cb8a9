"""Writes irregular_4s.txt: the displacement history of the isolator check (inputs/in.cyclic
-var history). A synthetic record, not a measured one: three sines (0.55 Hz 3.4 mm, 1.5 Hz 0.9 mm,
3.4 Hz 0.55 mm) under an envelope that rises over 1.2 s and decays to 0 at 4 s: 20 half-cycles
from under 0.1 mm to 3 mm (|u| up to 4.6 mm, inner loops at the peaks), peak speed 30 mm/s (twice
the cyclic runs' 15 mm/s). Rows every 1 ms (time s, u mm), starting and ending at rest at u = 0.
Run: /usr/bin/python3 inputs/histories/make_irregular.py (deterministic; no random numbers)."""
from pathlib import Path

import numpy as np

T, DT = 4.0, 0.001
COMPONENTS = ((0.55, 3.4, 0.0), (1.5, 0.9, 0.7), (3.4, 0.55, 1.9))   # Hz, mm, phase (rad)


def history():
    t = np.round(np.arange(0.0, T + DT / 2, DT), 6)
    env = np.where(t < 1.2, np.sin(0.5 * np.pi * t / 1.2) ** 2, np.cos(0.5 * np.pi * (t - 1.2) / (T - 1.2)) ** 2)
    u = env * sum(a * np.sin(2 * np.pi * f * t + p) - a * np.sin(p) for f, a, p in COMPONENTS)
    u[0] = 0.0
    return t, u


if __name__ == "__main__":
    t, u = history()
    out = Path(__file__).with_name("irregular_4s.txt")
    with open(out, "w") as fh:
        fh.write("# " + __doc__.splitlines()[0] + "\n# time_s u_mm (make_irregular.py)\n")
        for a, b in zip(t, u):
            fh.write("%.3f %.6f\n" % (a, b))
    v = np.diff(u) / np.diff(t)
    turns = np.flatnonzero(np.diff(np.sign(np.diff(u))) != 0) + 1
    half = np.abs(np.diff(u[np.r_[0, turns, len(u) - 1]])) / 2
    print("wrote %s: %d rows, |u| max %.3f mm, peak speed %.1f mm/s, half-cycle amplitudes %.2f-%.2f mm (%d)"
          % (out, len(t), np.abs(u).max(), np.abs(v).max(), half.min(), half.max(), len(half)))
