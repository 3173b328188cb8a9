"""The main job as a regression test: the demo bag (21 x 21 x 7) of `./tbags shear` built,
filled (seed 4821) and sheared with the preset's protocol (5.5 kN's stress, F_v 318.14 N, 15 mm/s
to 5 mm) on 1 rank (the suite makes it once, ctest fixture "demo", for this test and
test_liggghts_demo.py). The figures it reports, measured as tbagspost.realizations measures them,
must fall inside the spread of the committed realizations (results/demo-realizations.csv,
six fills: S at 5 mm 551 +- 17 N, contraction 0.156 +- 0.008 mm): within 3 standard
deviations of their mean, at least the half-range of the fills plus 5 % of the mean; F_v
within 0.5 % of its target; no yarn breaks. A change of physics that moves the result by more
than the realizations' own scatter fails here."""
import csv
import sys

import numpy as np
import pytest

import lmprun

sys.path.insert(0, str(lmprun.ROOT / "postprocess"))
from tbagspost import realizations  # noqa: E402

INPUTS = lmprun.INPUTS


def committed_spread():
    with open(lmprun.ROOT / "results" / "demo-realizations.csv") as fh:
        rows = list(csv.DictReader(fh))
    return {k: np.array([float(r[k]) for r in rows]) for k in ("S_5mm_N", "contraction_mm", "S_peak_N")}


def band(values):
    m, s = values.mean(), values.std(ddof=1)
    half = max(3 * s, 0.5 * (values.max() - values.min()) + 0.05 * abs(m))
    return m - half, m + half


def test_demo_bag_within_the_realizations(tmp_path):
    wd, output = lmprun.demo(tmp_path)    # the suite's shared run (fixture "demo"), or made here
    d = np.genfromtxt(wd / "shear.csv", delimiter=",", names=True, comments="#")
    got = realizations.metrics(d)
    ref = committed_spread()
    for key in ("S_5mm_N", "contraction_mm", "S_peak_N"):
        lo, hi = band(ref[key])
        print("%s: %.4g (realizations %s; band %.4g .. %.4g)" % (key, got[key], ref[key], lo, hi))
        assert lo <= got[key] <= hi, key
    assert got["Fv_N"] == pytest.approx(318.14, rel=0.005)
    assert "broken bonds 0" in output.split("SHEARED:")[1].splitlines()[0]
