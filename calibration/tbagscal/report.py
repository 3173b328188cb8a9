"""The calibration's report (report.md, runs.csv, curve CSVs) and the sand include for the decks."""
import contextlib
import csv
import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from .common import PAPER, W_VOL, fail, twisting_coeffs
from .confidence import indistinguishable, region
from .figure import figure
from .misfit import mean_curve, read_curve


@contextlib.contextmanager
def published(out_dir):
    """A temporary directory beside out_dir to write into; its files move into out_dir only when
    the block ends without error, so a failed call leaves no partial report."""
    out_dir = Path(out_dir)
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=".out-", dir=out_dir.parent))
    try:
        yield tmp
        out_dir.mkdir(parents=True, exist_ok=True)
        for f in tmp.iterdir():
            f.replace(out_dir / f.name)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def write_report(cal, data, rows, out_dir):
    a = cal.a
    with published(out_dir) as tmp:
        paper = rows[0]
        best = min(rows, key=lambda r: r["J"])
        ps = a.pressures
        cols = ["n", "mu", "mur", "E", "J", "J_sd"] + [c % p for p in ps for c in
                                                ("J_%g", "Jratio_%g", "Jvol_%g", "peak_sim_%g", "peak_sd_%g", "peak_data_%g",
                                                 "contraction_%g", "contraction_sd_%g", "ev10_%g", "ev10_sd_%g",
                                                 "contract_dilate_%g", "e0_%g", "I_%g", "wallerr_%g", "shearwall_mean_%g",
                                                 "shearwall_max_%g", "Z_end_%g", "seconds_%g")]
        (tmp / "options.json").write_text(json.dumps(dict(options(a), seeds=cal.seeds()), indent=1) + "\n")
        with open(tmp / "runs.csv", "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(cols)
            for r in rows:
                w.writerow([("%.6g" % r[c]) if isinstance(r[c], float) else r[c] for c in cols])
        curves = {}
        for tag, r in (("start", paper), ("best", best)):
            for p in ps:
                recs = [cal.eval_cache.get(cal.run_key(r, p, s)) for s in cal.seeds()]
                dest = tmp / ("curve_%s_%gMPa.csv" % (tag, p))
                if len(recs) == 1:
                    shutil.copy(recs[0]["csv"], dest)
                    curves[(tag, p)] = read_curve(recs[0]["csv"])
                else:
                    curves[(tag, p)] = mean_curve([read_curve(x["csv"]) for x in recs])
                    write_curve(dest, curves[(tag, p)], "mean of seeds %s" % ", ".join(map(str, cal.seeds())))
        L = []
        L.append("# Triaxial calibration report (calibration/fit.py)\n")
        L.append("Generated %s by `fit.py %s`.\n" % (time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
                                                     " ".join(sys.argv[1:])))
        L.append("Sample: %g x %g x %g mm, target void ratio %g +/- %g; inertial number %g; dt %g s (times sqrt(1.8 GPa / E) for stiffer grains); "
                 "strain to %g %%; misfit J = RMS(ratio error / data peak ratio) + %g RMS(eps_v error / "
                 "data eps_v range), at the data's axial strains, averaged over the pressures.\n"
                 % (a.width * 1e3, a.width * 1e3, a.height * 1e3, a.void_ratio, a.e_tol, a.inertial, a.dt,
                    a.strain * 100, W_VOL))
        L.append("Cell: %s.\n" % ("periodic, stress-controlled (in.triax_prep_periodic, in.triax_periodic: "
                                  "fix press/berendsen holds sigma3 on x and y while fix deform shortens z; "
                                  "stresses from the contact virial)" if a.cell == "periodic" else
                                  "walled: six frictionless servo plates (in.triax_prep, in.triax)"))
        L.append("Rolling resistance: EPSD with the %s rolling radius (pair_style gran/hertz/rolling "
                 "rolling_radius %s: %s).\n" % (a.rolling_radius, a.rolling_radius,
                                                "R* = RiRj/(Ri+Rj), the decks' convention" if a.rolling_radius == "effective"
                                                else "(Ri+Rj)/2, YADE's Rmean: about twice R*"))
        if a.twisting == "sds":
            L.append("Twisting resistance: sds with the mean contact's own coefficients at each sigma3 "
                     "(k_tw = 16/3 (G/2) a^3, cap 3 pi/16 mu a |F_n|, a of the mean contact force "
                     "pi d^2 sigma3 (1 + e) / 4.5; tbagscal.common.twisting_coeffs), at the start's mu and E: %s.\n" % "; ".join(
                         "%g MPa: k_tw %.3g N m/rad, c_tw %.3g N m s/rad, mu_tw %.3g m" % (
                             (p,) + twisting_coeffs(paper["E"], 0.1, paper["mu"], p * 1e6, a.void_ratio))
                         for p in ps))
        if len(cal.seeds()) > 1:
            L.append("Samples per pressure: %d (seeds %s). Each misfit is that of the samples' mean curve; "
                     "a peak ratio is the samples' mean +- their standard deviation.\n"
                     % (len(cal.seeds()), ", ".join(map(str, cal.seeds()))))
        for p in ps:
            if data[p][2]:
                L.append("- %s\n" % data[p][2])
        for E in sorted({r["E"] for r in (paper, best)}):
            L.append("Samples (E = %.3g GPa, N grains as in grains.inc): %s.\n" % (E / 1e9, "; ".join(
                "%g MPa%s: void ratio %.4f at mu_prep %.4f (%d preparation%s)" % (
                    p, (" seed %d" % s) if len(cal.seeds()) > 1 else "", pr["e"], pr["mu_prep"],
                    len(pr["tries"]), "s" if len(pr["tries"]) > 1 else "")
                for p in ps for s in cal.seeds() for pr in [cal.prep_cache.get(cal.prep_key(p, E, s))] if pr)))
        L.append("\n## Start (paper) and best parameters\n")
        L.append("| set | mu | mu_r | E (GPa) | J | " + " | ".join("J %g MPa" % p for p in ps) + " | "
                 + " | ".join("peak ratio %g MPa sim/data" % p for p in ps) + " | contracts then dilates |")
        L.append("|---" * (6 + 2 * len(ps)) + "|")
        for tag, r in (("start (paper)" if paper["mu"] == PAPER["mu"] and paper["mur"] == PAPER["mur"]
                        and paper["E"] == PAPER["E"] else "start", paper), ("best", best)):
            L.append("| %s | %.4g | %.4g | %.3g | %.4f | %s | %s | %s |" % (
                tag, r["mu"], r["mur"], r["E"] / 1e9, r["J"],
                " | ".join("%.4f" % r["J_%g" % p] for p in ps),
                " | ".join("%.3f%s / %.3f (%+.1f %%)" % (
                    r["peak_sim_%g" % p], (" +- %.3f" % r["peak_sd_%g" % p]) if len(cal.seeds()) > 1 else "",
                    r["peak_data_%g" % p], 100 * (r["peak_sim_%g" % p] / r["peak_data_%g" % p] - 1))
                           for p in ps),
                ", ".join("yes" if r["contract_dilate_%g" % p] else "no" for p in ps)))
        # the fit's confidence region and cost
        dJ = best.get("J_sd", 0.0)

        def ranges(reg):
            return ", ".join(("E %.3g to %.3g GPa" % (lo / 1e9, hi / 1e9)) if k == "E" else "%s %.3g to %.3g" % (
                "mu_r" if k == "mur" else k, lo, hi) for k, (lo, hi) in reg.items())
        reg = region(rows, a.fit, dJ)
        L.append("\nConfidence region of the best set (J <= J_best + %.4f, the samples' spread of their own "
                 "misfits there; a quadratic through the evaluations near it, tbagscal/confidence.py): %s.\n" % (
                     dJ, reg if isinstance(reg, str) else ranges(reg)))
        if dJ > 0:
            count, spread = indistinguishable(rows, a.fit, dJ)
            L.append("The evaluated sets the samples' noise cannot tell from the best (J <= J_best + 2 x %.4f): "
                     "%d of %d, spanning %s (bounded by where the search looked: the region is at least "
                     "this wide).\n" % (dJ, count, len(rows), ranges(spread)))
        L.append("Cost: %d evaluations, %.2f core-hours of triaxial runs (the samples' preparations besides).\n"
                 % (len(rows), sum(r["seconds_%g" % p] for r in rows for p in ps) / 3600.0))
        L.append("\n## All evaluations\n")
        L.append("| n | mu | mu_r | E (GPa) | J | " + " | ".join("J %g (ratio, vol)" % p for p in ps)
                 + " | void ratio | wall error: consolidated; shearing mean, max | I | run time (s) |")
        L.append("|---" * (9 + len(ps)) + "|")
        for r in rows:
            L.append("| %d | %.4g | %.4g | %.3g | %.4f | %s | %s | %s | %s | %s |" % (
                r["n"], r["mu"], r["mur"], r["E"] / 1e9, r["J"],
                " | ".join("%.4f (%.4f, %.4f)" % (r["J_%g" % p], r["Jratio_%g" % p], r["Jvol_%g" % p]) for p in ps),
                ", ".join("%.4f" % r["e0_%g" % p] for p in ps),
                "; ".join("%.2f; %.2f, %.2f %%" % (100 * r["wallerr_%g" % p], 100 * r["shearwall_mean_%g" % p],
                                                    100 * r["shearwall_max_%g" % p]) for p in ps),
                ", ".join("%.2g" % r["I_%g" % p] for p in ps),
                ", ".join("%.0f" % r["seconds_%g" % p] for p in ps)))
        L.append("\nFiles: runs.csv (this table, all columns), curve_start_*.csv and curve_best_*.csv "
                 "(the deck's CSV), triaxial.png (figure), sand_calibrated.lmp (the best parameters for "
                 "the shear decks: -var sand calibrated).\n")
        (tmp / "report.md").write_text("\n".join(L))
        (tmp / SAND_INCLUDE).write_text(sand_include(best, len(rows)))
        if not a.no_figure:
            figure(tmp / "triaxial.png", data, curves, ps, paper, best)
    return best


def write_curve(path, curve, note):
    """A curve (dict of columns) as the deck's CSV layout, with a comment line."""
    names = list(curve)
    rows = np.column_stack([curve[n] for n in names])
    with open(path, "w") as fh:
        fh.write("# %s\n%s\n" % (note, ",".join(names)))
        for r in rows:
            fh.write(",".join("%.6g" % x for x in r) + "\n")


SAND_INCLUDE = "sand_calibrated.lmp"


def options(a):
    """What a report's runs depend on (options.json): the conventions, the samples and the search,
    not its budget (a larger one extends it) nor where and how fast it runs."""
    return {"rolling_radius": a.rolling_radius, "twisting": a.twisting, "cell": a.cell,
            "inertial": a.inertial, "strain": a.strain, "void_ratio": a.void_ratio, "width": a.width,
            "height": a.height, "pressures": a.pressures, "seed": a.seed, "n_seeds": a.seeds, "dt": a.dt,
            "search": {"fit": a.fit, "mu": a.mu, "mur": a.mur, "E": a.E, "grid_mu": a.grid_mu,
                       "grid_mur": a.grid_mur, "star": a.star}}


def check_replace(a):
    """Refuse to replace OUT's report (and its sand_calibrated.lmp, which the decks read) with one
    of another search, unless --replace: a call with the same options extends or repeats it."""
    prev = Path(a.out) / "options.json"
    if not (Path(a.out) / "report.md").is_file() or a.replace:
        return
    try:
        old = json.loads(prev.read_text())
    except (OSError, ValueError):
        old = {}
    old.pop("seeds", None)
    new = json.loads(json.dumps(options(a)))    # as options.json holds it (lists, not tuples)
    if old != new:
        changed = sorted(k for k in set(old) | set(new) if old.get(k) != new.get(k))
        fail("%s holds the report of another search (it differs in: %s)%s; give --out DIR for a report "
             "of its own, or --replace to replace it" % (
                 a.out, ", ".join(changed) if old else "no options.json: an older fit.py's",
                 " and the sand_calibrated.lmp the decks read" if (Path(a.out) / SAND_INCLUDE).is_file() else ""))


def sand_include(best, n_evaluations, nu=0.1):
    """The best parameters as a LAMMPS include (read by inputs/sand.lmp for -var sand calibrated):
    the one place the decks take the calibrated sand from."""
    return ("# Calibrated sand parameters: written by calibration/fit.py (the best of %d evaluations,\n"
            "# misfit J = %.4f); read by inputs/sand.lmp for -var sand calibrated. Rewrite it with\n"
            "# ./tbags calibrate (or fit.py --sand-include from runs.csv), not by hand.\n"
            "variable sand_E equal %.6g\nvariable sand_nu equal %g\nvariable sand_mu equal %.6g\n"
            "variable sand_mur equal %.6g\n"
            "variable sand_source string 'calibration/results, fit n = %d, J = %.4f'\n"
            % (n_evaluations, best["J"], best["E"], nu, best["mu"], best["mur"], best["n"], best["J"]))


def read_runs(out_dir, missing="no %s: run the calibration first"):
    """The evaluations of OUT/runs.csv (n, mu, mur, E, J); missing: the message if it is absent."""
    path = Path(out_dir) / "runs.csv"
    if not path.is_file():
        fail(missing % path)
    with open(path, newline="") as fh:
        rows = [{k: float(v) for k, v in r.items() if k in ("n", "mu", "mur", "E", "J")}
                for r in csv.DictReader(fh)]
    if not rows:
        fail("%s has no evaluations" % path)
    for r in rows:
        r["n"] = int(r["n"])
    return rows


def rewrite_sand_include(out_dir):
    """sand_calibrated.lmp from an existing runs.csv (the row of least misfit J)."""
    rows = read_runs(out_dir)
    best = min(rows, key=lambda r: r["J"])
    (Path(out_dir) / SAND_INCLUDE).write_text(sand_include(best, len(rows)))
    return best
