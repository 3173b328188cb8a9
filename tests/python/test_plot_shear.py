"""postprocess/plot_shear.py: the figure is written and its curves carry the CSV's numbers;
a truncated or missing CSV gives a clear message."""
import importlib.util
import os
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
spec = importlib.util.spec_from_file_location("plot_shear", ROOT / "postprocess" / "plot_shear.py")
plot_shear = importlib.util.module_from_spec(spec)
spec.loader.exec_module(plot_shear)

CSV = "time_s,u_mm,w_mm,S_N,Fv_N,broken_bonds\n" + "\n".join(
    "%g,%g,%g,%g,%g,0" % (0.01 * k, 0.1 * k, -0.01 * k + 0.0005 * k * k, 100 * (1 - np.exp(-k / 10)), 5500)
    for k in range(40))


def test_figure_carries_the_csv(tmp_path, monkeypatch):
    (tmp_path / "shear.csv").write_text(CSV)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    saved = {}
    orig = plt.Figure.savefig

    def keep(self, *a, **k):
        saved["fig"] = self
        return orig(self, *a, **k)

    monkeypatch.setattr(plt.Figure, "savefig", keep)
    out = plot_shear.plot([tmp_path], tmp_path / "f.png")
    assert Path(out).stat().st_size > 10000
    a1, a2 = saved["fig"].axes
    line = a1.get_lines()[0]
    d = np.genfromtxt(tmp_path / "shear.csv", delimiter=",", names=True)
    assert np.allclose(line.get_xdata(), d["u_mm"]) and np.allclose(line.get_ydata(), d["S_N"] / 1000)
    assert "5.50 kN" in a1.get_legend().get_texts()[0].get_text()
    assert np.allclose(a2.get_lines()[0].get_ydata(), d["w_mm"] - d["w_mm"][0])


def test_truncated_and_missing(tmp_path):
    (tmp_path / "shear.csv").write_text(CSV.splitlines()[0] + "\n" + CSV.splitlines()[1] + "\n")
    with pytest.raises(SystemExit, match="fewer than two rows"):
        plot_shear.plot([tmp_path], tmp_path / "f.png")
    with pytest.raises(SystemExit, match="no .*shear.csv"):
        plot_shear.plot([tmp_path / "nowhere"], tmp_path / "f.png")
