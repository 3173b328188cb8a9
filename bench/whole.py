"""Whole-run benchmark (./tbags bench --whole): a sheared bag's shear stage with the project's
styles (inputs/in.shear resumed from its checkpoint: pair gran/hertz/rolling, bond bpm/yarn, the
servo plates, the CSV and its averages) against the closest stock setup on the same particles,
bonds and velocities (bench/in.bench_whole_stock), for the same steps, on 1 and 2 ranks; they
alternate --repeat times and the median of the pairwise ratios is the result. The bag: the demo
bag sheared to u = 1 mm (made once), or --state DIR, a checkpoint that in.shear -var state 1 wrote
(e.g. runs/paper/estimate/state, the paper bag's, from ./tbags shear paper --estimate).
--compare DIR also times the plugin built in DIR (another commit's build) in the same rotation.
Prints each run's time per particle-step and per section, and per item: ns per contact-step
(Pair), per bond-step (Bond) and per particle-step of the rest (Modify: plates, integrator,
gravity, averages).
"""
import json
import re
import sys
from pathlib import Path
from statistics import median

import lmprun
from tbagsrun.presets import DEMO_BAG as DEMO, PRESETS  # (launcher/ is on the path through lmprun)

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "postprocess"))
from tbagspost.dumps import read_header  # noqa: E402
from tbagspost.run import bag_size, log_timestep, loops, read_csv  # noqa: E402

V = PRESETS["demo"].runs[0].variables["v"]    # the demo's shear speed
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


class State:
    """A checkpoint of in.shear -var state 1: the bag's size, the shear speed and time step, the
    newest restart file, the data file and the top plate's height (the CSV's last row)."""

    def __init__(self, folder):
        self.folder = Path(folder).resolve()
        self.data = self.folder / "state.data"
        restarts = sorted(self.folder.glob("shear.restart.*"), key=lambda f: f.stat().st_mtime)
        if not self.data.is_file() or not restarts:
            raise SystemExit("bench --whole: %s has no state.data and shear.restart.* (in.shear -var state 1)"
                             % self.folder)
        self.restart = restarts[-1]
        size = bag_size(self.folder, self.folder.parent, self.folder.parent.parent)
        if size is None:
            raise SystemExit("bench --whole: no bag.json or log.bag in or above %s" % self.folder)
        self.bag = dict(nx=size[0], ny=size[1], nz=size[2])
        self.dt = log_timestep(self.folder / "log.shear") or log_timestep(self.folder / "log.lammps")
        if self.dt is None:
            raise SystemExit("bench --whole: no TIMESTEP line in %s/log.shear or log.lammps" % self.folder)
        # the speed: the launcher's stamp of the stage's variables, else the demo's (prepare())
        stamp = self.folder / ".shear.vars"
        self.v = float(json.loads(stamp.read_text()).get("v", V)) if stamp.is_file() else V
        self.ztop = float(read_csv(self.folder / "shear.csv")["zplate_mm"][-1]) / 1000


def timing(output):
    """Loop time, steps, atoms and section times (average over the ranks) of the last run."""
    last = loops(output)[-1]
    return dict(loop=last["loop"], ranks=last["ranks"], steps=last["steps"], atoms=last["atoms"],
                **{name: last["sections"][name][1] for name in SECTIONS})


def run_ours(state, wd, ranks, steps, plugin=True):
    res = lmprun.run(ROOT / "inputs" / "in.shear", wd, np_ranks=ranks, timeout=7200, plugin_path=plugin,
                     variables=dict(state.bag, v=state.v, dt=state.dt, restart=state.restart, steps=steps,
                                    du_dump=1)).check()
    return timing(res.output)


def run_stock(state, wd, ranks, steps):
    res = lmprun.run(ROOT / "bench" / "in.bench_whole_stock", wd, np_ranks=ranks, timeout=7200, variables=dict(
        state=state.data, ztop=state.ztop, v=state.v, dt=state.dt, nsteps=steps)).check()
    return timing(res.output)


def bond_count(data):
    return int(re.search(r"^\s*(\d+) bonds$", Path(data).read_text(), re.M).group(1))


def contact_count(folder):
    """Touching pairs at the start of the last run of ours in folder (in.shear's contact dump at
    its first step: the newest dump.contacts.* written; older runs' files may be there), or None
    when there is none (a malformed one stops, as in post-processing)."""
    dumps = sorted(Path(folder).glob("dump.contacts.*"), key=lambda f: f.stat().st_mtime)
    return read_header(dumps[-1]).count if dumps else None


def whole(ranks_list, repeat, steps, state_dir=None, compare=None):
    wd = ROOT / "runs" / "bench" / "whole"
    state = State(state_dir or prepare(wd))
    bonds = bond_count(state.data)
    setups = ["tbags"] + (["compare"] if compare else []) + ["stock"]
    print("bench --whole: %s, bag %d x %d x %d, %d steps%s" % (
        state.folder, state.bag["nx"], state.bag["ny"], state.bag["nz"], steps,
        "; compare: the plugin in %s" % compare if compare else ""))
    print("%-6s %-7s %8s %8s %12s   %s" % ("ranks", "setup", "atoms", "steps", "us/atom-step",
                                          "per section (us per atom-step): " + " ".join(SECTIONS)))
    for ranks in ranks_list:
        t = {name: [] for name in setups}
        for _ in range(repeat):
            for name in setups:
                d = wd / ("%s-np%d" % (name, ranks))
                if name == "stock":
                    x = run_stock(state, d, ranks, steps)
                else:
                    x = run_ours(state, d, ranks, steps, compare if name == "compare" else True)
                t[name].append(x)
                per = 1e6 * ranks / (x["steps"] * x["atoms"])
                print("%-6d %-7s %8d %8d %12.4f   %s" % (ranks, name, x["atoms"], x["steps"], x["loop"] * per,
                                                       " ".join("%.4f" % (x[s] * per) for s in SECTIONS)), flush=True)
        med = {n: {k: median(r[k] for r in t[n]) for k in ("loop",) + SECTIONS} for n in t}
        steps_run = t["tbags"][0]["steps"]
        contacts = contact_count(wd / ("tbags-np%d" % ranks))
        if contacts:
            print("%-6d contacts: %d (%.2f per atom; the same particles in every setup), ns per contact-step: %s"
                  % (ranks, contacts, contacts / t["tbags"][0]["atoms"], ", ".join(
                      "%s %.1f" % (n, 1e9 * ranks * med[n]["Pair"] / (steps_run * contacts)) for n in setups)),
                  flush=True)
        for other in setups[1:]:
            ratios = [s["loop"] / o["loop"] for o, s in zip(t["tbags"], t[other])]
            print("%-6d whole run: %s / tbags %.2fx (median of %d alternating pairs, range %.2f-%.2f); "
                  "bonds: tbags %.1f, %s %.1f ns per bond-step (%d bonds)"
                  % (ranks, other, median(ratios), len(ratios), min(ratios), max(ratios),
                     1e9 * ranks * med["tbags"]["Bond"] / (steps_run * bonds), other,
                     1e9 * ranks * med[other]["Bond"] / (steps_run * bonds), bonds), flush=True)
