#!/usr/bin/python3
"""T-BAGS calibration: drained triaxial compression decks against the Toyoura sand data.

Runs calibration/in.triax_prep (one sample per confining stress, void ratio reached by searching
the preparation friction) and calibration/in.triax (shear with the calibration micro-parameters),
compares the stress ratio and volumetric strain curves with calibration/data/, searches mu, mu_r
(and optionally E) and writes a report (report.md, runs.csv, curve CSVs) and a figure.
Resumable: every finished run is cached in the work directory (evaluations.json, prep.json).

  ./tbags calibrate                       # paper's parameters + search (defaults below)
  ./tbags calibrate --budget 1            # the paper's parameters only
  ./tbags calibrate --help

Needs TBAGS_LMP (path of lmp) and LAMMPS_PLUGIN_PATH (directory of tbagsplugin.so); the launcher
sets both. Debian Python: numpy, scipy, matplotlib.
"""
import argparse
import concurrent.futures as cf
import csv
import hashlib
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
PAPER = {"mu": 0.31, "mur": 0.05, "E": 1.8e9}
# physical ranges of the options (checked before anything runs)
RANGES = {
    "mu": (0.0, 1.5, "sliding friction"),
    "mur": (0.0, 0.5, "rolling friction (dimensionless)"),
    "E": (1e7, 1e12, "grain Young's modulus (Pa)"),
    "void_ratio": (0.45, 1.2, "void ratio"),
    "inertial": (1e-6, 1e-2, "inertial number"),
    "strain": (0.001, 0.4, "final axial strain"),
    "width": (0.01, 1.0, "cell width (m)"),
    "height": (0.01, 2.0, "cell height (m)"),
    "e_tol": (0.001, 0.1, "void ratio tolerance"),
}
PREP_MU_MAX = 1.0       # preparation friction searched in [0, PREP_MU_MAX]
PREP_SLOPE = 0.25       # d e / d mu_prep, first guess (measured on the 50 x 50 x 100 mm sample)
PREP_MU_START = 0.14
W_VOL = 0.5             # weight of the volumetric term in the misfit
RHO, D_MEAN = 2650.0, 0.005


class BudgetSpent(Exception):
    """The evaluation budget is used up (ends the search)."""


class FitError(Exception):
    """A clear message for the user (no traceback)."""


