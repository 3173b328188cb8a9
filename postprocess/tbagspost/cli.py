"""Command line: figures and ParaView files of shear runs.

    ./tbags plot RUN_DIR [RUN_DIR ...] [--u 1,5] [--vtk] [-o OUTDIR]
    PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost RUN_DIR ...
"""
import argparse
import os
from pathlib import Path

from tbagspost import (cyclic, fail, forces, history, isolator_report, loadpath, network, rate, realizations,
                       shape, shear, stack, style, triax, vtkout)
from tbagspost.run import Run

FIGURES = ("shear", "shape", "network", "forces")
DESCRIPTION = """Figures of the paper and ParaView files from shear runs (inputs/in.shear) and
triaxial runs (calibration/in.triax).

Writes, for each RUN_DIR, into RUN_DIR/figures (or OUTDIR/<run name> with -o):
  shear.png            S-u and w-u (kN, mm), legend with F_v            (from shear.csv)
  shape_u<U>mm.png     deformed bag: side view, central x-z and y-z sections, coloured by
                       displacement from the filled state; top-plate gap  (dump.grains.*)
  network_u<U>mm.png   contact-force network in the central x-z section (bag-sand reds,
                       sand-sand blues), bond tension along the bag, mean f_n against x
                                                             (dump.contacts.*, dump.bonds.*)
  forces_u<U>mm.png    the paper's Fig. 5 views of the resultant contact forces on the sand: 3D
                       (the strongest contacts), the centre section, the side (the sand behind
                       the front wall), one colour scale                  (dump.contacts.*)
  summary.txt          the numbers behind the figures (also printed), with the inertial number
                       nominal and from the sand's own stress (the load path's sand share)
with several RUN_DIRs also shear-overlay.png (all runs' S-u and w-u) into OUTDIR (default: the
runs' common parent folder). With --vtk, RUN_DIR/paraview (or OUTDIR/<run name>/paraview):
particles_<step>.vtu, contacts_<step>.vtp, bonds_<step>.vtp, plates_<step>.vtp and
particles/contacts/bonds/plates.pvd (time value = u in mm).
A triaxial RUN_DIR (a CSV with eps_a_pct, ... from in.triax, no shear.csv) gets triax.png:
sigma1/sigma3 and eps_v against eps_a; several of them also triax-overlay.png.
Cyclic RUN_DIRs (cyclic.csv from inputs/in.cyclic, e.g. one per load) get, together, in OUTDIR
(default: RUN_DIR/figures, or the runs' common parent folder/figures for several):
cyclic-loops.png (every cycle per load and amplitude, with the fitted Ramberg-Osgood/Masing
loop), cyclic-curves.png (K_eq/K_0 and h_eq against u_a, first and last cycle, with the R-O
curves), cyclic-settlement.png (w over the cycles), cyclic_table.csv (K_eq, W_d, h_eq per
cycle), ro_parameters.csv (K_0, S_y, r with their standard deviations and fit errors) and
report.md (conditions and tables for a design note). A cyclic RUN_DIR of a stack (stack.txt
from in.cyclic -var bags N) is among them as one more run, and also gets
stack-split-<run>.png (slip fraction, the amplitude of each bag's shear and each film's slip,
the film interfaces' loops), stack_split-<run>.csv and a stack section in report.md.
Every cyclic report ends with the isolator section (isolator.md beside it): the R-O/Masing,
R-O/Phillips-Hashash, bilinear and Bouc-Wen models fitted per load with their errors and the
recommended one, the designer's properties (k_eff, beta_eff, Q_d, K_d, D_y) per amplitude and
their property modification factors (isolator_models.csv, design_properties.csv); a stack gets a
friction slider in series with its bags' model. Runs of the same F_v are fills of one load;
--slow RUN_DIR (a run of a load at half the speed) adds the rate factors; --history RUN_DIR (a run
of in.cyclic -var history FILE at a load among the RUN_DIRs) compares the DEM's S along that
history with each model's (history_check.csv, history-<run>.png).
u of a dump step: time = step * dt (dt from the run's log) interpolated in shear.csv.
Shape, network and forces figures are made at the dump nearest to each --u (default: the last dump).
With --realizations, the RUN_DIRs are realizations of one test (fills of different seeds; runs of
the same name, e.g. r1/F5500 and r2/F5500, form a group): their mean curves with +-1 standard
deviation and min-max, and the table of peak S, S at 5 mm, contraction and dilatancy with their
spread go to OUTDIR (default: the runs' common parent folder / realizations)."""


