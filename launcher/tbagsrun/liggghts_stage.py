"""A preset's shear run in LIGGGHTS (./tbags shear --engine liggghts): inputs/liggghts/in.shear on
the run's LAMMPS fill, its outputs written as in.shear's CSV."""
import re
import subprocess
from pathlib import Path

from . import ROOT, LaunchError, lammps
from .stages import report, run_python


SAND_CALIBRATED = ROOT / "calibration" / "results" / "sand_calibrated.lmp"
SAND_NAMES = ("sand_E", "sand_nu", "sand_mu", "sand_mur")


def sand_variables(variables, path=SAND_CALIBRATED):
    """-var sand's parameters as variables of the LIGGGHTS deck, which has no sand.lmp: none for
    paper (model.lig's defaults are the paper's), those of calibration/results/sand_calibrated.lmp
    (the file inputs/sand.lmp reads) for calibrated."""
    name = variables.get("sand", "paper")
    if name == "paper":
        return {}
    if name != "calibrated":
        raise LaunchError("-var sand %s: the sand set must be paper or calibrated" % name)
    text = Path(path).read_text() if Path(path).is_file() else ""
    found = dict(re.findall(r"^variable\s+(sand_\w+)\s+equal\s+(\S+)\s*$", text, re.M))
    missing = [n for n in SAND_NAMES if n not in found]
    if missing:
        raise LaunchError("-var sand calibrated: %s has no %s (rewrite it: ./tbags calibrate "
                          "--sand-include)" % (path, ", ".join(missing)))
    return {n: found[n] for n in SAND_NAMES}


def stage_liggghts(folder, ranks, variables, say):
    """inputs/liggghts/in.shear in folder: the run's LAMMPS fill converted (tbagspost/liggghts_fill.py), then
    LIGGGHTS on `ranks` ranks (split across x, through the bag) with -var sand's parameters,
    then shear.csv (in.shear's columns) from its means and per-step trace (deleted unless -var trace 1); stops if it
    fails."""
    folder = Path(folder)
    say("tbags shear: shear (LIGGGHTS) in %s ..." % folder)
    ok, err = run_python(["-m", "tbagspost.liggghts_fill",
                          folder / str(variables.get("fill", "fill.data")), folder / "fill.liggghts.data"],
                         stdout=subprocess.DEVNULL)
    if not ok:
        raise LaunchError("%s\nshear: could not convert the fill for LIGGGHTS" % err.strip())
    res = lammps.run(ROOT / "inputs" / "liggghts" / "in.shear", folder, ranks,
                     dict(variables, fill="fill.liggghts.data", procs="%d 1 1" % ranks,
                          **sand_variables(variables)),
                     log="log.shear", screen="screen.shear.txt", engine="liggghts")
    report(res, "the LIGGGHTS shear", folder / "log.shear", say)
    means_to_csv(folder / "shear.means.txt", folder / "shear.csv", folder / "shear.start.txt",
                 folder / "shear.steps.txt")
    if str(variables.get("trace", 0)) != "1":    # -var trace 1 keeps it, as in.shear's trace
        (folder / "shear.steps.txt").unlink()


# inputs/in.shear's CSV columns, which the LIGGGHTS run's CSV gives too
SHEAR_CSV = ("time_s,u_mm,w_mm,S_N,Fv_N,broken_bonds,zplate_mm,steps,w_min_mm,w_max_mm,S_min_N,S_max_N,"
             "Fv_min_N,Fv_max_N,zplate_min_mm,zplate_max_mm")


def means_to_csv(means, csv, start, steps):
    """inputs/liggghts/in.shear's outputs (SI) as the shear CSV of inputs/in.shear (mm, N):
    fix ave/time's means (step t u w S F_v z_plate), after the row at u = 0 of `start`
    (shear.start.txt: one step, as LAMMPS's first row); the min and max of w, S, F_v and z_plate
    over each row's interval of steps, and the broken bonds at its last step, from the per-step
    trace `steps` (shear.steps.txt: step w S F_v z_plate broken). Stops if the trace does not
    cover every step of every row."""
    def table(path):
        return [[float(x) for x in line.split()] for line in Path(path).read_text().splitlines()
                if line.strip() and not line.startswith("#")]

    def row(t, u, w, S, F, broken, z, nsteps, lows, highs):
        """a CSV row: means (SI in, mm and N out), then min and max of w, S, F_v and z_plate"""
        scale = (1e3, 1.0, 1.0, 1e3)
        ext = [x * k for lo, hi, k in zip(lows, highs, scale) for x in (lo, hi)]
        return ",".join(["%.7f" % t] + ["%.4f" % x for x in (u * 1e3, w * 1e3, S, F)]
                        + ["%d" % broken, "%.4f" % (z * 1e3), "%d" % nsteps] + ["%.4f" % x for x in ext])

    out = [SHEAR_CSV, "# LIGGGHTS (inputs/liggghts/in.shear): means over each row's interval of steps "
           "(min, max beside); broken bonds since the compressed state"]
    t, u, w, S, F, z = table(start)[0][1:7]
    out.append(row(t, u, w, S, F, 0, z, 1, (w, S, F, z), (w, S, F, z)))
    trace = table(steps)
    k = last = 0
    for step, t, u, w, S, F, z in (r[:7] for r in table(means)):
        chunk = []    # the trace's rows of the steps last+1 .. step
        while k < len(trace) and trace[k][0] <= step:
            if trace[k][0] > last:
                chunk.append(trace[k])
            k += 1
        if len(chunk) != step - last:
            raise LaunchError("shear: %s has %d of the %d steps %d-%d of a row of %s" %
                              (steps, len(chunk), step - last, last + 1, step, means))
        cols = list(zip(*chunk))[1:5]    # w S F_v z_plate
        out.append(row(t, u, w, S, F, chunk[-1][5], z, step - last, map(min, cols), map(max, cols)))
        last = step
    Path(csv).write_text("\n".join(out) + "\n")
