"""The contraction study (fit.py --study): is the fitted sand's excess contraction before dilation
a property of spheres at the data's void ratio, or of the fit?

The fitted friction (the best row of OUT/runs.csv) is run again, at every pressure, on
- other samples (seeds): the spread one sample carries;
- other frictions (the search's grid): what the fit could trade;
- stiffer grains (E; the time step scaled to the same fraction of the Rayleigh step);
- denser samples (void ratio, reached through the preparation friction),
and the packing's own limits are probed (frictionless and mu_prep = 1 preparations), so that the
void ratio can be read as a relative density of these spheres and compared with the sand's."""
import argparse
import concurrent.futures as cf
import csv
import sys
import time

import numpy as np

from .common import PAPER, PREP_MU_MAX, FitError, fmt
from .evaluate import Calibration
from .misfit import misfit_one, read_curve, sd
from .report import published, read_runs
from .runs import run_deck, summary

# Toyoura sand's limiting void ratios (standard values, Ishihara 1993): the data's e0 = 0.68 is a
# relative density of 78 %
TOYOURA_EMAX, TOYOURA_EMIN = 0.977, 0.597
SEEDS = (7331, 7332, 7333, 7334, 7335)
E_FACTORS = (2.0, 4.0, 10.0)
VOID_RATIOS = (0.65, 0.62)
FRICTIONS = ((PAPER["mu"], PAPER["mur"]), (0.5, 0.25), (0.8, 0.1), (1.2, 0.25), (0.8, 0.4))


def read_best(out_dir):
    return min(read_runs(out_dir, "--study needs %s (the fit's evaluations): run the calibration first"),
               key=lambda r: r["J"])


def curve_measures(c):
    """Peak ratio and where; largest contraction and where; eps_v at 10 % and at the end."""
    ea, ev, ratio = c["eps_a_pct"], c["eps_v_pct"], c["ratio"]
    kp, kv = int(np.argmax(ratio)), int(np.argmax(ev))
    return {"peak": float(ratio[kp]), "ea_peak": float(ea[kp]), "contraction": float(ev[kv]),
            "ea_contraction": float(ea[kv]), "ev_10": float(np.interp(10.0, ea, ev)),
            "ea_end": float(ea[-1]), "ev_end": float(ev[-1])}


def data_measures(d):
    return curve_measures({"eps_a_pct": d[:, 0], "ratio": d[:, 1], "eps_v_pct": d[:, 2]})


class Case:
    """One variant of the sample or the parameters, run at every pressure."""

    def __init__(self, group, label, base, prm, **changes):
        self.group, self.label, self.prm = group, label, prm
        a = argparse.Namespace(**vars(base.a))
        for k, v in changes.items():
            setattr(a, k, v)
        self.cal = Calibration(a, share=base)
        self.runs, self.error = {}, None


def cases(base, best):
    fit = {"mu": best["mu"], "mur": best["mur"], "E": best["E"]}
    out = [Case("seed", "seed %d" % s, base, fit, seed=s) for s in SEEDS]
    for f in E_FACTORS:
        out.append(Case("E", "E %.3g GPa" % (fit["E"] * f / 1e9), base, dict(fit, E=fit["E"] * f)))
    out += [Case("void ratio", "e %.2f" % e, base, fit, void_ratio=e) for e in VOID_RATIOS]
    out += [Case("friction", "mu %.3g, mu_r %.3g" % (mu, mur), base, dict(fit, mu=mu, mur=mur))
            for mu, mur in FRICTIONS]
    return out


def probe_limits(cal, pressures, pool, E):
    """Void ratio of the frictionless (densest) and mu_prep = 1 (loosest) preparations."""
    def one(p, mu):
        key = "limit_" + cal.prep_key(p, E) + "_mu%s" % fmt(mu)
        hit = cal.prep_cache.get(key)
        if hit:
            return hit["e"]
        d = cal.work / "limits" / key
        run_deck(cal.decks()[0], d, dict(cal.cell_vars(E), sigma3=fmt(p * 1e6), E=fmt(E),
                                          mu_prep=fmt(mu), e0=fmt(cal.a.void_ratio), seed=cal.a.seed,
                                          out="prep.restart"))
        e = summary(d, "prep")["void_ratio"]
        cal.prep_cache.put(key, {"e": e})
        print("fit.py: study: limit at %g MPa, mu_prep %g -> void ratio %.4f" % (p, mu, e), flush=True)
        return e
    futs = {(p, mu): pool.submit(one, p, mu) for p in pressures for mu in (0.0, PREP_MU_MAX)}
    return {k: f.result() for k, f in futs.items()}


