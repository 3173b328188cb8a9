"""The height study (tbagspost.height) on hand-made shear CSVs of known S/F_v and w/H, and on the
two committed tall-bag runs, whose by-hand table it must give again."""
import os
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "postprocess"))
from tbagspost import height  # noqa: E402


def write_csv(path, h_mm, ratio, w_pct_per_pct, fv=200.0, strain_end=20.0, w0=-3.0):
    """A shear CSV on which S/F_v = ratio(strain %) and w/H = w_pct_per_pct x strain (%), rows
    every 0.1 mm to strain_end % of h_mm, w starting at w0 (the compression, to be removed)."""
    u = np.arange(0.0, strain_end / 100 * h_mm + 1e-9, 0.1)
    strain = 100 * u / h_mm
    rows = ["time_s,u_mm,w_mm,S_N,Fv_N"]
    rows += ["%.6f,%.6f,%.9f,%.9f,%.4f" % (0.01 * k, uk, w0 + w_pct_per_pct * s * h_mm / 100, ratio(s) * fv, fv)
             for k, (uk, s) in enumerate(zip(u, strain))]
    path.write_text("\n".join(rows) + "\n")
    return path


def test_known_ratios_and_settlement(tmp_path):
    small = write_csv(tmp_path / "a.csv", 25.0, lambda s: 0.05 * s, -0.1)
    tall = write_csv(tmp_path / "b.csv", 75.0, lambda s: 0.04 * s, -0.2, strain_end=10.0)
    m = height.measure([("small", 25.0, [small]), ("tall", 75.0, [tall])], [5, 10, 15])
    assert [round(v[0], 9) for v in m["small"]["ratio"]] == [0.25, 0.5, 0.75]
    assert [round(v[0], 9) for v in m["small"]["w"]] == [-0.5, -1.0, -1.5]
    assert np.isnan(m["tall"]["ratio"][2][0])    # 15 % not reached (10 % of 75 mm)
    dr, dw, ok = height.compare(m, "tall")["small"]
    assert (round(dr, 9), round(dw, 9), ok) == (0.25, 1.0, False)    # 0.5 / 0.4 - 1


def test_realizations_give_mean_and_spread(tmp_path):
    paths = [write_csv(tmp_path / ("r%d.csv" % k), 25.0, lambda s, k=k: (0.04 + 0.01 * k) * s, -0.1)
             for k in range(3)]
    m = height.measure([("r", 25.0, paths)], [10])
    mean, sd = m["r"]["ratio"][0]
    assert (round(mean, 9), round(sd, 9)) == (0.5, 0.1)


def test_within_ten_percent(tmp_path):
    ref = write_csv(tmp_path / "ref.csv", 75.0, lambda s: 0.05 * s, -0.1)
    near = write_csv(tmp_path / "near.csv", 45.0, lambda s: 0.054 * s, -0.1)
    text = height.report([("near", 45.0, [near]), ("paper", 75.0, [ref])], [5, 10])
    assert "| near | 8.0 % | 0.00 | yes |" in text


def test_committed_tall_bags_reproduce_the_results_table():
    """results/README.md's height table (made by hand) for the 35 and 45 mm bags at 5.50 kN."""
    bags = [("35", 35.0, [ROOT / "results" / "trends-tall-F5500-shear.csv"]),
            ("45", 45.0, [ROOT / "results" / "trends-height45-F5500-shear.csv"])]
    m = height.measure(bags, [5, 10, 15, 20])
    assert [round(v[0], 2) for v in m["35"]["ratio"]] == [0.71, 1.12, 1.50, 1.47]
    assert [round(v[0], 2) for v in m["45"]["ratio"]] == [0.60, 1.01, 1.17, 1.37]
    assert [round(v[0], 2) for v in m["35"]["w"]] == [-1.07, -2.24, -2.60, -2.83]
    assert [round(v[0], 2) for v in m["45"]["w"]] == [-1.28, -1.82, -2.10, -2.04]


@pytest.mark.parametrize("args, message", [
    (["a:25:x.csv"], "give two bags or more"),
    (["a:-3:x.csv", "b:5:y.csv"], "sand height must be a positive number"),
    (["a25x.csv", "b:5:y.csv"], "a bag is LABEL:H_MM:CSV"),
    (["--strains", "5,x"], "--strains takes numbers"),
    (["--bogus"], "unknown option --bogus"),
])
def test_bad_command_lines(args, message):
    with pytest.raises(SystemExit) as e:
        height.main(args)
    assert message in str(e.value)
