"""Check the paper's findings (Panganiban et al. 2025, Part 2) on the runs of `./tbags shear trends`.

usage: PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost.check_trends [--loads 5500,3730,1960] TRENDS_DIR
           (F5500/, F3730/, F1960/ inside, or realizations r1/, r2/, ... each with them)
       PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost.check_trends --speed RUN_A RUN_B [--tol 0.1]

Each finding is asserted in every realization, with a threshold that says how strongly it must
hold (H: the sand height, (nz - 2) x 5 mm, from the run's log):
  1. shear strength rises with F_v: peak S of each load at least RISE (1.1) times that of the next
     lower load;
  2. w contracts first, then dilates, at every load: the contraction (w at u = 0 minus the lowest w)
     and the dilatancy (w at the end minus the lowest w) each at least W_MIN (0.1 %) of H;
  3. larger F_v, more contraction and less dilatancy: contraction rises and dilatancy falls with
     F_v, each step by more than W_MIN of H;
  4. the top surface detaches from the top plate: at the last dump of the highest load at least
     DETACH (10 %) of the bag's top-face particles are more than 0.5 mm below the plate;
  5. contact forces are larger near the edges: in the central cross-section (|y - y_c| < 10 mm)
     the mean normal force of the contacts on sand (sand-sand and bag-sand) within 10 mm of the
     bag's sides is at least EDGE (1.2) times that within the central half.
--loads judges the loads named (at least two of the three; default all three, each required):
a load that is not run yet is left out by name, never by its folder's absence. Findings 1 and 3
then compare the loads present; a step that spans a missing load must hold for both steps it
stands for (RISE squared, 2 W_MIN of H); 4 and 5 read the highest load named.
Speed (quasi-static check): the two runs' S-u curves, interpolated on the shared u range beyond
0.5 mm, differ by at most TOL times the larger run's peak S (root mean square and maximum).
Prints every measured number and a table of the realizations; exits 1 if a check fails.
"""
import argparse
import sys
from pathlib import Path

import numpy as np

from . import rms
from .dumps import read_contacts, read_grains    # the project's dump readers
from .run import bag_size, shear_timestep

LOADS = (5500, 3730, 1960)
RISE, W_MIN, DETACH, EDGE = 1.1, 0.001, 0.10, 1.2


def read_csv(run):
    path = Path(run) / "shear.csv"
    if not path.is_file():
        raise SystemExit("check_trends: no %s (did the shear stage run?)" % path)
    d = np.atleast_1d(np.genfromtxt(path, delimiter=",", names=True))
    if d.dtype.names is None or "S_N" not in d.dtype.names or len(d) < 5:
        raise SystemExit("check_trends: %s is malformed or has fewer than 5 rows" % path)
    return d


def last_dump(run, kind):
    files = sorted(Path(run).glob("dump.%s.*" % kind), key=lambda p: int(p.suffix[1:]))
    if not files:
        raise SystemExit("check_trends: no dump.%s.* in %s" % (kind, run))
    return files[-1], int(files[-1].suffix[1:])


def w_path(d):
    """contraction (w0 - w_min, mm), dilatancy (w_end - w_min, mm), u at w_min (mm)."""
    w = d["w_mm"] - d["w_mm"][0]
    i = int(np.argmin(w))
    return -w[i], w[-1] - w[i], d["u_mm"][i]


def detachment(run, gap_mm=0.5):
    """fraction of the bag's top-face particles more than gap_mm below the plate at the last dump."""
    path, step = last_dump(run, "grains")
    g = read_grains(path)
    d = read_csv(run)
    zplate = np.interp(step * shear_timestep(run), d["time_s"], d["zplate_mm"]) / 1000
    z = g.pos[:, 2]
    z0 = z - g.disp[:, 2]
    top = g.bag & (z0 > z0[g.bag].max() - 1e-3)
    gap = zplate - (z[top] + g.radius[top])
    return float(np.mean(gap > gap_mm / 1000)), float(gap.max() * 1000), int(top.sum())