def fail(msg):
    raise FitError(msg)


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
    p.add_argument("--grid-mu", default="0.5,0.8",
                   help="coarse grid of mu searched first (with --grid-mur); empty: no grid")
    p.add_argument("--grid-mur", default="0.1,0.25", help="coarse grid of mu_r searched first")
    p.add_argument("--budget", type=int, default=8,
                   help="evaluations (parameter sets, each at every pressure), including the "
                        "start point; the grid comes first, then Nelder-Mead from the best point")
    p.add_argument("--void-ratio", type=float, default=0.68, help="void ratio of the samples")
    p.add_argument("--e-tol", type=float, default=0.01, help="void ratio tolerance")
    p.add_argument("--width", type=float, default=0.05, help="cell width W (m), x and y")
    p.add_argument("--height", type=float, default=0.10, help="cell height H (m)")
    p.add_argument("--inertial", type=float, default=1e-3,
                   help="inertial number I = rate d_mean sqrt(rho/sigma3) setting the strain rate")
    p.add_argument("--strain", type=float, default=0.20, help="final axial strain")
    p.add_argument("--dt", type=float, default=2e-6, help="time step (s)")
    p.add_argument("--seed", type=int, default=7331, help="insertion seed of the samples")
    p.add_argument("--jobs", type=int, default=max(1, (os.cpu_count() or 2) // 2),
                   help="decks run in parallel (1 rank each)")
    p.add_argument("--data", default=str(HERE / "data"),
                   help="directory with manifest.csv and the Test_<sigma3>.data files")
    p.add_argument("--workdir", default=str(HERE / "work"),
                   help="runs and the cache (evaluations.json, prep.json): rerun to resume")
    p.add_argument("--out", default=str(HERE / "results"), help="report directory")
    p.add_argument("--no-figure", action="store_true", help="skip the figure")
    p.add_argument("--sand-include", action="store_true",
                   help="only rewrite OUT/sand_calibrated.lmp from OUT/runs.csv (no runs)")
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
    if a.jobs < 1:
        p.error("--jobs %d: at least 1" % a.jobs)
    if not 1e-8 <= a.dt <= 1e-4:
        p.error("--dt %g: time step must be in [1e-8, 1e-4] s" % a.dt)
    return a


# ---------------------------------------------------------------------------------------------
# data
# ---------------------------------------------------------------------------------------------
def load_data(data_dir, pressures):
    """{sigma3 MPa: (label, array[eps_a %, ratio, eps_v %], note)} for the pressures asked."""
    d = Path(data_dir)
    man = d / "manifest.csv"
    if not man.is_file():
        fail("--data %s: no manifest.csv (sigma3_MPa,file,sha256) in that directory" % d)
    table = {}
    with open(man) as fh:
        for row in csv.DictReader(fh):
            f = d / row["file"]
            if not f.is_file():
                fail("--data %s: data file %s (sigma3 %s MPa, listed in manifest.csv) is missing"
                     % (d, row["file"], row["sigma3_MPa"]))
            digest = hashlib.sha256(f.read_bytes()).hexdigest()
            if row.get("sha256") and digest != row["sha256"]:
                fail("--data %s: %s differs from its manifest checksum (edited or truncated)" % (d, row["file"]))
            arr = np.loadtxt(f, comments="#")
            if arr.ndim != 2 or arr.shape[1] < 5:
                fail("--data %s: %s needs 5 columns e_v e_x e_y e_z s33_over_s11" % (d, row["file"]))
            table[float(row["sigma3_MPa"])] = (row["file"], np.column_stack([arr[:, 3], arr[:, 4], arr[:, 0]]))
    if not table:
        fail("--data %s: manifest.csv lists no data file" % d)
    out = {}
    for p in pressures:
        near = min(table, key=lambda q: abs(q - p))
        label, arr = table[near]
        note = ""
        if abs(near - p) > 1e-9:
            note = ("no data at sigma3 = %g MPa: compared with the nearest curve, %s (%g MPa)"
                    % (p, label, near))
            print("fit.py: " + note, flush=True)
        out[p] = (label, arr, note)
    return out


# ---------------------------------------------------------------------------------------------
# running decks
# ---------------------------------------------------------------------------------------------
def lmp_command():
    lmp = os.environ.get("TBAGS_LMP", "")
    if not lmp:
        fail("TBAGS_LMP is not set: run through './tbags calibrate ...' (which loads the "
             "environment) or export TBAGS_LMP=/path/to/lmp and LAMMPS_PLUGIN_PATH=/path/to/plugin")
    if not (Path(lmp).is_file() and os.access(lmp, os.X_OK)):
        fail("TBAGS_LMP=%s is not an executable file" % lmp)
    plug = os.environ.get("LAMMPS_PLUGIN_PATH", "")
    if not plug or not (Path(plug) / "tbagsplugin.so").is_file():
        fail("LAMMPS_PLUGIN_PATH=%r has no tbagsplugin.so: run './tbags setup' and use "
             "'./tbags calibrate'" % plug)
    return lmp


def run_deck(deck, workdir, variables):
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    cmd = [lmp_command(), "-nocite", "-log", "log.lammps", "-in", str(HERE / deck),
           "-var", "tbags", str(ROOT)]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    t0 = time.time()
    proc = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True)
    out = proc.stdout + proc.stderr
    (workdir / ("%s.out" % deck)).write_text(out)
    if proc.returncode != 0:
        err = [l for l in out.splitlines() if "ERROR" in l]
        fail("%s failed in %s (rc %d): %s" % (deck, workdir, proc.returncode,
                                              err[0] if err else out[-1500:]))
    return out, time.time() - t0


def summary(workdir, name):
    """A deck's machine-readable summary (name.json, written by its print ... file)."""
    path = Path(workdir) / (name + ".json")
    if not path.is_file():
        fail("the deck wrote no %s in %s" % (path.name, workdir))
    return json.loads(path.read_text())


# restart files of the plugin: 2 since the pair's contact history is in fix NEIGH_HISTORY/TBAGS
# (samples prepared before carry it under NEIGH_HISTORY, which read_restart no longer restores)
RESTART_FORMAT = 2


def deck_hash(*names):
    """Short hash of the decks a run depends on: an edited deck is not served from the cache."""
    h = hashlib.sha256()
    for n in names:
        h.update((HERE / n).read_bytes())
    return h.hexdigest()[:10]


def fmt(x):
    return "%.6g" % x


