#!/usr/bin/env python3
"""Pair benchmark: tbags gran/hertz/rolling against stock pair granular (hertz/material, mindlin,
coeff_restitution, rolling sds) on the same dense polydisperse packing of the model's sand (doc/tbags_model.rst), in one
invocation, serial and on 2 ranks. Prints ns per contact per step (pair time) and the ratio:
the two styles alternate --repeat times (the machine's speed drifts between runs) and the median
of the pairwise ratios is the result.
Both styles run the same deck (same neighbor settings: the runs report their neighbor list
builds, none in 1000 steps by default), so only pair compute() differs.

--callgrind S: instead, count instructions (valgrind callgrind, 1 rank, S steps) in pair
compute() per contact-step: independent of machine load, for comparing kernels.

usage: ./tbags bench [--atoms-per-cell N] [--rep R] [--steps S] [--ranks 1,2] [--repeat K] [--callgrind S]
       ./tbags bench --whole [--ranks 1,2] [--repeat K] [--steps S] [--state DIR] [--compare DIR]
                                                                   (bench/whole.py)
       ./tbags bench --engines [--ranks 1,2] [--repeat K] [--steps S] [--fill FILE]
                                                                   (bench/engines.py)
"""
import argparse
import re
import subprocess
import sys
from pathlib import Path
from statistics import median

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "decks"))
import lmprun  # noqa: E402
import packing  # noqa: E402

OURS = ["pair_style gran/hertz/rolling epsd",
        "pair_coeff * * material 1.8e9 0.1 friction 0.31 rolling 0.05 restitution 0.2"]
# stock: same normal/tangential physics; SDS rolling with a representative stiffness
STOCK = ["pair_style granular",
         "pair_coeff * * hertz/material 1.8e9 0.2 0.1 tangential mindlin NULL 0.97333 0.31 "
         "rolling sds 100.0 0.0 0.05 damping coeff_restitution"]


def run_one(lines, data, rep, steps, ranks, wd):
    deck = (ROOT / "bench" / "in.bench_pair").read_text().replace("PAIR_LINES", "\n".join(lines))
    res = lmprun.run(deck, wd, np_ranks=ranks, variables={"data": data, "rep": rep, "nsteps": steps},
                     timeout=7200).check()
    out = res.output
    pair = float(re.search(r"^Pair\s*\|\s*\S+\s*\|\s*(\S+)", out, re.M).group(1))
    loop = float(re.search(r"Loop time of (\S+)", out).group(1))
    contacts = float(re.search(r"^CONTACTS (\S+)", out, re.M).group(1))
    atoms = int(re.search(r"for \d+ steps with (\d+) atoms", out).group(1))
    builds = int(re.search(r"Neighbor list builds = (\d+)", out).group(1))
    return dict(pair=pair, loop=loop, contacts=contacts, atoms=atoms, builds=builds,
                ns=pair / steps / contacts * 1e9 * ranks)