def edge_forces(run, band=0.010):
    """mean normal force of contacts in the central y cross-section: near the sides, in the middle."""
    gpath, step = last_dump(run, "grains")
    g = read_grains(gpath)
    c = read_contacts(Path(run) / ("dump.contacts.%d" % step))
    mid = 0.5 * (g.pos[g.index(c["id1"]), :2] + g.pos[g.index(c["id2"]), :2])
    x, y = g.pos[g.bag, 0], g.pos[g.bag, 1]
    xlo, xhi = x.min(), x.max()
    yc = 0.5 * (y.min() + y.max())
    xc, half = 0.5 * (xlo + xhi), 0.5 * (xhi - xlo)
    # forces on sand: sand-sand and bag-sand contacts (bag-bag contacts carry the fabric's own
    # compression between neighbours, not the sand's)
    section = (np.abs(mid[:, 1] - yc) < band) & ((c["type1"] == 2) | (c["type2"] == 2))
    edge = section & (np.abs(mid[:, 0] - xc) > half - band)
    centre = section & (np.abs(mid[:, 0] - xc) < half / 2)
    return float(c["fn"][edge].mean()), float(c["fn"][centre].mean()), int(edge.sum()), int(centre.sum())


def sand_height_mm(run):
    """(nz - 2) x 5 mm, nz of the bag made beside the run or in its parent folder (where ./tbags
    shear makes it): bag.json, else log.bag's BAG line (tbagspost.run.bag_size)."""
    size = bag_size(run, Path(run).parent)
    if size is None:
        raise SystemExit("check_trends: no bag.json and no 'BAG nx x ny x nz' line in log.bag beside "
                         "%s or above it" % run)
    return (size[2] - 2) * 5.0


def parse_loads(text):
    """'5500,1960' -> (5500, 1960): two or three of LOADS, highest first."""
    try:
        loads = sorted({int(f) for f in text.split(",")}, reverse=True)
    except ValueError:
        loads = []
    if len(loads) < 2 or any(f not in LOADS for f in loads):
        raise SystemExit("check_trends: --loads takes two or three of %s, comma-separated, not '%s'"
                         % (",".join(map(str, LOADS)), text))
    return tuple(loads)


def steps(lo, hi):
    """how many of the paper's load steps lie between two loads (1 for neighbours)."""
    return LOADS.index(lo) - LOADS.index(hi)


def check_trends(root, loads=LOADS):
    root = Path(root)
    runs = {f: root / ("F%d" % f) for f in loads}
    data = {f: read_csv(r) for f, r in runs.items()}
    top = loads[0]
    H = sand_height_mm(runs[top])
    wmin = W_MIN * H
    results = []
    peak = {f: float(d["S_N"].max()) for f, d in data.items()}
    # (higher load, lower load, paper's load steps between them), neighbours among those named
    pairs = [(hi, lo, steps(lo, hi)) for hi, lo in zip(loads[:-1], loads[1:])]
    print("%s (sand height %.0f mm)" % (root, H))
    print("load (paper kN) | F_v here (N) | peak S (N) | u at peak (mm) | contraction (mm) | u at w_min (mm) | dilatancy (mm)")
    wp = {}
    for f, d in data.items():
        wp[f] = w_path(d)
        print("%15.2f | %12.1f | %10.1f | %14.2f | %16.4f | %15.2f | %14.4f"
              % (f / 1000, np.median(d["Fv_N"]), peak[f], d["u_mm"][np.argmax(d["S_N"])], wp[f][0], wp[f][2], wp[f][1]))
    if loads != LOADS:
        print("loads judged: %s kN (not run: %s kN)" % (", ".join("%.2f" % (f / 1000) for f in loads),
                                                       ", ".join("%.2f" % (f / 1000) for f in LOADS if f not in loads)))
    results.append(("1. peak S rises with F_v (x %s; >= %s each)"
                    % (", ".join("%.2f" % (peak[hi] / peak[lo]) for hi, lo, _ in pairs),
                       ", ".join("%.3g" % RISE ** n for _, _, n in pairs)),
                    all(peak[hi] >= RISE ** n * peak[lo] for hi, lo, n in pairs)))
    results.append(("2. w contracts, then dilates, at every load (each >= %.3f mm)" % wmin,
                    all(c >= wmin and dl >= wmin for c, dl, _ in wp.values())))
    step_w = ", ".join("%.3f" % (wmin * n) for _, _, n in pairs)
    results.append(("3a. more contraction at higher F_v (steps > %s mm)" % step_w,
                    all(wp[hi][0] - wp[lo][0] > wmin * n for hi, lo, n in pairs)))
    results.append(("3b. less dilatancy at higher F_v (steps > %s mm)" % step_w,
                    all(wp[lo][1] - wp[hi][1] > wmin * n for hi, lo, n in pairs)))
    frac, gmax, ntop = detachment(runs[top])
    print("top face at the last dump (%.2f kN): %.0f %% of %d particles more than 0.5 mm below the plate, largest gap %.2f mm"
          % (top / 1000, 100 * frac, ntop, gmax))
    results.append(("4. the top surface detaches (%.0f %% of the top face; >= %.0f %%)" % (100 * frac, 100 * DETACH),
                    frac >= DETACH))
    fe, fc, ne, nc = edge_forces(runs[top])
    print("central cross-section (%.2f kN, last dump): mean normal force %.3f N near the sides (%d contacts), "
          "%.3f N in the central half (%d contacts), ratio %.2f" % (top / 1000, fe, ne, fc, nc, fe / fc))
    results.append(("5. contact forces larger near the edges (ratio %.2f; >= %g)" % (fe / fc, EDGE), fe >= EDGE * fc))
    return results