class Cache:
    """JSON file of finished runs, keyed by their inputs; written atomically (resumable)."""

    def __init__(self, path):
        self.path = Path(path)
        self.lock = threading.Lock()
        self.data = json.loads(self.path.read_text()) if self.path.is_file() else {}

    def get(self, key):
        with self.lock:
            return self.data.get(key)

    def put(self, key, value):
        with self.lock:
            self.data[key] = value
            self.path.parent.mkdir(parents=True, exist_ok=True)
            tmp = self.path.with_suffix(".tmp")
            tmp.write_text(json.dumps(self.data, indent=1, sort_keys=True))
            tmp.replace(self.path)


class Calibration:
    def __init__(self, a):
        self.a = a
        self.work = Path(a.workdir)
        self.prep_cache = Cache(self.work / "prep.json")
        self.eval_cache = Cache(self.work / "evaluations.json")
        self.prep_locks = {}
        self.lock = threading.Lock()

    def cell_vars(self):
        a = self.a
        return {"W": fmt(a.width), "H": fmt(a.height), "dt": fmt(a.dt)}

    # ---- samples ------------------------------------------------------------------------
    def prep_key(self, p, E):
        a = self.a
        return "p%s_E%s_e%s_W%s_H%s_seed%d_dt%s_deck%s_r%d" % (
            fmt(p), fmt(E), fmt(a.void_ratio), fmt(a.width), fmt(a.height), a.seed, fmt(a.dt),
            deck_hash("in.triax_prep", "cell.inc"), RESTART_FORMAT)

    def sample(self, p, E):
        """Restart file of the sample at sigma3 = p MPa (void ratio within tolerance)."""
        key = self.prep_key(p, E)
        with self.lock:
            lk = self.prep_locks.setdefault(key, threading.Lock())
        with lk:
            hit = self.prep_cache.get(key)
            if hit and Path(hit["restart"]).is_file():
                return hit
            return self._prepare(p, E, key)

    def _prepare(self, p, E, key):
        a = self.a
        target, tol = a.void_ratio, a.e_tol
        tries = []
        mu = PREP_MU_START
        for k in range(6):
            d = self.work / "prep" / key / ("mu%s" % fmt(mu))
            out, secs = run_deck("in.triax_prep", d, dict(
                self.cell_vars(), sigma3=fmt(p * 1e6), E=fmt(E), mu_prep=fmt(mu), e0=fmt(target),
                seed=a.seed, out="prep.restart"))
            e = summary(d, "prep")["void_ratio"]
            tries.append((mu, e))
            print("fit.py: sample %g MPa: mu_prep %.4f -> void ratio %.4f (%.0f s)" % (p, mu, e, secs),
                  flush=True)
            if abs(e - target) <= tol:
                rec = {"restart": str(d / "prep.restart"), "mu_prep": mu, "e": e, "tries": tries,
                       "seconds": secs}
                self.prep_cache.put(key, rec)
                return rec
            # next guess: secant through the two closest tries, else the default slope
            if len(tries) >= 2:
                (m1, e1), (m2, e2) = sorted(tries, key=lambda t: abs(t[1] - target))[:2]
                slope = (e2 - e1) / (m2 - m1) if abs(m2 - m1) > 1e-9 and (e2 - e1) * (m2 - m1) > 0 else PREP_SLOPE
                base_mu, base_e = m1, e1
            else:
                slope, base_mu, base_e = PREP_SLOPE, mu, e
            nxt = min(PREP_MU_MAX, max(0.0, base_mu + (target - base_e) / slope))
            if any(abs(nxt - m) < 1e-4 for m, _ in tries):
                edge = [t for t in tries if abs(t[0] - nxt) < 1e-4][0]
                if nxt <= 0.0:
                    fail("--void-ratio %g: the sample cannot reach this void ratio at %g MPa: even "
                         "frictionless preparation (mu_prep = 0) gives e = %.4f (too dense a target "
                         "for these sizes)" % (target, p, edge[1]))
                if nxt >= PREP_MU_MAX:
                    fail("--void-ratio %g: the sample cannot reach this void ratio at %g MPa: the "
                         "loosest preparation (mu_prep = %g) gives e = %.4f (too loose a target)"
                         % (target, p, PREP_MU_MAX, edge[1]))
                nxt = 0.5 * (nxt + base_mu)
            mu = round(nxt, 4)
        best = min(tries, key=lambda t: abs(t[1] - target))
        fail("--void-ratio %g: the sample did not reach this void ratio within %g at %g MPa in %d "
             "preparations (closest e = %.4f at mu_prep = %.4f); widen --e-tol or check the sizes"
             % (target, tol, p, len(tries), best[1], best[0]))

    # ---- shear runs ---------------------------------------------------------------------
    def run_key(self, prm, p):
        a = self.a
        return "%s_mu%s_mur%s_I%s_strain%s_deck%s" % (self.prep_key(p, prm["E"]), fmt(prm["mu"]),
                                                      fmt(prm["mur"]), fmt(a.inertial), fmt(a.strain),
                                                      deck_hash("in.triax", "cell.inc"))

    def shear(self, prm, p):
        key = self.run_key(prm, p)
        hit = self.eval_cache.get(key)
        if hit and Path(hit["csv"]).is_file():
            return hit
        s = self.sample(p, prm["E"])
        d = self.work / "runs" / key
        out, secs = run_deck("in.triax", d, dict(
            self.cell_vars(), prep=s["restart"], sigma3=fmt(p * 1e6), E=fmt(prm["E"]),
            mu=fmt(prm["mu"]), mur=fmt(prm["mur"]), inertial=fmt(self.a.inertial),
            strain=fmt(self.a.strain), csv="triax.csv"))
        cons, shear = summary(d, "consolidated"), summary(d, "shear")
        rec = {"csv": str(d / "triax.csv"), "seconds": secs,
               "e0": cons["void_ratio"],
               "wall_err_max": max(abs(w / (p * 1e6) - 1) for w in cons["walls_Pa"][:4]),
               "inertial": shear["inertial_number"],
               "rate": shear["rate_per_s"],
               "mu_prep": s["mu_prep"]}
        self.eval_cache.put(key, rec)
        print("fit.py: run mu %.4g mur %.4g E %.3g at %g MPa: %.0f s" % (prm["mu"], prm["mur"], prm["E"], p, secs),
              flush=True)
        return rec

    def evaluate(self, prm, pool):
        futs = {p: pool.submit(self.shear, prm, p) for p in self.a.pressures}
        return {p: f.result() for p, f in futs.items()}