def parse(argv=None):
    ap = argparse.ArgumentParser(prog="tbagspost", description=DESCRIPTION,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", metavar="RUN_DIR", help="shear run directories")
    ap.add_argument("--u", default=None, metavar="U1,U2",
                    help="shear displacements (mm) for the shape and network figures; default: the last dump")
    ap.add_argument("--only", default=",".join(FIGURES), metavar="LIST",
                    help="figures to make, from %s (default: all); 'none' for none" % ",".join(FIGURES))
    ap.add_argument("--vtk", action="store_true", help="also write the ParaView files")
    ap.add_argument("-o", "--outdir", default=None, help="output folder (default: RUN_DIR/figures)")
    ap.add_argument("--band", type=float, default=None, metavar="MM",
                    help="half width (mm) of the central sections (default: one mean sand diameter, >= 2.5)")
    ap.add_argument("--realizations", action="store_true",
                    help="the runs are realizations of one test: their spread (realizations.md, .csv, .png)")
    ap.add_argument("--dt", type=float, default=None, help="time step (s) if the run has no log")
    ap.add_argument("--slow", action="append", default=[], metavar="RUN_DIR",
                    help="a cyclic run at half the speed of a load among the RUN_DIRs (repeatable): "
                         "the rate's property modification factors")
    ap.add_argument("--history", action="append", default=[], metavar="RUN_DIR",
                    help="a displacement history run (in.cyclic -var history) of a load among the "
                         "RUN_DIRs (repeatable): each model's S along it against the DEM's")
    ap.add_argument("--format", default="png", help="figure formats, e.g. png,pdf (default png)")
    ap.add_argument("--dpi", type=float, default=None, help="resolution of raster figures (default 200)")
    args = ap.parse_args(argv)
    args.only = set() if args.only == "none" else set(args.only.split(","))
    unknown = args.only - set(FIGURES)
    if unknown:
        ap.error("--only: unknown figure(s) %s" % ", ".join(sorted(unknown)))
    try:
        args.u = [float(x) for x in args.u.split(",")] if args.u else None
    except ValueError:
        ap.error("--u: give numbers in mm separated by commas, e.g. --u 1,5")
    args.format = tuple(args.format.split(","))
    return args


def run_outdir(path, args, several):
    """Output folder of one run directory."""
    path = Path(path)
    if args.outdir is None:
        return path / "figures"
    return Path(args.outdir) / path.resolve().name if several else Path(args.outdir)


def overlay_dir(paths, args):
    """Output folder of the overlays: -o, else the runs' common parent folder / figures."""
    if args.outdir:
        return Path(args.outdir)
    return Path(os.path.commonpath([str(Path(p).resolve().parent) for p in paths])) / "figures"


def steps_for(run, u_list, kind):
    """Dump steps for the requested u (nearest dump each; the last dump by default)."""
    if u_list is None:
        steps = run.steps(kind)
        if not steps:
            fail("%s: no dump.%s.* files" % (run.path, kind))
        return [steps[-1]]
    return sorted({run.step_near(u, kind) for u in u_list})


def process(run, args, several):
    """All outputs of one run; returns the summary lines."""
    out = run_outdir(run.path, args, several)
    lines, written = [], []
    half = args.band / 1000 if args.band else None
    # the load path at every dump (loadpath.csv); the network's summary lines reuse it
    found = loadpath.by_step(run) if "network" in args.only and run.steps("contacts") else None
    if "shear" in args.only:
        fig, st = shear.figure([run])
        written += style.save(fig, out / "shear", args.format, args.dpi)
        lines.append("S-u, w-u: " + shear.describe(st[0]))
    for name, module in (("shape", shape), ("network", network), ("forces", forces)):
        if name not in args.only:
            continue
        for step in steps_for(run, args.u, "grains" if name == "shape" else "contacts"):
            fig, st = module.figure(run, step, half)
            written += style.save(fig, out / ("%s_u%.1fmm" % (name, st["u_mm"])), args.format, args.dpi)
            lines.append("%s: %s" % (name, module.describe(st)))
            if name == "network":
                lines.append("u %.1f mm: %s" % (st["u_mm"], loadpath.describe(
                    found[step], run.at_step(step, "S_N"), run.at_step(step, "Fv_N"))))
    if found:
        line = rate.describe_inertial(run, found)
        if line:
            lines.append(line)
        out.mkdir(parents=True, exist_ok=True)
        loadpath.write_csv(loadpath.table(run, found), out / "loadpath.csv")
        written.append(out / "loadpath.csv")
    if args.vtk:
        written += vtkout.convert(run, out / "paraview" if args.outdir else None)
    if lines:
        out.mkdir(parents=True, exist_ok=True)
        (out / "summary.txt").write_text("\n".join(lines) + "\n")
    return lines, written


def process_triax(csv, args, several):
    """The triaxial figure of one run; returns the summary lines and written paths."""
    out = run_outdir(Path(csv).parent, args, several)
    fig, st = triax.figure([csv])
    written = style.save(fig, out / "triax", args.format, args.dpi)
    lines = ["triaxial: " + triax.describe(st[0])]
    (out / "summary.txt").write_text("\n".join(lines) + "\n")
    return lines, written


def classify(paths, dt):
    """Shear runs (tbagspost.run.Run), triaxial CSVs and cyclic runs among the run directories."""
    shear_runs, triax_csvs, cyclic_runs = [], [], []
    for p in paths:
        if (Path(p) / "cyclic.csv").exists() and not (Path(p) / "shear.csv").exists():
            kind = stack.StackRun if (Path(p) / "stack.txt").exists() else cyclic.CyclicRun
            cyclic_runs.append(kind(p))
            continue
        csv = None if (Path(p) / "shear.csv").exists() or not Path(p).is_dir() else triax.find_csv(p)
        if csv:
            triax_csvs.append(csv)
        else:
            shear_runs.append(Run(p, dt=dt))
    return shear_runs, triax_csvs, cyclic_runs


def main(argv=None):
    args = parse(argv)
    shear_runs, triax_csvs, cyclic_runs = classify(args.runs, args.dt)
    several = len(args.runs) > 1
    jobs = [(process, run) for run in shear_runs] + [(process_triax, csv) for csv in triax_csvs]
    for job, item in jobs:
        lines, written = job(item, args, several)
        for line in lines:
            print(line)
        for path in written:
            print("wrote %s" % path)
    overlays = []
    if len(shear_runs) > 1 and "shear" in args.only:
        overlays.append(("shear-overlay", shear.figure(shear_runs)[0], [r.path for r in shear_runs]))
    if len(triax_csvs) > 1:
        overlays.append(("triax-overlay", triax.figure(triax_csvs)[0], [Path(c).parent for c in triax_csvs]))
    for name, fig, paths in overlays:
        for path in style.save(fig, overlay_dir(paths, args) / name, args.format, args.dpi):
            print("wrote %s" % path)
    if cyclic_runs:
        paths = [r.path for r in cyclic_runs]
        out = overlay_dir(paths, args) if len(paths) > 1 else run_outdir(paths[0], args, False)
        written, text = cyclic.write(cyclic_runs, out, args.format, args.dpi)
        # a stack's section follows the cyclic report that cyclic.write() has written
        for run in cyclic_runs:
            if isinstance(run, stack.StackRun):
                more, section = stack.write(run, out, args.format, args.dpi)
                written += more
                text += section
                with open(out / "report.md", "a") as fh:
                    fh.write(section)
        more, section = isolator_report.write(
            cyclic_runs, out, [cyclic.CyclicRun(p) for p in args.slow],
            [history.HistoryRun(p) for p in args.history], args.format, args.dpi)
        written += more
        text += section
        with open(out / "report.md", "a") as fh:
            fh.write(section)
        print(text)
        for path in written:
            print("wrote %s" % path)
    if args.realizations:
        out = Path(args.outdir) if args.outdir else Path(os.path.commonpath(
            [str(realizations.realization_dir(r).parent) for r in shear_runs])) / "realizations"
        print(realizations.write(shear_runs, out))
        print("wrote %s/realizations.md, .csv, .png and curves_*.csv" % out)
    return 0
