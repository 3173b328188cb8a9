#!/usr/bin/python3
"""Projected wall time of the paper-size simple shear protocol from a measured short stretch.

usage: /usr/bin/python3 inputs/project_time.py ESTIMATE_DIR [--ranks N]

ESTIMATE_DIR holds log.bag and log.fill of a small bag and np<P>/log.shear of short shear runs at
P ranks (the `./tbags shear paper --estimate` layout). DEM cost is linear in the number of
particles at fixed density, so the measured cost per particle-step of the shear stage (compression
and shearing loops together: all contacts, bonds and plates) at P ranks is applied to the paper's
bag. Assumptions, printed with the table: the fill stage has the same fixed step counts at every
size (in.fill) and costs no more per particle-step than shearing (its grains grow from half size);
compression takes the measured number of steps times the ratio of sand heights; shearing takes
u_final / (v dt) steps per load (dt of the measured run). Ranks beyond those measured are extrapolated with ideal scaling
from the largest measured count (marked), which a larger bag approaches better than the demo bag.
"""
import argparse
import math
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "postprocess"))
from tbagspost.run import bag_size, log_timestep  # noqa: E402  (the readers of a run's summaries)

LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")

# the paper's protocol (doc/tbags_model.rst section 4)
PAPER = dict(nx=81, ny=81, nz=17, loads=(5500, 3730, 1960), v=0.004, ufinal=0.015)
DT_DECK = re.compile(r"^variable\s+dt\s+index\s+(\S+)", re.M)


def timestep(shear_log):
    """The time step of the measured shear run (its TIMESTEP line), else in.shear's default."""
    dt = log_timestep(shear_log)
    if dt is None:
        dt = float(DT_DECK.search((Path(__file__).resolve().parent / "in.shear").read_text()).group(1))
    return dt


D_MIN, D_STEP, E0 = 3.60465e-3, 0.310078e-3, 0.68


def loops(log):
    """[(seconds, ranks, steps, atoms)] of every run in a LAMMPS log."""
    if not log.is_file():
        raise SystemExit("project_time: no %s (run ./tbags shear paper --estimate)" % log)
    found = [(float(t), int(p), int(s), int(a)) for t, p, s, a in LOOP.findall(log.read_text())]
    if not found:
        raise SystemExit("project_time: %s has no completed run (truncated?)" % log)
    return found


def bag_particles(nx, ny, nz):
    return nx * ny * nz - (nx - 2) * (ny - 2) * (nz - 2)


def sand_grains(nx, ny, nz, s=0.005):
    """in.fill's count: nearest to e = 0.68; the paper's 97,130 on its 81 x 81 x 17 bag."""
    if (nx, ny, nz) == (81, 81, 17):
        return 97130
    v_mean = sum(math.pi / 6 * (D_MIN + k * D_STEP) ** 3 for k in range(10)) / 10
    return round((nx - 2) * (ny - 2) * (nz - 2) * s ** 3 / ((1 + E0) * v_mean))


def project(est_dir, ranks):
    est_dir = Path(est_dir)
    size = bag_size(est_dir)
    if size is None:
        raise SystemExit("project_time: no bag.json and no BAG line in %s" % (est_dir / "log.bag"))
    nx, ny, nz = size
    fill_steps = sum(s for _, _, s, _ in loops(est_dir / "log.fill"))
    cost, comp_steps, dt = {}, None, None
    for d in sorted(est_dir.glob("np*")):
        dt = dt or timestep(d / "log.shear")
        runs = loops(d / "log.shear")
        p = runs[0][1]
        cost[p] = sum(t for t, _, _, _ in runs) / sum(s * a for _, _, s, a in runs)
        comp_steps = runs[0][2]
    if not cost:
        raise SystemExit("project_time: no np*/log.shear in %s" % est_dir)
    atoms = bag_particles(PAPER["nx"], PAPER["ny"], PAPER["nz"]) + sand_grains(PAPER["nx"], PAPER["ny"], PAPER["nz"])
    comp_paper = comp_steps * (PAPER["nz"] - 2) / (nz - 2)
    shear_steps = PAPER["ufinal"] / (PAPER["v"] * dt)
    steps_per_load = comp_paper + shear_steps
    rows = []
    pmax = max(cost)
    for p in sorted(set(cost) | {ranks}):
        c = cost[p] if p in cost else cost[pmax] * pmax / p
        rows.append((p, c, p not in cost, fill_steps * atoms * c / 3600,
                     steps_per_load * atoms * c / 3600))
    return dict(size=(nx, ny, nz), atoms=atoms, fill_steps=fill_steps, comp_steps=comp_steps, dt=dt,
                comp_paper=comp_paper, shear_steps=shear_steps, rows=rows)


def report(r):
    nx, ny, nz = r["size"]
    out = ["Projected time of `./tbags shear paper` (81 x 81 x 17 bag, %d particles; 3 loads)" % r["atoms"],
           "measured on the %d x %d x %d bag's shear stage; steps: fill %d, compression %d x %.1f "
           "(sand height ratio) = %.0f, shear %.0f per load (dt %g s)"
           % (nx, ny, nz, r["fill_steps"], r["comp_steps"], (PAPER["nz"] - 2) / (nz - 2), r["comp_paper"],
              r["shear_steps"], r["dt"]),
           "%6s %22s %10s %14s %12s" % ("ranks", "us per particle-step", "fill (h)", "per load (h)", "total (h)")]
    for p, c, extrapolated, fill_h, load_h in r["rows"]:
        out.append("%6d %20.3f%2s %10.1f %14.1f %12.1f" % (p, c * 1e6, "*" if extrapolated else "", fill_h,
                                                          load_h, fill_h + 3 * load_h))
    if any(x[2] for x in r["rows"]):
        out.append("* extrapolated: ideal scaling from the largest measured rank count")
    return "\n".join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("estimate_dir")
    ap.add_argument("--ranks", type=int, default=1, help="also project for this many ranks")
    a = ap.parse_args(argv)
    if a.ranks < 1:
        raise SystemExit("project_time: --ranks must be >= 1")
    text = report(project(a.estimate_dir, a.ranks))
    print(text)
    (Path(a.estimate_dir) / "projection.txt").write_text(text + "\n")


if __name__ == "__main__":
    sys.exit(main())
