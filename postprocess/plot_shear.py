#!/usr/bin/python3
"""S-u and w-u figure of one or more shear runs (the paper's Fig. 3 of Part 2).

usage: /usr/bin/python3 postprocess/plot_shear.py RUN_DIR [RUN_DIR ...] [-o FIGURE.png]
Each RUN_DIR holds the shear.csv written by inputs/in.shear (time_s,u_mm,w_mm,S_N,Fv_N,...).
"""
import argparse
import sys
from pathlib import Path

import numpy as np


def read_csv(path):
    path = Path(path)
    if not path.is_file():
        raise SystemExit("plot_shear: no %s (run inputs/in.shear first)" % path)
    try:
        data = np.genfromtxt(path, delimiter=",", names=True)
    except ValueError as e:
        raise SystemExit("plot_shear: %s is malformed or truncated: %s" % (path, e))
    needed = {"u_mm", "w_mm", "S_N", "Fv_N"}
    if data.dtype.names is None or not needed <= set(data.dtype.names):
        raise SystemExit("plot_shear: %s lacks the columns %s" % (path, sorted(needed)))
    data = np.atleast_1d(data)
    if len(data) < 2:
        raise SystemExit("plot_shear: %s has fewer than two rows (truncated run?)" % path)
    return data


def plot(runs, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for run in runs:
        d = read_csv(Path(run) / "shear.csv")
        label = "F$_v$ = %.2f kN" % (np.median(d["Fv_N"]) / 1000)
        a1.plot(d["u_mm"], d["S_N"] / 1000, label=label)
        a2.plot(d["u_mm"], d["w_mm"] - d["w_mm"][0], label=label)
    a1.set_xlabel("horizontal displacement u (mm)")
    a1.set_ylabel("shear force S (kN)")
    a2.set_xlabel("horizontal displacement u (mm)")
    a2.set_ylabel("vertical displacement w (mm)")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        a.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("-o", "--output", default=None)
    a = ap.parse_args(argv)
    out = a.output or str(Path(a.runs[0]) / "shear.png")
    print(plot(a.runs, out))


if __name__ == "__main__":
    sys.exit(main())
