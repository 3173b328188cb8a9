"""Quasi-static check of the cyclic test: the same bag cycled at two speeds (e.g. `-var vpeak
0.015` and `0.0075`, half the frequency at every amplitude) must give the same secant stiffness
and damping.

usage: PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost.check_cyclic_rate RUN_FAST RUN_SLOW [--tol-k 0.05] [--tol-h 0.02]

For every cycle both runs completed: K_eq within TOL_K (relative) and h_eq within TOL_H (absolute)
of the faster run's. Prints the table; exits 1 if a cycle differs by more.
"""
import argparse
import sys
from statistics import mean, stdev

from . import cyclic


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("fast")
    ap.add_argument("slow")
    ap.add_argument("--tol-k", type=float, default=0.05, help="relative tolerance on K_eq (0.05)")
    ap.add_argument("--tol-h", type=float, default=0.02, help="absolute tolerance on h_eq (0.02)")
    args = ap.parse_args(argv)
    fast, slow = cyclic.CyclicRun(args.fast), cyclic.CyclicRun(args.slow)
    rows = cyclic.compare(fast, slow)
    if not rows:
        raise SystemExit("check_cyclic_rate: the runs share no complete cycle")
    print("| u_a (mm) | cycle | K_eq fast (N/mm) | K_eq slow | change | h_eq fast | h_eq slow | change |")
    print("|---|---|---|---|---|---|---|---|")
    bad = 0
    for r in rows:
        ok = abs(r["dK_rel"]) <= args.tol_k and abs(r["dh"]) <= args.tol_h
        bad += not ok
        print("| %g | %d | %.1f | %.1f | %+.1f %% | %.3f | %.3f | %+.3f |%s" % (
            r["ua_mm"], r["cycle"], r["K_a"], r["K_b"], 100 * r["dK_rel"], r["h_a"], r["h_b"], r["dh"],
            "" if ok else " FAIL"))
    worst_k = max(abs(r["dK_rel"]) for r in rows)
    worst_h = max(abs(r["dh"]) for r in rows)
    print("largest change: K_eq %.1f %% (tolerance %.0f %%), h_eq %.3f (tolerance %.3f) over %d cycles"
          % (100 * worst_k, 100 * args.tol_k, worst_h, args.tol_h, len(rows)))
    # a rate effect is systematic; the scatter of slip events is not: the mean change over the
    # cycles with its standard error, beside each run's own change from one cycle to the next
    if len(rows) > 1:
        dk = [r["dK_rel"] for r in rows]
        dh = [r["dh"] for r in rows]
        print("mean change over the %d cycles (+- standard error): K_eq %+.2f +- %.2f %%, h_eq %+.4f +- %.4f"
              % (len(rows), 100 * mean(dk), 100 * sem(dk), mean(dh), sem(dh)))
        for name, run in (("fast", fast), ("slow", slow)):
            k, h = cycle_to_cycle(run)
            if k:
                print("%s run alone, from one cycle to the next at each amplitude: K_eq up to %.1f %%, h_eq up to %.3f"
                      % (name, 100 * k, h))
    return 1 if bad else 0


def sem(x):
    """Standard error of the mean."""
    return stdev(x) / len(x) ** 0.5


def cycle_to_cycle(run):
    """The largest change of K_eq (relative) and h_eq between consecutive cycles of one amplitude,
    after the first (which starts from the previous amplitude's state)."""
    tab = {(t["amp"], t["cycle"]): t for t in cyclic.table(run)}
    k = h = 0.0
    for (amp, cyc), t in tab.items():
        prev = tab.get((amp, cyc - 1))
        if prev is None or cyc - 1 < 2:
            continue
        k = max(k, abs(t["K_eq_N_per_mm"] / prev["K_eq_N_per_mm"] - 1))
        h = max(h, abs(t["h_eq"] - prev["h_eq"]))
    return k, h


if __name__ == "__main__":
    sys.exit(main())