def callgrind_one(lines, data, rep, steps, wd):
    """Instructions in pair compute() (inclusive) per contact-step, from callgrind."""
    wd.mkdir(parents=True, exist_ok=True)
    deck = (ROOT / "bench" / "in.bench_pair").read_text().replace("PAIR_LINES", "\n".join(lines))
    (wd / "in.bench").write_text(deck)
    out = wd / "callgrind.out"
    cmd = ["valgrind", "--tool=callgrind", "--callgrind-out-file=%s" % out, lmprun.LMP, "-nocite",
           "-log", "none", "-in", "in.bench", "-var", "data", str(data), "-var", "rep", str(rep),
           "-var", "nsteps", str(steps)]
    res = subprocess.run(cmd, cwd=wd, capture_output=True, text=True, timeout=7200)
    if res.returncode != 0:
        raise RuntimeError(res.stdout[-2000:] + res.stderr[-2000:])
    contacts = float(re.search(r"^CONTACTS (\S+)", res.stdout, re.M).group(1))
    ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", str(out)], capture_output=True,
                         text=True).stdout
    ir = max(int(m.group(1).replace(",", "")) for m in re.finditer(
        r"^\s*([\d,]+) .*(?:PairGranHertzRolling|PairGranular)::compute\(int, int\)", ann, re.M))
    return ir / ((steps + 1) * contacts), contacts    # steps + the set-up call


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--atoms-per-cell", type=int, default=4000)
    ap.add_argument("--rep", type=int, default=2, help="replicate the packing rep^3 times (2: 32,000 atoms)")
    ap.add_argument("--steps", type=int, default=None,
                    help="steps per run (1000; --whole: 4444, 0.1 mm of shear)")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--repeat", type=int, default=3,
                    help="alternating runs of the two styles per rank count (median reported)")
    ap.add_argument("--phi", type=float, default=0.66)
    ap.add_argument("--callgrind", type=int, default=0, metavar="S",
                    help="instructions per contact-step over S steps instead of timings")
    ap.add_argument("--whole", action="store_true",
                    help="the whole run instead: the sheared demo bag against the closest stock setup (bench/whole.py)")
    ap.add_argument("--state", metavar="DIR", help="--whole: the checkpoint of in.shear -var state 1 to "
                    "time (e.g. runs/paper/estimate/state); default the demo bag at u = 1 mm")
    ap.add_argument("--compare", metavar="DIR", help="--whole: also time the plugin in DIR (another "
                    "build's plugin folder) in the same rotation")
    ap.add_argument("--engines", action="store_true",
                    help="LAMMPS against LIGGGHTS (our styles in both) on a filled bag between plates (bench/engines.py)")
    ap.add_argument("--fill", metavar="FILE", help="--engines: a LAMMPS fill.data (default: the demo bag's)")
    args = ap.parse_args()
    if (args.state or args.compare) and not args.whole:
        ap.error("--state and --compare are options of --whole")
    if args.compare and not (Path(args.compare) / "tbagsplugin.so").is_file():
        ap.error("--compare %s: no tbagsplugin.so there" % args.compare)
    if args.fill and not args.engines:
        ap.error("--fill is an option of --engines")
    if args.engines:
        import engines
        engines.main(args.fill, args.steps or 2000, [int(r) for r in args.ranks.split(",")], args.repeat)
        return
    if args.whole:
        import whole
        whole.whole([int(r) for r in args.ranks.split(",")], args.repeat, args.steps or 4444,
                    args.state, args.compare)
        return
    args.steps = args.steps or 1000
    wd = ROOT / "runs" / "bench"
    wd.mkdir(parents=True, exist_ok=True)
    # the random insertion (no overlaps) starts from a dilute box (solid fraction of the
    # insertion spheres about 0.25) so that all atoms_per_cell atoms fit; then compressed to phi
    L0 = 0.0625 * (args.atoms_per_cell / 400) ** (1 / 3)
    data = wd / ("packing-%d-%.2f-L%.4f.data" % (args.atoms_per_cell, args.phi, L0))
    if not data.exists():
        print("bench: making the packing (%d atoms, once) ..." % args.atoms_per_cell, flush=True)
        made = packing.make(wd / "packing", n=args.atoms_per_cell, phi=args.phi, L0=L0,
                            ncompress=20000, np_ranks=2)
        natoms = int(re.search(r"^(\d+) atoms$", made.read_text(), re.M).group(1))
        if natoms != args.atoms_per_cell:
            sys.exit("bench: only %d of %d atoms inserted" % (natoms, args.atoms_per_cell))
        made.rename(data)
    styles = (("tbags gran/hertz/rolling", OURS), ("stock granular", STOCK))
    ours, stock = (name for name, _ in styles)
    if args.callgrind:
        r = {}
        for name, lines in styles:
            r[name], c = callgrind_one(lines, data, args.rep, args.callgrind, wd / ("cg-" + name.split()[0]))
            print("%-24s %10.0f contacts %8.1f instructions per contact-step in pair compute()"
                  % (name, c, r[name]), flush=True)
        print("stock / tbags: %.2fx" % (r[stock] / r[ours]))
        return
    print("%-6s %-22s %8s %10s %12s %14s %8s" % ("ranks", "style", "atoms", "contacts", "pair time s",
                                                 "ns/contact/step", "nbuilds"))
    for ranks in [int(r) for r in args.ranks.split(",")]:
        # the two styles alternate, repeat times: on a shared machine the speed drifts by 10 %
        # over minutes, so each ratio compares neighbouring runs and the median is reported
        ns = {name: [] for name, _ in styles}
        for _ in range(args.repeat):
            for name, lines in styles:
                x = run_one(lines, data, args.rep, args.steps, ranks, wd / name.split()[0])
                ns[name].append(x["ns"])
                print("%-6d %-22s %8d %10.0f %12.3f %14.1f %8d" % (ranks, name, x["atoms"], x["contacts"],
                                                                 x["pair"], x["ns"], x["builds"]), flush=True)
        ratios = [s / o for o, s in zip(ns[ours], ns[stock])]
        print("%-6d median ns/contact/step: tbags %.1f, stock %.1f; speed-up of tbags over stock "
              "(pair time per contact-step): %.2fx (median of %d alternating pairs, range %.2f-%.2f)"
              % (ranks, median(ns[ours]), median(ns[stock]), median(ratios), len(ratios),
                 min(ratios), max(ratios)), flush=True)


if __name__ == "__main__":
    main()
