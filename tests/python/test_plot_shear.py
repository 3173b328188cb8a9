"""S-u and w-u (tbagspost.shear and its thin wrapper postprocess/plot_shear.py): the figure is
written and its curves carry the CSV's numbers; a truncated or missing CSV gives a clear message."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(os.environ.get("TBAGS_ROOT", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(ROOT / "postprocess"))
import plot_shear  # noqa: E402
from tbagspost import shear  # noqa: E402
from tbagspost.run import Run  # noqa: E402

HEADER = "time_s,u_mm,w_mm,S_N,Fv_N,broken_bonds,zplate_mm\n# w < 0: the top plate moved down\n"


def csv(fv):
    return HEADER + "\n".join(
        "%g,%g,%g,%g,%g,0,%g" % (0.07 + 0.005 * k, 0.1 * k, -0.01 * k + 0.0005 * k * k - 1.2,
                                 fv / 50 * (1 - np.exp(-k / 10)), fv, 30 - 0.01 * k)
        for k in range(40)) + "\n"


@pytest.fixture
def runs(tmp_path):
    out = []
    for fv in (5500, 3730, 1960):
        d = tmp_path / ("F%d" % fv)
        d.mkdir()
        (d / "shear.csv").write_text(csv(fv))
        out.append(d)
    return out


def test_figure_carries_the_csv(runs):
    fig, stats = shear.figure([Run(r) for r in runs])
    a_s, a_w = fig.axes
    assert len(a_s.get_lines()) == 3
    for line, wline, r in zip(a_s.get_lines(), a_w.get_lines(), runs):
        d = np.genfromtxt(r / "shear.csv", delimiter=",", names=True, comments="#")
        assert np.allclose(line.get_xdata(), d["u_mm"]) and np.allclose(line.get_ydata(), d["S_N"] / 1000)
        assert np.allclose(wline.get_ydata(), d["w_mm"] - d["w_mm"][0])
    labels = [t.get_text() for t in a_s.get_legend().get_texts()]
    assert labels == ["$F_v$ = 5.50 kN", "$F_v$ = 3.73 kN", "$F_v$ = 1.96 kN"]
    assert a_s.get_ylabel() == "shear force $S$ (kN)" and a_w.get_ylabel() == "vertical displacement $w$ (mm)"
    assert stats[0]["S_peak_kN"] == pytest.approx(5.5 / 50 * (1 - np.exp(-3.9)), rel=1e-5)
    assert "peak S" in shear.describe(stats[0])


def test_wrapper_writes_the_figure(runs, tmp_path):
    out = plot_shear.plot(runs, tmp_path / "f.png")
    assert Path(out).stat().st_size > 10000
    res = subprocess.run([sys.executable, str(ROOT / "postprocess" / "plot_shear.py"), str(runs[0]),
                          "-o", str(tmp_path / "g.pdf")], capture_output=True, text=True)
    assert res.returncode == 0 and (tmp_path / "g.pdf").stat().st_size > 5000, res.stderr


def test_truncated_and_missing(tmp_path, capsys):
    (tmp_path / "shear.csv").write_text(csv(5500).splitlines()[0] + "\n" + csv(5500).splitlines()[2] + "\n")
    with pytest.raises(SystemExit, match="fewer than two rows"):
        plot_shear.plot([tmp_path], tmp_path / "f.png")
    # cut inside the last row (a run stopped while writing it): that row is left out, and said
    (tmp_path / "shear.csv").write_text(csv(5500)[:-12])
    plot_shear.plot([tmp_path], tmp_path / "f.png")
    assert "shear.csv: its last line is cut short" in capsys.readouterr().err
    assert (tmp_path / "f.png").is_file()
    (tmp_path / "x").mkdir()
    with pytest.raises(SystemExit, match="no .*shear.csv"):
        plot_shear.plot([tmp_path / "x"], tmp_path / "f.png")
    with pytest.raises(SystemExit, match="no run directory"):
        plot_shear.plot([tmp_path / "nowhere"], tmp_path / "f.png")


def test_runs_of_one_load_are_labelled_by_what_differs(tmp_path):
    """Two speeds at one F_v (the quasistatic preset): be13c81 labelled both 'F_v = 0.32 kN'."""
    found = []
    for name, slow in (("v0.01", 1), ("v0.005", 2)):
        d = tmp_path / name
        d.mkdir()
        rows = csv(1960).splitlines()
        text = rows[:2] + [",".join([str(float(r.split(",")[0]) * slow)] + r.split(",")[1:]) for r in rows[2:]]
        (d / "shear.csv").write_text("\n".join(text) + "\n")
        found.append(Run(d))
    assert shear.labels(found) == ["$F_v$ = 1.96 kN, $v$ = 20 mm/s", "$F_v$ = 1.96 kN, $v$ = 10 mm/s"]
    fig, _ = shear.figure(found)
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert "min-max within each output interval" not in legend    # no band columns here