# ---------------------------------------------------------------------------------------------
# misfit
# ---------------------------------------------------------------------------------------------
def read_curve(path):
    rows = [l for l in Path(path).read_text().splitlines() if l and not l.startswith("#")]
    names = rows[0].split(",")
    arr = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    return {n: arr[:, k] for k, n in enumerate(names)}


def misfit_one(curve, data):
    """Misfit at one pressure: RMS of the stress ratio error relative to the data's peak ratio,
    plus W_VOL times the RMS of the volumetric strain error relative to the data's volumetric
    range (max - min), both at the data's axial strains (within the simulated range)."""
    ea, ratio, ev = data[:, 0], data[:, 1], data[:, 2]
    keep = ea <= curve["eps_a_pct"][-1] + 1e-9
    ea, ratio, ev = ea[keep], ratio[keep], ev[keep]
    r_sim = np.interp(ea, curve["eps_a_pct"], curve["ratio"])
    v_sim = np.interp(ea, curve["eps_a_pct"], curve["eps_v_pct"])
    jr = math.sqrt(np.mean(((r_sim - ratio) / ratio.max()) ** 2))
    jv = math.sqrt(np.mean(((v_sim - ev) / max(ev.max() - ev.min(), 1e-9)) ** 2))
    return jr + W_VOL * jv, jr, jv


def summarise(prm, runs, data):
    row = dict(prm)
    tot = []
    for p, rec in runs.items():
        c = read_curve(rec["csv"])
        j, jr, jv = misfit_one(c, data[p][1])
        tot.append(j)
        ev = c["eps_v_pct"]
        kmax = int(np.argmax(ev))
        lateral = np.column_stack([c[n] for n in ("sxlo_Pa", "sxhi_Pa", "sylo_Pa", "syhi_Pa")])[1:]
        lat_err = np.abs(lateral / (p * 1e6) - 1)
        row.update({
            "J_%g" % p: j, "Jratio_%g" % p: jr, "Jvol_%g" % p: jv,
            "peak_sim_%g" % p: float(c["ratio"].max()),
            "peak_data_%g" % p: float(data[p][1][:, 1].max()),
            "contract_dilate_%g" % p: bool(ev[kmax] > 0 and ev[-1] < ev[kmax] - 0.1),
            "e0_%g" % p: rec["e0"], "I_%g" % p: rec["inertial"],
            "wallerr_%g" % p: rec["wall_err_max"], "seconds_%g" % p: rec["seconds"],
            "shearwall_max_%g" % p: float(lat_err.max()), "shearwall_mean_%g" % p: float(lat_err.mean()),
            "Z_end_%g" % p: float(c["Z"][-1])})
    row["J"] = float(np.mean(tot))
    return row


