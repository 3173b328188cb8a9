"""The two engines on the same bag (./tbags bench --engines): a filled bag pressed between two
fixed plates with gravity, the same steps in LAMMPS (plugin) and in LIGGGHTS (our styles built
in), on 1 and 2 ranks, alternating --repeat times; the median of the pairwise ratios is the
result. The decks are the cross-check's (tests/decks/twoengines.py: the same model, forces equal
to round-off). The bag: the demo bag filled once into runs/bench/engines, or --fill FILE (a
LAMMPS fill.data, e.g. runs/paper/fill.data). Prints each run's time per particle-step and its
sections (Pair, Bond, Modify ...), and LIGGGHTS / LAMMPS.
"""
from pathlib import Path
from statistics import median

import lmprun
import twoengines
from tbagsrun.presets import DEMO_BAG as DEMO  # (launcher/ is on the path through lmprun)
from tbagspost.run import loops  # (postprocess/ is on the path through twoengines)

ROOT = Path(__file__).resolve().parents[1]
SECTIONS = ("Pair", "Bond", "Neigh", "Comm", "Modify", "Other")


def demo_fill(wd):
    """The demo bag, made and filled once (in.bag, in.fill)."""
    if not (wd / "fill.data").is_file():
        print("bench --engines: filling the demo bag (once, a few minutes) ...", flush=True)
        lmprun.bag_and_fill(wd, DEMO)
    return wd / "fill.data"


def time_once(engine, fill, ztop, steps, ranks, wd):
    """One run: its loop (tbagspost.run.loops) of the timed steps."""
    wd.mkdir(parents=True, exist_ok=True)
    if engine == "lammps":
        (wd / "fill.data").write_bytes(Path(fill).read_bytes())
        deck, variables = twoengines.bag_deck_lammps(ztop, steps, "id x y z"), {}
    else:
        twoengines.convert(fill, wd / "fill.liggghts.data")
        deck = twoengines.bag_deck_liggghts(ztop, steps, "id x y z")
        variables = {"procs": "%d 1 1" % ranks}    # split through the bag (as the cross-check)
    res = lmprun.run(deck, wd, np_ranks=ranks, engine=engine, variables=variables, timeout=7200)
    res.check(engine)
    return loops(res.output)[-1]


def per_step(loop):
    """us per particle-step (wall) of the run, and of each section."""
    scale = 1e6 / (loop["steps"] * loop["atoms"])
    return loop["loop"] * scale, {k: v[1] * scale for k, v in loop["sections"].items()}


def main(fill=None, steps=2000, ranks=(1, 2), repeat=2):
    wd = ROOT / "runs" / "bench" / "engines"
    fill = Path(fill) if fill else demo_fill(wd / "fill")
    ztop = twoengines.top_plate(fill)
    print("bench --engines: %s, %d steps between fixed plates, ranks %s, %d rotations"
          % (fill, steps, ",".join(map(str, ranks)), repeat))
    for np_ in ranks:
        times = {"lammps": [], "liggghts": []}
        for r in range(repeat):
            for engine in ("lammps", "liggghts"):
                loop = time_once(engine, fill, ztop, steps, np_, wd / ("%s-np%d" % (engine, np_)))
                total, sec = per_step(loop)
                times[engine].append(total)
                print("  np %d %-8s %.3f us/particle-step (%s)" % (
                    np_, engine, total, ", ".join("%s %.3f" % (k, sec[k]) for k in SECTIONS if k in sec)),
                    flush=True)
        ratios = [g / l for g, l in zip(times["liggghts"], times["lammps"])]
        print("np %d: LAMMPS %.3f, LIGGGHTS %.3f us/particle-step; LIGGGHTS / LAMMPS %.2f (%.2f-%.2f)"
              % (np_, median(times["lammps"]), median(times["liggghts"]), median(ratios),
                 min(ratios), max(ratios)), flush=True)
