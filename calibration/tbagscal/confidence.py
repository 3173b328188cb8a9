"""The fitted parameters' confidence region: a quadratic through the evaluations near the best
one, in the search's scaled coordinates (mu / 0.1, mu_r / 0.05, log10 E / 0.15), and the region
where it rises by less than the misfit's sample noise (the spread of the samples' own misfits at
the best set): J <= J_best + dJ. Its half-width along each parameter, the others free (the
marginal one), is sqrt(2 dJ (H^-1)_ii) in scaled units; H is the quadratic's Hessian."""
import math

import numpy as np

SCALE = {"mu": 0.1, "mur": 0.05, "E": 0.15}


def to_x(name, value):
    return math.log10(value) / SCALE[name] if name == "E" else value / SCALE[name]


def region(rows, names, dJ):
    """{name: (low, high)} of the parameters searched, or a sentence saying why there is none.
    rows: the evaluations (dicts with the names and J); dJ > 0: the misfit rise that bounds it."""
    n = len(names)
    need = 1 + n + n * (n + 1) // 2          # a full quadratic's coefficients
    if dJ <= 0:
        return "no sample noise to bound it (one sample per pressure: use --seeds 2 or more)"
    best = min(rows, key=lambda r: r["J"])
    xb = np.array([to_x(k, best[k]) for k in names])
    # the evaluations nearest the best, at least need + 2 of them (the quadratic's residual)
    near = sorted(rows, key=lambda r: np.linalg.norm(np.array([to_x(k, r[k]) for k in names]) - xb))
    if len(near) < need + 2:
        return "%d evaluations: a quadratic in %d parameters needs at least %d" % (len(near), n, need + 2)
    near = near[:max(need + 2, 2 * need)]
    X, y = [], []
    for r in near:
        d = np.array([to_x(k, r[k]) for k in names]) - xb
        quad = [d[i] * d[j] * (0.5 if i == j else 1.0) for i in range(n) for j in range(i, n)]
        X.append([1.0] + list(d) + quad)
        y.append(r["J"])
    coef = np.linalg.lstsq(np.array(X), np.array(y), rcond=None)[0]
    H = np.zeros((n, n))
    k = 1 + n
    for i in range(n):
        for j in range(i, n):
            H[i, j] = H[j, i] = coef[k]
            k += 1
    if np.any(np.linalg.eigvalsh(H) <= 0):
        return "the misfit is not convex around the best set (a flat or descending direction): no bounded region"
    g = coef[1:1 + n]
    Hinv = np.linalg.inv(H)
    step = Hinv @ g
    centre = xb - step                                     # the quadratic's own minimum
    jmin = coef[0] - 0.5 * g @ step
    out = {}
    for i, name in enumerate(names):
        half = math.sqrt(2.0 * (dJ + max(0.0, best["J"] - jmin)) * Hinv[i, i])
        lo, hi = centre[i] - half, centre[i] + half
        if name == "E":
            out[name] = (10 ** (lo * SCALE[name]), 10 ** (hi * SCALE[name]))
        else:
            out[name] = (lo * SCALE[name], hi * SCALE[name])
    return out


def indistinguishable(rows, names, dJ, k=2.0):
    """The evaluated sets whose misfit lies within k sample-noise standard deviations dJ of the
    best one (the noise cannot tell them from it): (count, {name: (low, high)} over them). A
    region from evaluations only: bounded by where the search looked, so at least this wide."""
    best = min(r["J"] for r in rows)
    near = [r for r in rows if r["J"] <= best + k * dJ]
    return len(near), {n: (min(r[n] for r in near), max(r[n] for r in near)) for n in names}
