#!/usr/bin/python3
"""S-u and w-u figure of one or more shear runs in one figure (thin wrapper of tbagspost.shear;
the full set of figures: ./tbags plot RUN_DIR, or python3 -m tbagspost --help).

usage: /usr/bin/python3 postprocess/plot_shear.py RUN_DIR [RUN_DIR ...] [-o FIGURE.png]
Each RUN_DIR holds the shear.csv written by inputs/in.shear (time_s,u_mm,w_mm,S_N,Fv_N,...).
"""
import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from tbagspost import shear, style  # noqa: E402
from tbagspost.run import Run  # noqa: E402


def plot(runs, out):
    """Write the S-u and w-u figure of the runs to out (a .png or .pdf path); returns out."""
    fig, _ = shear.figure([Run(r) for r in runs])
    out = Path(out)
    style.save(fig, out.parent / out.stem, (out.suffix.lstrip(".") or "png",))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("-o", "--output", default=None)
    a = ap.parse_args(argv)
    print(plot(a.runs, a.output or str(Path(a.runs[0]) / "shear.png")))


if __name__ == "__main__":
    sys.exit(main())
