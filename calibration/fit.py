#!/usr/bin/python3
"""T-BAGS calibration: drained triaxial compression decks against the Toyoura sand data.

Runs calibration/in.triax_prep (one sample per confining stress, void ratio reached by searching
the preparation friction) and calibration/in.triax (shear with the calibration micro-parameters),
compares the stress ratio and volumetric strain curves with calibration/data/, searches mu, mu_r
(and optionally E) and writes a report (report.md, runs.csv, curve CSVs) and a figure.
Resumable: every finished run is cached in the work directory (evaluations.json, prep.json).

  ./tbags calibrate                       # paper's parameters + search (defaults below)
  ./tbags calibrate --budget 1            # the paper's parameters only
  ./tbags calibrate --study               # the fitted sand on other seeds, frictions, E, void ratios
  ./tbags calibrate --help

Needs TBAGS_LMP (path of lmp) and LAMMPS_PLUGIN_PATH (directory of tbagsplugin.so); the launcher
sets both. Debian Python: numpy, scipy, matplotlib.
"""
import argparse
import math
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from tbagscal.bracket import write_bracket  # noqa: E402
from tbagscal.common import HERE, PAPER, RANGES, FitError  # noqa: E402
from tbagscal.evaluate import Calibration  # noqa: E402
from tbagscal.misfit import load_data, misfit_one  # noqa: E402,F401 (misfit_one: for the tests)
from tbagscal.report import SAND_INCLUDE, check_replace, rewrite_sand_include, write_report  # noqa: E402
from tbagscal.runs import lmp_command  # noqa: E402
from tbagscal.search import search  # noqa: E402
from tbagscal.study import run_study  # noqa: E402


