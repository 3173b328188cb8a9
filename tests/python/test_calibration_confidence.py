"""calibration/tbagscal/confidence.py on misfits of a known quadratic: the region J <= J_best + dJ
is recovered (each parameter's marginal half-width sqrt(2 dJ' (H^-1)_ii), the centre off the
best evaluation), E in log scale; a saddle, too few evaluations and no sample noise give a
sentence instead of numbers."""
import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "calibration"))
from tbagscal import confidence  # noqa: E402

NAMES = ("mu", "mur", "E")
CENTRE = {"mu": 0.40, "mur": 0.30, "E": 5e9}
H = np.array([[2.0, 0.5, 0.2], [0.5, 1.0, 0.1], [0.2, 0.1, 0.5]])   # in scaled units
J0 = 0.12


def x_of(r):
    return np.array([confidence.to_x(k, r[k]) for k in NAMES])


def misfit(r, hessian=H):
    d = x_of(r) - x_of(CENTRE)
    return J0 + 0.5 * d @ hessian @ d


def rows(n=14, hessian=H, seed=3):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        r = {"mu": CENTRE["mu"] + 0.1 * rng.normal(), "mur": CENTRE["mur"] + 0.05 * rng.normal(),
             "E": CENTRE["E"] * 10 ** (0.15 * rng.normal())}
        r["J"] = misfit(r, hessian)
        out.append(r)
    return out


def test_region_of_a_known_quadratic():
    rs = rows()
    dJ = 0.01
    got = confidence.region(rs, NAMES, dJ)
    best = min(r["J"] for r in rs)
    level = dJ + best - J0                      # the region's height above the quadratic's minimum
    inv = np.linalg.inv(H)
    for i, k in enumerate(NAMES):
        half = math.sqrt(2 * level * inv[i, i])
        c = confidence.to_x(k, CENTRE[k])
        lo, hi = got[k]
        print(k, got[k])
        assert confidence.to_x(k, lo) == pytest.approx(c - half, rel=1e-9)
        assert confidence.to_x(k, hi) == pytest.approx(c + half, rel=1e-9)
    assert got["E"][0] < CENTRE["E"] < got["E"][1] and got["E"][0] > 1e9


def test_no_region_without_curvature_evaluations_or_noise():
    saddle = H.copy()
    saddle[2, 2] = -0.5
    assert "not convex" in confidence.region(rows(hessian=saddle), NAMES, 0.01)
    assert "at least 12" in confidence.region(rows(n=8), NAMES, 0.01)
    assert "--seeds" in confidence.region(rows(), NAMES, 0.0)


def test_indistinguishable_sets_span_those_within_the_noise():
    """The evaluated sets within 2 dJ of the best one, and the range each parameter spans over them."""
    rs = [{"mu": 0.40, "mur": 0.30, "E": 4e9, "J": 0.080}, {"mu": 0.38, "mur": 0.35, "E": 5e9, "J": 0.089},
          {"mu": 0.45, "mur": 0.28, "E": 3e9, "J": 0.095}, {"mu": 0.30, "mur": 0.20, "E": 9e9, "J": 0.091}]
    n, spread = confidence.indistinguishable(rs, NAMES, 0.006)
    assert n == 3 and spread == {"mu": (0.30, 0.40), "mur": (0.20, 0.35), "E": (4e9, 9e9)}
    assert confidence.indistinguishable(rs, NAMES, 0.001)[1]["mu"] == (0.40, 0.40)


def test_figure_names_a_start_that_is_not_the_papers():
    from tbagscal.figure import label
    assert label("start", {"mu": 0.31, "mur": 0.05, "E": 1.8e9}).startswith("paper: mu 0.31, mu_r 0.05, E 1.8 GPa")
    assert label("start", {"mu": 0.379, "mur": 0.418, "E": 4.98e9}).startswith("start: mu 0.379")
    assert label("best", {"mu": 0.4149, "mur": 0.4206, "E": 3.99e9}) == "fitted: mu 0.415, mu_r 0.421, E 3.99 GPa"
