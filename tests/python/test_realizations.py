"""postprocess/tbagspost/realizations on made-up CSVs: the reported figures of a run, their spread
over realizations, the mean curves and the grouping of runs by load."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "postprocess"))
from tbagspost import realizations as rz  # noqa: E402
from tbagspost.run import Run  # noqa: E402

HEADER = "time_s,u_mm,w_mm,S_N,Fv_N,broken_bonds,zplate_mm\n"


def csv(path, peak, contraction, dilation, umax=5.0):
    """S rises to peak at 4 mm then falls by 10 %; w falls by contraction to 3 mm, then rises by dilation."""
    u = np.concatenate([[0.0], np.arange(0.05, umax, 0.1)])
    S = np.where(u < 4, peak * u / 4, peak * (1 - 0.1 * (u - 4)))
    w = np.where(u < 3, -contraction * u / 3, -contraction + dilation * (u - 3) / max(umax - 3, 1e-9)) - 1.0
    path.mkdir(parents=True)
    rows = ["%g,%g,%g,%g,100,0,30" % (1e-3 * k, a, b, c) for k, (a, b, c) in enumerate(zip(u, w, S))]
    (path / "shear.csv").write_text(HEADER + "\n".join(rows) + "\n")
    return Run(path)


def test_metrics_of_one_run(tmp_path):
    m = rz.metrics(csv(tmp_path / "a", 500.0, 0.3, 0.6).csv)
    assert m["S_peak_N"] == pytest.approx(500 * (1 - 0.1 * 0.05))    # the row at 4.05 mm
    assert m["u_peak_mm"] == pytest.approx(4.05)
    assert m["contraction_mm"] == pytest.approx(0.3 * 2.95 / 3)        # lowest row: 2.95 mm
    assert m["dilatancy_mm"] == pytest.approx(0.6 * 1.95 / 2 - 0.3 + 0.295)   # w(4.95) - w(2.95)
    assert m["S_5mm_N"] == pytest.approx(500 * (1 - 0.1 * 0.95))    # the last row (4.95 mm)
    assert m["Fv_N"] == 100.0
    assert np.isnan(rz.metrics(csv(tmp_path / "b", 500.0, 0.3, 0.2, umax=3.0).csv)["S_5mm_N"])


def test_spread():
    assert rz.spread([1.0, 2.0, 3.0]) == (2.0, 1.0, 1.0, 3.0)
    assert rz.spread([4.0]) == (4.0, 0.0, 4.0, 4.0)
    assert rz.spread([float("nan"), 1.0, 3.0])[0] == 2.0


def test_groups_mean_curves_and_files(tmp_path):
    runs = [csv(tmp_path / r / f, p * s, 0.3 * s, 0.1, umax=u) for r, s, u in (("r1", 1.0, 5.0), ("r2", 1.2, 4.5))
            for f, p in (("F5500", 800.0), ("F1960", 300.0))]
    groups = rz.group_runs(runs)
    assert list(groups) == ["F5500", "F1960"] and [rz.realization_name(r) for r in groups["F5500"]] == ["r1", "r2"]
    c = rz.mean_curves([r.csv for r in groups["F5500"]])
    assert c["u_mm"][-1] == pytest.approx(4.45)           # the shorter run's end
    k = np.searchsorted(c["u_mm"], 2.0)
    assert c["S_N_mean"][k] == pytest.approx(800 * 1.1 * c["u_mm"][k] / 4)
    assert c["S_N_std"][k] == pytest.approx(np.std([800 * c["u_mm"][k] / 4, 960 * c["u_mm"][k] / 4], ddof=1))
    md = rz.write(runs, tmp_path / "out")
    assert "| F5500 | 2 |" in md and "| F1960 | 2 |" in md
    assert (tmp_path / "out" / "curves_F1960.csv").exists() and (tmp_path / "out" / "realizations.png").exists()
    with pytest.raises(SystemExit, match="at least two runs"):
        rz.write(runs[:1], tmp_path / "one")