# ---------------------------------------------------------------------------------------------
# search
# ---------------------------------------------------------------------------------------------
def search(cal, data):
    a = cal.a
    start = {"mu": a.mu, "mur": a.mur, "E": a.E}
    rows, seen = [], {}

    def key(prm):
        return tuple(fmt(prm[k]) for k in ("mu", "mur", "E"))

    pool = cf.ThreadPoolExecutor(max_workers=a.jobs)

    def ev(prm):
        k = key(prm)
        if k in seen:
            return seen[k]["J"]
        if len(seen) >= a.budget:
            raise BudgetSpent
        for name in ("mu", "mur", "E"):
            lo, hi, what = RANGES[name]
            if not lo <= prm[name] <= hi:
                return 1e3    # outside the physical range: a wall for the optimiser
        row = summarise(prm, cal.evaluate(prm, pool), data)
        row["n"] = len(seen) + 1
        seen[k] = row
        rows.append(row)
        print("fit.py: evaluation %d/%d: mu %.4g mur %.4g E %.3g -> misfit %.4f" %
              (row["n"], a.budget, prm["mu"], prm["mur"], prm["E"], row["J"]), flush=True)
        return row["J"]

    try:
        ev(start)
        for mu in a.grid_mu:
            for mur in a.grid_mur:
                ev(dict(start, mu=mu, mur=mur))
        if len(seen) < a.budget:
            from scipy.optimize import minimize
            best = min(rows, key=lambda r: r["J"])
            names = a.fit
            scale = {"mu": 0.1, "mur": 0.05, "E": 0.5e9}
            x0 = np.array([best[n] / scale[n] for n in names])
            simplex = [x0] + [x0 + np.eye(len(names))[i] * (-1 if best[names[i]] / scale[names[i]] > 5 else 1)
                              for i in range(len(names))]

            def f(x):
                prm = dict(best)
                prm = {k: prm[k] for k in ("mu", "mur", "E")}
                for n, v in zip(names, x):
                    prm[n] = round(float(v) * scale[n], 4 if n != "E" else -6)
                return ev(prm)

            minimize(f, x0, method="Nelder-Mead",
                     options={"initial_simplex": np.array(simplex), "maxfev": 10 * a.budget,
                              "xatol": 0.05, "fatol": 1e-3})
    except BudgetSpent:
        pass
    finally:
        pool.shutdown(wait=True)
    return rows


