"""The Toyoura data and the misfit of a run's curves against them."""
import csv
import hashlib
import math
from pathlib import Path

import numpy as np

from .common import W_VOL, fail


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


def mean_curve(curves):
    """The samples' mean curve: every column interpolated at the axial strains of the shortest
    curve, then averaged (one curve: itself)."""
    if len(curves) == 1:
        return curves[0]
    grid = min(curves, key=lambda c: c["eps_a_pct"][-1])["eps_a_pct"]
    return {n: (grid if n == "eps_a_pct" else
                np.mean([np.interp(grid, c["eps_a_pct"], c[n]) for c in curves], axis=0))
            for n in curves[0]}


def sd(values):
    """The samples' standard deviation (0 for one sample)."""
    return float(np.std(values, ddof=1)) if len(values) > 1 else 0.0


def summarise(prm, runs, data):
    """One row of the evaluations' table: the misfit of the seeds' mean curve at each pressure,
    the seeds' mean peak ratio and its standard deviation, the samples' void ratio and the walls' errors."""
    row = dict(prm)
    tot, per_seed = [], []
    for p, recs in runs.items():
        each = [read_curve(rec["csv"]) for rec in recs]
        c = mean_curve(each)
        j, jr, jv = misfit_one(c, data[p][1])
        tot.append(j)
        per_seed.append([misfit_one(e, data[p][1])[0] for e in each])
        ev = c["eps_v_pct"]
        kmax = int(np.argmax(ev))
        names = ("sxlo_Pa", "sxhi_Pa", "sylo_Pa", "syhi_Pa")
        lat_err = np.concatenate([np.abs(np.column_stack([e[n] for n in names])[1:] / (p * 1e6) - 1).ravel()
                                  for e in each])
        peaks = np.array([e["ratio"].max() for e in each])
        # each sample's largest contraction and eps_v at 10 % axial strain (the bracket's measures)
        contraction = np.array([e["eps_v_pct"].max() for e in each])
        ev10 = np.array([np.interp(10.0, e["eps_a_pct"], e["eps_v_pct"], right=np.nan) for e in each])
        row.update({
            "J_%g" % p: j, "Jratio_%g" % p: jr, "Jvol_%g" % p: jv,
            "peak_sim_%g" % p: float(peaks.mean()),
            "peak_sd_%g" % p: sd(peaks),
            "peak_data_%g" % p: float(data[p][1][:, 1].max()),
            "contraction_%g" % p: float(contraction.mean()), "contraction_sd_%g" % p: sd(contraction),
            "ev10_%g" % p: float(ev10.mean()), "ev10_sd_%g" % p: sd(ev10),
            "contract_dilate_%g" % p: bool(ev[kmax] > 0 and ev[-1] < ev[kmax] - 0.1),
            "e0_%g" % p: float(np.mean([r["e0"] for r in recs])),
            "I_%g" % p: float(np.mean([r["inertial"] for r in recs])),
            "wallerr_%g" % p: max(r["wall_err_max"] for r in recs),
            "seconds_%g" % p: sum(r["seconds"] for r in recs),
            "shearwall_max_%g" % p: float(lat_err.max()), "shearwall_mean_%g" % p: float(lat_err.mean()),
            "Z_end_%g" % p: float(c["Z"][-1])})
    row["J"] = float(np.mean(tot))
    # the misfit's sample noise: the spread of each sample's own misfit (averaged over the pressures)
    row["J_sd"] = sd(np.mean(np.array(per_seed), axis=0))
    return row
