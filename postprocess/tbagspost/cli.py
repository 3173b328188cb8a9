"""Command line: figures and ParaView files of shear runs.

    ./tbags plot RUN_DIR [RUN_DIR ...] [--u 1,5] [--vtk] [-o OUTDIR]
    PYTHONPATH=postprocess /usr/bin/python3 -m tbagspost RUN_DIR ...
"""
import argparse
from pathlib import Path

from tbagspost import fail, network, shape, shear, style, vtkout
from tbagspost.run import Run

DESCRIPTION = """Figures of the paper (Part 2) and ParaView files from shear runs of inputs/in.shear.

Writes, for each RUN_DIR, into RUN_DIR/figures (or OUTDIR/<run name> with -o):
  shear.png            S-u and w-u (kN, mm), legend with F_v            (from shear.csv)
  shape_u<U>mm.png     deformed bag: side view, central x-z and y-z sections, coloured by
                       displacement from the filled state; top-plate gap  (dump.grains.*)
  network_u<U>mm.png   contact-force network in the central x-z section (bag-sand reds,
                       sand-sand blues), bond tension along the bag, mean f_n against x
                                                             (dump.contacts.*, dump.bonds.*)
  summary.txt          the numbers behind the figures (also printed)
with several RUN_DIRs also shear-overlay.png (all runs' S-u and w-u) into OUTDIR (default: the
runs' common parent folder). With --vtk, RUN_DIR/paraview (or OUTDIR/<run name>/paraview):
particles_<step>.vtu, contacts_<step>.vtp, bonds_<step>.vtp and particles/contacts/bonds.pvd
(time value = u in mm).
u of a dump step: time = step * dt (dt from the run's log) interpolated in shear.csv.
Shape and network figures are made at the dump nearest to each --u (default: the last dump)."""


def parse(argv=None):
    ap = argparse.ArgumentParser(prog="tbagspost", description=DESCRIPTION,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", metavar="RUN_DIR", help="shear run directories")
    ap.add_argument("--u", default=None, metavar="U1,U2",
                    help="shear displacements (mm) for the shape and network figures; default: the last dump")
    ap.add_argument("--only", default="shear,shape,network", metavar="LIST",
                    help="figures to make, from shear,shape,network (default: all); 'none' for none")
    ap.add_argument("--vtk", action="store_true", help="also write the ParaView files")
    ap.add_argument("-o", "--outdir", default=None, help="output folder (default: RUN_DIR/figures)")
    ap.add_argument("--band", type=float, default=None, metavar="MM",
                    help="half width (mm) of the central sections (default: one mean sand diameter, >= 2.5)")
    ap.add_argument("--dt", type=float, default=None, help="time step (s) if the run has no log")
    ap.add_argument("--format", default="png", help="figure formats, e.g. png,pdf (default png)")
    args = ap.parse_args(argv)
    args.only = set() if args.only == "none" else set(args.only.split(","))
    unknown = args.only - {"shear", "shape", "network"}
    if unknown:
        ap.error("--only: unknown figure(s) %s" % ", ".join(sorted(unknown)))
    try:
        args.u = [float(x) for x in args.u.split(",")] if args.u else None
    except ValueError:
        ap.error("--u: give numbers in mm separated by commas, e.g. --u 1,5")
    args.format = tuple(args.format.split(","))
    return args


def run_outdir(run, args, several):
    if args.outdir is None:
        return run.path / "figures"
    return Path(args.outdir) / run.name if several else Path(args.outdir)


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
    out = run_outdir(run, args, several)
    lines, written = [], []
    half = args.band / 1000 if args.band else None
    if "shear" in args.only:
        fig, st = shear.figure([run])
        written += style.save(fig, out / "shear", args.format)
        lines.append("S-u, w-u: " + shear.describe(st[0]))
    for name, module in (("shape", shape), ("network", network)):
        if name not in args.only:
            continue
        for step in steps_for(run, args.u, "grains" if name == "shape" else "contacts"):
            fig, st = module.figure(run, step, half)
            written += style.save(fig, out / ("%s_u%.1fmm" % (name, st["u_mm"])), args.format)
            lines.append("%s: %s" % (name, module.describe(st)))
    if args.vtk:
        written += vtkout.convert(run, out / "paraview" if args.outdir else None)
    if lines:
        out.mkdir(parents=True, exist_ok=True)
        (out / "summary.txt").write_text("\n".join(lines) + "\n")
    return lines, written


def main(argv=None):
    args = parse(argv)
    runs = [Run(p, dt=args.dt) for p in args.runs]
    several = len(runs) > 1
    for run in runs:
        lines, written = process(run, args, several)
        for line in lines:
            print(line)
        for path in written:
            print("wrote %s" % path)
    if several and "shear" in args.only:
        out = Path(args.outdir) if args.outdir else Path(*_common(runs)) / "figures"
        fig, _ = shear.figure(runs)
        for path in style.save(fig, out / "shear-overlay", args.format):
            print("wrote %s" % path)
    return 0


def _common(runs):
    """Parts of the runs' common parent folder."""
    import os
    return Path(os.path.commonpath([str(r.path.resolve().parent) for r in runs])).parts