# ---------------------------------------------------------------------------------------------
# options
# ---------------------------------------------------------------------------------------------
def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="fit.py", description=__doc__.split("\n\n")[0],
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--pressures", default="0.2,0.5,1.0",
                   help="confining stresses sigma3 in MPa, comma separated")
    p.add_argument("--mu", type=float, default=PAPER["mu"], help="start / paper sliding friction")
    p.add_argument("--mur", type=float, default=PAPER["mur"], help="start / paper rolling friction")
    p.add_argument("--E", type=float, default=PAPER["E"], help="start / paper Young's modulus (Pa)")
    p.add_argument("--fit", default="mu,mur", help="parameters searched: mu,mur or mu,mur,E")
    p.add_argument("--rolling-radius", dest="rolling_radius", choices=("effective", "mean"),
                   default="effective", help="the rolling resistance's lever arm (pair_style "
                   "gran/hertz/rolling rolling_radius): R* (effective, the decks') or (Ri+Rj)/2 (mean, "
                   "YADE's Rmean)")
    p.add_argument("--twisting", choices=("none", "sds"), default="none",
                   help="twisting resistance (pair_style gran/hertz/rolling twisting): none (the "
                   "decks') or sds with the mean contact's own coefficients at each sigma3 "
                   "(tbagscal.common.twisting_coeffs: k_tw = 16/3 (G/2) a^3, cap 3 pi/16 mu a)")
    p.add_argument("--cell", choices=("walled", "periodic"), default="walled",
                   help="the triaxial cell: six frictionless servo plates (walled: in.triax_prep, "
                   "in.triax) or a periodic box under stress control (periodic: "
                   "in.triax_prep_periodic, in.triax_periodic; the cited YADE route)")
    p.add_argument("--bracket", default="",
                   help="comma separated report directories of fit.py --budget 1 runs, one per "
                   "reading of the conventions: tabulate them (OUT/bracket.md) and run nothing")
    p.add_argument("--grid-mu", default="0.5,0.8",
                   help="coarse grid of mu searched first (with --grid-mur); empty: no grid")
    p.add_argument("--grid-mur", default="0.1,0.25", help="coarse grid of mu_r searched first")
    p.add_argument("--budget", type=int, default=8,
                   help="evaluations (parameter sets, each at every pressure), including the "
                        "start point; the grid comes first, then the star (--star), then "
                        "Nelder-Mead from the best point")
    p.add_argument("--star", type=float, default=0.0,
                   help="after the grid, the start +- STAR scaled units along each fitted "
                        "parameter (units 0.1 in mu, 0.05 in mu_r, a factor 10^0.15 in E): points "
                        "on both sides of the start for the confidence region's quadratic; 0: none")
    p.add_argument("--void-ratio", type=float, default=0.68, help="void ratio of the samples")
    p.add_argument("--e-tol", type=float, default=0.01, help="void ratio tolerance")
    p.add_argument("--width", type=float, default=0.05, help="cell width W (m), x and y")
    p.add_argument("--height", type=float, default=0.10, help="cell height H (m)")
    p.add_argument("--inertial", type=float, default=1e-3,
                   help="inertial number I = rate d_mean sqrt(rho/sigma3) setting the strain rate")
    p.add_argument("--strain", type=float, default=0.20, help="final axial strain")
    p.add_argument("--dt", type=float, default=2e-6,
                   help="time step (s) for grains up to the paper's E = 1.8 GPa; stiffer grains "
                        "get dt sqrt(1.8 GPa / E), the same fraction of the Rayleigh step")
    p.add_argument("--seed", type=int, default=7331, help="insertion seed of the samples")
    p.add_argument("--seeds", type=int, default=1,
                   help="samples per pressure (seeds SEED, SEED+1, ...): each misfit is that of "
                        "their mean curve, each peak ratio their mean and standard deviation")
    p.add_argument("--jobs", type=int, default=max(1, (os.cpu_count() or 2) // 2),
                   help="decks run in parallel (1 rank each)")
    p.add_argument("--data", default=str(HERE / "data"),
                   help="directory with manifest.csv and the Test_<sigma3>.data files")
    p.add_argument("--workdir", default=str(HERE / "work"),
                   help="runs and the cache (evaluations.json, prep.json): rerun to resume")
    p.add_argument("--out", default=str(HERE / "results"), help="report directory")
    p.add_argument("--no-figure", action="store_true", help="skip the figure")
    p.add_argument("--replace", action="store_true",
                   help="replace OUT's report (and its sand_calibrated.lmp) with one of another "
                        "search; without it such a call stops before it runs anything")
    p.add_argument("--sand-include", action="store_true",
                   help="only rewrite OUT/sand_calibrated.lmp from OUT/runs.csv (no runs)")
    p.add_argument("--study", action="store_true",
                   help="instead of the search: the contraction study of the fitted sand (the "
                        "best row of OUT/runs.csv on other seeds, frictions, E and void ratios), "
                        "written to OUT/contraction-study.md, .csv, .png")
    a = p.parse_args(argv)

    def check(name, value, opt):
        lo, hi, what = RANGES[name]
        if not (lo <= value <= hi) or not math.isfinite(value):
            p.error("%s %g: %s must be in [%g, %g]" % (opt, value, what, lo, hi))

    check("mu", a.mu, "--mu")
    check("mur", a.mur, "--mur")
    check("E", a.E, "--E")
    check("void_ratio", a.void_ratio, "--void-ratio")
    check("e_tol", a.e_tol, "--e-tol")
    check("inertial", a.inertial, "--inertial")
    check("strain", a.strain, "--strain")
    check("width", a.width, "--width")
    check("height", a.height, "--height")
    try:
        a.pressures = [float(x) for x in a.pressures.split(",") if x.strip()]
    except ValueError:
        p.error("--pressures %s: give numbers in MPa, e.g. 0.2,0.5,1.0" % a.pressures)
    if not a.pressures or any(not (0.0 < x <= 50.0) for x in a.pressures):
        p.error("--pressures %s: each confining stress must be in (0, 50] MPa" % ",".join(map(str, a.pressures)))
    a.fit = [x.strip() for x in a.fit.split(",") if x.strip()]
    if not a.fit or any(x not in ("mu", "mur", "E") for x in a.fit) or len(set(a.fit)) != len(a.fit):
        p.error("--fit %s: choose among mu, mur, E (e.g. mu,mur)" % ",".join(a.fit))
    for opt, name, key in (("--grid-mu", "grid_mu", "mu"), ("--grid-mur", "grid_mur", "mur")):
        raw = getattr(a, name)
        try:
            vals = [float(x) for x in raw.split(",") if x.strip()]
        except ValueError:
            p.error("%s %s: give comma separated numbers" % (opt, raw))
        for v in vals:
            lo, hi, what = RANGES[key]
            if not lo <= v <= hi:
                p.error("%s %g: %s must be in [%g, %g]" % (opt, v, what, lo, hi))
        setattr(a, name, vals)
    if a.budget < 1:
        p.error("--budget %d: at least 1 (the start point)" % a.budget)
    if not 0.0 <= a.star <= 2.0 or not math.isfinite(a.star):
        p.error("--star %g: give 0 (none) or a step in (0, 2] scaled units, e.g. 0.5" % a.star)
    if not 1 <= a.seeds <= 20:
        p.error("--seeds %d: between 1 and 20 samples per pressure" % a.seeds)
    if a.jobs < 1:
        p.error("--jobs %d: at least 1" % a.jobs)
    if not 1e-8 <= a.dt <= 1e-4:
        p.error("--dt %g: time step must be in [1e-8, 1e-4] s" % a.dt)
    return a


def main(argv):
    a = parse_args(argv)
    if a.sand_include:
        try:
            best = rewrite_sand_include(a.out)
        except FitError as e:
            print("fit.py: error: %s" % e, file=sys.stderr)
            return 2
        print("fit.py: %s: mu %.4g mur %.4g E %.3g (evaluation %d)"
              % (Path(a.out) / SAND_INCLUDE, best["mu"], best["mur"], best["E"], best["n"]))
        return 0
    try:
        if not a.bracket:
            lmp_command()
        data = load_data(a.data, a.pressures)
        if a.bracket:
            print(write_bracket([d for d in a.bracket.split(",") if d], data, Path(a.out) / "bracket.md"), end="")
            return 0
        if not a.study:
            check_replace(a)
        cal = Calibration(a)
        if a.study:
            run_study(cal, data, a.out)
            print("fit.py: study written to %s" % (Path(a.out) / "contraction-study.md"), flush=True)
            return 0
        rows = search(cal, data)
        best = write_report(cal, data, rows, a.out)
        print("fit.py: %d evaluations; best mu %.4g mur %.4g E %.3g misfit %.4f (start %.4f); report %s"
              % (len(rows), best["mu"], best["mur"], best["E"], best["J"], rows[0]["J"],
                 Path(a.out) / "report.md"), flush=True)
    except FitError as e:
        print("fit.py: error: %s" % e, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
