"""./tbags shear --realizations N on a tiny bag: N fills of different seeds run through the whole
protocol, and the summary writes the mean curves with their band and the table of the reported
figures with their spread."""
import os
import subprocess

import numpy as np

import lmprun

TINY = ["-var", "nx", "9", "-var", "ny", "9", "-var", "nz", "5", "-var", "v", "0.02", "-var", "ufinal", "0.0003"]


def test_two_realizations_write_band_and_table(tmp_path):
    out = tmp_path / "out"
    env = dict(os.environ, TBAGS_BUILD_DIR=os.environ.get("TBAGS_BUILD", str(lmprun.ROOT / "build")))
    r = subprocess.run([str(lmprun.ROOT / "tbags"), "shear", "--realizations", "2", "--out", str(out),
                        "-np", "2", "-var", "seed", "101"] + TINY,
                       env=env, capture_output=True, text=True, timeout=1200 * lmprun.SLOWDOWN)
    print(r.stdout[-3000:], r.stderr[-2000:])
    assert r.returncode == 0
    assert "2 realizations (seeds 101 to 102)" in r.stdout
    # two different packings of the same grains
    logs = [(out / k / "log.fill").read_text() for k in ("r1", "r2")]
    assert "random 0 101 " not in logs[0] and " 101 inner" in logs[0] and " 102 inner" in logs[1]
    assert (out / "r1" / "fill.data").read_text() != (out / "r2" / "fill.data").read_text()
    # the summary: a table row per realization, the spread, the curves with their band
    rows = np.genfromtxt(out / "realizations" / "realizations.csv", delimiter=",", names=True, dtype=None,
                         encoding=None)
    assert list(rows["realization"]) == ["r1", "r2"]
    for k, run in enumerate(("r1", "r2")):
        d = np.genfromtxt(out / run / "shear.csv", delimiter=",", names=True)
        assert rows["S_peak_N"][k] == np.float64("%.6g" % d["S_N"].max())
    md = (out / "realizations" / "realizations.md").read_text()
    assert "| all | 2 |" in md and "+-" in md
    c = np.genfromtxt(out / "realizations" / "curves_all.csv", delimiter=",", names=True)
    assert {"u_mm", "S_N_mean", "S_N_std", "S_N_min", "S_N_max", "w_mm_mean"} <= set(c.dtype.names)
    assert np.all(c["S_N_min"] <= c["S_N_mean"] + 1e-9) and np.all(c["S_N_mean"] <= c["S_N_max"] + 1e-9)
    assert np.any(c["S_N_std"] > 0)
    assert (out / "realizations" / "realizations.png").stat().st_size > 10000