def realizations(root):
    """The realization folders under root (r1, r2, ...), or root itself."""
    reals = sorted((p for p in Path(root).glob("r*") if p.is_dir() and p.name[1:].isdigit()),
                   key=lambda p: int(p.name[1:]))
    return reals or [Path(root)]


def check_speed(run_a, run_b, tol):
    a, b = read_csv(run_a), read_csv(run_b)
    hi = min(a["u_mm"].max(), b["u_mm"].max())
    u = np.linspace(0.5, hi, 50)
    sa, sb = np.interp(u, a["u_mm"], a["S_N"]), np.interp(u, b["u_mm"], b["S_N"])
    scale = max(sa.max(), sb.max())
    diff, mx = rms(sa - sb) / scale, float(np.abs(sa - sb).max() / scale)
    print("S-u of %s and %s over u = 0.5..%.2f mm: rms difference %.1f %%, max %.1f %% of peak S %.1f N (tolerance %.0f %%)"
          % (run_a, run_b, hi, 100 * diff, 100 * mx, scale, 100 * tol))
    return [("S-u independent of the shear speed (rms)", diff <= tol),
            ("S-u independent of the shear speed (max, 2 x tolerance)", mx <= 2 * tol)]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--speed", action="store_true", help="compare two runs at different shear speeds")
    ap.add_argument("--tol", type=float, default=0.1)
    ap.add_argument("--loads", type=parse_loads, default=LOADS,
                    help="the loads to judge (N, paper's scale), two or three of 5500,3730,1960")
    a = ap.parse_args(argv)
    if a.speed:
        if len(a.dirs) != 2:
            raise SystemExit("check_trends: --speed needs two run directories")
        results = check_speed(a.dirs[0], a.dirs[1], a.tol)
    else:
        if len(a.dirs) != 1:
            raise SystemExit("check_trends: give one trends directory (with F5500/, F3730/, F1960/)")
        reals = realizations(a.dirs[0])
        table = []
        for r in reals:
            res = check_trends(r, a.loads)
            for name, ok in res:
                print("%-4s %s" % ("PASS" if ok else "FAIL", name))
            table.append((r.name, res))
            print()
        print("finding | " + " | ".join(name for name, _ in table))
        for k, (name, _) in enumerate(table[0][1]):
            print("%s | %s" % (name.split(" (")[0], " | ".join("PASS" if res[k][1] else "FAIL" for _, res in table)))
        results = [(name, ok) for _, res in table for name, ok in res]
        print("%d of %d checks pass in %d realization(s)" % (sum(ok for _, ok in results), len(results), len(table)))
        return 0 if all(ok for _, ok in results) else 1
    for name, ok in results:
        print("%-4s %s" % ("PASS" if ok else "FAIL", name))
    return 0 if all(ok for _, ok in results) else 1


if __name__ == "__main__":
    sys.exit(main())
