"""Whole-run benchmark (./tbags bench --whole): the sheared demo bag's shear stage with the
project's styles (inputs/in.shear, resumed from a checkpoint at u = 1 mm: pair gran/hertz/rolling,
bond bpm/yarn, the servo plates, the CSV and its averages) against the closest stock setup on
the same particles, bonds and velocities (bench/in.bench_whole_stock), for the same steps, on 1
and 2 ranks; the two alternate --repeat times and the median of the pairwise ratios is the
result. Prints each run's time per particle-step and per section, and per item: ns per
contact-step (Pair), per bond-step (Bond) and per particle-step of the rest (Modify: plates,
integrator, gravity, averages).
"""
import re
import sys
from pathlib import Path
from statistics import median

import lmprun
from tbagsrun.presets import DEMO_BAG as DEMO, PRESETS  # (launcher/ is on the path through lmprun)

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "postprocess"))
from tbagspost.run import read_csv  # noqa: E402

V = PRESETS["demo"].runs[0].variables["v"]    # the demo's shear speed
DT = 1.5e-6                                   # in.shear's time step (the stock deck takes it)
SECTIONS = ("Pair", "Bond", "Neigh", "Comm", "Output", "Modify", "Other")


def prepare(wd):
    """The demo bag filled, compressed and sheared to u = 1 mm (once): its checkpoint for our
    runs, its data file and top plate height for the stock runs."""
    state = wd / "state"
    if (state / "state.data").is_file() and (state / "shear.restart.1").is_file():
        return state
    print("bench --whole: making the demo bag's state at u = 1 mm (once, a few minutes) ...", flush=True)
    lmprun.bag_and_fill(state, DEMO)
    lmprun.run(ROOT / "inputs" / "in.shear", state, np_ranks=2, timeout=7200, variables=dict(
        DEMO, v=V, ufinal=0.001, state=1)).check()
    return state


def top_plate(state):
    """The top plate's height (m) at the state: the CSV's last row."""
    return float(read_csv(state / "shear.csv")["zplate_mm"][-1]) / 1000


def timing(output):
    """Loop time, steps, atoms and section times of the last run in a LAMMPS output."""
    loops = re.findall(r"Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", output)
    t, p, steps, atoms = loops[-1]
    tail = output[output.rindex("Loop time of"):]
    # each section's average over the ranks (the second column; "Other" has no min and max)
    sec = {s: float(re.search(r"^%s\s*\|[^|]*\|\s*(\S+)" % s, tail, re.M).group(1)) for s in SECTIONS}
    return dict(loop=float(t), ranks=int(p), steps=int(steps), atoms=int(atoms), **sec)


def run_ours(state, wd, ranks, steps):
    res = lmprun.run(ROOT / "inputs" / "in.shear", wd, np_ranks=ranks, timeout=7200, variables=dict(
        DEMO, v=V, restart=state / "shear.restart.1", ufinal=0.001 + steps * V * DT)).check()
    return timing(res.output)


def run_stock(state, wd, ranks, steps, ztop):
    res = lmprun.run(ROOT / "bench" / "in.bench_whole_stock", wd, np_ranks=ranks, timeout=7200, variables=dict(
        state=state / "state.data", ztop=ztop, v=V, dt=DT, nsteps=steps)).check()
    return timing(res.output)


def bond_count(state):
    return int(re.search(r"^\s*(\d+) bonds$", (state / "state.data").read_text(), re.M).group(1))


def whole(ranks_list, repeat, steps):
    wd = ROOT / "runs" / "bench" / "whole"
    state = prepare(wd)
    ztop = top_plate(state)
    bonds = bond_count(state)
    print("%-6s %-7s %8s %8s %12s   %s" % ("ranks", "setup", "atoms", "steps", "us/atom-step",
                                          "per section (us per atom-step): " + " ".join(SECTIONS)))
    for ranks in ranks_list:
        t = {"tbags": [], "stock": []}
        for _ in range(repeat):
            for name in ("tbags", "stock"):
                d = wd / ("%s-np%d" % (name, ranks))
                x = run_ours(state, d, ranks, steps) if name == "tbags" else run_stock(state, d, ranks, steps, ztop)
                t[name].append(x)
                per = 1e6 * ranks / (x["steps"] * x["atoms"])
                print("%-6d %-7s %8d %8d %12.4f   %s" % (ranks, name, x["atoms"], x["steps"], x["loop"] * per,
                                                       " ".join("%.4f" % (x[s] * per) for s in SECTIONS)), flush=True)
        ratios = [s["loop"] / o["loop"] for o, s in zip(t["tbags"], t["stock"])]
        med = {n: {k: median(r[k] for r in t[n]) for k in ("loop",) + SECTIONS} for n in t}
        steps_run = t["tbags"][0]["steps"]
        print("%-6d whole run: stock / tbags %.2fx (median of %d alternating pairs, range %.2f-%.2f); "
              "bonds: tbags %.1f, stock %.1f ns per bond-step (%d bonds)"
              % (ranks, median(ratios), len(ratios), min(ratios), max(ratios),
                 1e9 * ranks * med["tbags"]["Bond"] / (steps_run * bonds),
                 1e9 * ranks * med["stock"]["Bond"] / (steps_run * bonds), bonds), flush=True)
