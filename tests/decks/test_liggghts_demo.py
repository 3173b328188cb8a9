"""The demo shear (the main job's bag, fill and protocol) in both engines from the same fill:
LAMMPS's inputs/in.shear and LIGGGHTS's inputs/liggghts/in.shear. A run from one packing is one
sample, and two engines that compute the same law to round-off still part ways in a packing, so
their results must agree as two samples of one packing could: within the spread that different
packings (realizations) give, as measured and committed in inputs/results/demo-realizations.csv
(6 fills: S at 5 mm 551 +- 17 N, contraction 0.156 +- 0.008 mm). Checked: S at u = 5 mm and the
contraction (tbagspost.realizations' figures of a run) within 2 standard deviations of that
spread, and F_v held within 1 % in both. About 10 minutes (1 rank each, LIGGGHTS most of it)."""
import csv

import numpy as np
import pytest

import lmprun
from tbagsrun.presets import DEMO_BAG, PRESETS
from tbagsrun.liggghts_stage import means_to_csv
from twoengines import convert
from tbagspost.realizations import metrics  # (postprocess/ is on the path through twoengines)
from tbagspost.run import read_csv

SHEAR = PRESETS["demo"].runs[0].variables


def spread():
    """Standard deviation over the committed demo realizations of each metric."""
    with open(lmprun.ROOT / "inputs" / "results" / "demo-realizations.csv") as fh:
        rows = list(csv.DictReader(fh))
    return {k: float(np.std([float(r[k]) for r in rows], ddof=1)) for k in ("S_5mm_N", "contraction_mm")}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    wd = tmp_path_factory.mktemp("demo")
    lmprun.bag_and_fill(wd, DEMO_BAG)
    variables = dict(DEMO_BAG, **SHEAR)
    lmp = wd / "lammps"
    lmp.mkdir()
    (lmp / "fill.data").write_bytes((wd / "fill.data").read_bytes())
    # LIGGGHTS's servo plates damp explicitly (as stock) at 1.5e-6 s: LAMMPS runs the same scheme
    lmprun.run(lmprun.INPUTS / "in.shear", lmp, variables=dict(variables, dt=1.5e-6, damping="explicit"),
               timeout=3600).check()
    lig = wd / "liggghts"
    lig.mkdir()
    convert(wd / "fill.data", lig / "fill.liggghts.data")
    lmprun.run(lmprun.INPUTS / "liggghts" / "in.shear", lig, engine="liggghts", timeout=3600,
               variables=dict(variables, fill="fill.liggghts.data")).check("liggghts")
    means_to_csv(lig / "shear.means.txt", lig / "shear.csv", lig / "shear.start.txt", lig / "shear.steps.txt")
    return read_csv(lmp / "shear.csv"), read_csv(lig / "shear.csv")


def test_demo_within_the_realization_spread(runs):
    a, b = (metrics(d) for d in runs)
    sd = spread()
    print("demo: S at 5 mm LAMMPS %.1f N, LIGGGHTS %.1f N (realizations' sd %.1f N); contraction "
          "%.3f / %.3f mm (sd %.3f mm); F_v while shearing %.2f / %.2f N"
          % (a["S_5mm_N"], b["S_5mm_N"], sd["S_5mm_N"], a["contraction_mm"], b["contraction_mm"],
             sd["contraction_mm"], a["Fv_N"], b["Fv_N"]))
    assert abs(a["S_5mm_N"] - b["S_5mm_N"]) < 2 * sd["S_5mm_N"]
    assert abs(a["contraction_mm"] - b["contraction_mm"]) < 2 * sd["contraction_mm"]
    target = 5500 * 19 * 19 / 79 ** 2
    for d in runs:
        assert np.all(np.abs(d["Fv_N"][1:] / target - 1) < 0.01)
