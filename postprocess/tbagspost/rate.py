"""The rate study (./tbags shear rate): the same bag and load sheared at multiples of the paper's
inertial number, in several realizations; the fastest speed whose curves stay inside the
realizations' spread.

For each speed folder I<m> (m times the paper's inertial number) in the realizations r1, r2, ...
of RATE_DIR (or in RATE_DIR itself for one realization): the mean S-u and w-u curves over the
realizations (realizations.mean_curves). Each faster speed is compared with the slowest over
u = U_FROM ... the shortest run's end: the rms difference of the mean curves against the rms of
the realizations' pooled standard deviation (sqrt((sd_m^2 + sd_slowest^2) / 2), the scatter of
one fill), for S and for w. A speed passes when both differences are within that spread; the
chosen speed is the fastest whose slower speeds all pass. Writes RATE_DIR/rate.md and rate.csv.

The inertial number I = (v/H) d sqrt(rho/p) is given twice: nominal, with p = F_v over the inner
plan area (the deck's INERTIAL line), and with the sand's own stress, p = the share of F_v that
sand-sand contacts pass across the bag's mid-height (tbagspost.loadpath, mean over the run's dumps
while shearing) times F_v over the plan area: I_sand = I / sqrt(share). Where the fabric carries
most of F_v (the solid cage), the sand shears at a far higher inertial number than the nominal.
Each run's share is kept in its folder (SHARE_FILE), so a study whose dumps were removed (or not
committed) is reported again from its CSVs, logs and these files.

usage: PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost.rate RATE_DIR
"""
import re
import sys
from pathlib import Path

import numpy as np

from . import loadpath, rms
from .check_trends import realizations
from .realizations import mean_curves
from .run import Run, read_csv

U_FROM = 0.25      # mm: the first rows hold the plate's start-up transient
INERTIAL = re.compile(r"^INERTIAL:.*?inertial number ([0-9.eE+-]+)", re.M)


def speed_folders(root):
    """{m: [run folders]} of the I<m> folders in root's realizations r<k> (or in root)."""
    runs = {}
    for r in realizations(root):
        for f in r.glob("I*"):
            if re.fullmatch(r"I\d+", f.name) and (f / "shear.csv").is_file():
                runs.setdefault(int(f.name[1:]), []).append(f)
    return dict(sorted(runs.items()))


def inertial_number(folder):
    """The deck's INERTIAL line (nominal: F_v over the inner plan area), or nan."""
    for name in ("log.shear", "screen.shear.txt"):
        f = Path(folder) / name
        if f.is_file():
            m = INERTIAL.search(f.read_text(errors="replace"))
            if m:
                return float(m.group(1))
    return float("nan")


SHARE_FILE = "sand_share.txt"    # a run's share and the dump steps it came from (the dumps may then go)


def sand_share(folder):
    """The sand's share of F_v while shearing: the compressive force the sand-sand contacts pass
    across the bag's mid-height over the plate's F_v, the mean over the dumps at u > 0; nan
    without contact dumps. Kept in the run's SHARE_FILE with the dumps' steps, and read from it
    when the dumps are the same or gone."""
    run = Run(folder)
    steps = run.steps("contacts")
    kept = Path(folder) / SHARE_FILE
    if kept.is_file():
        share, *said = kept.read_text().split()
        if not steps or [int(x) for x in said] == steps:
            return float(share)
    if not steps:
        return float("nan")
    share = share_while_shearing(run, loadpath.by_step(run))
    kept.write_text("%.17g %s\n" % (share, " ".join(map(str, steps))))
    return share


def share_while_shearing(run, found):
    """The mean over the dumps at u > 0 of the sand-sand contacts' vertical force across the
    mid-height over the plate's F_v (found: loadpath.by_step(run)); nan without such dumps."""
    shares = [r["sand-sand"][0] / run.at_step(step, "Fv_N") for step, r in found.items()
              if run.at_step(step) > 0]
    return float(np.mean(shares)) if shares else float("nan")


def describe_inertial(run, found):
    """The summary line of a run's inertial number: nominal (the deck's, F_v over the plan) and
    from the sand's own stress (I / sqrt(share)); None without the deck's INERTIAL line."""
    nominal = inertial_number(run.path)
    if np.isnan(nominal):
        return None
    share = share_while_shearing(run, found)
    if np.isnan(share) or share <= 0:
        return "inertial number %.2e (nominal: F_v over the plan area; no sand share measured)" % nominal
    return ("inertial number %.2e nominal (F_v over the plan area), %.2e from the sand's own stress "
            "(sand-sand contacts carry %.0f %% of F_v across mid-height, mean of %d dumps while "
            "shearing); quasi-static below 1e-3" % (nominal, nominal / np.sqrt(share), 100 * share,
                                                     sum(run.at_step(s) > 0 for s in found)))


