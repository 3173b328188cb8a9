"""The void ratio inside a triaxial sample, away from its walls: the solid fraction of a box set
in from the plates, by Monte Carlo points tested against the grains (exact up to the points'
noise, about 0.1 % of the solid fraction for 300,000 points). The walled cell's void ratio counts
the loose layer the flat plates leave at each face; this one does not.

  /usr/bin/python3 -m tbagscal.interior prep.restart [--inset 6.4] [--periodic]
(from calibration/; needs TBAGS_LMP to turn the restart into a data file)"""
import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

POSTPROCESS = str(Path(__file__).resolve().parents[2] / "postprocess")
if POSTPROCESS not in sys.path:    # tbagspost's data file reader
    sys.path.insert(0, POSTPROCESS)
from tbagspost.datafile import DataFile  # noqa: E402


def read_data(path):
    """(diameters, positions, box [[lo, hi] x 3]) of a LAMMPS data file (tbagspost's reader)."""
    d = DataFile(path)
    return d.diameter, d.x, d.box


def void_ratio(d, x, box, inset=0.0, periodic=False, points=300000, seed=1):
    """Void ratio of the box set in by `inset` (m) from the grains' extent (walled) or of the
    periodic box (periodic: its images count)."""
    r = 0.5 * d
    if periodic:
        lo, hi = box[:, 0], box[:, 1]
        shifts = np.array([[i, j, k] for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)])
        centres = np.concatenate([x + s * (hi - lo) for s in shifts])
        radii = np.tile(r, len(shifts))
    else:
        lo, hi = (x - r[:, None]).min(0) + inset, (x + r[:, None]).max(0) - inset
        centres, radii = x, r
    p = lo + np.random.default_rng(seed).random((points, 3)) * (hi - lo)
    dist, idx = cKDTree(centres).query(p, k=8)
    inside = np.any(dist <= radii[idx], axis=1)
    return 1.0 / inside.mean() - 1.0


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("restart")
    ap.add_argument("--inset", type=float, default=6.4, help="mm from the plates (walled)")
    ap.add_argument("--periodic", action="store_true")
    a = ap.parse_args(argv)
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from tbagscal.runs import lammps    # the launcher's runner (its environment, its errors)
    with tempfile.TemporaryDirectory() as tmp:
        deck = Path(tmp) / "in.data"
        deck.write_text("read_restart %s\nwrite_data %s/w.data nocoeff nofix\n" % (Path(a.restart).resolve(), tmp))
        lammps.run(deck, tmp, log="none").check()
        d, x, box = read_data(Path(tmp) / "w.data")
    whole = void_ratio(d, x, box, 0.0, a.periodic)
    if a.periodic:
        print("void ratio %.4f (periodic box)" % whole)
    else:
        print("void ratio %.4f of the grains' extent; %.4f from %.1f mm inside the plates"
              % (whole, void_ratio(d, x, box, a.inset * 1e-3), a.inset))


if __name__ == "__main__":
    main(sys.argv[1:])
