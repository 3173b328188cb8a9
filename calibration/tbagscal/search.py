"""The search over mu, mu_r (and E): a grid, the star around the start (points on both sides of it
along each fitted parameter, which the confidence region's quadratic needs), then Nelder-Mead from
the best point so far, within a budget."""
import concurrent.futures as cf

import numpy as np

from .common import BudgetSpent, RANGES, fmt
from .confidence import SCALE, to_x
from .misfit import summarise


def from_x(n, x):
    """A parameter from its scaled coordinate (confidence.SCALE: unit steps of 0.1 in mu, 0.05 in
    mu_r, a factor 10^0.15 = 1.41 in E, searched in log10 E: the grain stiffness matters by its
    ratio), rounded as the cache's keys are."""
    return float("%.3g" % 10 ** (x * SCALE[n])) if n == "E" else round(x * SCALE[n], 4)


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
        for n in a.fit if a.star > 0 else ():
            for sign in (-1, 1):
                ev(dict(start, **{n: from_x(n, to_x(n, start[n]) + sign * a.star)}))
        if len(seen) < a.budget:
            from scipy.optimize import minimize
            best = min(rows, key=lambda r: r["J"])
            names = a.fit

            x0 = np.array([to_x(n, best[n]) for n in names])
            # first steps away from the range's upper end (mu, mu_r) and towards stiffer grains (E)
            simplex = [x0] + [x0 + np.eye(len(names))[i] * (-1 if n != "E" and best[n] / SCALE[n] > 5 else 1)
                              for i, n in enumerate(names)]

            def f(x):
                prm = {k: best[k] for k in ("mu", "mur", "E")}
                for n, v in zip(names, x):
                    prm[n] = from_x(n, float(v))
                return ev(prm)

            minimize(f, x0, method="Nelder-Mead",
                     options={"initial_simplex": np.array(simplex), "maxfev": 10 * a.budget,
                              "xatol": 0.05, "fatol": 1e-3})
    except BudgetSpent:
        pass
    finally:
        pool.shutdown(wait=True)
    return rows