# ---------------------------------------------------------------------------------------------
# report
# ---------------------------------------------------------------------------------------------
def write_report(cal, data, rows, out_dir):
    a = cal.a
    out_dir = Path(out_dir)
    tmp = Path(tempfile.mkdtemp(prefix=".fit-", dir=out_dir.parent))
    try:
        paper = rows[0]
        best = min(rows, key=lambda r: r["J"])
        ps = a.pressures
        cols = ["n", "mu", "mur", "E", "J"] + [c % p for p in ps for c in
                                                ("J_%g", "Jratio_%g", "Jvol_%g", "peak_sim_%g", "peak_data_%g",
                                                 "contract_dilate_%g", "e0_%g", "I_%g", "wallerr_%g", "shearwall_mean_%g",
                                                 "shearwall_max_%g", "Z_end_%g", "seconds_%g")]
        with open(tmp / "runs.csv", "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(cols)
            for r in rows:
                w.writerow([("%.6g" % r[c]) if isinstance(r[c], float) else r[c] for c in cols])
        curves = {}
        for tag, r in (("start", paper), ("best", best)):
            for p in ps:
                rec = cal.eval_cache.get(cal.run_key(r, p))
                shutil.copy(rec["csv"], tmp / ("curve_%s_%gMPa.csv" % (tag, p)))
                curves[(tag, p)] = read_curve(rec["csv"])
        L = []
        L.append("# Triaxial calibration report (calibration/fit.py)\n")
        L.append("Generated %s by `fit.py %s`.\n" % (time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
                                                     " ".join(sys.argv[1:])))
        L.append("Sample: %g x %g x %g mm, target void ratio %g +/- %g; inertial number %g; dt %g s; "
                 "strain to %g %%; misfit J = RMS(ratio error / data peak ratio) + %g RMS(eps_v error / "
                 "data eps_v range), at the data's axial strains, averaged over the pressures.\n"
                 % (a.width * 1e3, a.width * 1e3, a.height * 1e3, a.void_ratio, a.e_tol, a.inertial, a.dt,
                    a.strain * 100, W_VOL))
        for p in ps:
            if data[p][2]:
                L.append("- %s\n" % data[p][2])
        for E in sorted({r["E"] for r in (paper, best)}):
            L.append("Samples (E = %.3g GPa, N grains as in in.triax_prep): %s.\n" % (E / 1e9, "; ".join(
                "%g MPa: void ratio %.4f at mu_prep %.4f (%d preparation%s)" % (
                    p, pr["e"], pr["mu_prep"], len(pr["tries"]), "s" if len(pr["tries"]) > 1 else "")
                for p in ps for pr in [cal.prep_cache.get(cal.prep_key(p, E))] if pr)))
        L.append("\n## Start (paper) and best parameters\n")
        L.append("| set | mu | mu_r | E (GPa) | J | " + " | ".join("J %g MPa" % p for p in ps) + " | "
                 + " | ".join("peak ratio %g MPa sim/data" % p for p in ps) + " | contracts then dilates |")
        L.append("|---" * (6 + 2 * len(ps)) + "|")
        for tag, r in (("start (paper)" if paper["mu"] == PAPER["mu"] and paper["mur"] == PAPER["mur"]
                        and paper["E"] == PAPER["E"] else "start", paper), ("best", best)):
            L.append("| %s | %.4g | %.4g | %.3g | %.4f | %s | %s | %s |" % (
                tag, r["mu"], r["mur"], r["E"] / 1e9, r["J"],
                " | ".join("%.4f" % r["J_%g" % p] for p in ps),
                " | ".join("%.3f / %.3f (%+.1f %%)" % (r["peak_sim_%g" % p], r["peak_data_%g" % p],
                                                      100 * (r["peak_sim_%g" % p] / r["peak_data_%g" % p] - 1))
                           for p in ps),
                ", ".join("yes" if r["contract_dilate_%g" % p] else "no" for p in ps)))
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
        out_dir.mkdir(parents=True, exist_ok=True)
        for f in tmp.iterdir():
            f.replace(out_dir / f.name)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return best


SAND_INCLUDE = "sand_calibrated.lmp"


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


def rewrite_sand_include(out_dir):
    """sand_calibrated.lmp from an existing runs.csv (the row of least misfit J)."""
    path = Path(out_dir) / "runs.csv"
    if not path.is_file():
        fail("no %s: run the calibration first" % path)
    with open(path, newline="") as fh:
        rows = [{k: float(v) for k, v in r.items() if k in ("n", "mu", "mur", "E", "J")}
                for r in csv.DictReader(fh)]
    if not rows:
        fail("%s has no evaluations" % path)
    best = min(rows, key=lambda r: r["J"])
    best["n"] = int(best["n"])
    (Path(out_dir) / SAND_INCLUDE).write_text(sand_include(best, len(rows)))
    return best


def figure(path, data, curves, ps, paper, best):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, len(ps), figsize=(4.2 * len(ps), 7), squeeze=False, sharex="col")
    for k, p in enumerate(ps):
        d = data[p][1]
        ax[0, k].plot(d[:, 0], d[:, 1], "ko", ms=3, label="Toyoura e0 0.68 (%s)" % data[p][0])
        ax[1, k].plot(d[:, 0], d[:, 2], "ko", ms=3)
        for tag, r, sty in (("start", paper, "C0--"), ("best", best, "C3-")):
            c = curves[(tag, p)]
            lab = "%s: mu %.3g, mu_r %.3g" % ("paper" if tag == "start" else "fitted", r["mu"], r["mur"])
            ax[0, k].plot(c["eps_a_pct"], c["ratio"], sty, label=lab)
            ax[1, k].plot(c["eps_a_pct"], c["eps_v_pct"], sty)
        ax[0, k].set_title("sigma3 = %g MPa" % p)
        ax[0, k].set_ylabel("sigma1 / sigma3")
        ax[1, k].set_ylabel("volumetric strain (%, contraction +)")
        ax[1, k].set_xlabel("axial strain (%)")
        ax[0, k].legend(fontsize=7)
        ax[1, k].axhline(0, color="0.7", lw=0.5)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


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
        lmp_command()
        data = load_data(a.data, a.pressures)
        cal = Calibration(a)
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