def compare(curves, ref, u_from=U_FROM):
    """rms differences of the mean S and w of `curves` from `ref`'s, and the pooled spread of
    each, over u >= u_from on the common grid (both on the same u grid up to the shorter end)."""
    umax = min(curves["u_mm"][-1], ref["u_mm"][-1])
    grid = np.linspace(u_from, umax, 200)
    out = {}
    for col in ("S_N", "w_mm"):
        a = np.interp(grid, curves["u_mm"], curves[col + "_mean"])
        b = np.interp(grid, ref["u_mm"], ref[col + "_mean"])
        sa = np.interp(grid, curves["u_mm"], curves[col + "_std"])
        sb = np.interp(grid, ref["u_mm"], ref[col + "_std"])
        out[col] = (rms(a - b), rms(np.sqrt(0.5 * (sa ** 2 + sb ** 2))))
    return out


def study(root):
    """(rows, chosen m or None, n realizations): per speed its comparison with the slowest."""
    runs = speed_folders(root)
    if len(runs) < 2:
        raise SystemExit("rate: %s holds fewer than two speed folders I<m> with a shear.csv" % root)
    n = min(len(v) for v in runs.values())
    curves = {m: mean_curves([read_csv(f / "shear.csv") for f in fs]) for m, fs in runs.items()}
    slowest = min(runs)
    rows, chosen, ok_so_far = [], slowest, True
    for m, fs in runs.items():
        c = compare(curves[m], curves[slowest])
        passed = all(d <= s for d, s in c.values()) if n > 1 else None
        if m != slowest:
            ok_so_far = ok_so_far and bool(passed)
            if ok_so_far:
                chosen = m
        shares = [x for x in map(sand_share, fs) if not np.isnan(x)]    # runs with contact dumps
        share = float(np.mean(shares)) if shares else np.nan
        inertial = np.nanmean([inertial_number(f) for f in fs])
        rows.append(dict(m=m, n=len(fs), inertial=inertial, share=share, inertial_sand=inertial / np.sqrt(share),
                         dS=c["S_N"][0], sS=c["S_N"][1], dw=c["w_mm"][0], sw=c["w_mm"][1],
                         S_end=float(curves[m]["S_N_mean"][-1]), passed=passed))
    return rows, (chosen if n > 1 else None), n


def report(root):
    rows, chosen, n = study(root)
    lines = ["# Rate study: %s (%d realization%s per speed)" % (root, n, "" if n == 1 else "s"), "",
             "Each speed against the slowest over u = %g mm to the end: rms difference of the mean "
             "curves and the realizations' pooled standard deviation (a speed passes when both "
             "differences are within it)." % U_FROM, "",
             "| speed (x the paper's inertial number) | runs | inertial number (nominal) | the sand's share of F_v "
             "| inertial number (the sand's stress) | S: rms difference (N) "
             "| S: spread (N) | w: rms difference (mm) | w: spread (mm) | S at the end (N) | within the spread |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %d | %d | %.2e | %s | %s | %.1f | %.1f | %.4f | %.4f | %.1f | %s |" % (
            r["m"], r["n"], r["inertial"], "n/a (no dumps)" if np.isnan(r["share"]) else "%.2f" % r["share"],
            "n/a" if np.isnan(r["share"]) else "%.2e" % r["inertial_sand"], r["dS"], r["sS"], r["dw"], r["sw"], r["S_end"],
            "reference" if r["m"] == rows[0]["m"] else {True: "yes", False: "no", None: "n/a"}[r["passed"]]))
    lines.append("")
    if chosen is None:
        lines.append("One realization: no spread to judge by; run with --realizations 3.")
    else:
        lines.append("Chosen: %d x the paper's inertial number, the fastest speed whose slower speeds "
                     "all stay within the spread." % chosen)
    text = "\n".join(lines) + "\n"
    (Path(root) / "rate.md").write_text(text)
    keys = ["m", "n", "inertial", "share", "inertial_sand", "dS", "sS", "dw", "sw", "S_end", "passed"]
    with open(Path(root) / "rate.csv", "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join(str(r[k]) if not isinstance(r[k], float) else "%.6g" % r[k] for k in keys) + "\n")
    return text, chosen


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        print(__doc__.strip())
        return 2
    text, _ = report(argv[0])
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