def run_study(base, data, out_dir):
    a = base.a
    best = read_best(out_dir)
    todo = cases(base, best)
    pool = cf.ThreadPoolExecutor(max_workers=a.jobs)
    t0 = time.time()
    limits = probe_limits(base, a.pressures, pool, best["E"])
    futs = [(c, p, pool.submit(c.cal.shear, c.prm, p)) for c in todo for p in a.pressures]
    for c, p, f in futs:
        try:
            c.runs[p] = f.result()
        except FitError as e:     # an unreachable void ratio is a result, not a crash
            c.error = str(e)
    pool.shutdown()
    write_study(base, data, best, todo, limits, out_dir, time.time() - t0)


def dr(e, emax, emin):
    return (emax - e) / (emax - emin)


def write_study(base, data, best, todo, limits, out_dir, seconds):
    a, ps = base.a, base.a.pressures
    rows = []
    for c in todo:
        for p in ps:
            if p not in c.runs:
                continue
            rec = c.runs[p]
            cur = read_curve(rec["csv"])
            j, jr, jv = misfit_one(cur, data[p][1])
            emin, emax = limits[(p, 0.0)], limits[(p, PREP_MU_MAX)]
            rows.append(dict(curve_measures(cur), group=c.group, case=c.label, p=p, mu=c.prm["mu"],
                             mur=c.prm["mur"], E=c.prm["E"], seed=c.cal.a.seed, e0=rec["e0"],
                             Dr=dr(rec["e0"], emax, emin), Z0=float(cur["Z"][0]), J=j, Jratio=jr,
                             Jvol=jv))
    meas = {p: data_measures(data[p][1]) for p in ps}
    L = ["# The contraction study (calibration/fit.py --study)\n",
         "Generated %s by `fit.py %s` in %.0f s. The fitted sand (evaluation %d of runs.csv: mu %.4g, "
         "mu_r %.4g, E %.3g GPa) run again on other samples, frictions, grain stiffnesses and void "
         "ratios; every run at every pressure, %g x %g x %g mm cell, I = %g, to %g %% axial strain.\n"
         % (time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), " ".join(sys.argv[1:]), seconds,
            best["n"], best["mu"], best["mur"], best["E"] / 1e9, a.width * 1e3, a.width * 1e3,
            a.height * 1e3, a.inertial, a.strain * 100),
         "## The packing's limits and relative density\n",
         "Void ratio after isotropic consolidation of a frictionless preparation (the densest these "
         "spheres pack: e_min) and of one with mu_prep = %g (the loosest stable packing the protocol "
         "makes: e_max), seed %d. Toyoura sand: e_max %.3f, e_min %.3f (standard values), so the "
         "data's e0 = 0.68 is a relative density Dr = %.0f %%.\n"
         % (PREP_MU_MAX, a.seed, TOYOURA_EMAX, TOYOURA_EMIN, 100 * dr(0.68, TOYOURA_EMAX, TOYOURA_EMIN)),
         "| sigma3 (MPa) | e_min (spheres) | e_max (spheres) | Dr of e = 0.68 | e at the sand's Dr |",
         "|---|---|---|---|---|"]
    dr_sand = dr(0.68, TOYOURA_EMAX, TOYOURA_EMIN)
    for p in ps:
        emin, emax = limits[(p, 0.0)], limits[(p, PREP_MU_MAX)]
        L.append("| %g | %.4f | %.4f | %.0f %% | %.4f |" % (p, emin, emax, 100 * dr(0.68, emax, emin),
                                                            emax - dr_sand * (emax - emin)))
    L += ["\n## Every run\n",
          "Peak stress ratio (and the axial strain at it), the largest contraction eps_v (and where), "
          "eps_v at 10 % axial strain (negative: dilated), the void ratio e0 and coordination Z0 "
          "before shearing, Dr = the void ratio as a relative density of these spheres, misfit J "
          "(ratio, volume) as in report.md.\n",
          "| group | case | sigma3 | peak ratio (at %) | contraction % (at %) | eps_v at 10 % | e0 | Dr | Z0 | J (ratio, vol) |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for p in ps:
        m = meas[p]
        L.append("| data | Toyoura e0 0.68 | %g | %.2f (%.1f) | %.2f (%.1f) | %.2f | 0.68 | %.0f %% | - | - |"
                 % (p, m["peak"], m["ea_peak"], m["contraction"], m["ea_contraction"], m["ev_10"],
                    100 * dr_sand))
    for r in rows:
        L.append("| %s | %s | %g | %.2f (%.1f) | %.2f (%.1f) | %.2f | %.4f | %.0f %% | %.2f | %.3f (%.3f, %.3f) |"
                 % (r["group"], r["case"], r["p"], r["peak"], r["ea_peak"], r["contraction"],
                    r["ea_contraction"], r["ev_10"], r["e0"], 100 * r["Dr"], r["Z0"], r["J"], r["Jratio"],
                    r["Jvol"]))
    for c in todo:
        if c.error:
            L.append("\n- %s: %s" % (c.label, c.error))
    L += ["\n## Seed spread (the fitted sand, e0 %.2f)\n" % a.void_ratio,
          "| sigma3 (MPa) | peak ratio | contraction % | eps_v at 10 % | J | data: peak, contraction |",
          "|---|---|---|---|---|---|"]
    for p in ps:
        s = [r for r in rows if r["group"] == "seed" and r["p"] == p]
        if not s:
            continue
        def ms(k):
            v = np.array([r[k] for r in s])
            return "%.3f +- %.3f [%.3f, %.3f]" % (v.mean(), sd(v),
                                                 v.min(), v.max())
        L.append("| %g | %s | %s | %s | %s | %.2f, %.2f |" % (p, ms("peak"), ms("contraction"), ms("ev_10"),
                                                         ms("J"), meas[p]["peak"], meas[p]["contraction"]))
    L.append("\n(mean +- standard deviation over %d seeds [range])\n" % len(SEEDS))
    with published(out_dir) as tmp:
        (tmp / "contraction-study.md").write_text("\n".join(L) + "\n")
        cols = ["group", "case", "p", "mu", "mur", "E", "seed", "e0", "Dr", "Z0", "peak", "ea_peak",
                "contraction", "ea_contraction", "ev_10", "ea_end", "ev_end", "J", "Jratio", "Jvol"]
        with open(tmp / "contraction-study.csv", "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(cols)
            for r in rows:
                w.writerow([("%.6g" % r[k]) if isinstance(r[k], float) else r[k] for k in cols])
        if not a.no_figure:
            study_figure(tmp / "contraction-study.png", data, todo, ps)


def study_figure(path, data, todo, ps):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    groups = ["seed", "E", "void ratio", "friction"]
    fig, ax = plt.subplots(len(groups), len(ps), figsize=(4.2 * len(ps), 3.2 * len(groups)),
                           squeeze=False, sharex=True)
    for g, group in enumerate(groups):
        for k, p in enumerate(ps):
            d = data[p][1]
            ax[g, k].plot(d[:, 0], d[:, 2], "ko", ms=3, label="Toyoura e0 0.68")
            base = todo[0]    # the fitted sand on the first seed: the reference of every group
            if group != base.group and p in base.runs:
                cur = read_curve(base.runs[p]["csv"])
                ax[g, k].plot(cur["eps_a_pct"], cur["eps_v_pct"], "k--", lw=1, label="fitted, " + base.label)
            for n, c in enumerate([c for c in todo if c.group == group and p in c.runs]):
                cur = read_curve(c.runs[p]["csv"])
                ax[g, k].plot(cur["eps_a_pct"], cur["eps_v_pct"], color="C%d" % n, lw=1, label=c.label)
            ax[g, k].axhline(0, color="0.7", lw=0.5)
            ax[g, k].set_title("%s, sigma3 = %g MPa" % (group, p), fontsize=9)
            if k == 0:
                ax[g, k].set_ylabel("eps_v (%, contraction +)")
            ax[g, k].legend(fontsize=6)
    for k in range(len(ps)):
        ax[-1, k].set_xlabel("axial strain (%)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
